// `trionet ring learn crc|layout`, `trionet genius learn crc`, `trionet profile show|header` and `--profile`
// run as a user would: captures made by the library's encoders under hidden parameters are learned back, the
// profile written, and a separate capture decoded with it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "learn/crc_catalogue.hpp"
#include "learn/profile.hpp"
#include "learn/ring_capture.hpp"
#include "support/live_process.hpp"
#include "support/run_cli.hpp"
#include "support/sent_variables.hpp"
#include "trionet/host/pcapng.hpp"
#include "trionet/host/text.hpp"
#include "trionet/genius/crc6.hpp"
#include "trionet/ring/keypad.hpp"

namespace {

using trionet::test::expect_usage_error;
using trionet::test::run_cli;
using trionet::test::slurp;
namespace learn = trionet::learn;
using trionet::test::random_sent;
namespace ring = trionet::ring;

std::string temp_path(const std::string& name) {
  return "/tmp/trionet-learn-cli-" + std::to_string(::getpid()) + "-" + name;
}

void write_file(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// The whole frame of each transfer (header, 14 data bytes, end of message; hops 1) as hex lines.
std::string hex_frames(const std::vector<learn::variable_frame>& frames) {
  std::string out;
  char pair[4];
  for (const learn::variable_frame& f : frames) {
    out += "8a";
    for (std::uint8_t b : f) {
      std::snprintf(pair, sizeof pair, " %02x", b);
      out += pair;
    }
    out += " 88\n";
  }
  return out;
}

std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// Learns the CRC from 8 frames with `ring learn crc -o`, then decodes 100 other frames with the profile.
void learn_back(const ring::crc16_parameters& hidden, const ring::variable_layout_parameters& layout,
                std::mt19937_64& rng) {
  const std::string capture = temp_path("capture.hex"), profile = temp_path("profile.json");
  write_file(capture, hex_frames(learn::encode_capture(random_sent(rng, 8), hidden, layout)));
  const auto r = run_cli("ring learn crc " + capture + " -o " + profile);
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(
      r.out.find("{\"event\":\"result\",\"status\":\"ok\",\"frames\":8,\"skipped_bytes\":0,\"classes\":1"),
      std::string::npos)
      << r.out;
  const learn::profile_result written = learn::read_profile(slurp(profile));
  ASSERT_TRUE(written) << slurp(profile);
  // Every validation frame decodes with the learned CRC (any member of the hidden CRC's class will do).
  const std::vector<learn::sent_variable> validation = random_sent(rng, 100);
  const std::string frames = hex_frames(learn::encode_capture(validation, hidden, layout));
  const auto decoded = run_cli("ring decode --profile " + profile, frames);
  EXPECT_EQ(decoded.exit_code, 0);
  EXPECT_EQ(count_of(decoded.out, "\"event\":\"message\""), 100u) << decoded.out.substr(0, 400);
  EXPECT_EQ(count_of(decoded.out, "crc_error"), 0u);
  std::remove(capture.c_str());
  std::remove(profile.c_str());
}

TEST(LearnCli, RingCrcLearnedBackForCatalogueAndRandomCrcs) {
  std::mt19937_64 rng(16);
  std::size_t tried = 0;
  for (const learn::catalogue_entry& e : learn::crc_catalogue()) {
    if (e.width != 16) continue;
    if (tried++ % 4 != 0) continue;  // every fourth: the library's tests and figures run them all
    SCOPED_TRACE(e.name);
    learn_back({e.polynomial, e.initial, e.reflect_in, e.reflect_out, e.xor_out}, {}, rng);
  }
  EXPECT_GT(tried, 20u);
  for (int i = 0; i < 4; ++i) {
    const ring::crc16_parameters hidden{static_cast<std::uint16_t>(rng() | 1U),
                                        static_cast<std::uint16_t>(rng()), (i & 1) != 0, (i & 2) != 0,
                                        static_cast<std::uint16_t>(rng())};
    SCOPED_TRACE(hidden.polynomial);
    learn_back(hidden, {}, rng);
  }
}

TEST(LearnCli, WithoutTheLearnedProfileEveryFrameIsACrcError) {
  const ring::crc16_parameters modbus{0x8005, 0xFFFF, true, true, 0};
  std::mt19937_64 rng(1);
  const auto r = run_cli("ring decode", hex_frames(learn::encode_capture(random_sent(rng, 10), modbus)));
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(count_of(r.out, "crc_error"), 10u);
}

TEST(LearnCli, RingCrcNamesTheCatalogueEntryAndComposesWithAProfile) {
  std::mt19937_64 rng(2);
  const ring::crc16_parameters modbus{0x8005, 0xFFFF, true, true, 0};
  const ring::variable_layout_parameters msf{ring::group_order::most_significant_first,
                                             ring::group_order::most_significant_first,
                                             ring::crc_input::least_significant_first};
  // A CRC over the bytes in the default order is learned with the layout the profile gives.
  learn::profile p;
  p.name = "plant";
  p.ring.layout = msf;
  const std::string base = temp_path("base.json"), out = temp_path("out.json");
  write_file(base, learn::write_profile(p));
  const std::string frames = hex_frames(learn::encode_capture(random_sent(rng, 6), modbus, msf));
  const auto r = run_cli("ring learn crc --profile " + base + " -o " + out, frames);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(
      r.out.find("\"polynomial\":\"0x8005\",\"initial\":\"0xffff\",\"reflect_in\":true,\"reflect_out\":true,"
                 "\"xor_out\":\"0x0000\",\"name\":\"CRC-16/MODBUS\""),
      std::string::npos)
      << r.out;
  const learn::profile_result written = learn::read_profile(slurp(out));
  ASSERT_TRUE(written);
  p.ring.crc = modbus;
  EXPECT_TRUE(written.value == p) << "the profile in effect, with the CRC found";
  std::remove(base.c_str());
  std::remove(out.c_str());
}

TEST(LearnCli, RingCrcFromTooFewFramesListsOrRefusesAndExits3) {
  std::mt19937_64 rng(3);
  const ring::crc16_parameters ccitt{};
  const auto one = run_cli("ring learn crc", hex_frames(learn::encode_capture(random_sent(rng, 1), ccitt)));
  EXPECT_EQ(one.exit_code, 3);
  EXPECT_NE(one.out.find("\"status\":\"too_many_candidates\",\"frames\":1"), std::string::npos) << one.out;
  const auto none = run_cli("ring learn crc", "91 48 49 90\n");  // a character transfer only
  EXPECT_EQ(none.exit_code, 3);
  EXPECT_NE(none.out.find("\"status\":\"no_frames\",\"frames\":0,\"skipped_bytes\":4"), std::string::npos)
      << none.out;
  const std::string profile = temp_path("not-written.json");
  const auto two =
      run_cli("ring learn crc -o " + profile, hex_frames(learn::encode_capture(random_sent(rng, 2), ccitt)));
  EXPECT_EQ(two.exit_code, 3);
  EXPECT_NE(two.out.find("\"status\":\"ambiguous\""), std::string::npos) << two.out;
  EXPECT_GT(count_of(two.out, "\"event\":\"crc\""), 1u);
  EXPECT_FALSE(std::ifstream(profile).good()) << "no profile is written when nothing was learned";
}

TEST(LearnCli, RingCrcReadsRawBytesAndCaptures) {
  std::mt19937_64 rng(4);
  const ring::crc16_parameters xmodem{0x1021, 0, false, false, 0};
  const std::vector<learn::variable_frame> frames = learn::encode_capture(random_sent(rng, 8), xmodem);
  std::string raw;
  std::vector<std::vector<std::uint8_t>> records;
  for (const learn::variable_frame& f : frames) {
    std::vector<std::uint8_t> record = {0x8a};
    record.insert(record.end(), f.begin(), f.end());
    record.push_back(0x88);
    raw.append(record.begin(), record.end());
    records.push_back(record);
  }
  const auto from_raw = run_cli("ring learn crc --raw", raw);
  EXPECT_EQ(from_raw.exit_code, 0) << from_raw.err;
  EXPECT_NE(from_raw.out.find("\"name\":\"CRC-16/XMODEM\""), std::string::npos) << from_raw.out;

  const std::string pcap = temp_path("ring.pcapng");
  {
    std::ofstream file(pcap, std::ios::binary);
    trionet::host::pcapng_writer writer(file);
    const auto ring_link = writer.add_interface("ring", trionet::host::capture_network::ring);
    ASSERT_TRUE(ring_link);
    std::uint64_t t = 0;
    for (const auto& record : records) {
      ASSERT_EQ(writer.write(ring_link.id, t += 1000, trionet::byte_view(record.data(), record.size())),
                trionet::host::pcapng_write_status::ok);
    }
  }
  const auto from_pcap = run_cli("ring learn crc --pcap " + pcap);
  EXPECT_EQ(from_pcap.exit_code, 0) << from_pcap.err;
  EXPECT_NE(from_pcap.out.find("\"name\":\"CRC-16/XMODEM\""), std::string::npos) << from_pcap.out;
  std::remove(pcap.c_str());
  const auto not_pcap = run_cli("ring learn crc --pcap /nonexistent/capture.pcapng");
  EXPECT_EQ(not_pcap.exit_code, 1);
}

// The layout from 4 frames, for every group-order pair and both CRC inputs; then the whole profile decodes.
TEST(LearnCli, RingLayoutLearnedForEveryOrderFromFourFrames) {
  std::mt19937_64 rng(5);
  const ring::crc16_parameters hidden{0x3D65, 0, true, true, 0xFFFF};  // CRC-16/DNP
  const std::string crc_profile = temp_path("crc.json"), full = temp_path("full.json"),
                    sent_list = temp_path("sent.txt");
  learn::profile p;
  p.ring.crc = hidden;
  write_file(crc_profile, learn::write_profile(p));
  for (int orders = 0; orders < 4; ++orders) {
    for (int input = 0; input < 2; ++input) {
      const ring::variable_layout_parameters layout{
          (orders & 2) != 0 ? ring::group_order::most_significant_first
                            : ring::group_order::least_significant_first,
          (orders & 1) != 0 ? ring::group_order::most_significant_first
                            : ring::group_order::least_significant_first,
          input != 0 ? ring::crc_input::least_significant_first : ring::crc_input::as_sent};
      if (orders == 0 && input != 0) continue;  // the same bytes either way
      SCOPED_TRACE(orders * 2 + input);
      std::vector<learn::sent_variable> sent = random_sent(rng, 4);
      std::string list = "# VR VALUE\n";
      for (auto& s : sent) {
        s.value = static_cast<std::int64_t>(rng() % 2000001) - 1000000;
        s.value *= std::int64_t{1} << 30;  // quarters: exact in decimal
        list +=
            std::to_string(s.vr) + " " + std::to_string(static_cast<double>(s.value) / 4294967296.0) + "\n";
      }
      write_file(sent_list, list);
      const std::string frames = hex_frames(learn::encode_capture(sent, hidden, layout));
      const auto r = run_cli(
          "ring learn layout --sent " + sent_list + " --profile " + crc_profile + " -o " + full, frames);
      EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
      EXPECT_NE(r.out.find(std::string("\"vr_group_order\":\"") + ring::to_string(layout.vr) +
                           "\",\"value_group_order\":\"" + ring::to_string(layout.value) +
                           "\",\"crc_input\":\"" + ring::to_string(layout.crc) + "\""),
                std::string::npos)
          << r.out;
      const learn::profile_result written = learn::read_profile(slurp(full));
      ASSERT_TRUE(written);
      EXPECT_EQ(written.value.ring.crc, hidden);
      EXPECT_EQ(written.value.ring.layout, layout);
      const auto decoded = run_cli("ring decode --profile " + full, frames);
      EXPECT_EQ(count_of(decoded.out, "\"event\":\"message\""), 4u) << decoded.out;
      EXPECT_NE(decoded.out.find("\"vr\":" + std::to_string(sent[0].vr) + ","), std::string::npos)
          << decoded.out;
    }
  }
  std::remove(crc_profile.c_str());
  std::remove(full.c_str());
  std::remove(sent_list.c_str());
}

TEST(LearnCli, RingLayoutShowsTheFirstFrameThatContradicts) {
  const std::string sent_list = temp_path("sent-wrong.txt");
  write_file(sent_list, "200 99\n7 1.5\n");
  const std::string frames =
      "8a 48 01 00 00 00 00 30 0c 00 00 00 00 7f 3e 88\n"   // VR 200 = 99 (docs/protocol.md's example)
      "8a 48 01 00 00 00 00 30 0c 00 00 00 00 7f 3e 88\n";  // the same again, but 7 = 1.5 was sent
  const auto r = run_cli("ring learn layout --sent " + sent_list, frames);
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(
      r.out.find(
          "{\"event\":\"order\",\"vr_group_order\":\"least_significant_first\",\"value_group_order\":"
          "\"least_significant_first\",\"fits\":false,\"first_contradiction\":2,\"frame\":\"48 01 00 00 "
          "00 00 30 0c 00 00 00 00 7f 3e\",\"reads_vr\":200,\"reads_value\":99,\"sent_vr\":7,"
          "\"sent_value\":1.5}"),
      std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("\"status\":\"no_layout_fits\""), std::string::npos) << r.out;
  write_file(sent_list, "200 99\n");
  const auto more = run_cli("ring learn layout --sent " + sent_list, frames);
  EXPECT_EQ(more.exit_code, 3);
  EXPECT_NE(more.out.find("\"status\":\"count_mismatch\",\"frames\":2,\"sent\":1"), std::string::npos)
      << more.out;
  std::remove(sent_list.c_str());
}

TEST(LearnCli, GeniusCrcLearnedFromEncodedTransmissions) {
  std::string tokens;
  for (const char* t : {"--from 1 --to 2 11", "--from 3 --to 4 a1b2c3d4 block:5:0102",
                        "--from 7 --broadcast 010203040506070809", "--from 9 --to 1 ff"}) {
    const auto encoded = run_cli(std::string("genius encode ") + t);
    ASSERT_EQ(encoded.exit_code, 0) << encoded.err;
    tokens += encoded.out;
  }
  learn::profile p;
  p.genius.crc = {0x19, 0, false, false, 0};  // overwritten by what is learned
  const std::string base = temp_path("genius-base.json"), out = temp_path("genius.json");
  write_file(base, learn::write_profile(p));
  const auto r = run_cli("genius learn crc --profile " + base + " -o " + out, tokens);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(
      r.out.find(
          "{\"event\":\"crc\",\"class\":1,\"polynomial\":\"0x03\",\"initial\":\"0x00\",\"reflect_in\":true,"
          "\"reflect_out\":true,\"xor_out\":\"0x00\",\"name\":\"CRC-6/G-704\",\"members\":1}"),
      std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("\"status\":\"ok\",\"samples\":5,\"skipped_characters\":0"), std::string::npos)
      << r.out;
  const learn::profile_result written = learn::read_profile(slurp(out));
  ASSERT_TRUE(written);
  EXPECT_EQ(written.value.genius.crc, trionet::genius::crc6_parameters{});
  // The same as 2-byte words (--raw), the 11-bit word big-endian.
  std::string raw;
  for (const char* t : {"--from 1 --to 2 11", "--from 3 --to 4 a1b2c3d4 block:5:0102",
                        "--from 7 --broadcast 010203040506070809", "--from 9 --to 1 ff"}) {
    const std::string words = run_cli(std::string("genius encode --words ") + t).out;
    for (std::size_t at = words.find("w:"); at != std::string::npos; at = words.find("w:", at + 1)) {
      const unsigned long w = std::stoul(words.substr(at + 2, 3), nullptr, 16);
      raw += static_cast<char>(w >> 8U);
      raw += static_cast<char>(w & 0xFFU);
    }
  }
  const auto from_raw = run_cli("genius learn crc --raw", raw);
  EXPECT_EQ(from_raw.exit_code, 0) << from_raw.err;
  EXPECT_NE(from_raw.out.find("\"name\":\"CRC-6/G-704\""), std::string::npos) << from_raw.out;
  expect_usage_error("genius learn crc --raw", "odd number of bytes", raw.substr(1));
  // And from a capture `genius decode --write-pcap` wrote.
  const std::string pcap = temp_path("genius.pcapng");
  ASSERT_EQ(run_cli("genius decode --write-pcap " + pcap, tokens).exit_code, 0);
  const auto from_pcap = run_cli("genius learn crc --pcap " + pcap);
  EXPECT_EQ(from_pcap.exit_code, 0) << from_pcap.err;
  EXPECT_NE(from_pcap.out.find("\"status\":\"ok\",\"samples\":5,"), std::string::npos) << from_pcap.out;
  std::remove(pcap.c_str());
  const auto one = run_cli("genius learn crc c:01 02 11 c:5d");
  EXPECT_EQ(one.exit_code, 2) << "tokens come from FILE or standard input, not the arguments";
  const auto few = run_cli("genius learn crc", "c:01 02 11 c:5d\n");
  EXPECT_EQ(few.exit_code, 3);
  EXPECT_NE(few.out.find("\"status\":\"too_many_candidates\",\"samples\":1"), std::string::npos) << few.out;
  std::remove(base.c_str());
  std::remove(out.c_str());
}

// genius encode and decode use the profile's CRC-6: what is encoded with a profile decodes with it (hex
// tokens and a capture) and fails the CRC check without it; and a CRC learned from such transmissions is a
// profile that decodes them.
TEST(LearnCli, GeniusEncodeAndDecodeUseTheProfileCrc) {
  learn::profile darc;
  darc.genius.crc = {0x19, 0x00, true, true, 0x00};  // CRC-6/DARC
  const std::string profile = temp_path("genius-darc.json"), learned = temp_path("genius-learned.json");
  write_file(profile, learn::write_profile(darc));
  const auto example = run_cli("genius encode --profile " + profile + " --from 4 --to 7 1122 block:9:aabb 33");
  ASSERT_EQ(example.exit_code, 0) << example.err;
  EXPECT_NE(example.out, run_cli("genius encode --from 4 --to 7 1122 block:9:aabb 33").out);
  const auto decoded = run_cli("genius decode --profile " + profile, example.out);
  EXPECT_EQ(decoded.exit_code, 0);
  EXPECT_EQ(decoded.out,
            "transmission from SBA 4, directed to SBA 7 (line 1, character 1)\n"
            "  data 11 22\n"
            "  block to SBA 9: aa bb\n"
            "  data 33\n"
            "1 transmission, 0 errors, 0 characters skipped\n");
  const auto by_default = run_cli("genius decode", example.out);
  EXPECT_EQ(by_default.exit_code, 0);
  EXPECT_NE(by_default.out.find("block_crc_mismatch"), std::string::npos) << by_default.out;
  EXPECT_NE(by_default.out.find("0 transmissions, 1 error,"), std::string::npos) << by_default.out;

  std::string tokens;
  for (const char* t : {"--from 1 --to 2 11", "--from 3 --to 4 a1b2c3d4 block:5:0102",
                        "--from 7 --broadcast 010203040506070809", "--from 9 --to 1 ff", "--from 2 --to 30 5a5a"}) {
    const auto encoded = run_cli("genius encode --profile " + profile + " " + t);
    ASSERT_EQ(encoded.exit_code, 0) << encoded.err;
    tokens += encoded.out;
  }
  const auto r = run_cli("genius learn crc -o " + learned, tokens);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const learn::profile_result written = learn::read_profile(slurp(learned));
  ASSERT_TRUE(written);
  EXPECT_EQ(written.value.genius.crc, darc.genius.crc);
  const auto with_learned = run_cli("genius decode --profile " + learned, tokens);
  EXPECT_NE(with_learned.out.find("5 transmissions, 0 errors, 0 characters skipped"), std::string::npos)
      << with_learned.out;
  const auto without = run_cli("genius decode", tokens);
  EXPECT_NE(without.out.find("0 transmissions, 5 errors,"), std::string::npos) << without.out;
  // A capture of them: decoded with the profile, CRC errors without.
  const std::string pcap = temp_path("genius-darc.pcapng");
  ASSERT_EQ(run_cli("genius decode --profile " + learned + " --write-pcap " + pcap, tokens).exit_code, 0);
  EXPECT_NE(run_cli("genius decode --profile " + learned + " --pcap " + pcap).out.find("5 transmissions, 0 errors"),
            std::string::npos);
  EXPECT_NE(run_cli("genius decode --pcap " + pcap).out.find("0 transmissions, 5 errors"), std::string::npos);
  std::remove(pcap.c_str());
  std::remove(profile.c_str());
  std::remove(learned.c_str());
}

// The ring's character capacities are compile-time: the tool applies a smaller max_characters to the text it
// encodes, and refuses (exit 2, naming the field, its value and what it supports) what it cannot honour.
TEST(LearnCli, RingCharacterCapacitiesAreAppliedOrRefused) {
  const std::string small = temp_path("max8.json"), large = temp_path("max300.json"), buffer = temp_path("rb64.json");
  learn::profile p;
  p.ring.max_characters = 8;
  write_file(small, learn::write_profile(p));
  p.ring.max_characters = 300;
  write_file(large, learn::write_profile(p));
  p = learn::profile{};
  p.ring.receive_buffer = 64;
  write_file(buffer, learn::write_profile(p));

  // Applied: ring encode and ring send refuse longer text.
  const auto eight = run_cli("ring encode print --to 10 12345678 --profile " + small);
  EXPECT_EQ(eight.exit_code, 0) << eight.err;
  EXPECT_EQ(eight.out, "89 31 32 33 34 35 36 37 38 88\n");
  expect_usage_error("ring encode print --to 10 123456789 --profile " + small,
                     "TEXT has 9 characters; a character transfer carries at most 8 (docs/protocol.md 1.4, the "
                     "profile's ring.max_characters)");
  expect_usage_error("ring send - print --to 10 123456789 --profile " + small, "carries at most 8");
  // Refused: more than the tool's 256, and any other value where a decoder or node is built for 256.
  const std::string firmware = " (a compile-time capacity; build a firmware with this profile from `trionet profile header`)";
  expect_usage_error("ring encode print --to 10 x --profile " + large,
                     "profile " + large + ": ring.max_characters is 300: `trionet ring encode` supports at most 256" + firmware);
  for (const char* command : {"ring decode 00", "ring monitor /dev/null", "ring join /dev/null --as keypad",
                              "ring simulate example1"}) {
    const std::string name = std::string(command).substr(0, std::string(command).find(' ', 5));
    expect_usage_error(std::string(command) + " --profile " + small,
                       "profile " + small + ": ring.max_characters is 8: `trionet " + name + "` supports only 256" + firmware);
  }
  expect_usage_error("ring simulate example1 --profile " + buffer,
                     "ring.receive_buffer is 64: `trionet ring simulate` supports only 256");
  expect_usage_error("ring join /dev/null --as mc --profile " + buffer,
                     "ring.receive_buffer is 64: `trionet ring join` supports only 256");
  // A receive buffer does not concern a decoder or a keypad.
  EXPECT_EQ(run_cli("ring decode 00 --profile " + buffer).exit_code, 0);
  EXPECT_EQ(run_cli("ring encode print --to 10 x --profile " + buffer).exit_code, 0);
  std::remove(small.c_str());
  std::remove(large.c_str());
  std::remove(buffer.c_str());
}

TEST(LearnCli, BadInputAndArgumentsNameTheProblem) {
  expect_usage_error("ring learn", "ring learn needs what to learn: crc or layout");
  expect_usage_error("ring learn crcs", "unknown ring learn kind 'crcs' (expected crc or layout)");
  expect_usage_error("ring learn crc", "line 2: '8x' is not hex bytes", "8a 48\n8x\n");
  expect_usage_error("ring learn crc --pcap a.pcapng b.hex", "--pcap reads a capture file");
  expect_usage_error("ring learn crc --sent list.txt", "--sent applies to ring learn layout");
  expect_usage_error("ring learn layout", "ring learn layout needs --sent LIST");
  expect_usage_error("ring learn crc -o", "option -o needs a value");
  expect_usage_error("genius learn crc", "line 1: 'c:zz' is not a character", "c:01 c:zz\n");
  expect_usage_error("genius learn", "genius learn needs what to learn: crc");
  const std::string sent_list = temp_path("sent-bad.txt");
  write_file(sent_list, "1 2\n3 x\n");
  expect_usage_error("ring learn layout --sent " + sent_list, "line 2: syntax", "");
  write_file(sent_list, "16384 0\n");
  expect_usage_error("ring learn layout --sent " + sent_list, "line 1: vr_out_of_range", "");
  std::remove(sent_list.c_str());
  const auto missing = run_cli("ring learn crc /nonexistent/capture.hex");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.err.find("/nonexistent/capture.hex"), std::string::npos) << missing.err;
  const auto no_list = run_cli("ring learn layout --sent /nonexistent/sent.txt");
  EXPECT_EQ(no_list.exit_code, 1);
  // Input is bounded: 64 MiB and one byte is refused, not held.
  const std::string big = temp_path("big.raw");
  { std::ofstream(big, std::ios::binary).put('\0'); }
  std::filesystem::resize_file(big, (std::uintmax_t{64} << 20U) + 1U);
  trionet::test::expect_io_error("ring learn crc --raw " + big, "is larger than 67108864 bytes (64 MiB)");
  std::filesystem::resize_file(big, std::uintmax_t{64} << 20U);
  EXPECT_EQ(run_cli("ring learn crc --raw " + big).exit_code, 3) << "64 MiB is read: no frames in it";
  std::remove(big.c_str());
}

TEST(LearnCli, EveryCommandTakesProfileAndABadOneIsNamed) {
  const std::string bad = temp_path("bad.json"), nodes = temp_path("nodes.json");
  write_file(bad, "{\"trionet_profile\": 1,\n \"ring\": {\"crc\": {\"polynomial\": \"0x10000\"}}}\n");
  expect_usage_error("ring decode 00 --profile " + bad,
                     "profile " + bad + ": out_of_range at ring.crc.polynomial (line 2, column 33)");
  expect_usage_error("can table --profile " + bad, "out_of_range at ring.crc.polynomial");
  expect_usage_error("ring decode --profile", "option --profile needs a value");
  write_file(nodes, "{\"trionet_profile\": 1, \"can\": {\"node_count\": 3}}");
  expect_usage_error("ring decode --profile " + nodes + " --profile " + nodes,
                     "option --profile given twice");
  const auto missing = run_cli("genius scan-time --profile /nonexistent/profile.json");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.err.find("cannot open profile /nonexistent/profile.json: No such file or directory"), std::string::npos)
      << missing.err;
  // The CAN node count comes from the profile unless --nodes says otherwise.
  const auto three = run_cli("can table --profile " + nodes);
  EXPECT_EQ(three.exit_code, 0);
  EXPECT_EQ(three.out, run_cli("can table --nodes 3").out);
  EXPECT_NE(three.out, run_cli("can table").out);
  EXPECT_EQ(run_cli("can table --profile " + nodes + " --nodes 5").out, run_cli("can table").out);
  // After "--" it is a word like any other: here the text to print.
  const auto text = run_cli("ring encode print --to 11 -- --profile");
  EXPECT_EQ(text.exit_code, 0) << text.err;
  EXPECT_EQ(text.out, "91 2d 2d 70 72 6f 66 69 6c 65 90\n");
  std::remove(bad.c_str());
  std::remove(nodes.c_str());
}

TEST(LearnCli, EncodeAndDecodeUseTheProfile) {
  learn::profile p;
  p.ring.crc = {0x8005, 0xFFFF, true, true, 0};
  p.ring.layout.vr = ring::group_order::most_significant_first;
  const std::string path = temp_path("encode.json");
  write_file(path, learn::write_profile(p));
  const auto encoded = run_cli("ring encode var --to 10 --vr 200 --value 99 --profile " + path);
  EXPECT_EQ(encoded.exit_code, 0) << encoded.err;
  const std::vector<learn::variable_frame> expected =
      learn::encode_capture({{200, std::int64_t{99} << 32}}, p.ring.crc, p.ring.layout);
  EXPECT_EQ(encoded.out, hex_frames(expected));
  const auto decoded = run_cli("ring decode --profile " + path, encoded.out);
  EXPECT_NE(decoded.out.find("\"event\":\"message\",\"line\":1,\"type\":\"var\",\"hops\":1,\"vr\":200,"),
            std::string::npos)
      << decoded.out;
  EXPECT_NE(run_cli("ring decode", encoded.out).out.find("crc_error"), std::string::npos);
  std::remove(path.c_str());
}

// The CAN byte order and the Genius control layout of a profile reach the encoders and decoders.
TEST(LearnCli, CanByteOrderAndGeniusControlLayoutComeFromTheProfile) {
  learn::profile p;
  p.can.byte_order = trionet::can::byte_order::little_endian;
  p.genius.control = {1, 0, 3, 2, trionet::genius::tag_position::low};
  const std::string path = temp_path("orders.json");
  write_file(path, learn::write_profile(p));

  const auto frame = run_cli("can encode --from 1 --to 4 --vr 1 --value 2.345 --profile " + path);
  EXPECT_EQ(frame.exit_code, 0) << frame.err;
  EXPECT_EQ(frame.out, "028#0100020000007A0D\n");  // docs/protocol.md 2.2's example, numbers reversed
  const auto read = run_cli("can decode --profile " + path, frame.out);
  EXPECT_NE(read.out.find("\"vr\":1,\"negative\":false,\"int\":2,\"frac\":3450,\"value\":2.345"),
            std::string::npos)
      << read.out;
  const auto read_by_default = run_cli("can decode", frame.out);
  EXPECT_NE(read_by_default.out.find("\"reason\":\"bad_fraction\""), std::string::npos) << read_by_default.out;

  const std::uint8_t data[] = {0x11};
  const unsigned crc = trionet::genius::crc6_g704::compute(trionet::byte_view(data, 1));
  char expected[64];
  std::snprintf(expected, sizeof expected, "c:91 11 c:%02x\n", crc << 2);  // Start: 1 00100 01; Stop: tag 0
  const auto encoded = run_cli("genius encode --from 4 --broadcast 11 --profile " + path);
  EXPECT_EQ(encoded.exit_code, 0) << encoded.err;
  EXPECT_EQ(encoded.out, expected);
  const auto decoded = run_cli("genius decode --profile " + path, encoded.out);
  EXPECT_NE(decoded.out.find("transmission from SBA 4, broadcast"), std::string::npos) << decoded.out;
  EXPECT_NE(decoded.out.find("1 transmission, 0 errors"), std::string::npos) << decoded.out;
  const auto decoded_by_default = run_cli("genius decode", encoded.out);
  EXPECT_EQ(decoded_by_default.out.find("transmission from"), std::string::npos) << decoded_by_default.out;
  EXPECT_NE(decoded_by_default.out.find("0 transmissions, 1 error"), std::string::npos) << decoded_by_default.out;
  std::remove(path.c_str());
}

// The keypad display model of a profile reaches the simulated keypads (the manual's Example 1 prints
// "SPEED:" and "LENGTH:" each with CR LF).
TEST(LearnCli, DisplayModelComesFromTheProfile) {
  learn::profile p;
  p.keypad.display.carriage_return = ring::carriage_return_rule::ignored;
  const std::string path = temp_path("display.json");
  write_file(path, learn::write_profile(p));
  const auto by_default = run_cli("ring simulate example1 --json");
  const auto ignored = run_cli("ring simulate example1 --json --profile " + path);
  EXPECT_EQ(by_default.exit_code, 0) << by_default.err;
  EXPECT_EQ(ignored.exit_code, 0) << ignored.err;
  EXPECT_NE(by_default.out.find("\"display\":[\"SPEED:"), std::string::npos) << by_default.out;
  EXPECT_NE(by_default.out.find("\"LENGTH:"), std::string::npos) << by_default.out;
  // With CR ignored, LENGTH: follows SPEED: on the first line (and CURSOR(7) then writes over most of it).
  EXPECT_NE(ignored.out.find("\"display\":[\"SPEED:L "), std::string::npos) << ignored.out;
  EXPECT_EQ(ignored.out.find("LENGTH:"), std::string::npos) << ignored.out;
  std::remove(path.c_str());
}

TEST(LearnCli, ProfileShowAndHeader) {
  const auto shown = run_cli("profile show");
  EXPECT_EQ(shown.exit_code, 0);
  EXPECT_EQ(shown.out, learn::write_profile(learn::profile{}));
  learn::profile p;
  p.name = "ring 7";
  p.ring.crc = {0x8005, 0xFFFF, true, true, 0};
  p.can.node_count = 11;
  const std::string path = temp_path("show.json"), header = temp_path("profile.hpp");
  write_file(path,
             "{\"trionet_profile\": 1, \"name\": \"ring 7\", \"can\": {\"node_count\": 11},\n"
             " \"ring\": {\"crc\": {\"polynomial\": 32773, \"reflect_in\": true, \"reflect_out\": true}}}");
  EXPECT_EQ(run_cli("profile show " + path).out, learn::write_profile(p));
  EXPECT_EQ(run_cli("profile show --profile " + path).out, learn::write_profile(p));
  const auto text = run_cli("profile header " + path + " --namespace plant::ring7");
  EXPECT_EQ(text.exit_code, 0);
  EXPECT_EQ(text.out, learn::profile_header(p, "plant::ring7").text);
  const auto to_file = run_cli("profile header --profile " + path + " -o " + header);
  EXPECT_EQ(to_file.exit_code, 0);
  EXPECT_EQ(to_file.out, "");
  EXPECT_EQ(slurp(header), learn::profile_header(p).text);
  expect_usage_error("profile header " + path + " --namespace 7up",
                     "cannot be used: it is not a C++ namespace name");
  expect_usage_error("profile show a.json b.json", "unexpected argument 'b.json'");
  expect_usage_error("profile", "profile needs a command: show or header");
  write_file(path, "{\"trionet_profile\": 2}");
  expect_usage_error("profile show " + path, "unsupported_version");
  const auto unwritable = run_cli("profile header -o /nonexistent/dir/profile.hpp");
  EXPECT_EQ(unwritable.exit_code, 1);
  std::remove(path.c_str());
  std::remove(header.c_str());
}

// A keypad with codes of its own and key OFF = key ON, on the other end of a pty: the MC puts it in network
// mode and keypad mode 127, the keys are pressed in the order asked, and the profile gets the codes.
// `pressed(i)` is the key pressed when the tool asks for the i-th key.
void play_keypad(trionet::test::pty_pair& pty, ring::keypad<>& keypad, trionet::test::tool_process& mc,
                 const std::function<ring::key(std::size_t)>& pressed) {
  const auto pump = [&](int ms) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(ms);
    do {
      for (std::uint8_t b : pty.read_bytes(1, 10)) keypad.receive(b);
      std::vector<std::uint8_t> out;
      std::uint8_t b = 0;
      while (keypad.transmit(b)) out.push_back(b);
      if (!out.empty()) pty.write_all(out);
    } while (std::chrono::steady_clock::now() < until);
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (keypad.mode() != 127 && std::chrono::steady_clock::now() < deadline) pump(20);
  ASSERT_TRUE(keypad.network_mode());
  ASSERT_EQ(keypad.mode(), 127);
  EXPECT_EQ(keypad.offset(), 1);
  for (std::size_t i = 0; i < ring::key_count; ++i) {
    // The tool asks for each key: wait for its "press" event (a person would read the prompt).
    mc.read_lines_with("\"event\":\"press\"", i + 1, 20000);
    const ring::key k = pressed(i);
    EXPECT_EQ(keypad.press(k), ring::key_status::ok);
    pump(5);
    EXPECT_EQ(keypad.release(k), ring::key_status::ok);
    pump(5);
  }
  pump(50);
}

ring::key in_order(std::size_t i) {
  return static_cast<ring::key>(i);
}

TEST(LearnCli, KeypadCodesLearnedFromAKeypadOnAPty) {
  trionet::test::pty_pair pty;
  ASSERT_TRUE(pty.ok());
  static constexpr ring::keypad_codes codes = {
      {'a', 'b', 'c', 'd', 'e', 'f', 'g', 'h', 'i', 'j', 0x7E, 0x01, 'C', '\r', 0x1B, ',', 'S', 0x7F}};
  ring::keypad<> keypad(ring::keypad_config{&codes, ring::same_key_off_code});
  const std::string base = temp_path("keypad-base.json"), out = temp_path("keypad.json");
  learn::profile p;
  p.name = "plant";
  p.can.node_count = 7;
  write_file(base, learn::write_profile(p));
  trionet::test::tool_process mc({"ring", "join", pty.slave_path, "--as", "mc", "--json", "--learn-keypad",
                                  "10", "--profile", base, "-o", out});
  play_keypad(pty, keypad, mc, in_order);
  EXPECT_EQ(mc.wait(20000), 0) << mc.output();
  EXPECT_NE(mc.output().find("\"key\":\"stop\",\"on\":127,\"off\":127}"), std::string::npos) << mc.output();
  const learn::profile_result written = learn::read_profile(slurp(out));
  ASSERT_TRUE(written) << slurp(out);
  p.keypad.codes = codes;
  p.keypad.key_off = learn::key_off_rule::same;
  p.keypad.defkey = ring::make_default_defkey(codes);
  EXPECT_TRUE(written.value == p) << slurp(out);
  std::remove(base.c_str());
  std::remove(out.c_str());
}

TEST(LearnCli, KeypadLearningRefusesKeysAlikeAndBadArguments) {
  trionet::test::pty_pair pty;
  ASSERT_TRUE(pty.ok());
  static constexpr ring::keypad_codes codes = {
      {'0', '1', '2', '3', '4', '5', '6', '7', '8', '9', 'U', 'D', 'C', 'Y', 'N', '.', 'S', 'T'}};
  ring::keypad<> keypad(ring::keypad_config{&codes, ring::default_key_off_code});
  const std::string out = temp_path("keypad-alike.json");
  trionet::test::tool_process mc(
      {"ring", "join", pty.slave_path, "--as", "mc", "--json", "--learn-keypad", "10", "-o", out});
  play_keypad(pty, keypad, mc, in_order);
  EXPECT_EQ(mc.wait(20000), 0);
  const learn::profile_result written = learn::read_profile(slurp(out));
  ASSERT_TRUE(written);
  EXPECT_TRUE(written.value == learn::profile{}) << "the default keypad gives the default profile";
  std::remove(out.c_str());

  // Key 1 pressed when 0 is asked for too: two keys alike, no profile.
  ring::keypad<> again(ring::keypad_config{&codes, ring::default_key_off_code});
  trionet::test::tool_process alike(
      {"ring", "join", pty.slave_path, "--as", "mc", "--json", "--learn-keypad", "10", "-o", out});
  play_keypad(pty, again, alike, [](std::size_t i) { return static_cast<ring::key>(i == 0 ? 1 : i); });
  EXPECT_EQ(alike.wait(20000), 3);
  EXPECT_FALSE(std::ifstream(out).good());

  expect_usage_error("ring join " + pty.slave_path + " --as keypad --learn-keypad 10 -o x.json",
                     "--learn-keypad goes with --as mc");
  expect_usage_error("ring join " + pty.slave_path + " --as mc --learn-keypad 10", "needs -o PROFILE");
  expect_usage_error("ring join " + pty.slave_path + " --as mc --learn-keypad 9 -o x.json",
                     "--learn-keypad takes the keypad's BASIC address 10..24, got '9'");
  expect_usage_error(
      "ring join " + pty.slave_path + " --as mc --learn-keypad 10 --keypad-offset 25 -o x.json",
      "--keypad-offset takes a BASIC address 10..24, got '25'");
  expect_usage_error("ring join " + pty.slave_path + " --as mc -o x.json", "go with --learn-keypad");
}

}  // namespace

namespace {

// `ring join` takes the profile's keypad codes (as a keypad) and DEFKEY (as an MC).
TEST(LearnCli, AnUnknownOptionOfProfileShowOrHeaderIsABadArgumentNotAFile) {
  expect_usage_error("profile show -x", "unexpected argument '-x' (not an option here; a file named so is ./-x)");
  expect_usage_error("profile header -x", "unexpected argument '-x'");
  const auto missing = run_cli("profile show ./-x");  // a file of that name: looked for, and not there
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.err.find("./-x"), std::string::npos) << missing.err;
}

TEST(LearnCli, ProfileHeaderRefusesANamespaceTheHeaderCouldNotUse) {
  expect_usage_error("profile header --namespace int", "--namespace 'int' cannot be used: 'int' is a C++ keyword");
  expect_usage_error("profile header --namespace namespace", "'namespace' is a C++ keyword");
  expect_usage_error("profile header --namespace plant::and", "'and' is a C++ keyword");
  expect_usage_error("profile header --namespace not::x", "'not' is a C++ keyword");
  expect_usage_error("profile header --namespace thread_local", "'thread_local' is a C++ keyword");
  expect_usage_error("profile header --namespace trionet::ring",
                     "it is or lies inside the library's own namespace trionet");
  expect_usage_error("profile header --namespace trionet", "the library's own namespace trionet");
  expect_usage_error("profile header --namespace plant::trionet", "would hide the library's trionet::");
  const auto fine = run_cli("profile header --namespace plant::trionet_x::integer");
  EXPECT_EQ(fine.exit_code, 0) << fine.err;
  EXPECT_NE(fine.out.find("namespace plant::trionet_x::integer {"), std::string::npos);
}

TEST(LearnCli, MoreThan64MiBOfLearningInputIsStatusOneAsTheProfilePageSays) {
  const auto r = trionet::test::run_cli_redirected("ring learn crc --raw </dev/zero");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("64 MiB"), std::string::npos) << r.err;
  std::string page = slurp(std::string(TRIONET_SOURCE_DIR) + "/docs/profile.md");
  std::replace(page.begin(), page.end(), '\n', ' ');
  EXPECT_NE(page.find("1 when a file cannot be read or written, or for more than 64 MiB of input"), std::string::npos);
  EXPECT_EQ(page.find("or more than 64 MiB of input (a few frames suffice; the input is held in memory); 1 when"),
            std::string::npos);
}

TEST(LearnCli, JoinUsesTheProfilesKeypadCodesAndDefkey) {
  learn::profile p;
  p.keypad.codes.raw[static_cast<std::size_t>(ring::key::digit_1)] = 'b';
  p.keypad.defkey = ring::make_default_defkey(p.keypad.codes);
  const std::string path = temp_path("join.json");
  write_file(path, learn::write_profile(p));
  {
    trionet::test::pty_pair pty;
    ASSERT_TRUE(pty.ok());
    trionet::test::tool_process keypad(
        {"ring", "join", pty.slave_path, "--as", "keypad", "--json", "--profile", path});
    pty.write_all({0x8b, 0x01, 0x88});  // keypad offset 1: network mode
    keypad.read_lines_with("\"network\":true", 1, 20000);
    keypad.write("1\nquit\n");
    EXPECT_EQ(pty.read_bytes(3, 20000), (std::vector<std::uint8_t>{0x89, 'b', 0x88}));
    EXPECT_EQ(keypad.wait(20000), 0);
  }
  {
    trionet::test::pty_pair pty;
    ASSERT_TRUE(pty.ok());
    trionet::test::tool_process mc(
        {"ring", "join", pty.slave_path, "--as", "mc", "--json", "--profile", path});
    pty.write_all({0x89, 'b', 0x88, 0x89, '1', 0x88});      // 'b' is key 1 now; '1' is no key
    mc.read_lines_with("\"event\":\"message\"", 2, 20000);  // both in the receive buffer
    mc.write("get 3\nget 3\nquit\n");
    EXPECT_EQ(mc.wait(20000), 0);
    EXPECT_NE(mc.output().find("\"channel\":3,\"value\":1}"), std::string::npos) << mc.output();
    EXPECT_NE(mc.output().find("\"channel\":3,\"value\":49}"), std::string::npos) << mc.output();
  }
  std::remove(path.c_str());
}

}  // namespace

namespace {

// `ring monitor` decodes with the profile's CRC and layout; `ring send` encodes with them.
TEST(LearnCli, MonitorAndSendUseTheProfile) {
  learn::profile p;
  p.ring.crc = {0x8005, 0xFFFF, true, true, 0};
  p.ring.layout.value = ring::group_order::most_significant_first;
  const std::string path = temp_path("monitor.json");
  write_file(path, learn::write_profile(p));
  trionet::test::pty_pair pty;
  ASSERT_TRUE(pty.ok());
  trionet::test::tool_process monitor({"ring", "monitor", pty.slave_path, "--json", "--profile", path});
  std::mt19937_64 rng(6);
  const std::vector<learn::sent_variable> sent = random_sent(rng, 3);
  for (const learn::variable_frame& f : learn::encode_capture(sent, p.ring.crc, p.ring.layout)) {
    std::vector<std::uint8_t> frame = {0x8a};
    frame.insert(frame.end(), f.begin(), f.end());
    frame.push_back(0x88);
    pty.write_all(frame);
  }
  const std::string& out = monitor.read_lines_with("\"event\":\"message\"", 3, 20000);
  EXPECT_EQ(count_of(out, "crc_error"), 0u) << out;
  for (const learn::sent_variable& s : sent) {
    EXPECT_NE(out.find("\"vr\":" + std::to_string(s.vr) + ","), std::string::npos) << out;
  }
  monitor.signal(SIGINT);
  EXPECT_EQ(monitor.wait(20000), 0);

  const auto r = run_cli("ring send - var --to 10 --vr 200 --value 99 --profile " + path);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  // With "-" the bytes go to standard output as they are: the frame `ring encode` prints with the profile.
  std::vector<std::uint8_t> expected;
  ASSERT_TRUE(trionet::host::parse_hex_bytes(
      [&] {
        std::string hex = run_cli("ring encode var --to 10 --vr 200 --value 99 --profile " + path).out;
        hex.erase(std::remove_if(hex.begin(), hex.end(), [](char c) { return c == ' ' || c == '\n'; }),
                  hex.end());
        return hex;
      }(),
      expected));
  EXPECT_EQ(std::vector<std::uint8_t>(r.out.begin(), r.out.end()), expected);

  std::remove(path.c_str());
}

}  // namespace

namespace {

// `ring join --as mc` checks and sends direct variable transfers with the profile's CRC and layout.
TEST(LearnCli, JoinAsMcUsesTheProfilesCrcAndLayout) {
  learn::profile p;
  p.ring.crc = {0x8005, 0xFFFF, true, true, 0};
  p.ring.layout = {ring::group_order::most_significant_first, ring::group_order::most_significant_first,
                   ring::crc_input::least_significant_first};
  const std::string path = temp_path("join-crc.json");
  write_file(path, learn::write_profile(p));
  trionet::test::pty_pair pty;
  ASSERT_TRUE(pty.ok());
  trionet::test::tool_process mc({"ring", "join", pty.slave_path, "--as", "mc", "--json", "--profile", path});
  const auto frame_of = [&](std::uint16_t vr, std::int64_t value) {
    const learn::variable_frame f = learn::encode_capture({{vr, value}}, p.ring.crc, p.ring.layout)[0];
    std::vector<std::uint8_t> frame = {0x8a};
    frame.insert(frame.end(), f.begin(), f.end());
    frame.push_back(0x88);
    return frame;
  };
  pty.write_all(frame_of(7, std::int64_t{5} << 31));
  mc.read_lines_with("\"event\":\"vr_write\"", 1, 20000);
  mc.write("send 10 300 -1.5\nquit\n");
  EXPECT_EQ(pty.read_bytes(16, 20000), frame_of(300, -(std::int64_t{3} << 31)));
  EXPECT_EQ(mc.wait(20000), 0);
  EXPECT_NE(mc.output().find("\"vr\":7,\"value\":2.5,\"status\":\"ok\""), std::string::npos) << mc.output();
  EXPECT_NE(mc.output().find("\"crc_errors\":0,"), std::string::npos) << mc.output();
  std::remove(path.c_str());
}

}  // namespace
