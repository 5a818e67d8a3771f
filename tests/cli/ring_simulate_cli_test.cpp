// `trionet ring simulate`: the built-in networks (the manual's programs and the ordering example), a user's own
// programs from files, the JSON summary, and the usage errors.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "support/run_cli.hpp"

using trionet::test::expect_usage_error;
using trionet::test::run_cli;

namespace {

// A file in /tmp that goes away with the test.
class temporary_file {
 public:
  temporary_file(const std::string& name, const std::string& text)
      : path_("/tmp/trionet-simulate-" + std::to_string(::getpid()) + "-" + name) {
    std::ofstream(path_, std::ios::binary) << text;
  }
  ~temporary_file() { std::remove(path_.c_str()); }
  temporary_file(const temporary_file&) = delete;
  temporary_file& operator=(const temporary_file&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

std::string last_line(const std::string& out) {
  const std::size_t end = out.find_last_not_of('\n');
  if (end == std::string::npos) return "";
  const std::size_t start = out.rfind('\n', end);
  return out.substr(start == std::string::npos ? 0 : start + 1, end + 1 - (start == std::string::npos ? 0 : start + 1));
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST(RingSimulateCli, Example1ShowsSpeedAndLengthOnBothDisplays) {
  const auto r = run_cli("ring simulate example1");  // run from the build tree: the programs are built in
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const std::string box =
      "        +--------------------+\n"
      "        |SPEED:    125       |\n"
      "        |LENGTH:      0.2    |\n"
      "        +--------------------+\n";
  EXPECT_TRUE(has(r.out, "node 2  keypad 1: network mode, keys go 2 hops along (BASIC 11)\n" + box)) << r.out;
  EXPECT_TRUE(has(r.out, "node 3  keypad 2: network mode, keys go 1 hop along (BASIC 10)\n" + box)) << r.out;
  EXPECT_TRUE(has(r.out, "node 1  mc examples/manual/example1.bas: running at line ")) << r.out;
  EXPECT_TRUE(has(r.out, "        VR: VR(2)=0.2\n")) << r.out;  // 0.1 + 0.1 + 0.1 - 0.1, printed as BASIC does
  EXPECT_TRUE(has(r.out, "        variables: length=2 k=11 a=125\n")) << r.out;
}

TEST(RingSimulateCli, Example2RunsTheHandshake) {
  const auto r = run_cli("ring simulate example2 --trace");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(has(r.out, "node 1  1 -> 2  hops 1  PRINT \"I\"\n")) << r.out;
  EXPECT_TRUE(has(r.out, "node 1  VR(200) is now 99 (from the ring)\n")) << r.out;
  EXPECT_TRUE(has(r.out, "node 2  VR(0) is now 0.3 (from the ring)\n")) << r.out;
  EXPECT_TRUE(has(r.out, "node 1  VR(200) is now 999 (from the ring)\n")) << r.out;
  EXPECT_TRUE(has(r.out, "|PRESS START TO RUN  |")) << r.out;
  EXPECT_TRUE(has(r.out, "node 1  mc examples/manual/example2_three_axis.bas: ended at line ")) << r.out;
  EXPECT_TRUE(has(r.out, "        axis 0: DPOS 0 MPOS 0, idle SPEED=0.02\n")) << r.out;
  EXPECT_FALSE(has(r.out, "NETSTAT 1")) << r.out;
}

TEST(RingSimulateCli, Example3ShowsWhatWasDroppedWhereAndWhy) {
  const auto broken = run_cli("ring simulate example3");
  EXPECT_EQ(broken.exit_code, 0) << broken.err;
  EXPECT_TRUE(has(broken.out, "node 3  dropped PRINT \"\\x1bH\\x14FEEDER READY\" from node 2, sent to this keypad: "
                              "the keypad is in local mode"))
      << broken.out;
  EXPECT_TRUE(has(broken.out, "node 3  dropped PRINT \"R\" from node 2, passing through to node 1: the keypad is in "
                              "local mode"))
      << broken.out;
  EXPECT_TRUE(has(broken.out, "node 1  mc examples/keypad_order/master.bas: waiting at line 7 (GET #)\n"))
      << broken.out;
  EXPECT_TRUE(has(broken.out, "        dropped in local mode: 2 message(s); keys lost: 0\n")) << broken.out;

  const auto fixed = run_cli("ring simulate example3-fixed");
  EXPECT_EQ(fixed.exit_code, 0) << fixed.err;
  EXPECT_FALSE(has(fixed.out, "dropped")) << fixed.out;
  EXPECT_TRUE(has(fixed.out, "|MASTER READY  RUN   |\n        |FEEDER READY        |\n")) << fixed.out;
  EXPECT_TRUE(has(fixed.out, "node 1  mc examples/keypad_order/master_fixed.bas: ended at line 9\n")) << fixed.out;
}

TEST(RingSimulateCli, JsonSummaryIsTheLastLine) {
  const auto r = run_cli("ring simulate example2 --json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find('\n'), r.out.size() - 1) << "only the JSON line without --trace: " << r.out;
  const std::string json = last_line(r.out);
  EXPECT_EQ(json.rfind("{\"byte_times\":", 0), 0u) << json;
  EXPECT_TRUE(has(json, ",\"end\":\"settled\",\"nodes\":[{\"node\":1,\"kind\":\"mc\","
                        "\"program\":\"examples/manual/example2_three_axis.bas\",\"state\":\"ended\",\"ended\":true,"
                        "\"line\":40,\"error\":null,\"netstat\":0,\"wdog\":false,\"vr\":{\"0\":0.3,\"1\":0.02,\"100\":20,\"200\":999},"
                        "\"table\":{},\"variables\":{},\"inputs_on\":[],\"outputs_on\":[],\"axes\":[]}"))
      << json;
  EXPECT_TRUE(has(json, "{\"node\":3,\"kind\":\"keypad\",\"keypad\":1,\"network_mode\":true,\"offset\":1,"
                        "\"display\":[\"PRESS START TO RUN  \",\"                    \"],\"dropped\":0,"
                        "\"keys_lost\":0}]}"))
      << json;
  EXPECT_TRUE(has(json, "\"axes\":[{\"axis\":0,\"dpos\":0,\"mpos\":0,\"idle\":true,\"mtype\":0,"
                        "\"vp_speed\":0,\"parameters\":{\"SPEED\":0.02}}]")) << json;

  const auto traced = run_cli("ring simulate example1 --json --trace");
  EXPECT_TRUE(has(traced.out, "hops 1  keypad offset 2")) << traced.out;
  EXPECT_TRUE(has(last_line(traced.out),
                  "\"variables\":{\"length\":2,\"k\":11,\"a\":125}"))
      << traced.out;
}

TEST(RingSimulateCli, AUsersOwnTwoControllerProgramsFromFiles) {
  const temporary_file counter("counter.bas",
                               "' counts to 3 and hands each count to the other controller\n"
                               "FOR i=1 TO 3\n"
                               "  SEND(10,1,20,i)\n"
                               "  WAIT UNTIL VR(21)=i   ' the other side's acknowledgement\n"
                               "NEXT i\n");
  const temporary_file echo("echo.bas",
                            "REPEAT\n"
                            "  WAIT UNTIL VR(20)<>VR(21)\n"
                            "  SEND(10,1,21,VR(20))\n"
                            "  VR(21)=VR(20)\n"
                            "UNTIL VR(20)=3\n");
  const auto r = run_cli("ring simulate --node mc:" + counter.path() + " --node mc:" + echo.path() + " --json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const std::string json = last_line(r.out);
  EXPECT_TRUE(has(json, "\"end\":\"settled\"")) << json;
  EXPECT_TRUE(has(json, "\"state\":\"ended\",\"ended\":true,\"line\":5,\"error\":null,\"netstat\":0,"
                        "\"wdog\":false,\"vr\":{\"21\":3},\"table\":{},\"variables\":{\"i\":4}"))
      << json;
  EXPECT_TRUE(has(json, "\"vr\":{\"20\":3,\"21\":3}")) << json;
}

// With a profile, the simulated nodes send and check direct variable transfers with its CRC and layout: the
// programs' handshake completes, the trace shows the transfers, and the capture decodes with the profile and
// is all CRC errors without it.
TEST(RingSimulateCli, TheNodesUseTheProfilesCrcAndLayout) {
  const temporary_file counter("counter.bas", "FOR i=1 TO 3\n  SEND(10,1,20,i)\n  WAIT UNTIL VR(21)=i\nNEXT i\n");
  const temporary_file echo("echo.bas",
                            "REPEAT\n  WAIT UNTIL VR(20)<>VR(21)\n  SEND(10,1,21,VR(20))\n  VR(21)=VR(20)\n"
                            "UNTIL VR(20)=3\n");
  const temporary_file profile(
      "modbus.json",
      "{\"trionet_profile\": 1, \"ring\": {\"crc\": {\"polynomial\": \"0x8005\", \"initial\": \"0xffff\", "
      "\"reflect_in\": true, \"reflect_out\": true, \"xor_out\": \"0x0000\"}, "
      "\"vr_group_order\": \"most_significant_first\", \"value_group_order\": \"most_significant_first\"}}\n");
  const temporary_file capture("profile.pcapng", "");
  const std::string nodes = " --node mc:" + counter.path() + " --node mc:" + echo.path();
  const auto r = run_cli("ring simulate --profile " + profile.path() + nodes + " --trace --json --pcap " +
                         capture.path());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(has(last_line(r.out), "\"end\":\"settled\"")) << r.out;
  EXPECT_TRUE(has(last_line(r.out), "\"vr\":{\"20\":3,\"21\":3}")) << r.out;
  EXPECT_TRUE(has(r.out, "VR(20) = 3")) << r.out;
  EXPECT_FALSE(has(r.out, "CRC error")) << r.out;
  const auto with_profile = run_cli("ring decode --profile " + profile.path() + " --pcap " + capture.path());
  EXPECT_EQ(with_profile.exit_code, 0) << with_profile.err;
  EXPECT_TRUE(has(with_profile.out, "\"type\":\"var\",\"hops\":1,\"vr\":21,\"raw\":\"0x0000000300000000\"")) << with_profile.out;
  EXPECT_FALSE(has(with_profile.out, "crc_error")) << with_profile.out;
  const auto by_default = run_cli("ring decode --pcap " + capture.path());
  EXPECT_TRUE(has(by_default.out, "{\"event\":\"crc_error\",\"record\":1,")) << by_default.out;
  EXPECT_FALSE(has(by_default.out, "\"type\":\"var\"")) << by_default.out;
  // And the same run without the profile: the default CRC, which the profile's decoder refuses.
  ASSERT_EQ(run_cli("ring simulate" + nodes + " --pcap " + capture.path()).exit_code, 0);
  EXPECT_FALSE(has(run_cli("ring decode --pcap " + capture.path()).out, "crc_error"));
  EXPECT_TRUE(has(run_cli("ring decode --profile " + profile.path() + " --pcap " + capture.path()).out, "crc_error"));
}

// The simulated keypads send the profile's keypad codes.
TEST(RingSimulateCli, TheKeypadsSendTheProfilesCodes) {
  const temporary_file program("key.bas", "SEND(10,2,10)\nGET #4,c\nVR(1)=c\n");
  const temporary_file profile("codes.json", "{\"trionet_profile\": 1, \"keypad\": {\"codes\": {\"up\": \"u\"}}}\n");
  const std::string run = " --node mc:" + program.path() + " --node keypad --keys \"wait=2000 1:up\" --json";
  EXPECT_TRUE(has(last_line(run_cli("ring simulate --profile " + profile.path() + run).out), "\"vr\":{\"1\":117}"));
  EXPECT_TRUE(has(last_line(run_cli("ring simulate" + run).out), "\"vr\":{\"1\":85}"));
}

TEST(RingSimulateCli, RunsAreDeterministic) {
  const auto first = run_cli("ring simulate example2 --trace --json");
  const auto second = run_cli("ring simulate example2 --trace --json");
  EXPECT_EQ(first.exit_code, 0);
  EXPECT_GT(first.out.size(), 5000u);
  EXPECT_EQ(first.out, second.out);
}

TEST(RingSimulateCli, ARuntimeErrorExitsWithOne) {
  const temporary_file bad("bad.bas", "x=1\nGOSUB sub\nSTOP\nsub: y=VR(5000)\nRETURN\n");
  const auto r = run_cli("ring simulate --node mc:" + bad.path() + " --node keypad --json");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(has(last_line(r.out), "\"state\":\"failed\",\"ended\":true,\"line\":4,"
                                    "\"error\":\"VR(5000): bad address (this controller has VR(0) to VR(1023))\""))
      << r.out;
}

TEST(RingSimulateCli, OptionsSetTheClock) {
  const temporary_file wait("wait.bas", "WA(100)\n");
  const auto r = run_cli("ring simulate --node mc:" + wait.path() +
                         " --node mc --bit-rate 12500 --statements-per-byte-time 3 --key-gap 5 --json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  // 100 ms at 12.5 kbit/s and 10 bits per byte: 125 byte-times, then the program ends and the ring settles.
  EXPECT_EQ(last_line(r.out).rfind("{\"byte_times\":127,\"seconds\":0.1016,", 0), 0u) << r.out;
  const auto limited = run_cli("ring simulate --node mc:" + wait.path() + " --node mc --byte-times 50 --json");
  EXPECT_EQ(last_line(limited.out).rfind("{\"byte_times\":50,\"seconds\":0.004,\"end\":\"limit\"", 0), 0u)
      << limited.out;
}

TEST(RingSimulateCli, ARunTheByteTimeLimitCutsShortSaysSoAndExitsFourWhenAskedTo) {
  const temporary_file wait("wait.bas", "WA(100)\n");
  const std::string said = "trionet: ring simulate: stopped after --byte-times 50: the run had not settled\n";
  const auto limited = run_cli("ring simulate --node mc:" + wait.path() + " --node mc --byte-times 50 --json");
  EXPECT_EQ(limited.exit_code, 0);
  EXPECT_EQ(limited.err, said);
  const auto failing = run_cli("ring simulate --node mc:" + wait.path() + " --node mc --byte-times 50 --json --fail-on-limit");
  EXPECT_EQ(failing.exit_code, 4);
  EXPECT_EQ(failing.err, said);
  EXPECT_EQ(last_line(failing.out), last_line(limited.out));
  // A run that settles before the limit reaches no limit.
  const auto settled = run_cli("ring simulate --node mc:" + wait.path() + " --node mc --fail-on-limit --json");
  EXPECT_EQ(settled.exit_code, 0) << settled.err;
  EXPECT_EQ(settled.err, "");
}

TEST(RingSimulateCli, CompileErrorsNameTheFileLineAndColumn) {
  const temporary_file bad("syntax.bas", "x=1\nIF x=1 GOTO done\ndone:\n");
  const auto r = run_cli("ring simulate --node mc:" + bad.path() + " --node keypad");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, "trionet: " + bad.path() + ":2:8: expected THEN after the IF condition, found the program structure word GOTO\n");
}

TEST(RingSimulateCli, UsageErrors) {
  expect_usage_error("ring simulate", "needs a built-in network");
  expect_usage_error("ring simulate example9", "unknown network 'example9'");
  expect_usage_error("ring simulate example1 example2", "one built-in network");
  expect_usage_error("ring simulate example1 --node keypad", "--node cannot be used with a built-in network");
  expect_usage_error("ring simulate --node mc", "a ring has 2 to 15 nodes, not 1");
  expect_usage_error("ring simulate --node keypad --node keypad", "at least one Motion Coordinator");
  expect_usage_error("ring simulate --node router --node mc", "--node takes mc:FILE, mc or keypad, not 'router'");
  expect_usage_error("ring simulate example1 --keys 3:up", "there is no keypad 3");
  expect_usage_error("ring simulate example1 --byte-times 0", "--byte-times");
  expect_usage_error("ring simulate example1 --bit-rate 0", "--bit-rate");
  expect_usage_error("ring simulate example1 --statements-per-byte-time x", "--statements-per-byte-time");
  expect_usage_error("ring simulate example1 --colour red", "unknown option --colour");
}

TEST(RingSimulateCli, MessagesNameTheLimitOrTheCause) {
  expect_usage_error("ring simulate example1 --key-gap 1000000001",
                     "--key-gap must be a whole number of byte-times 0..10^9, got '1000000001'");
  expect_usage_error("ring simulate example1 --keys wait=1000000000001",
                     "wait=N takes a whole number of byte-times 0..10^12");
  // Node and keypad 16 are as absent as node 15: the same message, not a syntax error.
  expect_usage_error("ring simulate example1 --keys node15:in3=on", "node 15 is not a Motion Coordinator of this ring");
  expect_usage_error("ring simulate example1 --keys node16:in3=on", "node 16 is not a Motion Coordinator of this ring");
  expect_usage_error("ring simulate example1 --keys 16:7", "there is no keypad 16");
  expect_usage_error("ring simulate example1 --keys 15:7", "there is no keypad 15");
  const auto full = run_cli("ring simulate example1 --pcap /dev/full");
  EXPECT_EQ(full.exit_code, 1);
  EXPECT_EQ(full.err, "trionet: cannot write /dev/full: No space left on device\n");
}

TEST(RingSimulateCli, HelpDescribesTheOptions) {
  const auto r = run_cli("ring simulate --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_TRUE(has(r.out, "--node mc:FILE.bas|mc|keypad")) << r.out;
  EXPECT_TRUE(has(r.out, "--keys SCRIPT")) << r.out;
}

// ---- hostile input, closed output, progress ----

namespace {

// Runs `trionet <args>` with standard output to `stdout_to` (a shell redirection target); the exit status and
// standard error.
trionet::test::cli_result run_with_stdout(const std::string& args, const std::string& stdout_to) {
  const std::string err_path = "/tmp/trionet-simulate-" + std::to_string(::getpid()) + ".err";
  const std::string command = std::string(TRIONET_CLI_PATH) + " " + args + " </dev/null >" + stdout_to + " 2>" + err_path;
  const int status = std::system(command.c_str());
  trionet::test::cli_result r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.err = trionet::test::slurp(err_path);
  std::remove(err_path.c_str());
  return r;
}

}  // namespace

TEST(RingSimulateCli, AnOutputThatCannotBeWrittenExits1WithOneMessage) {
  for (const char* args : {"ring simulate example1", "ring simulate example2 --json", "ring simulate example3 --trace"}) {
    const auto r = run_with_stdout(args, "/dev/full");
    EXPECT_EQ(r.exit_code, 1) << args;
    EXPECT_EQ(r.err, "trionet: cannot write standard output: No space left on device\n") << args;
  }
}

TEST(RingSimulateCli, AProgramThatIsADirectoryADeviceOrMissingIsRefusedWithTheCause) {
  const auto directory = run_cli("ring simulate --node mc:. --node mc");
  EXPECT_EQ(directory.exit_code, 1);
  EXPECT_EQ(directory.out, "");
  EXPECT_EQ(directory.err, "trionet: program . is a directory, not a file\n");
  const auto device = run_cli("ring simulate --node mc:/dev/zero --node mc");  // read without bound before
  EXPECT_EQ(device.exit_code, 1);
  EXPECT_EQ(device.err, "trionet: program /dev/zero is a device, not a file\n");
  const auto missing = run_cli("ring simulate --node mc:/no/such/program.bas --node mc");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_EQ(missing.err, "trionet: cannot open program /no/such/program.bas: No such file or directory\n");
}

TEST(RingSimulateCli, ACompileErrorEchoesAtMost40CharactersOfTheProgram) {
  const temporary_file huge("huge.bas", std::string(1000000, 'a') + " 5\n");
  const auto r = run_cli("ring simulate --node mc:" + huge.path() + " --node mc");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "trionet: " + huge.path() + ":1:1000002: expected '=' after '" + std::string(40, 'a') +
                       "...', found the number 5 (it is not a Trio BASIC command: docs/basic.md lists the words)\n");
  const temporary_file control("control.bas", "x=1 \x1b[31m\n");
  const auto escaped = run_cli("ring simulate --node mc:" + control.path() + " --node mc");
  EXPECT_EQ(escaped.exit_code, 2);
  EXPECT_EQ(escaped.err, "trionet: " + control.path() + ":1:5: unexpected character byte 0x1b\n");
}

TEST(RingSimulateCli, PrintToTheTerminalShowsEveryCharacterEscaped) {
  const temporary_file program("nul.bas", "PRINT \"A\";CHR(0);\"B\";CHR(27);\"[31m\";CHR(7);\"C\\\"\n");
  const auto r = run_cli("ring simulate --node mc:" + program.path() + " --node mc");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(has(r.out, "node 1  prints: A\\x00B\\x1b[31m\\x07C\\\\\n")) << r.out;  // nothing lost after NUL
  EXPECT_EQ(r.out.find('\x1b'), std::string::npos);
  EXPECT_EQ(r.out.find('\x07'), std::string::npos);
}

TEST(RingSimulateCli, ALongRunIsSilentOnStderrWhenItIsNotATerminal) {
  const temporary_file program("busy.bas", "loop: n=n+1: GOTO loop\n");
  const auto r = run_cli("ring simulate --node mc:" + program.path() + " --node mc --byte-times 800000 --json");
  EXPECT_EQ(r.exit_code, 0);
  // The progress line is for terminals only: standard error has nothing but the limit reached.
  EXPECT_EQ(r.err, "trionet: ring simulate: stopped after --byte-times 800000: the run had not settled\n");
  EXPECT_TRUE(has(r.out, "\"end\":\"limit\"")) << r.out;
}

TEST(RingSimulateCli, TheServoPeriodIsAnOptionAndClocksTicksAndWa) {
  const temporary_file program("servo.bas", "t=TICKS\nWA(10)\nPRINT SERVO_PERIOD;\" \";t-TICKS\n");
  const auto r = run_cli("ring simulate --node mc:" + program.path() + " --node mc --servo-period 500");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(has(r.out, "prints: 500.0000 20.0000\n")) << r.out;  // 10 ms are 20 ticks of 500 us
  EXPECT_TRUE(has(r.out, "per program; servo period 500 us\n")) << r.out;
  expect_usage_error("ring simulate example1 --servo-period 0", "--servo-period");
  expect_usage_error("ring simulate example1 --servo-period \x1b", "\\x1b");
}

TEST(RingSimulateCli, InputsComeFromTheScriptAndOutputsAndMovesAreShown) {
  const temporary_file program("io.bas",
                               "WDOG=ON\n"
                               "WAIT UNTIL IN(3)=ON\n"
                               "OP(8,ON)\n"
                               "MOVE(10)\n"
                               "WAIT IDLE\n"
                               "PRINT MPOS\n");
  const auto r = run_cli("ring simulate --node mc:" + program.path() + " --node mc --keys \"wait=100 node1:in3=on\" --trace");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(has(r.out, "node 1  WDOG ON\n")) << r.out;
  EXPECT_TRUE(has(r.out, "node 1  input 3 on\n")) << r.out;
  EXPECT_TRUE(has(r.out, "node 1  OP(8,ON)\n")) << r.out;
  EXPECT_TRUE(has(r.out, "node 1  axis 0: MOVE(10) starts at DPOS 0\n")) << r.out;
  EXPECT_TRUE(has(r.out, "node 1  axis 0: MOVE(10) ends at DPOS 10\n")) << r.out;
  EXPECT_TRUE(has(r.out, "prints: 10.0000\n")) << r.out;
  EXPECT_TRUE(has(r.out, "        outputs on: 8\n")) << r.out;
  EXPECT_TRUE(has(r.out, "        axis 0: DPOS 10 MPOS 10, idle\n")) << r.out;
  expect_usage_error("ring simulate --node mc --node mc --keys node3:in1=on", "node 3 is not a Motion Coordinator");
  expect_usage_error("ring simulate --node mc --node mc --keys node1:in99=on", "inputs 0 to 31");
}
