// Progress of long work (docs/cli.md, "Progress"): a line on standard error redrawn in place when standard
// error is a terminal, nothing at all otherwise.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "support/live_process.hpp"
#include "support/run_cli.hpp"

namespace {

using trionet::test::pty_pair;
using trionet::test::run_cli;
using trionet::test::tool_process;

// Direct variable transfers as hex lines, to feed `ring learn crc` slowly.
std::vector<std::string> frames() {
  std::vector<std::string> lines;
  for (int i = 0; i < 12; ++i) {
    lines.push_back(run_cli("ring encode var --to 10 --vr " + std::to_string(7 + 31 * i) + " --value " +
                            std::to_string(i * 13 - 40) + ".25")
                        .out);
  }
  return lines;
}

TEST(Progress, LearningShowsWhatItHasReadOnATerminal) {
  pty_pair terminal;
  ASSERT_TRUE(terminal.ok());
  tool_process learn({"ring", "learn", "crc"}, terminal.slave_path);  // standard error: the terminal
  for (const std::string& line : frames()) {
    learn.write(line);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));  // a slow source: 1.2 s in all
  }
  learn.close_input();
  EXPECT_EQ(learn.wait(5000), 0) << learn.output();
  const std::vector<std::uint8_t> bytes = terminal.read_until([](const std::vector<std::uint8_t>&) { return false; }, 500);
  const std::string shown(bytes.begin(), bytes.end());
  EXPECT_NE(shown.find("\rring learn crc: "), std::string::npos) << shown;
  EXPECT_NE(shown.find(" bytes read, "), std::string::npos) << shown;
  EXPECT_NE(shown.find(" elapsed"), std::string::npos) << shown;
  EXPECT_EQ(shown.substr(shown.size() - 4), "\r\x1b[K") << "the line is cleared at the end: " << shown;
  EXPECT_NE(learn.output().find("\"status\":\"ok\""), std::string::npos) << learn.output();
}

TEST(Progress, NothingWhenStandardErrorIsNotATerminal) {
  const std::string err_path = ::testing::TempDir() + "trionet-progress-" + std::to_string(::getpid()) + ".err";
  tool_process learn({"ring", "learn", "crc"}, err_path);  // standard error: a file
  for (const std::string& line : frames()) {
    learn.write(line);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  learn.close_input();
  EXPECT_EQ(learn.wait(5000), 0);
  EXPECT_EQ(trionet::test::slurp(err_path), "");
  std::remove(err_path.c_str());
}

}  // namespace
