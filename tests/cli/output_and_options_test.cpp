// What every command shares about its output and options (docs/cli.md): a closed or full output is one
// message and exit 1, JSON numbers are plain decimals, and every option takes `--name=value` as well as
// `--name value`.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "support/run_cli.hpp"
#include "support/temp_files.hpp"
#include "support/text_match.hpp"

namespace {

using trionet::test::find_pattern;
using trionet::test::replace_pattern;
using trionet::test::temp_path;
using trionet::test::cli_result;
using trionet::test::run_cli;
using trionet::test::run_cli_redirected;

// `trionet <args> | head -c 1`: the tool's status and its standard error.
cli_result into_a_pipe_that_closes(const std::string& args, const std::string& input) {
  const std::string in = temp_path("pipe.in");
  const std::string err = temp_path("pipe.err");
  std::ofstream(in, std::ios::binary) << input;
  const std::string command = "bash -c '" + std::string(TRIONET_CLI_PATH) + " " + args + " <" + in + " 2>" + err +
                              " | head -c 1 >/dev/null; exit ${PIPESTATUS[0]}'";
  const int status = std::system(command.c_str());
  cli_result r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.err = trionet::test::slurp(err);
  std::remove(in.c_str());
  std::remove(err.c_str());
  return r;
}

TEST(Output, AClosedPipeIsOneMessageAndExit1NotASignal) {
  std::string frames;
  for (int i = 0; i < 20000; ++i) frames += "91 48 45 4c 4c 4f 90\n";
  std::string candump;
  for (int i = 0; i < 20000; ++i) candump += "028#0100000000020D7A\n";
  std::string tokens;
  for (int i = 0; i < 20000; ++i) tokens += "c:23 5a c:75\n";
  // `ring monitor -` reads the port's raw bytes (hex text would be 251 bytes of stray-data report, which fits in
  // the pipe and ends well before the reader closes it, or not, as the two processes happen to run).
  std::string wire;
  for (int i = 0; i < 20000; ++i) wire += std::string("\x91\x48\x45\x4c\x4c\x4f\x90", 7);
  // Each run writes well over a pipe's 64 KiB (1.4 to 2.2 MB), so the tool is still writing when the reader leaves.
  const std::vector<std::pair<std::string, std::string>> runs = {
      {"ring decode", frames}, {"can decode", candump}, {"genius decode", tokens}, {"ring monitor - --json", wire}};
  for (const auto& [args, input] : runs) {
    const cli_result r = into_a_pipe_that_closes(args, input);
    EXPECT_EQ(r.exit_code, 1) << args;
    EXPECT_EQ(r.err, "trionet: cannot write standard output: Broken pipe\n") << args;
  }
}

TEST(Output, AFullDiskIsOneMessageAndExit1) {
  for (const std::string args : {"ring encode print --to 11 HI", "can table", "genius scan-time --rate 76.8 --device 4",
                                   "genius timing --rate 153.6s --after 4 --device 4@0 --device 5@2000", "profile show",
                                   "--help", "ring --help", "ring decode --help", "--version"}) {
    const cli_result r = run_cli_redirected(args + " >/dev/full");
    EXPECT_EQ(r.exit_code, 1) << args;
    EXPECT_EQ(r.err, "trionet: cannot write standard output: No space left on device\n") << args;
  }
}

// A standard stream closed at start (`>&-`, `2>&-`) is never taken by a file the command opens: the capture stays
// a capture, a closed standard output still fails the run.
TEST(Output, AClosedStandardStreamNeverLandsInAFileTheCommandWrites) {
  const std::string capture = temp_path("closed.pcapng");
  const cli_result closed_out = run_cli_redirected("ring simulate example1 --byte-times 3000 --pcap " + capture + " >&-");
  EXPECT_EQ(closed_out.exit_code, 1);
  EXPECT_EQ(closed_out.err, "trionet: cannot write standard output: Bad file descriptor\n");
  const cli_result read_back = run_cli("ring decode --pcap " + capture);
  EXPECT_EQ(read_back.exit_code, 0) << read_back.err;
  EXPECT_EQ(read_back.out.find("capture_error"), std::string::npos) << read_back.out;
  EXPECT_NE(read_back.out.find("\"record\":35,"), std::string::npos) << read_back.out;
  const cli_result closed_err =
      run_cli_redirected("ring simulate example1 --byte-times 3000 --pcap " + capture + " 2>&- >/dev/null");
  EXPECT_EQ(closed_err.exit_code, 0);
  const cli_result read_again = run_cli("ring decode --pcap " + capture);
  EXPECT_EQ(read_again.exit_code, 0) << read_again.err;
  EXPECT_EQ(read_again.out.find("capture_error"), std::string::npos) << read_again.out;
  EXPECT_NE(read_again.out.find("\"record\":35,"), std::string::npos) << read_again.out;
  const std::string genius = temp_path("closed-genius.pcapng");
  EXPECT_EQ(run_cli_redirected("genius decode c:24 11 22 c:4a --write-pcap " + genius + " >&-").exit_code, 1);
  const cli_result genius_back = run_cli("genius decode --pcap " + genius);
  EXPECT_EQ(genius_back.exit_code, 0) << genius_back.err;
  EXPECT_NE(genius_back.out.find("1 transmission, 0 errors"), std::string::npos) << genius_back.out;
  std::remove(capture.c_str());
  std::remove(genius.c_str());
}

TEST(Output, JsonNumbersArePlainDecimalsNeverExponents) {
  // The smallest step of a Q32.32 value, a tenth of a thousandth, and values past 10^5 (to_chars' shortest
  // form would write 2.3283064365386963e-10, 1e-04 and 1e+05).
  const std::pair<const char*, const char*> cases[] = {{"0.0000000002", "0.00000000023283064365386963"},
                                                       {"0.0001", "0.0001"},
                                                       {"100000", "100000"},
                                                       {"-2000000000", "-2000000000"}};
  for (const auto& [given, printed] : cases) {
    const cli_result r = run_cli(std::string("ring decode $(" TRIONET_CLI_PATH " ring encode var --to 10 --vr 1 --value ") +
                                 given + ")");
    EXPECT_NE(r.out.find(std::string("\"value\":") + printed), std::string::npos) << given << ": " << r.out;
    EXPECT_TRUE(find_pattern(r.out, "[0-9][eE][-+]?[0-9]").empty()) << r.out;
  }
  const cli_result can = run_cli("can decode", run_cli("can encode --from 1 --to 4 --vr 1 --value 0.0001").out);
  EXPECT_NE(can.out.find("\"value\":0.0001}"), std::string::npos) << can.out;
  // No JSON line of these commands has an exponent anywhere.
  const std::string exponent = "[0-9][eE][-+]?[0-9]";
  for (const std::string& line : {can.out, run_cli("genius timing --rate 38.4 --after 1 --device 1@0 --device 2@0.001 "
                                                   "--prop-us-per-2000ft 0.0001 --json").out}) {
    EXPECT_TRUE(find_pattern(line, exponent).empty()) << line;
  }
}

// Every option of every command takes --name=value: the same output as --name value.
TEST(Options, EveryOptionTakesTheEqualsForm) {
  const std::vector<std::string> command_lines = {
      "ring encode var --to 10 --vr 200 --value 99",
      "ring encode offset --to 11 --offset 10",
      "can encode --from 1 --to 4 --vr 1 --value 2.345 --nodes 5",
      "can table --nodes 7",
      "genius encode --from 3 --to 5 1122",
      "genius timing --rate 153.6s --after 4 --device 4@0 --device 5@2000 --skip-us 26 --detect-us 3",
      "genius scan-time --rate 76.8 --device 4 --device 2,3",
      "profile header --namespace my::profile",
  };
  const std::string option = "(--[a-z-]+) ([^-][^ ]*)";
  for (const std::string& spaced : command_lines) {
    const std::string joined = replace_pattern(spaced, option, "$1=$2");
    ASSERT_NE(joined, spaced);
    const cli_result a = run_cli(spaced, "\x89HI\x88");
    const cli_result b = run_cli(joined, "\x89HI\x88");
    EXPECT_EQ(a.exit_code, 0) << spaced << ": " << a.err;
    EXPECT_EQ(b.exit_code, 0) << joined << ": " << b.err;
    EXPECT_EQ(a.out, b.out) << joined;
  }
  // The options every command takes, too.
  EXPECT_EQ(run_cli("can table --profile=/nonexistent/p.json").exit_code, 1);
  EXPECT_EQ(run_cli("can table --fail-on-limit").exit_code, 0);
  // A flag takes no value; an empty value is a value.
  trionet::test::expect_usage_error("ring decode --raw=yes", "option --raw takes no value");
  // A flag given twice is a usage error, as an option with a value is (s37 item 11: --json --json was taken).
  trionet::test::expect_usage_error("genius timing --rate 153.6s --after 4 --device 4@0 --json --json",
                                    "option --json given twice");
  trionet::test::expect_usage_error("ring decode --raw --raw", "option --raw given twice");
  trionet::test::expect_usage_error("can table --fail-on-limit --fail-on-limit", "option --fail-on-limit given twice");
  trionet::test::expect_usage_error("genius encode --from 3 --words --words 1122", "option --words given twice");
  trionet::test::expect_usage_error("can encode --from= --to 4 --vr 1 --value 2", "--from must be");
}

}  // namespace
