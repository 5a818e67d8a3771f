// `trionet genius simulate` and `trionet genius plan`: GE's worked example as a simulated bus, its collision,
// the planner's answer for its layout, and clear refusals of bad arguments.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "support/run_cli.hpp"

namespace {

using trionet::test::expect_usage_error;
using trionet::test::run_cli;
using trionet::test::slurp;

const char* const seed = "--rate 153.6s --device 4@0 --device 5@2000 --device 6@0";

TEST(GeniusSimulateCli, SeedExampleWithSkip26UsPrintsTheSeedsNumbers) {
  const auto r = run_cli(std::string("genius simulate ") + seed + " --skip-us 26 --scans 3");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_NE(r.out.find("first scan, after the Stop of SBA 4 (time 0):\n"
                       "  SBA  turn_us  what\n"
                       "    5   29.000  transmitted\n"
                       "    6   52.000  cancelled: SBA 5's start bit arrived at 32.000 us, margin 20.000 us\n"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("collisions: 0;"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(", 0 not what their sender sent\n"), std::string::npos) << r.out;
}

TEST(GeniusSimulateCli, JsonLastLineHoldsCollisionsScansTurnsAndScanTime) {
  const auto r = run_cli(std::string("genius simulate ") + seed + " --skip-us 26 --json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  ASSERT_FALSE(r.out.empty());
  ASSERT_EQ(r.out.back(), '\n');
  const std::string last = r.out.substr(r.out.rfind('\n', r.out.size() - 2) + 1);
  EXPECT_EQ(last.front(), '{');
  EXPECT_NE(last.find("\"collisions\":0,"), std::string::npos) << last;
  EXPECT_NE(last.find("\"scans\":10,"), std::string::npos) << last;
  EXPECT_NE(last.find("\"turns\":[{\"sba\":5,\"start_us\":29,\"what\":\"transmitted\"},{\"sba\":6,\"start_us\":52,"
                      "\"what\":\"cancelled\",\"by\":5,\"arrived_us\":32,\"margin_us\":20}]"),
            std::string::npos)
      << last;
  EXPECT_NE(last.find("\"scan_ms\":{\"median\":1.483,\"max\":1.483}"), std::string::npos) << last;
  EXPECT_NE(last.find("\"ge_scan_ms\":{\"sum\":3.0435,\"scan\":3.0435,\"minimum_applies\":false}"), std::string::npos)
      << last;
}

TEST(GeniusSimulateCli, SeedLayoutWithTheRulesSkipTimeCollidesEveryScan) {
  const auto r = run_cli(std::string("genius simulate ") + seed + " --scans 5 --json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\"turns\":[{\"sba\":5,\"start_us\":9.51,\"what\":\"transmitted\"},{\"sba\":6,\"start_us\":"
                       "13.021,\"what\":\"transmitted\"}]"),
            std::string::npos)
      << r.out;
  // The bus's count comes before the devices' own.
  const std::size_t at = r.out.find("\"collisions\":");
  ASSERT_NE(at, std::string::npos);
  EXPECT_GE(std::stoi(r.out.substr(at + 13)), 5) << r.out;
  EXPECT_NE(r.out.find("\"wrong_deliveries\":0,"), std::string::npos) << r.out;
}

TEST(GeniusSimulateCli, EachRemedyRunsWithoutACollision) {
  for (const char* layout : {"--rate 153.6s --device 4@0 --device 5@2000 --device 7@0",
                             "--rate 153.6s --device 4@0 --device 5@0 --device 6@2000",
                             "--rate 153.6e --device 4@0 --device 5@2000 --device 6@0",
                             "--rate 76.8 --device 4@0 --device 5@2000 --device 6@0"}) {
    const auto r = run_cli(std::string("genius simulate ") + layout + " --json");
    EXPECT_EQ(r.exit_code, 0) << layout << ": " << r.err;
    EXPECT_NE(r.out.find("\"collisions\":0,"), std::string::npos) << layout << ": " << r.out;
    EXPECT_NE(r.out.find("\"complete\":true"), std::string::npos) << layout;
  }
}

TEST(GeniusSimulateCli, AControllerSendsOutputsAndFaultsAreRecoveredFrom) {
  const auto r = run_cli(
      "genius simulate --rate 153.6s --device 0@0:4/2 --device 3@400:2/8 --device 31@100:0/0 --controller 31 "
      "--scans 20 --fault noise:200@5000+60 --fault off:3@9000+4000 --json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\"opener\":31,"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"complete\":true"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"wrong_deliveries\":0,"), std::string::npos) << r.out;
}

TEST(GeniusSimulateCli, TraceShowsTheCollisionAsItHappens) {
  const auto r = run_cli(std::string("genius simulate ") + seed + " --scans 1 --trace");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("us  SBA 5 starts a transmission\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("us  collision: SBA 6 and SBA 5\n"), std::string::npos) << r.out;
}

TEST(GeniusSimulateCli, PcapHoldsTheTransmissionsTheDecoderReads) {
  const std::string path = "/tmp/trionet-genius-simulate-" + std::to_string(::getpid()) + ".pcapng";
  const auto r = run_cli(std::string("genius simulate ") + seed + " --skip-us 26 --scans 2 --pcap " + path);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const auto decoded = run_cli("genius decode --pcap " + path);
  EXPECT_EQ(decoded.exit_code, 0) << decoded.err;
  EXPECT_NE(decoded.out.find("transmission from SBA 5, broadcast"), std::string::npos) << decoded.out;
  EXPECT_NE(decoded.out.find(" transmissions, 0 errors, 0 characters skipped\n"), std::string::npos) << decoded.out;
  std::remove(path.c_str());
}

// A capture that cannot be opened exits 1 (unwritable output) with one message naming the file and the cause.
TEST(GeniusSimulateCli, ACaptureThatCannotBeOpenedNamesTheFileAndTheCause) {
  const auto r = run_cli(std::string("genius simulate ") + seed + " --scans 1 --pcap /nonexistent-directory/bus.pcapng");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err, "trionet: cannot write the capture /nonexistent-directory/bus.pcapng: No such file or directory\n");
}

// Peak resident memory (KiB) of one run of the tool, from wait4; its output goes to /dev/null.
long peak_kib(const std::vector<std::string>& args) {
  std::vector<std::string> words{TRIONET_CLI_PATH};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(null, 2);
    // Under AddressSanitizer freed memory waits in a quarantine (256 MB by default), which would look like
    // growth: keep it small, so that the figure is the tool's own memory.
    const char* asan = std::getenv("ASAN_OPTIONS");
    const std::string options = std::string(asan != nullptr ? asan : "") + ":quarantine_size_mb=1";
    ::setenv("ASAN_OPTIONS", options.c_str(), 1);
    ::execv(TRIONET_CLI_PATH, argv.data());
    ::_exit(127);
  }
  int status = 0;
  struct rusage usage {};
  EXPECT_EQ(::wait4(pid, &status, 0, &usage), pid);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
  return usage.ru_maxrss;
}

// A long run keeps only the first scans' turns and transmissions (which it shows): its memory does not grow
// with --scans (it grew by about 100 KiB a scan on a 32-station bus, 10 GB at the allowed 100,000 scans; on
// this test's 16-station bus by about 25 KiB a scan, 25 MiB over the larger run's extra 1,000 scans).
TEST(GeniusSimulateCli, MemoryDoesNotGrowWithTheScans) {
  std::vector<std::string> args{"genius", "simulate", "--rate", "153.6s", "--controller", "0", "--device", "0@0:0/0"};
  for (int sba = 1; sba < 16; ++sba) {
    args.push_back("--device");
    args.push_back(std::to_string(sba) + "@" + std::to_string(sba * 50) + ":4/4");
  }
  args.push_back("--json");
  args.push_back("--scans");
  std::vector<std::string> few = args, many = args;
  few.push_back("20");
  many.push_back("1020");
  const long small = peak_kib(few);
  const long large = peak_kib(many);
  EXPECT_LT(large, small + 4096) << "20 scans: " << small << " KiB, 1020 scans: " << large << " KiB";
}

TEST(GeniusSimulateCli, BadArgumentsExit2WithAMessage) {
  expect_usage_error("genius simulate --device 4@0", "--rate");
  expect_usage_error("genius simulate --rate 153.6s", "--device");
  expect_usage_error("genius simulate --rate 153.6s --device 4", "--device '4'");
  expect_usage_error("genius simulate --rate 153.6s --device 4@0:300", "--device '4@0:300'");
  expect_usage_error("genius simulate --rate 153.6s --device 4@0 --device 4@10", "SBA 4 is given twice");
  expect_usage_error("genius simulate --rate 153.6s --device 4@0 --controller 9", "controller");
  expect_usage_error("genius simulate --rate 153.6s --device 4@0 --fault noise@1", "--fault");
  expect_usage_error("genius simulate --rate 153.6s --device 4@0 --fault off:9@1+1", "SBA 9");
  expect_usage_error("genius simulate --rate 153.6s --device 4@0 --scans 0", "--scans");
  expect_usage_error("genius simulate --rate 153.6s --device 4@0 --detect-us 7", "--detect-us");
  expect_usage_error("genius simulate --rate 153.6s --device 4@0 --skip-us 0", "--skip-us");
}

TEST(GeniusSimulateCli, AnOutOfRangeNumberIsNamedWithItsRange) {
  const std::string run = "genius simulate --rate 153.6s --device 4@0 ";
  expect_usage_error(run + "--seed 9223372036854775808",
                     "--seed must be 0..9223372036854775807, got '9223372036854775808'");
  expect_usage_error(run + "--fault cut:50@0+1000000001",
                     "--fault 'cut:50@0+1000000001': the duration D must be 0..1000000000 us, got '1000000001'");
  expect_usage_error(run + "--fault noise:1000001@0+1",
                     "--fault 'noise:1000001@0+1': the place FEET must be 0..1000000 feet, got '1000001'");
  expect_usage_error(run + "--fault off:4@2000000000+1", "the start T must be 0..1000000000 us");
  expect_usage_error(run + "--fault stop:32@0+1", "the SBA must be 0..31, got '32'");
  expect_usage_error(run + "--fault cut:x@0+1", "must be noise:FEET@T+D");
}

// The simulated devices are built for CRC-6/G-704 and the layout of docs/protocol.md 3.2: a profile with other
// Genius keys is refused with the field, its value and what simulate supports, not ignored (s37 item 3).
TEST(GeniusSimulateCli, AProfileWithAnotherGeniusCrcOrLayoutIsRefusedNotIgnored) {
  const std::string shown = run_cli("profile show").out;
  const std::string path = "/tmp/trionet-genius-sim-profile-" + std::to_string(::getpid()) + ".json";
  const auto write_with = [&](const std::string& from, const std::string& to) {
    std::string text = shown;
    const std::size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
    FILE* f = std::fopen(path.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs(text.c_str(), f);
    std::fclose(f);
  };
  const std::string run = "genius simulate --rate 153.6s --device 4@0 --device 5@10 --scans 2 --profile " + path;
  write_with("\"polynomial\": \"0x03\"", "\"polynomial\": \"0x2f\"");
  auto r = run_cli(run);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err,
            "trionet: the profile's genius.crc6 is polynomial 0x2f, initial 0x00, reflect_in true, reflect_out "
            "true, xor_out 0x00: `trionet genius simulate` supports only polynomial 0x03, initial 0x00, "
            "reflect_in true, reflect_out true, xor_out 0x00 (its devices are the library's genius::device, "
            "built for the defaults)\n");
  write_with("\"tag_position\": \"high\"", "\"tag_position\": \"low\"");
  r = run_cli(run);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("genius.control is start 0, stop 1, start_of_block 2, end_of_block 3, tag_position low"),
            std::string::npos)
      << r.err;
  write_with("\"name\"", "\"name\"");  // the defaults: simulated as without --profile
  r = run_cli(run);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::remove(path.c_str());
}

// A run its time bound cut short (nobody sends, so no scan completes) says so on stderr and exits 4 with
// --fail-on-limit, 0 without, as cli.md's rules for limits say (s37 item 4).
TEST(GeniusSimulateCli, ARunCutShortByItsTimeBoundSaysSoAndExits4WithFailOnLimit) {
  const std::string run = "genius simulate --rate 153.6s --device 4@0:0 --device 5@10:0";
  const std::string said =
      "trionet: genius simulate: stopped at the run's time bound, 154.220 ms (room for 10 scans), with 0 of 10 "
      "scans complete\n";
  auto r = run_cli(run);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.err, said);
  EXPECT_NE(r.out.find("scans: none complete in 154.220 ms\n"), std::string::npos) << r.out;
  r = run_cli(run + " --fail-on-limit");
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_EQ(r.err, said);
  r = run_cli(run + " --json --fail-on-limit");
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_NE(r.out.find("\"complete\":false"), std::string::npos) << r.out;
  r = run_cli("genius simulate --rate 153.6s --device 4@0 --device 5@10 --scans 2 --fail-on-limit");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
}

// The controller sends the others' OUT_BYTES and nothing of its own: bytes given to it, or a bus where no
// other device has OUT_BYTES (the controller would never send, no scan would open), are refused, not
// dropped (s37 item 5).
TEST(GeniusSimulateCli, ControllerBytesThatWouldBeDroppedAreRefused) {
  auto r = run_cli("genius simulate --rate 153.6s --device 4@0:5 --device 5@10:1/2 --controller 4 --scans 3");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err,
            "trionet: --device '4@0:5' is the controller: it sends the other devices' OUT_BYTES as blocks and no "
            "bytes of its own; give it as SBA@FEET or SBA@FEET:0\n");
  r = run_cli("genius simulate --rate 153.6s --device 4@0 --device 5@100 --device 6@200 --controller 4 --scans 10");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err,
            "trionet: --controller 4: no other device has OUT_BYTES (SBA@FEET:IN_BYTES/OUT_BYTES), so the "
            "controller would never send and no scan would open\n");
  for (const char* controller : {"4@0", "4@0:0", "4@0:0/0"}) {
    r = run_cli(std::string("genius simulate --rate 153.6s --device ") + controller +
                " --device 5@10:1/2 --controller 4 --scans 3");
    EXPECT_EQ(r.exit_code, 0) << controller << r.err;
    EXPECT_EQ(r.err, "") << controller;
  }
}

// A fault the run never reaches is said on stderr, not dropped silently (s37 item 7).
TEST(GeniusSimulateCli, AFaultAfterTheRunsEndIsSaidToHaveNeverHappened) {
  auto r = run_cli("genius simulate --rate 153.6s --device 0@0 --device 1@100 --fault off:1@100000+1000 --scans 10");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.err,
            "trionet: genius simulate: --fault off:1@100000+1000 never happened: the run ended at 7099.505 us\n");
  r = run_cli("genius simulate --rate 153.6s --device 0@0 --device 1@100 --fault off:1@1000+1000 --scans 10");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.err, "");
}

// A lone device has no turns because there is no other device, not because a Stop never came (s37 item 11).
TEST(GeniusSimulateCli, ALoneDeviceHasNoTurnsBecauseThereIsNoOtherDevice) {
  const auto r = run_cli("genius simulate --rate 153.6s --device 0@0 --scans 3");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("  no turns (no other device)\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("scans: 3;"), std::string::npos) << r.out;
}

// A capture that cannot be written whole names the system's cause, as every other write error does (s37
// item 11): a full device, for simulate --pcap and decode --write-pcap.
TEST(GeniusSimulateCli, ACaptureOnAFullDeviceNamesTheCause) {
  if (::access("/dev/full", W_OK) != 0) GTEST_SKIP() << "no /dev/full";
  for (const char* command : {"genius simulate --rate 153.6s --device 0@0 --device 1@100 --pcap /dev/full",
                              "genius simulate --rate 153.6s --device 0@0 --device 1@100 --scans 3000 --pcap /dev/full",
                              "genius decode --write-pcap /dev/full c:24 11 c:52"}) {
    const auto r = run_cli(command);
    EXPECT_EQ(r.exit_code, 1) << command;
    EXPECT_EQ(r.err, "trionet: cannot write the capture /dev/full: No space left on device\n") << command;
  }
}

TEST(GeniusPlanCli, SeedLayoutGetsAPlanWithoutCollisionRiskAt153k6s) {
  const auto r = run_cli("genius plan --rate 153.6s --device A@0 --device B@2000 --device C@0");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out,
            "the devices in the order given, from SBA 0 at 153.6s (153.6 kbaud standard):\n"
            "  name     feet  SBA\n"
            "  A           0    0\n"
            "  B        2000    1\n"
            "  C           0    2\n"
            "  smallest margin 0.51 us (after A's Stop, C's turn after B's start bit); detection 3.26 us\n"
            "collision risk: 3 margins below the detection time\n"
            "plan at 153.6s (153.6 kbaud standard), without collision risk:\n"
            "  name     feet  SBA\n"
            "  A           0    0\n"
            "  B        2000    2\n"
            "  C           0    4\n"
            "  smallest margin 7.02 us (after A's Stop, C's turn after B's start bit); detection 3.26 us\n"
            "remedy: skip an SBA: SBA 1 left unused: B's turn comes 2 skip times after A's, so that B detects A's "
            "start bit (3.00 us away) before its own turn, also at an idle restart that follows B's own Stop (the "
            "start bit's way there and back: 6.00 us)\n"
            "remedy: skip an SBA: SBA 3 left unused: C's turn comes 2 skip times after B's, so that C detects B's "
            "start bit (3.00 us away) before its own turn, also at an idle restart that follows C's own Stop (the "
            "start bit's way there and back: 6.00 us)\n"
            "turn overhead per scan: 214.33 us (32 skip times and the propagation between turns)\n");
}

TEST(GeniusPlanCli, ChecksSbasGivenAndExits3WithCheck) {
  const char* const given = "genius plan --rate 153.6s --device A@0=4 --device B@2000=5 --device C@0=6";
  EXPECT_EQ(run_cli(given).exit_code, 0);
  EXPECT_EQ(run_cli(std::string(given) + " --check").exit_code, 3);
  const auto ok = run_cli("genius plan --rate 153.6s --device A@0=4 --device B@0=5 --device C@2000=7 --check");
  EXPECT_EQ(ok.exit_code, 0);
  EXPECT_NE(ok.out.find("no collision risk"), std::string::npos) << ok.out;
}

// The idle restart (docs/protocol.md 3.4) times every turn from the last sender's Stop, that sender included: when
// C sent last, B's start bit must go to C and back within C's one skip time after B. No Stop's own turns have
// that pair (a sender takes no turn after its own Stop).
TEST(GeniusPlanCli, AMarginOfTheIdleRestartIsChecked) {
  const auto r = run_cli("genius plan --rate 153.6s --device A@0=4 --device B@0=5 --device C@2000=6 --check");
  EXPECT_EQ(r.exit_code, 3) << r.out;
  EXPECT_NE(r.out.find("smallest margin 0.51 us (at an idle restart after C's Stop, C's turn after B's start bit)"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("collision risk: 1 margin below the detection time"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  C        2000    7\n"), std::string::npos) << r.out;
  const auto json = run_cli("genius plan --rate 153.6s --device A@0=4 --device B@0=5 --device C@2000=6 --json");
  EXPECT_NE(json.out.find("\"margins_below_detection\":1,\"idle_restart_margins_below_detection\":1,"
                          "\"smallest_margin_us\":0.51,\"smallest_margin_at_idle_restart\":true,"),
            std::string::npos)
      << json.out;
}

// GE's example layout with SBAs 4, 5, 6 given: moving SBA 5's device alone keeps every margin (two changes were
// proposed before the planner tried moves of one device).
TEST(GeniusPlanCli, SbasGivenAreFixedWithOneChangeWhereOneDoes) {
  const auto r = run_cli("genius plan --rate 153.6s --device SBA4@0=4 --device SBA5@2000=5 --device SBA6@0=6 --json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\"plan\":{\"rate\":\"153.6s\",\"devices\":[{\"name\":\"SBA4\",\"feet\":0,\"sba\":4},"
                       "{\"name\":\"SBA5\",\"feet\":2000,\"sba\":0},{\"name\":\"SBA6\",\"feet\":0,\"sba\":6}],"
                       "\"margins_below_detection\":0,"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("{\"remedy\":\"resequence\",\"why\":\"SBA5 from SBA 5 to SBA 0: one change that keeps every "
                       "margin\"}"),
            std::string::npos)
      << r.out;
}

TEST(GeniusPlanCli, ABusTooLongForTheRateMovesTo153k6Extended) {
  const auto r = run_cli("genius plan --rate 153.6s --device A@0 --device B@3000 --device C@100 --json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\"plan\":{\"rate\":\"153.6e\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("{\"remedy\":\"153.6e\",\"why\":\"from 153.6s to 153.6e: the bus is 3000 ft long and 153.6s "
                       "allows 2000 ft"),
            std::string::npos)
      << r.out;
}

// More devices than 38.4 allows: the reason is the count, not the margins (s37 item 11).
TEST(GeniusPlanCli, TooManyDevicesAt38k4IsTheReasonGiven) {
  std::string devices;
  for (int i = 0; i <= 16; ++i) devices += " --device D" + std::to_string(i) + "@" + std::to_string(i * 10);
  const auto r = run_cli("genius plan --rate 38.4" + devices);
  EXPECT_NE(r.out.find("no plan: 17 devices, and 38.4 allows 16\n"), std::string::npos) << r.out;
  const auto json = run_cli("genius plan --rate 38.4 --json" + devices);
  EXPECT_NE(json.out.find("17 devices, and 38.4 allows 16"), std::string::npos) << json.out;
}

TEST(GeniusPlanCli, BadArgumentsExit2WithAMessage) {
  expect_usage_error("genius plan --device A@0", "--rate");
  expect_usage_error("genius plan --rate 153.6s --device A", "--device 'A'");
  expect_usage_error("genius plan --rate 153.6s --device A@0=32", "--device 'A@0=32'");
  expect_usage_error("genius plan --rate 153.6s --device A@0=1 --device B@0", "every device");
  expect_usage_error("genius plan --rate 153.6s --device A@0 --device A@10", "given twice");
  expect_usage_error("genius plan --rate 153.6s --device A@0=3 --device B@10=3", "SBA 3 is given twice");
  // A name holding '@' or '=' would be read as another device (A@0@1 was the name A@0 at 1 ft).
  expect_usage_error("genius plan --rate 153.6s --device A@0@1", "without blanks, '@' or '='");
  expect_usage_error("genius plan --rate 153.6s --device A=1@0", "without blanks, '@' or '='");
}

}  // namespace
