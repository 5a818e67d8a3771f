// The live CAN commands: over candump text (always) and over SocketCAN on a vcan interface (skipped, saying
// what is missing, where the kernel has no CAN support or no vcan module).
#include <gtest/gtest.h>

#include <net/if.h>
#include <signal.h>
#include <sys/socket.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#include "support/live_process.hpp"
#include "support/run_cli.hpp"
#include "support/vcan.hpp"
#include "trionet/host/candump.hpp"
#include "trionet/host/capture.hpp"
#include "trionet/host/pcapng.hpp"

namespace {

using trionet::test::run_cli;
using trionet::test::tool_process;

constexpr int patience_ms = 20000;

TEST(LiveCan, MonitorDecodesCandumpTextAndCapturesIt) {
  const std::string pcap = "/tmp/trionet-live-can-" + std::to_string(::getpid()) + ".pcapng";
  const auto r = run_cli("can monitor - --json --pcap " + pcap,
                         "(1700000000.123456) can0 028#0100000000020D7A\n"
                         "\n"
                         "016#0501000000011388\n"
                         "028#02\n"
                         "not a frame\n"
                         "7FF#0000000000000000\n");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  // The fields of `can decode`, with the line's own time
  EXPECT_NE(r.out.find("{\"event\":\"vr\",\"time\":\"1700000000.123456000\",\"line\":1,\"id\":40,\"from\":1,\"to\":4,"
                       "\"vr\":1,\"negative\":false,\"int\":2,\"frac\":3450,\"value\":2.345}"),
            std::string::npos)
      << r.out;
  std::size_t untimed = 0;
  const std::string out = trionet::test::without_times(r.out, &untimed);
  EXPECT_EQ(untimed, 0u) << r.out;
  EXPECT_NE(out.find("\"event\":\"vr\",\"line\":3,\"id\":22,\"from\":4,\"to\":2,\"vr\":5,\"negative\":true,\"int\":1,"
                       "\"frac\":5000,\"value\":-1.5}"),
            std::string::npos)
      << r.out;
  EXPECT_NE(out.find("\"event\":\"error\",\"line\":4,\"reason\":\"bad_dlc\",\"id\":40}"), std::string::npos) << r.out;
  EXPECT_NE(out.find("\"event\":\"error\",\"line\":5,\"reason\":\"syntax\",\"detail\":\"identifier\"}"),
            std::string::npos)
      << r.out;
  EXPECT_NE(out.find("\"event\":\"frame\",\"line\":6,\"kind\":\"foreign_id\",\"id\":2047,\"length\":8}"),
            std::string::npos)
      << r.out;
  EXPECT_NE(out.find("\"event\":\"counters\",\"frames\":4,\"vr\":2,\"vr_errors\":1,\"other\":1,\"error_frames\":0,"
                     "\"syntax\":1}"),
            std::string::npos)
      << r.out;

  // What `can decode --pcap` reads back from the capture: the same events with the same fields.
  const auto decoded = run_cli("can decode --pcap " + pcap);
  ASSERT_EQ(decoded.exit_code, 0) << decoded.err;
  const std::vector<std::string> kinds = {"vr", "frame", "error"};
  std::vector<std::string> frames = trionet::test::events_without_positions(r.out, kinds);
  frames.erase(std::remove_if(frames.begin(), frames.end(),
                              [](const std::string& e) { return e.find("\"syntax\"") != std::string::npos; }),
               frames.end());  // a line that is not a frame has no record
  EXPECT_EQ(frames.size(), 4u) << r.out;
  EXPECT_EQ(trionet::test::events_without_positions(decoded.out, kinds), frames) << decoded.out;

  std::ifstream in(pcap, std::ios::binary);
  trionet::host::pcapng_reader reader(in);
  std::size_t records = 0;
  trionet::host::pcapng_read_result read;
  while ((read = reader.next())) {
    EXPECT_EQ(read.record.network, trionet::host::capture_network::can);
    const auto frame = trionet::host::read_socketcan_record(read.record.bytes);
    ASSERT_TRUE(frame);
    if (records == 0) {
      EXPECT_EQ(trionet::host::format_candump_frame(frame.frame), "028#0100000000020D7A");
      EXPECT_EQ(read.record.time_ns, 1700000000123456000ull);  // the line's own time
    }
    ++records;
  }
  EXPECT_EQ(read.status, trionet::host::pcapng_read_status::end_of_file);
  EXPECT_EQ(records, 4u);
  std::remove(pcap.c_str());
}

// A line without end is cut at line_reader::max_line: memory stays bounded and the next line is read as usual.
TEST(LiveCan, AnEndlessLineIsOneSyntaxErrorAndTheNextIsRead) {
  const auto r = run_cli("can monitor - --json", std::string(300000, '0') + "\n028#0100000000020D7A\n");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const std::string out = trionet::test::without_times(r.out);
  EXPECT_NE(out.find("\"event\":\"error\",\"line\":1,\"reason\":\"syntax\""), std::string::npos) << r.out;
  EXPECT_EQ(out.find("\"line\":2,\"reason\""), std::string::npos) << "the rest of the long line is not a line of its own";
  EXPECT_NE(out.find("\"event\":\"vr\",\"line\":2,\"id\":40"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"frames\":1,\"vr\":1,\"vr_errors\":0,\"other\":0,\"error_frames\":0,\"syntax\":1}"),
            std::string::npos)
      << r.out;
}

TEST(LiveCan, SendWritesACandumpLogLine) {
  const auto r = run_cli("can send - --from 1 --to 4 --vr 1 --value 2.345 --interface-name vcan0");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const trionet::host::candump_result line = trionet::host::parse_candump_line(r.out.substr(0, r.out.size() - 1));
  ASSERT_TRUE(line) << r.out;
  EXPECT_TRUE(line.record.has_timestamp);
  EXPECT_EQ(line.record.interface_name, "vcan0");
  EXPECT_EQ(trionet::host::format_candump_frame(line.record.frame), "028#0100000000020D7A");
  trionet::test::expect_usage_error("can send - --from 1 --to 1 --vr 1 --value 2", "own_node");
  trionet::test::expect_usage_error("can send - --from 1 --to 4 --vr 256 --value 2", "--vr must be");
}

TEST(LiveCan, AnInterfaceNameLinuxOrACandumpLineCannotHoldIsABadArgument) {
  const std::string send = "can send - --from 1 --to 4 --vr 1 --value 2.345 --interface-name ";
  trionet::test::expect_usage_error(send + "'a b'", "--interface-name 'a b' holds a space");
  trionet::test::expect_usage_error(send + "'a\nb'", "holds a control character");
  trionet::test::expect_usage_error(send + "''", "--interface-name is empty");
  trionet::test::expect_usage_error(send + "a/b", "holds '/'");
  trionet::test::expect_usage_error(send + "abcdefghijklmnop",
                                    "has 16 bytes: a Linux interface name has at most 15 (IFNAMSIZ 16 with its NUL)");
  trionet::test::expect_usage_error("can node - --node 2 --interface-name 'x y'", "holds a space");
  trionet::test::expect_usage_error("can monitor ''", "can monitor: IFACE is empty");
  trionet::test::expect_usage_error("can monitor abcdefghijklmnop", "IFACE 'abcdefghijklmnop' has 16 bytes");
  trionet::test::expect_usage_error("can send 'vcan 0' --from 1 --to 4 --vr 1 --value 2", "holds a space");
  // 15 bytes is a name Linux allows: written, and read back.
  const auto r = run_cli(send + "abcdefghijklmno");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const trionet::host::candump_result line = trionet::host::parse_candump_line(r.out.substr(0, r.out.size() - 1));
  ASSERT_TRUE(line) << r.out;
  EXPECT_EQ(line.record.interface_name, "abcdefghijklmno");
}

TEST(LiveCan, NodeWritesWhatItReceivesAndSendsWhatItIsAsked) {
  const auto r = run_cli("can node - --node 4 --json",
                         "(1700000000.000001) can0 028#0100000000020D7A\n"
                         "016#0501000000011388\n"  // node 4 to node 2: not for this node 4
                         "028#0102000000000000\n"  // ours, a bad sign byte
                         "vr 1\n"
                         "send 2 5 -1.5\n"
                         "send 4 5 1\n"
                         "counters\n");
  const std::string events = trionet::test::without_times(r.err);
  EXPECT_EQ(r.exit_code, 0) << events;
  // standard output: the frames it sent, as candump log lines (for canplayer)
  const trionet::host::candump_result sent = trionet::host::parse_candump_line(r.out.substr(0, r.out.find('\n')));
  ASSERT_TRUE(sent) << r.out;
  EXPECT_EQ(trionet::host::format_candump_frame(sent.record.frame), "016#0501000000011388");  // node 4 -> node 2
  EXPECT_EQ(tool_process::occurrences(r.out, "\n"), 1u) << r.out;
  // standard error: the events
  EXPECT_NE(r.err.find("{\"event\":\"vr_write\",\"time\":\"1700000000.000001000\",\"from\":1,\"vr\":1,\"value\":2.345,"
                       "\"status\":\"ok\"}"),
            std::string::npos)
      << r.err;
  EXPECT_NE(events.find("\"event\":\"error\",\"from\":1,\"frame\":\"028#0102000000000000\",\"status\":\"bad_sign\""),
            std::string::npos)
      << events;
  EXPECT_NE(events.find("\"event\":\"vr\",\"vr\":1,\"value\":2.345"), std::string::npos) << events;
  EXPECT_NE(events.find("\"event\":\"sent\",\"to\":2,\"vr\":5,\"value\":-1.5"), std::string::npos) << events;
  EXPECT_NE(events.find("\"command\":\"send\",\"reason\":\"own_node\""), std::string::npos) << events;
  EXPECT_NE(events.find("\"sent\":1,\"send_busy\":0,\"send_failed\":0,\"written\":1,\"refused\":0,\"out_of_range\":0,"
                        "\"foreign\":1,\"bad_dlc\":0,\"bad_sign\":1"),
            std::string::npos)
      << events;
}

// The pipelines the README shows: one tool's frames into another's, as candump text.
TEST(LiveCan, CandumpPipelines) {
  const std::string tool = TRIONET_CLI_PATH;
  const std::string out = "/tmp/trionet-live-can-pipe-" + std::to_string(::getpid());
  const std::string command = tool + " can send - --from 1 --to 4 --vr 9 --value 0.5 | " + tool +
                              " can node - --node 4 --json 2>" + out + ".err >" + out + ".out";
  ASSERT_EQ(std::system(command.c_str()), 0);
  const std::string events = trionet::test::without_times(trionet::test::slurp(out + ".err"));
  EXPECT_NE(events.find("\"event\":\"vr_write\",\"from\":1,\"vr\":9,\"value\":0.5,\"status\":\"ok\""), std::string::npos)
      << events;
  const std::string chain = "printf 'send 3 7 12.25\\n' | " + tool + " can node - --node 1 2>/dev/null | " + tool +
                            " can monitor - >" + out + ".out";
  ASSERT_EQ(std::system(chain.c_str()), 0);
  const std::string seen = trionet::test::slurp(out + ".out");
  EXPECT_NE(seen.find(" vr line=1 id=30 from=1 to=3 vr=7 negative=false int=12 frac=2500 value=12.25\n"),
            std::string::npos)
      << seen;
  std::remove((out + ".err").c_str());
  std::remove((out + ".out").c_str());
}

// can-utils read what the tool writes and the tool reads what can-utils write (log2asc and asc2log convert
// between candump log files and Vector ASC).
TEST(LiveCan, CanUtilsReadAndWriteTheSameText) {
  if (std::system("command -v log2asc >/dev/null 2>&1 && command -v asc2log >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "can-utils is not installed (Debian: apt-get install can-utils)";
  const std::string tool = TRIONET_CLI_PATH;
  const std::string base = "/tmp/trionet-live-can-utils-" + std::to_string(::getpid());
  ASSERT_EQ(std::system((tool + " can send - --from 1 --to 4 --vr 1 --value 2.345 >" + base + ".log").c_str()), 0);
  ASSERT_EQ(std::system(("log2asc -I " + base + ".log can0 >" + base + ".asc").c_str()), 0);
  EXPECT_NE(trionet::test::slurp(base + ".asc").find("28              Rx   d 8 01 00 00 00 00 02 0D 7A"),
            std::string::npos)
      << trionet::test::slurp(base + ".asc");
  ASSERT_EQ(std::system(("asc2log -I " + base + ".asc | " + tool + " can monitor - --json >" + base + ".out").c_str()), 0);
  EXPECT_NE(trionet::test::without_times(trionet::test::slurp(base + ".out")).find("\"event\":\"vr\",\"line\":1,\"id\":40,\"from\":1,\"to\":4,\"vr\":1"),
            std::string::npos)
      << trionet::test::slurp(base + ".out");
  for (const char* ext : {".log", ".asc", ".out"}) std::remove((base + ext).c_str());
}

TEST(LiveCan, CandumpLogLinesMayEndWithADirectionFlag) {
  for (const char* line : {"(1700000000.123456) can0 028#0100000000020D7A R", "(1.5) vcan0 028#0100000000020D7A T"}) {
    const trionet::host::candump_result r = trionet::host::parse_candump_line(line);
    ASSERT_TRUE(r) << line << ": " << to_string(r.status);
    EXPECT_EQ(trionet::host::format_candump_frame(r.record.frame), "028#0100000000020D7A");
  }
  EXPECT_EQ(trionet::host::parse_candump_line("(1.5) vcan0 028#01 X").status, trionet::host::candump_status::trailing);
  EXPECT_EQ(trionet::host::parse_candump_line("028#01 R").status, trionet::host::candump_status::trailing);
}

TEST(LiveCan, NoSocketCanIsSaidPlainly) {
  const int probe = ::socket(PF_CAN, SOCK_RAW, 1);
  if (probe >= 0) {
    ::close(probe);
    trionet::test::expect_io_error("can monitor trionet-no-such-if0", "no_such_interface");
    return;
  }
  trionet::test::expect_io_error("can monitor can0", "this kernel has no SocketCAN support: use - and candump text");
}

// The three commands on a virtual CAN interface, if this machine can make one.
TEST(LiveCan, OverSocketCanOnVcan) {
  const std::string name = "trionetlive0";
  const int probe = ::socket(PF_CAN, SOCK_RAW, 1);
  if (probe < 0) {
    GTEST_SKIP() << "this kernel has no SocketCAN support (socket(PF_CAN) failed: " << std::strerror(errno)
                 << "); the candump-text variants are tested instead";
  }
  ::close(probe);
  const trionet::test::vcan_interface vcan(name);
  if (!vcan.usable()) {
    GTEST_SKIP() << "cannot create the vcan interface " << name << ": " << vcan.missing()
                 << "; the candump-text variants are tested instead";
  }
  tool_process monitor({"can", "monitor", name, "--json"});
  tool_process node({"can", "node", name, "--node", "4", "--json"});
  ::usleep(200000);  // both bound before the frame goes out
  const auto sent = run_cli("can send " + name + " --from 1 --to 4 --vr 1 --value 2.345");
  EXPECT_EQ(sent.exit_code, 0) << sent.err;
  EXPECT_EQ(sent.out, "028#0100000000020D7A\n");
  EXPECT_NE(monitor.read_lines_with("\"event\":\"vr\"", 1, patience_ms).find("\"value\":2.345"), std::string::npos);
  EXPECT_NE(node.read_lines_with("vr_write", 1, patience_ms).find("\"vr\":1,\"value\":2.345,\"status\":\"ok\""),
            std::string::npos);
  node.write("send 2 3 4\n");
  EXPECT_NE(monitor.read_lines_with("\"event\":\"vr\"", 2, patience_ms).find("\"from\":4,\"to\":2,\"vr\":3"),
            std::string::npos);
  monitor.signal(SIGINT);
  EXPECT_EQ(monitor.wait(patience_ms), 0);
  node.write("quit\n");
  EXPECT_EQ(node.wait(patience_ms), 0);
}

}  // namespace
