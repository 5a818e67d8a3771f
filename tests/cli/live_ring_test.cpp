// The live ring commands against pseudo-terminals, with this test as the other end of the link: monitor
// sees what was written, send writes exactly the encoded bytes, join as MC forwards and delivers, join as
// keypad draws its display and sends its keys, and the port is left as it was.
#include <gtest/gtest.h>

#include <signal.h>
#include <termios.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "support/live_process.hpp"
#include "support/run_cli.hpp"
#include "trionet/host/link_device.hpp"
#include "trionet/host/pcapng.hpp"
#include "trionet/ring.hpp"

namespace {

using trionet::test::pty_pair;
using trionet::test::run_cli;
using trionet::test::tool_process;
namespace ring = trionet::ring;

constexpr int patience_ms = 20000;  // waiting for a process on a loaded machine; never a speed measure

std::vector<std::uint8_t> frame_of(const ring::message& m) {
  std::vector<std::uint8_t> out(ring::frame_length(m));
  const ring::encode_result r = ring::encode(trionet::byte_buffer(out.data(), out.size()), m);
  out.resize(r.length);
  return out;
}

std::vector<std::uint8_t> text_frame(std::uint8_t hops, const std::string& text) {
  return frame_of(ring::message::characters(
      hops, trionet::byte_view(reinterpret_cast<const std::uint8_t*>(text.data()), text.size())));
}

std::vector<std::uint8_t> concat(std::vector<std::vector<std::uint8_t>> parts) {
  std::vector<std::uint8_t> all;
  for (const auto& p : parts) all.insert(all.end(), p.begin(), p.end());
  return all;
}

std::string temp_path(const std::string& name) {
  return "/tmp/trionet-live-" + std::to_string(::getpid()) + "-" + name;
}

// Every record of a capture: (interface name, bytes).
std::vector<std::pair<std::string, std::vector<std::uint8_t>>> capture_records(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  trionet::host::pcapng_reader reader(in);
  std::vector<std::pair<std::string, std::vector<std::uint8_t>>> out;
  trionet::host::pcapng_read_result r;
  while ((r = reader.next())) {
    EXPECT_EQ(r.record.network, trionet::host::capture_network::ring);
    EXPECT_GT(r.record.time_ns, 1500000000ull * 1000000000ull);  // a real time of day, not a byte count
    out.emplace_back(reader.interfaces()[r.record.interface].name,
                     std::vector<std::uint8_t>(r.record.bytes.begin(), r.record.bytes.end()));
  }
  EXPECT_EQ(r.status, trionet::host::pcapng_read_status::end_of_file);
  return out;
}

TEST(LiveRing, MonitorDecodesWhatArrivesAndCapturesIt) {
  pty_pair pty;
  ASSERT_TRUE(pty.ok());
  const std::string pcap = temp_path("monitor.pcapng");
  tool_process monitor({"ring", "monitor", pty.slave_path, "--json", "--pcap", pcap});
  pty.write_all(concat({text_frame(2, "HELLO"), frame_of(ring::message::variable(1, 200, std::int64_t{99} << 32)),
                        frame_of(ring::message::keypad_offset(1, 2)), frame_of(ring::message::keypad_mode(3, 127)),
                        {0x89, 0x41}}));  // the last message never ends: the idle line cuts it
  const std::string& timed = monitor.read_lines_with("\"event\":\"frame_error\"", 1, patience_ms);
  std::size_t untimed = 0;
  const std::string out = trionet::test::without_times(timed, &untimed);
  EXPECT_EQ(untimed, 0u) << timed;
  EXPECT_NE(out.find("\"event\":\"message\",\"type\":\"char\",\"hops\":2,\"text\":\"HELLO\""), std::string::npos) << out;
  EXPECT_NE(out.find("\"type\":\"var\",\"hops\":1,\"vr\":200,\"raw\":\"0x0000006300000000\",\"value\":99"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("\"type\":\"offset\",\"hops\":1,\"offset\":2"), std::string::npos) << out;
  EXPECT_NE(out.find("\"type\":\"mode\",\"hops\":3,\"mode\":127"), std::string::npos) << out;
  EXPECT_NE(out.find("\"event\":\"frame_error\",\"reason\":\"idle_line\""), std::string::npos) << out;
  EXPECT_EQ(timed.rfind("{\"event\":\"message\",\"time\":\"", 0), 0u) << timed;  // as ring decode --pcap

  monitor.signal(SIGUSR1);  // counters now, and the monitor goes on
  monitor.read_lines_with("\"event\":\"counters\"", 1, patience_ms);
  pty.write_all(text_frame(1, "MORE"));
  monitor.read_lines_with("\"text\":\"MORE\"", 1, patience_ms);
  monitor.signal(SIGINT);
  EXPECT_EQ(monitor.wait(patience_ms), 0);
  const std::string all = trionet::test::without_times(monitor.output());
  EXPECT_EQ(tool_process::occurrences(all, "\"event\":\"counters\""), 2u) << all;
  EXPECT_NE(all.find("\"bytes\":37,\"messages\":5,\"char\":2,\"var\":1,\"offset\":1,\"mode\":1,\"crc_errors\":0,"
                     "\"frame_errors\":1,\"idle_line\":1,\"netstat\":8}"),
            std::string::npos)
      << all;

  // What `ring decode --pcap` reads back from the capture: the same messages with the same fields; the
  // message the idle line cut is a record whose message never ended.
  const auto decoded = run_cli("ring decode --pcap " + pcap);
  ASSERT_EQ(decoded.exit_code, 0) << decoded.err;
  const auto messages = trionet::test::events_without_positions(monitor.output(), {"message", "crc_error"});
  EXPECT_EQ(messages.size(), 5u) << monitor.output();
  EXPECT_EQ(trionet::test::events_without_positions(decoded.out, {"message", "crc_error"}), messages) << decoded.out;
  EXPECT_EQ(tool_process::occurrences(decoded.out, "\"event\":\"unfinished\""), 1u) << decoded.out;
  EXPECT_NE(decoded.out.find("\"interface\":\"received on " + pty.slave_path + "\""), std::string::npos) << decoded.out;

  const auto records = capture_records(pcap);
  ASSERT_EQ(records.size(), 6u);  // five messages and the one the idle line cut
  EXPECT_EQ(records[0].first, "received on " + pty.slave_path);
  EXPECT_EQ(records[0].second, text_frame(2, "HELLO"));
  EXPECT_EQ(records[4].second, (std::vector<std::uint8_t>{0x89, 0x41}));
  EXPECT_EQ(records[5].second, text_frame(1, "MORE"));
  std::remove(pcap.c_str());
}

TEST(LiveRing, MonitorTextIsOneTimedLinePerEvent) {
  pty_pair pty;
  ASSERT_TRUE(pty.ok());
  tool_process monitor({"ring", "monitor", pty.slave_path});
  pty.write_all({0x89, 0x41, 0x91, 0x42, 0x90});
  const std::string& out = monitor.read_lines_with("text=", 1, patience_ms);
  // "HH:MM:SS.ffffff frame_error reason=..." then the message
  EXPECT_NE(out.find(" frame_error reason=\"interrupted\"\n"), std::string::npos) << out;
  EXPECT_NE(out.find(" message type=\"char\" hops=2 text=\"B\"\n"), std::string::npos) << out;
  EXPECT_EQ(out[2], ':');
  EXPECT_EQ(out[8], '.');
}

TEST(LiveRing, SendWritesExactlyTheEncodedBytes) {
  pty_pair pty;
  ASSERT_TRUE(pty.ok());
  const std::vector<std::vector<std::string>> cases = {
      {"print", "--to", "11", "HELLO"},
      {"var", "--to", "10", "--vr", "200", "--value", "99"},
      {"offset", "--to", "10", "--offset", "11"},
      {"mode", "--to", "10", "--mode", "127"}};
  for (const auto& message : cases) {
    std::string words;
    for (const auto& w : message) words += " " + w;
    const auto encoded = run_cli("ring encode" + words);
    ASSERT_EQ(encoded.exit_code, 0) << words;
    const auto sent = run_cli("ring send " + pty.slave_path + words);
    EXPECT_EQ(sent.exit_code, 0) << sent.err;
    EXPECT_EQ(sent.out, encoded.out);  // it prints what it wrote
    std::vector<std::uint8_t> expected;
    std::string error;
    const auto got = pty.read_bytes((encoded.out.size()) / 3, patience_ms);
    std::string hex;
    for (std::size_t i = 0; i < got.size(); ++i) {
      char two[4];
      std::snprintf(two, sizeof two, "%02x", got[i]);
      hex += (i ? " " : "") + std::string(two);
    }
    EXPECT_EQ(hex + "\n", encoded.out) << words;
  }
  const auto written = run_cli("ring send - print --to 10 AB");  // standard output: the raw bytes
  EXPECT_EQ(written.exit_code, 0);
  EXPECT_EQ(written.out, std::string("\x89" "AB" "\x88"));
  const auto piped = run_cli("ring monitor - --json", written.out);  // and standard input, to its end
  EXPECT_EQ(piped.exit_code, 0) << piped.err;
  EXPECT_NE(trionet::test::without_times(piped.out).find("\"event\":\"message\",\"type\":\"char\",\"hops\":1,\"text\":\"AB\"}"),
            std::string::npos)
      << piped.out;
}

TEST(LiveRing, PortErrorsNameThePortAndTheCause) {
  // A port that cannot be opened is an input that cannot be read (exit 1), with the cause.
  trionet::test::expect_io_error("ring monitor /nonexistent/ttyX", "cannot open /nonexistent/ttyX: No such file");
  trionet::test::expect_io_error("ring monitor /dev/null", "/dev/null is not a serial port");
  trionet::test::expect_io_error("ring monitor /tmp", "/tmp is not a serial port, pty, FIFO or socket");
  trionet::test::expect_io_error("ring send /nonexistent/ttyX print --to 11 A", "cannot open /nonexistent/ttyX");
  trionet::test::expect_io_error("ring join /nonexistent/ttyX --as mc", "cannot open /nonexistent/ttyX");
  trionet::test::expect_usage_error("ring monitor /dev/null --baud 10", "--baud must be a rate 50..4000000");
  trionet::test::expect_usage_error("ring monitor /dev/null --flow maybe", "--flow must be none, rtscts or xonxoff");
  trionet::test::expect_usage_error("ring send /dev/null print --to 11", "print takes exactly one TEXT");
  trionet::test::expect_usage_error("ring send /dev/null var --to 10 --offset 11", "does not apply to a var message");
  trionet::test::expect_usage_error("ring join /dev/null", "needs --as mc or --as keypad");
  trionet::test::expect_usage_error("ring join - --as mc", "a node needs a port it can read and write");
  trionet::test::expect_usage_error("ring join /dev/null --as plc", "--as must be mc or keypad");
}

// The port's settings after the tool are those before it: a monitor ended by Ctrl-C, at a non-standard rate.
TEST(LiveRing, CtrlCLeavesThePortAsItWas) {
  pty_pair pty;
  ASSERT_TRUE(pty.ok());
  termios before{};
  ASSERT_EQ(::tcgetattr(pty.slave_keep, &before), 0);
  before.c_lflag |= ECHO | ICANON;
  ::cfsetspeed(&before, B9600);
  ASSERT_EQ(::tcsetattr(pty.slave_keep, TCSANOW, &before), 0);
  ASSERT_EQ(::tcgetattr(pty.slave_keep, &before), 0);
  tool_process monitor({"ring", "monitor", pty.slave_path, "--baud", "125000"});
  pty.write_all(text_frame(1, "X"));
  monitor.read_lines_with("text=\"X\"", 1, patience_ms);
  termios during{};
  ASSERT_EQ(::tcgetattr(pty.slave_keep, &during), 0);
  EXPECT_EQ(during.c_lflag & (ECHO | ICANON), 0u);  // raw while the tool has it
  monitor.signal(SIGINT);
  EXPECT_EQ(monitor.wait(patience_ms), 0);
  termios after{};
  ASSERT_EQ(::tcgetattr(pty.slave_keep, &after), 0);
  EXPECT_EQ(after.c_lflag, before.c_lflag);
  EXPECT_EQ(after.c_iflag, before.c_iflag);
  EXPECT_EQ(after.c_oflag, before.c_oflag);
  EXPECT_EQ(after.c_cflag, before.c_cflag);
  EXPECT_EQ(::cfgetospeed(&after), B9600);
}

TEST(LiveRing, JoinAsMcForwardsDeliversAndTakesCommands) {
  pty_pair pty;
  ASSERT_TRUE(pty.ok());
  const std::string pcap = temp_path("join.pcapng");
  tool_process mc({"ring", "join", pty.slave_path, "--as", "mc", "--json", "--pcap", pcap});
  // This test is the rest of the ring: what it writes arrives at the MC, what the MC sends comes back.
  pty.write_all(concat({text_frame(2, "FWD"), text_frame(1, "ME"),
                        frame_of(ring::message::variable(1, 7, std::int64_t{5} << 31))}));
  const auto forwarded = pty.read_bytes(5, patience_ms);
  EXPECT_EQ(forwarded, text_frame(1, "FWD"));  // hops decremented, passed on
  mc.read_lines_with("\"event\":\"vr_write\"", 1, patience_ms);
  mc.write("key 4\nget 4\nget 4\nget 4\nvr 7\nprint 10 HI\\r\\n\nsend 12 300 -1.5\nnetstat\nbogus\n");
  const std::string out = trionet::test::without_times(mc.read_lines_with("\"event\":\"error\"", 1, patience_ms));
  EXPECT_NE(out.find("\"event\":\"message\",\"link\":\"in\",\"type\":\"char\",\"hops\":1,\"text\":\"ME\""),
            std::string::npos)
      << out;
  EXPECT_EQ(out.find("FWD"), std::string::npos) << "passing traffic is shown only with --trace";
  EXPECT_NE(out.find("\"event\":\"vr_write\",\"vr\":7,\"value\":2.5,\"status\":\"ok\""), std::string::npos) << out;
  EXPECT_NE(out.find("\"event\":\"key\",\"channel\":4,\"waiting\":true,\"characters\":2"), std::string::npos) << out;
  EXPECT_NE(out.find("\"event\":\"get\",\"channel\":4,\"value\":77"), std::string::npos) << out;
  EXPECT_NE(out.find("\"event\":\"get\",\"channel\":4,\"value\":69"), std::string::npos) << out;
  EXPECT_NE(out.find("\"event\":\"get\",\"channel\":4,\"status\":\"nothing_yet\""), std::string::npos) << out;
  EXPECT_NE(out.find("\"event\":\"vr\",\"vr\":7,\"value\":2.5"), std::string::npos) << out;
  EXPECT_EQ(tool_process::occurrences(out, "\"event\":\"queued\""), 2u) << out;
  EXPECT_NE(out.find("\"event\":\"netstat\",\"netstat\":0"), std::string::npos) << out;
  EXPECT_NE(out.find("\"command\":\"bogus\",\"reason\":\"unknown command"), std::string::npos) << out;
  const auto sent = pty.read_bytes(6 + 16, patience_ms);
  EXPECT_EQ(sent, concat({text_frame(1, "HI\r\n"), frame_of(ring::message::variable(3, 300, -(std::int64_t{3} << 31)))}));
  mc.write("quit\n");
  EXPECT_EQ(mc.wait(patience_ms), 0);
  const std::string& all = mc.output();
  EXPECT_NE(all.find("\"messages_forwarded\":1,\"forwards_lost\":0"), std::string::npos) << all;
  EXPECT_NE(all.find("\"character_messages\":1,\"receive_overflows\":0,\"variables_written\":1"), std::string::npos)
      << all;

  const auto records = capture_records(pcap);  // both directions, one interface each
  ASSERT_EQ(records.size(), 6u);
  EXPECT_EQ(records[0], std::make_pair("received on " + pty.slave_path, text_frame(2, "FWD")));
  std::size_t sent_records = 0;
  for (const auto& r : records) {
    if (r.first == "sent on " + pty.slave_path) ++sent_records;
  }
  EXPECT_EQ(sent_records, 3u);
  std::remove(pcap.c_str());
}

// send N VR VALUE reads VALUE exactly to Q32.32 (docs/protocol.md 1.3), not through a double: the documented
// top of the range goes out, digits beyond a double's count, and a value outside the range is refused.
TEST(LiveRing, JoinSendsTheExactQ32Value) {
  pty_pair pty;
  ASSERT_TRUE(pty.ok());
  tool_process mc({"ring", "join", pty.slave_path, "--as", "mc", "--json"});
  mc.write("send 10 1 2147483647.99999999977\nsend 10 2 123456789.123456789\nsend 10 3 -2147483648.0000000001\n"
           "send 10 4 2147483647.9999999999\nsend 10 5 nan\nsend 10 6 0." +
           std::string(1000, '1') + "\nbogus\n");
  const std::string out = trionet::test::without_times(mc.read_lines_with("unknown command", 1, patience_ms));
  EXPECT_EQ(tool_process::occurrences(out, "\"event\":\"queued\""), 3u) << out;
  EXPECT_NE(out.find("\"command\":\"send\",\"reason\":\"value_out_of_range\""), std::string::npos) << out;
  EXPECT_NE(out.find("\"command\":\"send\",\"reason\":\"usage: send N VR VALUE"), std::string::npos) << out;
  EXPECT_NE(out.find("\"command\":\"send\",\"reason\":\"VALUE has more than 1000 characters\""), std::string::npos)
      << out;
  const auto sent = pty.read_bytes(3 * 16, patience_ms);
  EXPECT_EQ(sent, concat({frame_of(ring::message::variable(1, 1, INT64_MAX)),
                          frame_of(ring::message::variable(1, 2, std::int64_t{0x075bcd151f9add37})),
                          frame_of(ring::message::variable(1, 3, INT64_MIN))}));
  mc.write("quit\n");
  EXPECT_EQ(mc.wait(patience_ms), 0);
}

// A stream of messages through the MC with no loss: the counters on both sides agree.
TEST(LiveRing, JoinAsMcForwardsAStreamWithoutLoss) {
  pty_pair pty;
  ASSERT_TRUE(pty.ok());
  tool_process mc({"ring", "join", pty.slave_path, "--as", "mc", "--json", "--idle-ms", "1000"});
  constexpr std::size_t count = 2000;
  std::vector<std::uint8_t> stream;
  std::vector<std::uint8_t> expected;
  for (std::size_t i = 0; i < count; ++i) {
    const std::string text = "M" + std::to_string(i);
    const auto in = i % 3 == 0 ? frame_of(ring::message::variable(3, static_cast<std::uint16_t>(i), std::int64_t(i) << 32))
                               : text_frame(2, text);
    const auto out = i % 3 == 0 ? frame_of(ring::message::variable(2, static_cast<std::uint16_t>(i), std::int64_t(i) << 32))
                                : text_frame(1, text);
    stream.insert(stream.end(), in.begin(), in.end());
    expected.insert(expected.end(), out.begin(), out.end());
  }
  std::vector<std::uint8_t> back;
  std::size_t written = 0;
  const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(60000);
  while (back.size() < expected.size() && std::chrono::steady_clock::now() < until) {
    if (written < stream.size()) {
      const ssize_t n = ::write(pty.master, stream.data() + written, std::min<std::size_t>(1024, stream.size() - written));
      if (n > 0) written += static_cast<std::size_t>(n);
    }
    std::uint8_t chunk[4096];
    const ssize_t got = ::read(pty.master, chunk, sizeof chunk);
    if (got > 0) back.insert(back.end(), chunk, chunk + got);
    if (got <= 0 && written == stream.size()) {
      pollfd p{pty.master, POLLIN, 0};
      ::poll(&p, 1, 20);
    }
  }
  EXPECT_EQ(back.size(), expected.size());
  EXPECT_TRUE(back == expected) << "the forwarded stream differs";
  mc.write("quit\n");
  EXPECT_EQ(mc.wait(patience_ms), 0);
  const std::string& all = mc.output();
  EXPECT_NE(all.find("\"messages_forwarded\":2000,\"forwards_lost\":0,\"forwards_cut\":0,\"forwards_ended_idle\":0"),
            std::string::npos)
      << all;
  EXPECT_NE(all.find("\"in_messages\":2000,"), std::string::npos) << all;
  EXPECT_NE(all.find("\"out_messages\":2000,"), std::string::npos) << all;
}

TEST(LiveRing, JoinAsKeypadShowsTheDisplayAndSendsKeys) {
  pty_pair pty;
  ASSERT_TRUE(pty.ok());
  tool_process keypad({"ring", "join", pty.slave_path, "--as", "keypad", "--json"});
  keypad.write("1\n");  // in local mode: lost, as on the real keypad
  keypad.read_lines_with("\"press\":\"local_mode\"", 1, patience_ms);
  pty.write_all(concat({frame_of(ring::message::keypad_offset(1, 2)), text_frame(1, "\x0c" "SPEED:\r\nLENGTH:\r\n"),
                        text_frame(3, "PASS")}));
  const auto passed = pty.read_bytes(6, patience_ms);
  EXPECT_EQ(passed, text_frame(2, "PASS"));  // in network mode it forwards
  keypad.read_lines_with("LENGTH:", 1, patience_ms);
  keypad.write("7 up wait=50 y\n");
  const auto keys = pty.read_bytes(9, patience_ms);
  EXPECT_EQ(keys, concat({text_frame(2, "7"), text_frame(2, "U"), text_frame(2, "Y")}));
  pty.write_all(concat({frame_of(ring::message::keypad_mode(1, 127)), text_frame(1, "\x1bH\x07" "42")}));
  keypad.read_lines_with("SPEED: 42", 1, patience_ms);
  keypad.write("5 quit\n");
  EXPECT_EQ(keypad.wait(patience_ms), 0);
  const auto key_on_off = pty.read_bytes(6, patience_ms);
  EXPECT_EQ(key_on_off, concat({text_frame(2, "5"), text_frame(2, "u")}));  // key ON and key OFF (+64)
  const std::string out = trionet::test::without_times(keypad.output());
  EXPECT_NE(out.find("\"event\":\"mode\",\"network\":true,\"offset\":2,\"keypad_mode\":0"), std::string::npos) << out;
  EXPECT_NE(out.find("\"event\":\"display\",\"line1\":\"SPEED:              \",\"line2\":\"LENGTH:             \""),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("\"event\":\"display\",\"line1\":\"SPEED: 42           \""), std::string::npos) << out;
  EXPECT_NE(out.find("\"key\":\"up\",\"press\":\"ok\",\"release\":\"nothing_to_send\""), std::string::npos) << out;
  EXPECT_NE(out.find("\"key\":\"digit_5\",\"press\":\"ok\",\"release\":\"ok\""), std::string::npos) << out;
  EXPECT_NE(out.find("\"keys_sent\":5,\"keys_lost\":1"), std::string::npos) << out;
}

// Every bad wait=MS word of a key script is reported, in its place among the other words.
TEST(LiveRing, JoinAsKeypadReportsEveryBadWaitInOrder) {
  pty_pair pty;
  ASSERT_TRUE(pty.ok());
  tool_process keypad({"ring", "join", pty.slave_path, "--as", "keypad", "--json"});
  keypad.write("wait=-1 wait=zz 1 wait=qq\nquit\n");
  EXPECT_EQ(keypad.wait(patience_ms), 0);
  const std::string out = trionet::test::without_times(keypad.output());
  const std::size_t first = out.find("\"word\":\"wait=-1\",\"reason\":\"wait=MS takes 0..3600000\"");
  const std::size_t second = out.find("\"word\":\"wait=zz\",\"reason\":\"wait=MS takes 0..3600000\"");
  const std::size_t key = out.find("\"key\":\"digit_1\"");
  const std::size_t third = out.find("\"word\":\"wait=qq\",\"reason\":\"wait=MS takes 0..3600000\"");
  ASSERT_NE(first, std::string::npos) << out;
  ASSERT_NE(second, std::string::npos) << out;
  ASSERT_NE(key, std::string::npos) << out;
  ASSERT_NE(third, std::string::npos) << out;
  EXPECT_LT(first, second);
  EXPECT_LT(second, key);
  EXPECT_LT(key, third);
}

// The keypad on a real terminal (tmux): the display drawn in place, keys from the keyboard.
TEST(LiveRing, KeypadEmulatorInATerminal) {
  if (std::system("tmux -V >/dev/null 2>&1") != 0) GTEST_SKIP() << "tmux is not installed (Debian: apt-get install tmux)";
  pty_pair pty;
  ASSERT_TRUE(pty.ok());
  const std::string session = "trionet-keypad-" + std::to_string(::getpid());
  const std::string socket = "-L " + session;
  const std::string after = temp_path("stty-after");  // the terminal's settings once the keypad has quit
  std::remove(after.c_str());
  const std::string start = "tmux " + socket + " new-session -d -s " + session + " -x 120 -y 24 '" +
                            std::string(TRIONET_CLI_PATH) + " ring join " + pty.slave_path + " --as keypad; stty -a >" +
                            after + ".part; mv " + after + ".part " + after + "; sleep 60'";
  ASSERT_EQ(std::system(start.c_str()), 0);
  struct kill_session {
    std::string command;
    ~kill_session() { (void)std::system(command.c_str()); }
  } cleanup{"tmux " + socket + " kill-server >/dev/null 2>&1"};
  const auto screen = [&]() {  // the terminal as the user sees it
    std::string shown;
    std::FILE* pane = ::popen(("tmux " + socket + " capture-pane -p -t " + session).c_str(), "r");
    if (pane == nullptr) return shown;
    char chunk[4096];
    std::size_t got = 0;
    while ((got = std::fread(chunk, 1, sizeof chunk, pane)) > 0) shown.append(chunk, got);
    ::pclose(pane);
    return shown;
  };
  const auto wait_for = [&](const std::string& text) {
    std::string shown;
    for (int i = 0; i < patience_ms / 50; ++i) {
      shown = screen();
      if (shown.find(text) != std::string::npos) return shown;
      ::usleep(50000);
    }
    return shown;
  };
  std::string shown = wait_for("local mode");
  EXPECT_NE(shown.find("trionet keypad on " + pty.slave_path), std::string::npos) << shown;
  pty.write_all(concat({frame_of(ring::message::keypad_offset(1, 1)), text_frame(1, "\x0cSPEED:\r\nLENGTH:")}));
  shown = wait_for("|LENGTH:             |");
  EXPECT_NE(shown.find("|SPEED:              |\n  |LENGTH:             |"), std::string::npos) << shown;
  EXPECT_NE(shown.find("network mode: keys to BASIC 10 (1 hop)"), std::string::npos) << shown;
  ASSERT_EQ(std::system(("tmux " + socket + " send-keys -t " + session + " 3 Up Enter").c_str()), 0);
  EXPECT_EQ(pty.read_bytes(9, patience_ms), concat({text_frame(1, "3"), text_frame(1, "U"), text_frame(1, "Y")}));
  pty.write_all(text_frame(1, "\x1bH\x07" "3"));
  shown = wait_for("|SPEED: 3            |");
  EXPECT_NE(shown.find("|SPEED: 3            |"), std::string::npos) << shown;
  EXPECT_EQ(trionet::test::tool_process::occurrences(shown, "|SPEED:"), 1u) << "drawn in place, not scrolled:\n" << shown;
  ASSERT_EQ(std::system(("tmux " + socket + " send-keys -t " + session + " q").c_str()), 0);
  std::string settings;
  for (int i = 0; i < patience_ms / 50 && settings.empty(); ++i) {
    ::usleep(50000);
    settings = trionet::test::slurp(after);
  }
  ASSERT_FALSE(settings.empty()) << "q ends the keypad";
  EXPECT_NE(settings.find(" icanon"), std::string::npos) << "line editing is back:\n" << settings;
  EXPECT_NE(settings.find(" echo "), std::string::npos) << "echo is back:\n" << settings;
  std::remove(after.c_str());
}

TEST(LiveRing, SimulateInteractiveTakesKeyWordsWithoutATerminal) {
  const auto r = run_cli("ring simulate example1 --interactive", "wait=300 1:1 2:2 wait=300\n");  // ends with them
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("keypad 1: key 1 sent to node 1"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("keypad 2: key 2 sent to node 1"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("display |SPEED:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("keypad 1 at t="), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("|SPEED:     21       |LENGTH:      0.0    |"), std::string::npos) << r.out;
}

}  // namespace
