// How the live commands end (docs/cli.md, "Live commands: how they end"): when their commands or their link
// on standard input end (exit 0), when their link is lost or their output closes (exit 1, one message), and
// a serial port or pty held by one command is refused to a second and left as it was.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "support/live_process.hpp"
#include "support/run_cli.hpp"
#include "support/temp_files.hpp"

namespace {

using trionet::test::temp_path;
using trionet::test::pty_pair;
using trionet::test::run_cli;
using trionet::test::tool_process;

void pause_ms(int ms) {
  std::this_thread::sleep_for(std::chrono::milliseconds(ms));
}

TEST(LiveEnding, JoinAsMcEndsWhenStandardInputEndsAfterSendingWhatItQueued) {
  pty_pair pty;
  ASSERT_TRUE(pty.ok());
  tool_process mc({"ring", "join", pty.slave_path, "--as", "mc", "--json"});
  mc.write("print 11 HELLO\n");
  mc.close_input();  // no quit: the end of the commands is the end
  EXPECT_EQ(mc.wait(5000), 0) << mc.output();
  const std::vector<std::uint8_t> sent = pty.read_bytes(7, 2000);
  EXPECT_EQ(sent, (std::vector<std::uint8_t>{0x91, 'H', 'E', 'L', 'L', 'O', 0x90}));  // to BASIC 11: 2 hops
  EXPECT_NE(mc.output().find("\"event\":\"queued\""), std::string::npos) << mc.output();
  EXPECT_NE(mc.output().find("\"event\":\"counters\""), std::string::npos) << mc.output();
}

TEST(LiveEnding, JoinAsKeypadEndsWhenItsKeyWordsAreDone) {
  pty_pair pty;
  ASSERT_TRUE(pty.ok());
  tool_process keypad({"ring", "join", pty.slave_path, "--as", "keypad", "--json"});
  keypad.write("wait=200 1\n");
  keypad.close_input();
  EXPECT_EQ(keypad.wait(5000), 0) << keypad.output();
  EXPECT_NE(keypad.output().find("\"event\":\"key\""), std::string::npos) << keypad.output();
}

TEST(LiveEnding, CanNodeEndsWhenItsCommandsEnd) {
  const auto r = run_cli("can node - --node 1 --json", "send 3 7 12.25\n");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const auto frame = run_cli("can encode --from 1 --to 3 --vr 7 --value 12.25");
  ASSERT_EQ(frame.exit_code, 0);
  EXPECT_EQ(r.out.substr(r.out.find(')') + 1), " can0 " + frame.out) << r.out;
}

// The link lost: the counters, then one message naming the port, and exit 1.
TEST(LiveEnding, AMonitorWhosePtyClosesSaysSoAndExits1) {
  auto pty = std::make_unique<pty_pair>();
  ASSERT_TRUE(pty->ok());
  const std::string port = pty->slave_path;
  const std::string err = temp_path("lost.err");
  tool_process monitor({"ring", "monitor", port, "--json"}, err);
  // Closed only once the tool has the port open (a loaded machine under ASan took over 300 ms to open it, and
  // the tool then rightly said it could not open the port), then given the time to set the port up.
  ASSERT_TRUE(monitor.holds_open(port, 30000));
  pause_ms(300);
  pty.reset();
  EXPECT_EQ(monitor.wait(5000), 1);
  EXPECT_NE(monitor.output().find("\"event\":\"counters\""), std::string::npos) << monitor.output();
  EXPECT_EQ(trionet::test::slurp(err), "trionet: ring monitor: " + port + " closed\n");
  std::remove(err.c_str());
}

// The output closed (`| head -1`): the command ends with one message instead of running on.
TEST(LiveEnding, AMonitorWhoseOutputClosesEnds) {
  pty_pair pty;
  ASSERT_TRUE(pty.ok());
  const std::string err = temp_path("closed.err");
  const std::string command = std::string(TRIONET_CLI_PATH) + " ring monitor " + pty.slave_path + " --json 2>" +
                              err + " | head -c 1 >/dev/null; exit ${PIPESTATUS[0]}";
  std::thread feed([&] {
    for (int i = 0; i < 40; ++i) {
      pause_ms(50);
      pty.write_all({0x91, 'H', 'I', 0x90});
    }
  });
  const auto started = std::chrono::steady_clock::now();
  const int status = std::system(("bash -c '" + command + "'").c_str());
  feed.join();
  EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(5));
  EXPECT_EQ(WEXITSTATUS(status), 1);
  EXPECT_EQ(trionet::test::slurp(err), "trionet: cannot write standard output: Broken pipe\n");
  std::remove(err.c_str());
}

TEST(LiveEnding, ASecondCommandOnAPortInUseIsRefusedAndTheFirstGoesOn) {
  pty_pair pty;
  ASSERT_TRUE(pty.ok());
  termios before{};
  ::tcgetattr(pty.slave_keep, &before);
  tool_process first({"ring", "monitor", pty.slave_path, "--json", "--baud", "57600"});
  pause_ms(300);
  const auto second = run_cli("ring monitor " + pty.slave_path);
  EXPECT_EQ(second.exit_code, 1);
  EXPECT_EQ(second.err, "trionet: ring monitor: " + pty.slave_path +
                            " is in use: another process holds its lock (another monitor or node on it?)\n");
  const auto joined = run_cli("ring join " + pty.slave_path + " --as mc", "quit\n");
  EXPECT_EQ(joined.exit_code, 1);
  EXPECT_NE(joined.err.find("is in use"), std::string::npos) << joined.err;
  // A sender writes beside the monitor (README's examples send where a monitor listens).
  EXPECT_EQ(run_cli("ring send " + pty.slave_path + " print --to 11 A").exit_code, 0);
  // The first still has the port.
  pty.write_all({0x91, 'O', 'K', 0x90});
  first.read_lines_with("\"text\":\"OK\"", 1, 3000);
  EXPECT_NE(first.output().find("\"text\":\"OK\""), std::string::npos) << first.output();
  first.signal(SIGINT);
  EXPECT_EQ(first.wait(5000), 0);
  // Afterwards: the settings as before, not in exclusive mode, free for the next command.
  termios after{};
  ::tcgetattr(pty.slave_keep, &after);
  EXPECT_EQ(cfgetispeed(&after), cfgetispeed(&before));
  EXPECT_EQ(after.c_lflag, before.c_lflag);
  EXPECT_EQ(after.c_iflag, before.c_iflag);
  int exclusive = 1;
  ASSERT_EQ(::ioctl(pty.slave_keep, TIOCGEXCL, &exclusive), 0);
  EXPECT_EQ(exclusive, 0);
  EXPECT_EQ(run_cli("ring send " + pty.slave_path + " print --to 11 A").exit_code, 0);
}

TEST(LiveEnding, AProgramThatHoldsAPortInExclusiveModeIsRespected) {
  pty_pair pty;
  ASSERT_TRUE(pty.ok());
  ASSERT_EQ(::ioctl(pty.slave_keep, TIOCEXCL), 0);  // as a terminal program would
  const auto r = run_cli("ring monitor " + pty.slave_path);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("is in use: another program has it in exclusive mode"), std::string::npos) << r.err;
  // Regression: a user who is not root is refused by open() itself (EBUSY), and got other words
  // ("cannot open ...: Device or resource busy"). Run as root, the test runs the tool as nobody too.
  if (::geteuid() == 0 && ::access("/usr/bin/setpriv", X_OK) == 0) {
    ASSERT_EQ(::fchmod(pty.slave_keep, 0666), 0);
    const std::string err_path = "/tmp/trionet-exclusive-" + std::to_string(::getpid()) + ".err";
    const std::string command = "/usr/bin/setpriv --reuid=65534 --regid=65534 --clear-groups " +
                                std::string(TRIONET_CLI_PATH) + " ring monitor " + pty.slave_path +
                                " </dev/null >/dev/null 2>" + err_path;
    const int status = std::system(command.c_str());
    const std::string err = trionet::test::slurp(err_path);
    std::remove(err_path.c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 1) << err;
    EXPECT_NE(err.find(pty.slave_path + " is in use: another program has it in exclusive mode"), std::string::npos)
        << err;
  }
  ASSERT_EQ(::ioctl(pty.slave_keep, TIOCNXCL), 0);
}

}  // namespace
