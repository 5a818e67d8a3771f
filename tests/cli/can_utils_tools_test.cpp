// `trionet can decode` on lines written by can-utils' own tools (Debian package can-utils): log2long (the
// screen format with timestamps and the ASCII column), log2asc then asc2log (log lines with the direction),
// and canplayer's input checked by can-utils' own parser (log2long reads every line with parse_canframe and
// stops at the first it rejects). Skipped, saying so, where can-utils is not installed.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support/run_cli.hpp"

namespace {

using trionet::test::run_cli;
using trionet::test::slurp;

bool have(const char* tool) {
  return std::system((std::string("command -v ") + tool + " >/dev/null 2>&1").c_str()) == 0;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.find_first_not_of(" \t\r") != std::string::npos) lines.push_back(line);
  }
  return lines;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// The VR part of every vr event ("id" to the end), in order.
std::vector<std::string> vr_payloads(const std::string& events) {
  std::vector<std::string> out;
  for (const std::string& line : lines_of(events)) {
    if (line.rfind("{\"event\":\"vr\"", 0) == 0) out.push_back(line.substr(line.find("\"id\":")));
  }
  return out;
}

class CanUtilsTools : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const char* tool : {"log2long", "log2asc", "asc2log"}) {
      if (!have(tool)) GTEST_SKIP() << tool << " is not installed (Debian: apt-get install can-utils)";
    }
    dir_ = "/tmp/trionet-can-utils-" + std::to_string(::getpid());
    ASSERT_EQ(std::system(("mkdir -p " + dir_).c_str()), 0);
    // Our own log: every pair of a 5-node exchange, then one frame of every other kind.
    std::ofstream log(dir_ + "/in.log");
    unsigned long long micros = 123456;
    for (int from = 1; from <= 5; ++from) {
      for (int to = 1; to <= 5; ++to) {
        if (from == to) continue;
        const auto frame = run_cli("can encode --from " + std::to_string(from) + " --to " + std::to_string(to) +
                                   " --vr " + std::to_string(from * 10 + to) + " --value -" +
                                   std::to_string(from) + "." + std::to_string(to));
        ASSERT_EQ(frame.exit_code, 0);
        log << "(1700000000." << micros++ << ") can" << (from % 2) << " " << frame.out;
      }
    }
    log << "(1700000001.000000) can0 123#R\n"
           "(1700000001.000001) can0 12345678#1122\n"
           "(1700000001.000002) can0 20000080#0000000000000000\n"
           "(1700000001.000003) can0 123##1AABBCC\n"
           "(1700000001.000004) can1 7FF#\n"
           "(1700000001.000005) can1 03C#0100000000000000\n";
  }
  void TearDown() override {
    if (!dir_.empty()) (void)std::system(("rm -rf " + dir_).c_str());
  }

  // Runs a shell command; its standard output.
  std::string shell(const std::string& command) {
    const std::string out = dir_ + "/out";
    EXPECT_EQ(std::system((command + " >" + out + " 2>/dev/null").c_str()), 0) << command;
    return slurp(out);
  }

  std::string dir_;
};

TEST_F(CanUtilsTools, EveryLineTheToolsWriteIsReadAndEveryVrFrameDecoded) {
  const std::string original = slurp(dir_ + "/in.log");
  const std::string screen = shell("log2long <" + dir_ + "/in.log");
  shell("log2asc -I " + dir_ + "/in.log -O " + dir_ + "/in.asc can0 can1");
  const std::string directed = shell("asc2log -I " + dir_ + "/in.asc");
  ASSERT_EQ(lines_of(screen).size(), lines_of(original).size());
  ASSERT_EQ(lines_of(directed).size(), lines_of(original).size());
  EXPECT_GT(count(directed, " R\n"), 20u) << "asc2log writes the direction after the frame:\n" << directed;

  // can-utils' own parser accepts every line asc2log wrote (log2long stops with an error at the first it
  // does not), so each must be read here too.
  std::ofstream(dir_ + "/directed.log") << directed;
  shell("log2long <" + dir_ + "/directed.log");

  const auto from_original = run_cli("can decode", original);
  for (const std::string* text : {&screen, &directed}) {
    const auto decoded = run_cli("can decode", *text);
    EXPECT_EQ(decoded.exit_code, 0);
    EXPECT_EQ(count(decoded.out, "\"reason\":\"syntax\""), 0u) << *text << decoded.out;
    EXPECT_EQ(lines_of(decoded.out).size(), lines_of(*text).size()) << "one event per line";
    EXPECT_EQ(vr_payloads(decoded.out), vr_payloads(from_original.out));
    EXPECT_EQ(vr_payloads(decoded.out).size(), 20u);
    for (const char* kind : {"remote", "extended", "error_frame", "fd", "foreign_id"}) {
      EXPECT_EQ(count(decoded.out, std::string("\"kind\":\"") + kind + "\""), kind == std::string("foreign_id") ? 2u : 1u)
          << kind << "\n" << decoded.out;
    }
  }
}

// python-can's log writer writes an error frame of a CAN FD channel as "20000080##0"; log2long prints it as
// an error frame with a CAN FD length ("[00] ... ERRORFRAME"). Both lines are one error frame.
TEST_F(CanUtilsTools, ErrorFlagInCanFdFrameIsAnErrorFrameInBothForms) {
  std::ofstream(dir_ + "/fd_error.log") << "(30.806898) can4 20000080##0\n";
  const std::string screen = shell("log2long <" + dir_ + "/fd_error.log");
  ASSERT_NE(screen.find("ERRORFRAME"), std::string::npos) << screen;
  for (const std::string& text : {slurp(dir_ + "/fd_error.log"), screen}) {
    const auto decoded = run_cli("can decode", text);
    EXPECT_EQ(decoded.exit_code, 0);
    EXPECT_NE(decoded.out.find("\"kind\":\"error_frame\",\"id\":128,\"length\":0"), std::string::npos)
        << text << decoded.out;
  }
}

}  // namespace
