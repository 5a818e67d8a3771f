// Hostile input to the tool: every file it reads is read with a bound before it is parsed (directories and
// devices refused, endless pipes cut), every value it echoes is cut to 40 characters and escaped, and a
// missing file names the system's cause (docs/cli.md, "Untrusted input").
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <string>
#include <thread>

#include "support/run_cli.hpp"
#include "support/temp_files.hpp"

namespace {

using trionet::test::temp_file;
using trionet::test::temp_path;
using trionet::test::cli_result;
using trionet::test::expect_io_error;
using trionet::test::expect_usage_error;
using trionet::test::run_cli;

// No byte below 0x20 other than the line ends, and no DEL: what a terminal can show as it is.
bool no_raw_control_characters(const std::string& text) {
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if ((byte < 0x20 && c != '\n') || byte == 0x7f) return false;
  }
  return true;
}

TEST(UntrustedInput, AProfileThatIsADeviceOrADirectoryIsRefusedBeforeItIsRead) {
  const auto started = std::chrono::steady_clock::now();
  expect_io_error("ring decode 00 --profile /dev/zero", "profile /dev/zero is a device, not a file");
  expect_io_error("profile show /dev/zero", "profile /dev/zero is a device, not a file");
  expect_io_error("profile show /dev/urandom", "is a device, not a file");
  expect_io_error("can table --profile /", "profile / is a directory, not a file");
  EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(10));
}

TEST(UntrustedInput, AnEndlessPipeAsAProfileIsCutAt1MiB) {
  // A FIFO whose writer never stops: the tool reads 1 MiB and a byte, then refuses it.
  const std::string fifo = temp_path("endless.fifo");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  void (*const old_handler)(int) = std::signal(SIGPIPE, SIG_IGN);  // the writer learns of the end from EPIPE
  std::thread writer([&] {
    const int fd = ::open(fifo.c_str(), O_WRONLY);
    const std::string block(65536, ' ');
    while (::write(fd, block.data(), block.size()) > 0) {
    }
    ::close(fd);
  });
  const cli_result r = run_cli("profile show " + fifo);
  writer.join();
  std::signal(SIGPIPE, old_handler);
  ::unlink(fifo.c_str());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("is larger than 1048576 bytes"), std::string::npos) << r.err;
  // The same through standard input (`--profile /dev/stdin`), a regular file of 2 MiB here.
  const cli_result piped = run_cli("profile show /dev/stdin", std::string(2U << 20U, ' '));
  EXPECT_EQ(piped.exit_code, 1) << piped.err;
  EXPECT_NE(piped.err.find("is larger than 1048576 bytes"), std::string::npos) << piped.err;
}

TEST(UntrustedInput, AProfileValueIsEchoedEscapedAndCut) {
  // A JSON "\u001b" in a value must not reach the terminal as ESC; a 900 KB value must not make a 900 KB line.
  const std::string path = temp_file(
      "escape.json", "{\"trionet_profile\": 1, \"ring\": {\"vr_group_order\": \"\\u001b[31mred\\u0007" +
                         std::string(900000, 'a') + "\"}}");
  const cli_result r = run_cli("profile show " + path);
  std::remove(path.c_str());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(no_raw_control_characters(r.err)) << r.err;
  EXPECT_NE(r.err.find("got \"\\x1b[31mred\\x07" + std::string(31, 'a') + "...\""), std::string::npos) << r.err;
  EXPECT_LT(r.err.size(), 400U) << r.err;
}

TEST(UntrustedInput, AProfileKeyIsEchoedEscaped) {
  const std::string path = temp_file("key.json", "{\"trionet_profile\": 1, \"ring\": {\"\\u009b2J\\u0000\": 1}}");
  const cli_result r = run_cli("profile show " + path);
  std::remove(path.c_str());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("unknown_key at ring.\\xc2\\x9b2J\\x00"), std::string::npos) << r.err;
  EXPECT_TRUE(no_raw_control_characters(r.err)) << r.err;
}

TEST(UntrustedInput, ArgumentsAreEchoedEscapedAndCut) {
  const std::string hostile = "'\x1b[2J\x07" + std::string(100, 'z') + "'";
  for (const std::string& args : {"ring decode --bogus" + hostile, "can encode --from " + hostile + " --to 2 --vr 1 --value 1",
                                   "genius timing --rate " + hostile, "ring nosuch" + hostile, "nosuchpart" + hostile,
                                   "can table extra" + hostile, "genius scan-time --rate 153.6s --device " + hostile}) {
    const cli_result r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_TRUE(no_raw_control_characters(r.err)) << args << ": " << r.err;
    EXPECT_NE(r.err.find("\\x1b[2J\\x07"), std::string::npos) << args << ": " << r.err;
    EXPECT_LT(r.err.size(), 300U) << args << ": " << r.err;
  }
}

TEST(UntrustedInput, AMissingFileNamesTheSystemsCause) {
  const std::string cause = "No such file or directory";
  expect_io_error("ring decode --pcap /nonexistent/x.pcapng", "cannot open capture /nonexistent/x.pcapng: " + cause);
  expect_io_error("can decode --pcap /nonexistent/x.pcapng", cause);
  expect_io_error("genius decode --pcap /nonexistent/x.pcapng", cause);
  expect_io_error("ring learn crc /nonexistent/frames.hex", "cannot open /nonexistent/frames.hex: " + cause);
  expect_io_error("ring learn layout --sent /nonexistent/sent.txt", "cannot open /nonexistent/sent.txt: " + cause);
  expect_io_error("genius learn crc /nonexistent/tokens.txt", cause);
  expect_io_error("profile show /nonexistent/p.json", "cannot open profile /nonexistent/p.json: " + cause);
  expect_io_error("can table --profile /nonexistent/p.json", "cannot open profile /nonexistent/p.json: " + cause);
  expect_io_error("ring monitor /nonexistent/ttyX", "cannot open /nonexistent/ttyX: " + cause);
  expect_io_error("ring send /nonexistent/ttyX print --to 11 A", cause);
  expect_io_error("ring join /nonexistent/ttyX --as keypad", cause);
  expect_io_error("profile header -o /nonexistent/dir/h.hpp", "cannot write header /nonexistent/dir/h.hpp: " + cause);
  expect_io_error("ring decode --pcap /dev/zero", "capture /dev/zero is a device, not a file");
  expect_io_error("ring learn crc --raw /", "/ is a directory, not a file");
}

TEST(UntrustedInput, AFileNameInAMessageIsEscaped) {
  const cli_result r = run_cli("profile show \"$(printf '/nonexistent/\\033[2J')\"");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("/nonexistent/\\x1b[2J: No such file"), std::string::npos) << r.err;
  EXPECT_TRUE(no_raw_control_characters(r.err)) << r.err;
}

TEST(UntrustedInput, LearningInputIsBoundedEvenFromAnEndlessDevice) {
  // Standard input may be a terminal, so a device is read there, but never more than 64 MiB of it.
  expect_io_error("ring learn crc --raw < /dev/zero", "standard input is larger than 67108864 bytes (64 MiB)");
  expect_io_error("genius learn crc --raw < /dev/zero", "standard input is larger than 67108864 bytes");
}

TEST(UntrustedInput, DecoderTextIsShownEscapedInJson) {
  const cli_result r = run_cli("ring decode", "89 1b 5b 32 4a 07 00 88\n");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out, "{\"event\":\"message\",\"line\":1,\"type\":\"char\",\"hops\":1,\"text\":\"\\u001b[2J\\u0007\\u0000\"}\n");
}

}  // namespace
