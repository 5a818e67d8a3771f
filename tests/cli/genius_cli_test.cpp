// `trionet genius encode | decode | timing`: exact output, and exit 2 with a message on bad arguments.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include <unistd.h>

#include "support/run_cli.hpp"

namespace {

using trionet::test::expect_usage_error;
using trionet::test::run_cli;

const std::string seed_devices = "--after 4 --device 4@0 --device 5@2000 --device 6@0";

TEST(GeniusCliSeedWorkedExample, TimingTableWithSkip26us) {
  const auto r = run_cli("genius timing --rate 153.6s " + seed_devices + " --skip-us 26");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(r.out,
            "rate 153.6s (153.6 kbaud standard): bit time 6.51 us, skip time 26.00 us (explicit)\n"
            "propagation 3 us per 2000 ft, detection time 3.26 us\n"
            "after the Stop of SBA 4 at 0 ft:\n"
            "  SBA  position_ft  turn_start_us\n"
            "    5         2000          29.00\n"
            "    6            0          52.00\n"
            "margins (second's turn minus the arrival of first's start bit at second):\n"
            "  first  second  margin_us\n"
            "      5       6      20.00  ok\n");
}

TEST(GeniusCliSeedWorkedExample, TimingJsonWithSkip26us) {
  const auto r = run_cli("genius timing --rate 153.6s " + seed_devices + " --skip-us 26 --json");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out,
            "{\"rate\":\"153.6s\",\"skip_us\":26,\"turns\":[{\"sba\":5,\"start_us\":29},{\"sba\":6,\"start_"
            "us\":52}],"
            "\"margins\":[{\"first\":5,\"second\":6,\"margin_us\":20}]}\n");
}

TEST(GeniusCliSeedWorkedExample, TimingWithTheRuleSkipTimeIsFlagged) {
  const auto r = run_cli("genius timing --rate 153.6s " + seed_devices);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out,
            "rate 153.6s (153.6 kbaud standard): bit time 6.51 us, skip time 6.51 us (rule)\n"
            "propagation 3 us per 2000 ft, detection time 3.26 us\n"
            "after the Stop of SBA 4 at 0 ft:\n"
            "  SBA  position_ft  turn_start_us\n"
            "    5         2000           9.51\n"
            "    6            0          13.02\n"
            "margins (second's turn minus the arrival of first's start bit at second):\n"
            "  first  second  margin_us\n"
            "      5       6       0.51  TOO SMALL\n"
            "1 margin below the detection time: collision risk\n");
  const auto json = run_cli("genius timing --rate 153.6s " + seed_devices + " --json");
  EXPECT_EQ(json.out,
            "{\"rate\":\"153.6s\",\"skip_us\":6.51,\"turns\":[{\"sba\":5,\"start_us\":9.51},{\"sba\":6,"
            "\"start_us\":13.021}],"
            "\"margins\":[{\"first\":5,\"second\":6,\"margin_us\":0.51}]}\n");
}

TEST(GeniusCli, TimingOptionsChangeTheNumbers) {
  const auto r = run_cli(
      "genius timing --rate 153.6e --after 4 --device 6@0 --device 5@2000 --device 4@0 "
      "--skip-us 26 --prop-us-per-2000ft 4 --detect-us 19 --json");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out,
            "{\"rate\":\"153.6e\",\"skip_us\":26,\"turns\":[{\"sba\":5,\"start_us\":30},{\"sba\":6,\"start_"
            "us\":52}],"
            "\"margins\":[{\"first\":5,\"second\":6,\"margin_us\":18}]}\n");
  const auto table = run_cli(
      "genius timing --rate 153.6e --after 4 --device 6@0 --device 5@2000 --device 4@0 "
      "--skip-us 26 --prop-us-per-2000ft 4 --detect-us 19");
  EXPECT_NE(table.out.find("      5       6      18.00  TOO SMALL\n"), std::string::npos) << table.out;
}

TEST(GeniusCli, TimingWarnsAboutRateLimits) {
  const auto r = run_cli("genius timing --rate 153.6s --after 1 --device 1@0 --device 2@2500");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("warning: the bus is 2500 ft long; 153.6s allows 2000 ft\n"), std::string::npos)
      << r.out;
}

TEST(GeniusCli, EncodeTheRunningExample) {
  const auto r = run_cli("genius encode --from 4 --to 7 1122 block:9:aabb 33");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(r.out, "c:04 07 11 22 c:89 aa bb c:ce 33 c:50\n");
  const auto words = run_cli("genius encode --from 4 --to 7 1122 block:9:aabb 33 --words");
  EXPECT_EQ(words.out, "w:412 w:41c w:444 w:488 w:626 w:6a8 w:6ec w:73a w:4cc w:542\n");
  const auto broadcast = run_cli("genius encode --from 3 --broadcast 5a");
  EXPECT_EQ(broadcast.out, "c:23 5a c:75\n");
}

TEST(GeniusCli, DecodeRoundTripsFromStdinAndArguments) {
  const std::string expected =
      "transmission from SBA 4, directed to SBA 7 (line 1, character 1)\n"
      "  data 11 22\n"
      "  block to SBA 9: aa bb\n"
      "  data 33\n"
      "1 transmission, 0 errors, 0 characters skipped\n";
  const auto from_stdin = run_cli("genius decode", "c:04 07 11 22 c:89 aa bb c:ce 33 c:50\n");
  EXPECT_EQ(from_stdin.exit_code, 0);
  EXPECT_EQ(from_stdin.out, expected);
  const auto from_words =
      run_cli("genius decode w:412 w:41c w:444 w:488 w:626 w:6a8 w:6ec w:73a w:4cc w:542");
  EXPECT_EQ(from_words.exit_code, 0);
  EXPECT_EQ(from_words.out, expected);
}

TEST(GeniusCli, DecodeReportsWireErrorsWithWhereTheyAreAndExit0) {
  const auto r = run_cli("genius decode",
                         "11 c:04 07 11 22 c:89 aa bb c:ce 33 c:51\nc:23 5a c:75 w:412 w:41c w:489");
  EXPECT_EQ(r.exit_code, 0) << "wire errors are events, not failures";
  EXPECT_EQ(r.out,
            "error at line 1, character 1 (11): data_outside_transmission\n"
            "error at line 1, character 11 (c:51): stop_crc_mismatch\n"
            "transmission from SBA 3, broadcast (line 2, character 12)\n"
            "  data 5a\n"
            "error at line 2, character 17 (w:489): framing_error (start bit not 0)\n"
            "1 transmission, 3 errors, 0 characters skipped\n");
  const auto unfinished = run_cli("genius decode c:04 07");
  EXPECT_EQ(unfinished.exit_code, 0);
  EXPECT_EQ(unfinished.out,
            "error at end of input: transmission not finished (its Start at line 1, character 1)\n"
            "0 transmissions, 1 error, 0 characters skipped\n");
}

TEST(GeniusCli, BadTokensAreErrorsWithTheTokenClippedAndEscaped) {
  const std::string huge(100000, 'q');
  const auto r = run_cli("genius decode", "c:4 w:800 c:23 zz\x01 5a c:75 " + huge + "\n11");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(r.out,
            "error at line 1, character 1 (c:4): not a character (XX, c:XX or w:XXX)\n"
            "error at line 1, character 2 (w:800): framing_error (more than 11 bits)\n"
            "error at line 1, character 4 (zz\\x01): not a character (XX, c:XX or w:XXX)\n"
            "error at line 1, character 7 (" + std::string(40, 'q') + "...): not a character (XX, c:XX or w:XXX)\n"
            "0 transmissions, 4 errors, 3 characters skipped\n")
      << "a bad token inside a transmission loses it, as a framing error would: 5a c:75 11 are skipped up to "
         "the next Start";
}

// A word of 3 hex digits above 11 bits is the framing error the same word read with --raw is (s37 item 11);
// 4 digits is no token.
TEST(GeniusCli, AWordTokenAbove11BitsIsAFramingErrorAsWithRaw) {
  EXPECT_EQ(run_cli("genius decode w:fff").out,
            "error at line 1, character 1 (w:fff): framing_error (more than 11 bits)\n"
            "0 transmissions, 1 error, 0 characters skipped\n");
  EXPECT_EQ(run_cli("genius decode --raw", std::string("\x0f\xff", 2)).out,
            "error at offset 0 (w:fff): framing_error (more than 11 bits)\n"
            "0 transmissions, 1 error, 0 characters skipped\n");
  EXPECT_EQ(run_cli("genius decode w:1000").out,
            "error at line 1, character 1 (w:1000): not a character (XX, c:XX or w:XXX)\n"
            "0 transmissions, 1 error, 0 characters skipped\n");
}

TEST(GeniusCli, RawWordsWithOffsets) {
  // c:23 5a c:75 as 11-bit words, two bytes each, big-endian; then a lone byte.
  const auto r = run_cli("genius decode --raw", std::string("\x04\x8e\x05\x68\x05\xd6\x07", 7));
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out,
            "transmission from SBA 3, broadcast (offset 0)\n"
            "  data 5a\n"
            "error at offset 6: an odd byte at the end of the input\n"
            "1 transmission, 1 error, 0 characters skipped\n");
}

TEST(GeniusCli, EncodeRefusesWhatTheDecoderRejects) {
  const std::string most(2 * 256, 'a');
  const auto ok = run_cli("genius encode --from 3 --broadcast " + most);
  ASSERT_EQ(ok.exit_code, 0);
  EXPECT_NE(run_cli("genius decode", ok.out).out.find("1 transmission, 0 errors"), std::string::npos);
  expect_usage_error("genius encode --from 3 --broadcast " + most + "aa", "overflow");
  std::string blocks;
  for (int i = 0; i < 17; ++i) blocks += " block:1:aa";
  expect_usage_error("genius encode --from 3 --broadcast" + blocks, "16 segments");
}

TEST(GeniusCli, TimingCheckFailsOnACollisionRisk) {
  const auto risky = run_cli("genius timing --rate 153.6s " + seed_devices + " --check");
  EXPECT_EQ(risky.exit_code, 3);
  EXPECT_NE(risky.out.find("TOO SMALL"), std::string::npos);
  EXPECT_EQ(run_cli("genius timing --rate 153.6s " + seed_devices + " --check --json").exit_code, 3);
  EXPECT_EQ(run_cli("genius timing --rate 153.6s " + seed_devices + " --skip-us 26 --check").exit_code, 0);
  EXPECT_EQ(run_cli("genius timing --rate 153.6s " + seed_devices).exit_code, 0) << "without --check: a report";
  // A layout the rate does not allow fails the check as well (s37 item 11: 21 devices at 38.4 passed it).
  std::string many;
  for (int i = 0; i < 21; ++i) many += " --device " + std::to_string(i) + "@" + std::to_string(i * 10);
  const auto crowded = run_cli("genius timing --rate 38.4 --after 0" + many + " --check");
  EXPECT_EQ(crowded.exit_code, 3) << crowded.out;
  EXPECT_NE(crowded.out.find("warning: 21 devices; 38.4 allows 16\n"), std::string::npos) << crowded.out;
  EXPECT_EQ(run_cli("genius timing --rate 38.4 --after 0" + many).exit_code, 0) << "without --check: a report";
  const auto long_bus = run_cli("genius timing --rate 153.6s --after 4 --device 4@0 --device 5@2500 --skip-us 26 --check");
  EXPECT_EQ(long_bus.exit_code, 3) << long_bus.out;
  EXPECT_NE(long_bus.out.find("warning: the bus is 2500 ft long; 153.6s allows 2000 ft\n"), std::string::npos);
}

TEST(GeniusCli, TimingJsonIsAlwaysFinite) {
  expect_usage_error("genius timing --rate 153.6s --after 4 --device 4@0 --device 5@1e308 --json", "5@1e308");
  expect_usage_error("genius timing --rate 153.6s --after 4 --device 4@0 --device 5@1 --skip-us 1e300", "--skip-us");
  const auto far = run_cli("genius timing --rate 38.4 --after 4 --device 4@0 --device 5@1000000 --skip-us 1000000 "
                           "--prop-us-per-2000ft 1000000 --json");
  EXPECT_EQ(far.exit_code, 0);
  EXPECT_EQ(far.out.find("inf"), std::string::npos) << far.out;
  EXPECT_EQ(far.out.find("nan"), std::string::npos) << far.out;
}

TEST(GeniusCli, BadArgumentsExit2WithAMessage) {
  const auto no_command = run_cli("genius");
  EXPECT_EQ(no_command.exit_code, 2);
  EXPECT_EQ(no_command.out, "");
  EXPECT_EQ(no_command.err.rfind("trionet: genius needs a command", 0), 0u) << no_command.err;
  EXPECT_NE(no_command.err.find("usage: trionet genius"), std::string::npos) << "the part's usage follows";
  expect_usage_error("genius frobnicate", "frobnicate");
  expect_usage_error("genius timing --after 4 --device 4@0", "--rate");
  expect_usage_error("genius timing --rate 153.6 --after 4 --device 4@0", "153.6");
  expect_usage_error("genius timing --rate 76.8 --device 4@0", "--after");
  expect_usage_error("genius timing --rate 76.8 --after 4", "--device");
  expect_usage_error("genius timing --rate 76.8 --after 32 --device 4@0", "--after");
  expect_usage_error("genius timing --rate 76.8 --after 4 --device 4@0 --device 5@x", "5@x");
  expect_usage_error("genius timing --rate 76.8 --after 4 --device 4@0 --device 5@-1", "5@-1");
  expect_usage_error("genius timing --rate 76.8 --after 4 --device 4@0 --device 40@1", "40@1");
  expect_usage_error("genius timing --rate 76.8 --after 4 --device 4@0 --device 4@1", "SBA 4");
  expect_usage_error("genius timing --rate 76.8 --after 5 --device 4@0", "--after 5");
  expect_usage_error("genius timing --rate 76.8 --after 4 --device 4@0 --skip-us 0", "--skip-us");
  // A skip time that would print as 0.00 us (s37 item 11: 1e-300 was taken and printed as 0).
  expect_usage_error("genius timing --rate 76.8 --after 4 --device 4@0 --skip-us 1e-300", "from 0.01");
  expect_usage_error("genius timing --rate 76.8 --after 4 --device 4@0 --skip-us 0.009", "from 0.01");
  EXPECT_EQ(run_cli("genius timing --rate 76.8 --after 4 --device 4@0 --device 5@0 --skip-us 0.01").exit_code, 0);
  expect_usage_error("genius simulate --rate 76.8 --device 4@0 --device 5@0 --skip-us 1e-300", "from 0.01");
  expect_usage_error("genius timing --rate 76.8 --after 4 --device 4@0 --prop-us-per-2000ft -1", "--prop");
  expect_usage_error("genius timing --rate 76.8 --after 4 --device 4@0 --detect-us x", "--detect-us");
  expect_usage_error("genius timing --rate 76.8 --after 4 --device 4@0 --bogus 1", "--bogus");
  expect_usage_error("genius encode --to 3 11", "--from");
  expect_usage_error("genius encode --from 3 11", "--to");
  expect_usage_error("genius encode --from 3 --to 4 --broadcast 11", "--broadcast");
  expect_usage_error("genius encode --from 32 --broadcast 11", "--from");
  expect_usage_error("genius encode --from 3 --to 32 11", "--to");
  expect_usage_error("genius encode --from 3 --broadcast", "data");
  expect_usage_error("genius encode --from 3 --broadcast 123", "123");
  expect_usage_error("genius encode --from 3 --broadcast block:32:11", "block:32:11");
  expect_usage_error("genius encode --from 3 --broadcast block:3:", "block:3:");
  expect_usage_error("genius decode --raw 11", "--raw");
  expect_usage_error("genius decode --json", "--json");
  expect_usage_error("genius decode --rate 76.8", "--rate");
  expect_usage_error("genius decode --write-pcap /tmp/x --rate 99", "99");
  expect_usage_error("genius timing --rate 76.8 --after 4 --device 4@0 --check=1", "option --check takes no value");
}

}  // namespace

namespace {

TEST(GeniusCli, WritePcapThenReadItBack) {
  const std::string capture = "/tmp/trionet-genius-" + std::to_string(::getpid()) + ".pcapng";
  const auto written = run_cli("genius decode --write-pcap " + capture + " --rate 76.8",
                               "c:04 07 11 22 c:89 aa bb c:ce 33 c:50 c:23 5a c:75 c:23 5a");
  ASSERT_EQ(written.exit_code, 0) << written.err;
  const auto read = run_cli("genius decode --pcap " + capture);
  EXPECT_EQ(read.exit_code, 0) << read.err;
  EXPECT_EQ(read.out,
            "transmission from SBA 4, directed to SBA 7 (record 1 (genius 76.8) at 0.000000000, character 1)\n"
            "  data 11 22\n"
            "  block to SBA 9: aa bb\n"
            "  data 33\n"
            "transmission from SBA 3, broadcast (record 2 (genius 76.8) at 0.001432292, character 1)\n"
            "  data 5a\n"
            "error at end of record 3: transmission not finished (its Start at record 3 (genius 76.8) at "
            "0.001861979, character 1)\n"
            "2 transmissions, 1 error, 0 characters skipped\n")
      << "one record per transmission, 11 bit times (143.2 us at 76.8 kbaud) per character";
  const auto fields = run_cli("genius decode --pcap " + capture + " --json");
  EXPECT_EQ(fields.exit_code, 0);
  EXPECT_NE(fields.out.find("\"frame.interface_name\":\"genius 76.8\""), std::string::npos) << fields.out;
  EXPECT_NE(fields.out.find("\"trionet_genius.status\":\"ok\""), std::string::npos) << fields.out;
  std::remove(capture.c_str());
}

// A token that is not a character is a lost character: the capture holds a framing error (0xFFFF) in its
// place, so that it never shows a transmission that passes its CRC where the decoder lost one (s37 item 2).
TEST(GeniusCli, WritePcapKeepsABadTokenAsAFramingErrorNotAValidTransmission) {
  const std::string capture = "/tmp/trionet-genius-bad-" + std::to_string(::getpid()) + ".pcapng";
  for (const std::string bad : {"zz", "w:fff"}) {
    const auto written = run_cli("genius decode --write-pcap " + capture, "c:24 11 " + bad + " c:52");
    ASSERT_EQ(written.exit_code, 0) << written.err;
    EXPECT_EQ(written.out.substr(written.out.find("0 transmissions")), "0 transmissions, 1 error, 1 character skipped\n")
        << bad;
    const auto read = run_cli("genius decode --pcap " + capture);
    EXPECT_EQ(read.exit_code, 0) << read.err;
    EXPECT_EQ(read.out.find("transmission from"), std::string::npos) << bad << "\n" << read.out;
    EXPECT_NE(read.out.find("framing_error (more than 11 bits)"), std::string::npos) << bad << "\n" << read.out;
    EXPECT_NE(read.out.find(bad == "zz" ? "(w:ffff)" : "(w:fff)"), std::string::npos) << bad << "\n" << read.out;
  }
  std::remove(capture.c_str());
}

// In text, a record the capture reader rejects is an error like the others, counted in the summary, and a
// record of another network is named, not printed as a JSON event among text lines (s37 item 11).
TEST(GeniusCli, CaptureProblemsAreTextErrorsCountedInTheSummary) {
  const std::string capture = "/tmp/trionet-genius-cut-" + std::to_string(::getpid()) + ".pcapng";
  const auto written = run_cli("genius decode --write-pcap " + capture, "c:24 11 c:52 c:24 11 c:52");
  ASSERT_EQ(written.exit_code, 0) << written.err;
  const auto whole = run_cli("genius decode --pcap " + capture);
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  ASSERT_NE(whole.out.find("\n2 transmissions, 0 errors, 0 characters skipped\n"), std::string::npos) << whole.out;
  {
    std::FILE* f = std::fopen(capture.c_str(), "r+b");
    ASSERT_NE(f, nullptr);
    ASSERT_EQ(std::fseek(f, 0, SEEK_END), 0);
    const long size = std::ftell(f);
    std::fclose(f);
    ASSERT_EQ(::truncate(capture.c_str(), size - 6), 0);  // the last record cut short
  }
  const auto cut = run_cli("genius decode --pcap " + capture);
  EXPECT_EQ(cut.exit_code, 0) << cut.err;
  EXPECT_EQ(cut.out.find('{'), std::string::npos) << cut.out;
  EXPECT_NE(cut.out.find("error at record 2: the capture cannot be read there (truncated)\n"), std::string::npos)
      << cut.out;
  EXPECT_NE(cut.out.find("\n1 transmission, 1 error, 0 characters skipped\n"), std::string::npos) << cut.out;
  const auto fields = run_cli("genius decode --pcap " + capture + " --json");
  EXPECT_NE(fields.out.find("{\"event\":\"capture_error\",\"record\":2,\"reason\":\"truncated\"}"),
            std::string::npos)
      << "--json keeps the event: " << fields.out;

  const auto ring = run_cli("ring simulate example2 --byte-times 20000 --pcap " + capture);
  ASSERT_EQ(ring.exit_code, 0) << ring.err;
  const auto other = run_cli("genius decode --pcap " + capture);
  EXPECT_EQ(other.exit_code, 0) << other.err;
  EXPECT_EQ(other.out.find('{'), std::string::npos) << other.out;
  EXPECT_NE(other.out.find("record 1: not a Genius record (ring), not decoded\n"), std::string::npos) << other.out;
  EXPECT_NE(other.out.find("\n0 transmissions, 0 errors, 0 characters skipped\n"), std::string::npos) << other.out;
  std::remove(capture.c_str());
}

}  // namespace
