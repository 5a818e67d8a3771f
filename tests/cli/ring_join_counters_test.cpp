// `ring join --as keypad` gives the keypad's own counters (keys, frame and CRC errors, forwarding losses,
// NETSTAT) on SIGUSR1 as at the end, not only its link's: scripts/lab reads them every 10 ms while it puts
// faults on the wire, to see when the keypad counted a loss.
#include <gtest/gtest.h>

#include <signal.h>

#include <string>

#include "support/live_process.hpp"

namespace {

using trionet::test::pty_pair;
using trionet::test::tool_process;

constexpr int patience_ms = 20000;  // waiting for a process on a loaded machine; never a speed measure

TEST(RingJoinCounters, TheKeypadGivesItsOwnCountersOnSigusr1) {
  pty_pair pty;
  ASSERT_TRUE(pty.ok());
  tool_process keypad({"ring", "join", pty.slave_path, "--as", "keypad", "--json"});
  keypad.read_lines_with("\"event\":\"display\"", 1, patience_ms);  // it runs
  pty.write_all({0x8b, 0x01, 0x88, 0x89, 0x41});                   // its keypad offset, then a message cut short
  keypad.read_lines_with("\"reason\":\"idle_line\"", 1, patience_ms);
  keypad.signal(SIGUSR1);
  const std::string& out = keypad.read_lines_with("\"event\":\"counters\"", 1, patience_ms);
  const std::string counters = out.substr(out.find("{\"event\":\"counters\""));
  for (const char* field : {"\"network\":true", "\"keys_sent\":0", "\"frame_errors\":1", "\"crc_errors\":0",
                            "\"netstat\":8", "\"forwards_lost\":0", "\"forwards_cut\":0", "\"forwards_ended_idle\":0",
                            "\"dropped_in_local_mode\":0", "\"in_bytes\":5"}) {
    EXPECT_NE(counters.find(field), std::string::npos) << field << " in " << counters;
  }
  keypad.write("quit\n");
  EXPECT_EQ(keypad.wait(patience_ms), 0);
}

}  // namespace
