// `trionet ring encode|decode` run as a user would, output compared byte for byte.
#include <gtest/gtest.h>

#include "support/run_cli.hpp"

using trionet::test::expect_usage_error;
using trionet::test::run_cli;

TEST(RingCli, EncodeVarGoldenExample) {
  const auto r = run_cli("ring encode var --to 10 --vr 200 --value 99");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out, "8a 48 01 00 00 00 00 30 0c 00 00 00 00 7f 3e 88\n");
  EXPECT_EQ(r.err, "");
}

TEST(RingCli, EncodePrintOffsetMode) {
  EXPECT_EQ(run_cli("ring encode print --to 11 HELLO").out, "91 48 45 4c 4c 4f 90\n");
  EXPECT_EQ(run_cli("ring encode print --to 10 'A B'").out, "89 41 20 42 88\n");
  EXPECT_EQ(run_cli("ring encode offset --to 10 --offset 12").out, "8b 03 88\n");
  EXPECT_EQ(run_cli("ring encode mode --to 12 --mode 127").out, "9c 7f 98\n");
  EXPECT_EQ(run_cli("ring encode mode --to 24 --mode 0").out, "fc 00 f8\n");
}

TEST(RingCli, DecodeGoldenExampleFromArgumentsAndStdin) {
  const std::string expected =
      "{\"event\":\"message\",\"line\":1,\"type\":\"var\",\"hops\":1,\"vr\":200,\"raw\":\"0x0000006300000000\","
      "\"value\":99}\n";
  auto r = run_cli("ring decode 8a 48 01 00 00 00 00 30 0c 00 00 00 00 7f 3e 88");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out, expected);
  r = run_cli("ring decode", "8a4801000000\n0030 0c00000000 7f3e88\n");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out, expected) << "the message is where its header is: line 1";
}

TEST(RingCli, DecodeEveryEventKind) {
  const auto r = run_cli("ring decode",
                         "91 48 49 90 "                                      // char "HI" hops 2
                         "8b 03 88 "                                         // offset 3
                         "9c 7f 98 "                                         // mode 127
                         "8a 48 01 00 00 00 00 30 0c 00 00 00 00 7f 3f 88 "  // CRC error
                         "01 02 "                                            // stray data
                         "88 "                                               // stray eom
                         "89 41 91 42 90 "                                   // interrupted, then "B"
                         "89 41 90 "                                         // eom mismatch
                         "89 88 "                                            // bad length
                         "8c 05 88 "                                         // bad field
                         "8d 01 88 "                                         // unknown type
                         "81 01 80"                                          // zero hops
  );
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out,
            "{\"event\":\"message\",\"line\":1,\"type\":\"char\",\"hops\":2,\"text\":\"HI\"}\n"
            "{\"event\":\"message\",\"line\":1,\"type\":\"offset\",\"hops\":1,\"offset\":3}\n"
            "{\"event\":\"message\",\"line\":1,\"type\":\"mode\",\"hops\":3,\"mode\":127}\n"
            "{\"event\":\"crc_error\",\"line\":1,\"hops\":1,\"vr\":200}\n"
            "{\"event\":\"frame_error\",\"line\":1,\"reason\":\"stray_data\"}\n"
            "{\"event\":\"frame_error\",\"line\":1,\"reason\":\"stray_eom\"}\n"
            "{\"event\":\"frame_error\",\"line\":1,\"reason\":\"interrupted\"}\n"
            "{\"event\":\"message\",\"line\":1,\"type\":\"char\",\"hops\":2,\"text\":\"B\"}\n"
            "{\"event\":\"frame_error\",\"line\":1,\"reason\":\"eom_mismatch\"}\n"
            "{\"event\":\"frame_error\",\"line\":1,\"reason\":\"bad_length\"}\n"
            "{\"event\":\"frame_error\",\"line\":1,\"reason\":\"bad_field\"}\n"
            "{\"event\":\"frame_error\",\"line\":1,\"reason\":\"unknown_type\"}\n"
            "{\"event\":\"frame_error\",\"line\":1,\"reason\":\"zero_hops\"}\n");
}

TEST(RingCli, DecodeEscapesControlCharactersInJson) {
  const auto r = run_cli("ring decode 89 0c 22 5c 41 88");
  EXPECT_EQ(r.out,
            "{\"event\":\"message\",\"line\":1,\"type\":\"char\",\"hops\":1,\"text\":\"\\u000c\\\"\\\\A\"}\n");
}

TEST(RingCli, DecodeNegativeAndFractionalValues) {
  const auto r = run_cli("ring decode $(" TRIONET_CLI_PATH " ring encode var --to 10 --vr 1 --value -2.5)");
  EXPECT_EQ(r.out,
            "{\"event\":\"message\",\"line\":1,\"type\":\"var\",\"hops\":1,\"vr\":1,\"raw\":\"0xfffffffd80000000\","
            "\"value\":-2.5}\n");
}

// Whole values print as their digits, at any size (never an exponent such as 1e+05); the sign of a negative
// value is kept.
TEST(RingCli, DecodeWholeValuesAtTheEdgesOfTheirShortForm) {
  const std::pair<const char*, const char*> cases[] = {
      {"0", "0"},         {"7", "7"},         {"-7", "-7"},         {"99999", "99999"},
      {"-99999", "-99999"}, {"100000", "100000"}, {"-100000", "-100000"}, {"123456", "123456"},
      {"2147483647", "2147483647"}, {"-2147483648", "-2147483648"}, {"0.5", "0.5"}, {"99999.5", "99999.5"}};
  for (const auto& [given, printed] : cases) {
    const auto r = run_cli(std::string("ring decode $(" TRIONET_CLI_PATH " ring encode var --to 10 --vr 1 --value ") +
                           given + ")");
    EXPECT_NE(r.out.find(std::string("\"value\":") + printed + "}"), std::string::npos) << given << ": " << r.out;
  }
}

// --value is read exactly to Q32.32 (docs/protocol.md 1.3), not through a double: the documented top of the
// range is accepted, and digits beyond a double's 53 bits count.
std::string encoded_raw(const std::string& value) {
  const auto r = run_cli("ring decode $(" TRIONET_CLI_PATH " ring encode var --to 10 --vr 1 --value " + value + ")");
  const std::size_t at = r.out.find("\"raw\":\"");
  return at == std::string::npos ? "none: " + r.out : r.out.substr(at + 7, 18);
}

TEST(RingCli, EncodeVarValueIsExactToTheNearest2ToTheMinus32) {
  EXPECT_EQ(encoded_raw("2147483647.99999999977"), "0x7fffffffffffffff");  // the bound of docs/protocol.md 1.3
  EXPECT_EQ(encoded_raw("2147483647.9999999998"), "0x7fffffffffffffff");
  EXPECT_EQ(encoded_raw("2147483647.9999999"), "0x7ffffffffffffe53");
  EXPECT_EQ(encoded_raw("2147483647.5000001"), "0x7fffffff800001ad");
  EXPECT_EQ(encoded_raw("123456789.123456789"), "0x075bcd151f9add37");
  EXPECT_EQ(encoded_raw("-0.5"), "0xffffffff80000000");
  EXPECT_EQ(encoded_raw("-2147483648"), "0x8000000000000000");
  EXPECT_EQ(encoded_raw("-2147483648.0000000001"), "0x8000000000000000");
  EXPECT_EQ(encoded_raw("0.000000000116415321826934814453125"), "0x0000000000000001");  // a tie: away from 0
  EXPECT_EQ(encoded_raw("-0.000000000116415321826934814453125"), "0xffffffffffffffff");
  EXPECT_EQ(encoded_raw("1e-10"), "0x0000000000000000");
  EXPECT_EQ(encoded_raw("2.5E-4"), "0x000000000010624e");
  EXPECT_EQ(encoded_raw("+1e3"), "0x000003e800000000");
  EXPECT_EQ(encoded_raw("0." + std::string(60, '3')), "0x0000000055555555");
  const auto golden = run_cli("ring encode var --to 10 --vr 200 --value 0.0000000000000000099e19");
  EXPECT_EQ(golden.out, "8a 48 01 00 00 00 00 30 0c 00 00 00 00 7f 3e 88\n") << golden.err;
}

TEST(RingCli, EncodeVarValueOutsideTheRangeOrNotANumberIsRefused) {
  const std::string range = "outside the Q32.32 range [-2147483648, 2147483647.99999999977]";
  expect_usage_error("ring encode var --to 10 --vr 1 --value 2147483647.9999999999", range);
  expect_usage_error("ring encode var --to 10 --vr 1 --value 2147483648", range);
  expect_usage_error("ring encode var --to 10 --vr 1 --value -2147483648.0000000002", range);
  expect_usage_error("ring encode var --to 10 --vr 1 --value 1e400", range);
  for (const char* text : {"nan", "inf", "-inf", "0x10", "1e", "1.5x", "' 1'", "''", "."})
    expect_usage_error(std::string("ring encode var --to 10 --vr 1 --value ") + text, "must be a real number");
  expect_usage_error("ring encode var --to 10 --vr 1 --value 0." + std::string(999, '1'), "at most 1000");
  const auto longest = run_cli("ring encode var --to 10 --vr 1 --value 0." + std::string(998, '0'));
  EXPECT_EQ(longest.exit_code, 0) << longest.err;
}

TEST(RingCli, DecodeEmptyInputPrintsNothing) {
  const auto r = run_cli("ring decode", "");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out, "");
}

TEST(RingCli, BadHexIsAnEventWithItsLineAndDecodingGoesOn) {
  const auto r = run_cli("ring decode", "89 41 88\n8a zz 01\n8a4 8b 03 88\n0x8b 8b 03 88\n\xc3\xa9 8b 03 88");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(r.out,
            "{\"event\":\"message\",\"line\":1,\"type\":\"char\",\"hops\":1,\"text\":\"A\"}\n"
            "{\"event\":\"error\",\"line\":2,\"reason\":\"not_hex\",\"character\":\"z\"}\n"
            "{\"event\":\"frame_error\",\"line\":2,\"reason\":\"interrupted\"}\n"
            "{\"event\":\"error\",\"line\":3,\"reason\":\"odd_digits\"}\n"
            "{\"event\":\"frame_error\",\"line\":3,\"reason\":\"interrupted\"}\n"
            "{\"event\":\"message\",\"line\":3,\"type\":\"offset\",\"hops\":1,\"offset\":3}\n"
            "{\"event\":\"error\",\"line\":4,\"reason\":\"not_hex\",\"character\":\"x\"}\n"
            "{\"event\":\"message\",\"line\":4,\"type\":\"offset\",\"hops\":1,\"offset\":3}\n"
            "{\"event\":\"error\",\"line\":5,\"reason\":\"not_hex\",\"character\":\"\\u00c3\"}\n"
            "{\"event\":\"message\",\"line\":5,\"type\":\"offset\",\"hops\":1,\"offset\":3}\n")
      << "8a4: the byte 8a, then a lone digit; 0x8b: the word is skipped from the x on";
}

TEST(RingCli, UnfinishedMessageAtTheEndIsReported) {
  const auto r = run_cli("ring decode", "8b 03 88\n91 48 49");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out,
            "{\"event\":\"message\",\"line\":1,\"type\":\"offset\",\"hops\":1,\"offset\":3}\n"
            "{\"event\":\"unfinished\",\"line\":2}\n");
}

TEST(RingCli, RawBytesWithPositions) {
  // Raw input is what a serial port gives: byte 0 a stray byte, 1.. an offset message, then "HI" cut short.
  // Regression: the byte's place was keyed "offset", as is a keypad offset message's offset: one object held
  // the key twice, and a JSON reader kept only the second.
  const auto r = run_cli("ring decode --raw", std::string("\x01\x8b\x03\x88\x91\x48\x49", 7));
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(r.out,
            "{\"event\":\"frame_error\",\"position\":0,\"reason\":\"stray_data\"}\n"
            "{\"event\":\"message\",\"position\":1,\"type\":\"offset\",\"hops\":1,\"offset\":3}\n"
            "{\"event\":\"unfinished\",\"position\":4}\n");
  const auto golden = run_cli("ring decode --raw < /dev/null");
  EXPECT_EQ(golden.exit_code, 0);
  EXPECT_EQ(golden.out, "");
}

TEST(RingCli, EncodePrintRefusesWhatTheDecoderRejects) {
  const std::string longest(256, 'a');
  const auto ok = run_cli("ring encode print --to 10 " + longest);
  ASSERT_EQ(ok.exit_code, 0);
  const auto back = run_cli("ring decode", ok.out);
  EXPECT_NE(back.out.find("\"type\":\"char\""), std::string::npos) << back.out;
  expect_usage_error("ring encode print --to 10 " + longest + "a", "at most 256");
}

TEST(RingCli, BadArgumentsAreUsageErrors) {
  expect_usage_error("ring encode print --to 9 HI");
  expect_usage_error("ring encode print --to 25 HI");
  expect_usage_error("ring encode print --to 10");
  expect_usage_error("ring encode print --to 10 ''");
  expect_usage_error("ring encode print --to 10 \"$(printf '\\303\\251')\"");  // UTF-8 e-acute
  expect_usage_error("ring encode var --to 10 --vr 16384 --value 1");
  expect_usage_error("ring encode var --to 10 --vr 1 --value 2147483648");
  expect_usage_error("ring encode var --to 10 --vr 1 --value abc");
  expect_usage_error("ring encode var --to 10 --vr 1");
  expect_usage_error("ring encode offset --to 10 --offset 9");
  expect_usage_error("ring encode mode --to 10 --mode 1");
  expect_usage_error("ring encode mode --to 10 --mode 0 --vr 3");
  expect_usage_error("ring encode bogus --to 10");
  expect_usage_error("ring bogus");
  expect_usage_error("ring encode var --to 10 --to 11 --vr 1 --value 1");
  expect_usage_error("ring decode --raw 8a");
  expect_usage_error("ring decode --json");
  expect_usage_error("ring decode --pcap");
  expect_usage_error("ring decode --bogus");
}

TEST(RingCli, ErrorMessagesNameTheProblem) {
  EXPECT_NE(run_cli("ring encode print --to 9 HI").err.find("--to"), std::string::npos);
  EXPECT_NE(run_cli("ring encode var --to 10 --vr 1 --value 3e9").err.find("range"), std::string::npos);
}

TEST(RingCli, AMissingCaptureIsAnIoFailure) {
  const auto r = run_cli("ring decode --pcap /nonexistent/capture.pcapng");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("cannot open"), std::string::npos) << r.err;
}

TEST(RingCli, HelpAndVersionEverywhere) {
  for (const char* command : {"ring encode var --help", "ring decode --help", "ring simulate --help", "ring --help",
                              "genius encode --help", "genius decode --help", "genius timing --help", "--help"}) {
    const auto r = run_cli(command);
    EXPECT_EQ(r.exit_code, 0) << command;
    EXPECT_EQ(r.out.rfind("usage: trionet", 0), 0u) << command << ": " << r.out;
    EXPECT_EQ(r.err, "") << command;
  }
  for (const char* command : {"--version", "ring --version", "can --version", "genius --version"}) {
    const auto r = run_cli(command);
    EXPECT_EQ(r.exit_code, 0) << command;
    EXPECT_EQ(r.out.rfind("trionet ", 0), 0u) << command << ": " << r.out;
  }
  for (const char* part : {"ring", "can", "genius"}) {  // no command: the same for every part
    const auto r = run_cli(part);
    EXPECT_EQ(r.exit_code, 2) << part;
    EXPECT_EQ(r.out, "") << part;
    EXPECT_EQ(r.err.rfind(std::string("trionet: ") + part + " needs a command", 0), 0u) << r.err;
  }
}

TEST(RingCli, SimulatePcapThenDecodeIt) {
  const std::string capture = "/tmp/trionet-ring-" + std::to_string(::getpid()) + ".pcapng";
  const auto simulated = run_cli("ring simulate example1 --pcap " + capture);
  ASSERT_EQ(simulated.exit_code, 0) << simulated.err;
  const auto r = run_cli("ring decode --pcap " + capture);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("{\"event\":\"message\",\"record\":1,\"interface_id\":0,"
                        "\"interface\":\"link 0: node 1 (mc) -> node 2 (keypad)\",\"time\":\"0.000080000\",", 0),
            0u)
      << r.out.substr(0, 300);
  EXPECT_NE(r.out.find("\"interface\":\"link 2: node 3 (keypad) -> node 1 (mc)\""), std::string::npos);
  EXPECT_EQ(r.out.find("frame_error"), std::string::npos) << "a simulated ring without faults";
  std::remove(capture.c_str());
  const auto missing_dir = run_cli("ring simulate example1 --pcap /nonexistent/dir/x.pcapng");
  EXPECT_EQ(missing_dir.exit_code, 1);
}
