// Learning the ring's CRC from captures (src/learn/ring_crc_learn.hpp): captures made by the library's own
// encoder under hidden parameters (every 16-bit CRC of the CRC RevEng catalogue, random ones, both group
// orders) are learned back, and a separate validation capture is decoded with what was learned.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "learn/crc_catalogue.hpp"
#include "learn/ring_capture.hpp"
#include "support/sent_variables.hpp"
#include "learn/ring_crc_learn.hpp"
#include "trionet/ring.hpp"

namespace ring = trionet::ring;
namespace learn = trionet::learn;
using trionet::test::random_sent;

namespace {

constexpr std::uint8_t check_bytes[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};

ring::crc16_parameters parameters_of(const learn::catalogue_entry& e) {
  return {e.polynomial, e.initial, e.reflect_in, e.reflect_out, e.xor_out};
}

std::vector<learn::catalogue_entry> catalogue_of_width(unsigned width) {
  std::vector<learn::catalogue_entry> out;
  for (const auto& e : learn::crc_catalogue()) {
    if (e.width == width) out.push_back(e);
  }
  return out;
}

const ring::variable_layout_parameters lsf_layout{};
const ring::variable_layout_parameters msf_layout{ring::group_order::most_significant_first,
                                                  ring::group_order::most_significant_first,
                                                  ring::crc_input::as_sent};

// True if `a` and `b` give the same 14 transmitted bits on every 12-byte message: the same polynomial and
// reflections (the linear part) and the same CRC of twelve zero bytes (the constant), checked directly, and
// on random messages as well.
bool same_on_twelve_bytes(const ring::crc16_parameters& a, const ring::crc16_parameters& b,
                          std::mt19937_64& rng) {
  const ring::crc16_runtime ca(a), cb(b);
  std::uint8_t m[12] = {};
  if (ring::crc_wire_bits(ca.compute(m, 12)) != ring::crc_wire_bits(cb.compute(m, 12))) return false;
  for (int k = 0; k < 200; ++k) {
    for (auto& byte : m) byte = static_cast<std::uint8_t>(rng() & 0x7F);
    if (ring::crc_wire_bits(ca.compute(m, 12)) != ring::crc_wire_bits(cb.compute(m, 12))) return false;
  }
  return true;
}

// Decodes `frames` (header and end of message added, hops 1) with the ring decoder holding the learned CRC
// and the layout; counts the messages that come out with the vr and value that were sent.
std::size_t verified_by_decoder(const std::vector<learn::variable_frame>& frames,
                                const std::vector<learn::sent_variable>& sent,
                                const ring::crc16_parameters& crc,
                                const ring::variable_layout_parameters& layout) {
  std::size_t verified = 0;
  ring::with_variable_layout(layout, [&](auto policy) {
    ring::decoder<256, ring::crc16_runtime, decltype(policy)> d{ring::crc16_runtime(crc)};
    for (std::size_t i = 0; i < frames.size(); ++i) {
      ring::decode_result last;
      last = d.push(ring::make_header(1, 2));
      for (std::uint8_t b : frames[i]) last = d.push(b);
      last = d.push(ring::make_end_of_message(1));
      if (last.status == ring::decode_status::ok && last.msg.vr == sent[i].vr &&
          last.msg.value == sent[i].value) {
        ++verified;
      }
    }
  });
  return verified;
}

// Learns the hidden CRC from `learn_count` frames, then decodes a separate validation capture with it.
// Also the smallest number of leading frames that gives exactly one class (0 if none up to learn_count).
struct outcome {
  learn::crc_learn_result learned;
  std::size_t frames_needed = 0;
  std::size_t validation_verified = 0;
};
outcome learn_and_validate(const ring::crc16_parameters& hidden,
                           const ring::variable_layout_parameters& layout, std::mt19937_64& rng,
                           std::size_t learn_count = 8, const learn::crc_learn_options& options = {},
                           std::size_t validation_count = 100) {
  outcome o;
  const auto sent = random_sent(rng, learn_count);
  const auto frames = learn::encode_capture(sent, hidden, layout);
  // From two frames: one never suffices (OneFrameFitsEveryPolynomialAndReflection), and is the slow call.
  for (std::size_t k = 2; k <= learn_count && o.frames_needed == 0; ++k) {
    const std::vector<learn::variable_frame> first(frames.begin(), frames.begin() + static_cast<long>(k));
    if (learn::learn_ring_crc(first, options).status == learn::crc_learn_status::ok) o.frames_needed = k;
  }
  o.learned = learn::learn_ring_crc(frames, options);
  if (o.learned) {
    const auto validation_sent = random_sent(rng, validation_count);
    const auto validation = learn::encode_capture(validation_sent, hidden, layout);
    o.validation_verified =
        verified_by_decoder(validation, validation_sent, o.learned.classes[0].members[0].parameters, layout);
  }
  return o;
}

}  // namespace

// ---- the catalogue ----

TEST(LearnCatalogue, HoldsTheRevEngSixAndSixteenBitCrcsWithTheirCheckValues) {
  const auto sixteen = catalogue_of_width(16);
  EXPECT_EQ(sixteen.size(), 31u);
  EXPECT_EQ(catalogue_of_width(6).size(), 5u);
  EXPECT_EQ(learn::crc_catalogue().size(), 36u);
  for (const auto& e : sixteen) {
    const ring::crc16_runtime crc(parameters_of(e));
    EXPECT_EQ(crc.compute(check_bytes, 9), e.check) << e.name;
  }
  const auto ccitt = std::find_if(sixteen.begin(), sixteen.end(), [](const learn::catalogue_entry& e) {
    return e.name == "CRC-16/IBM-3740";
  });
  ASSERT_NE(ccitt, sixteen.end());
  EXPECT_EQ(parameters_of(*ccitt), ring::crc16_parameters{});  // the ring's default, CCITT-FALSE
}

TEST(LearnCatalogue, ReadsTheCatalogueLineFormatAndNamesTheFirstError) {
  const auto ok = learn::parse_crc_catalogue(
      "# comment\n\nwidth=16 poly=0x8005 init=0x0000 refin=true refout=true xorout=0x0000 check=0xbb3d "
      "residue=0x0000 name=\"CRC-16/ARC\" alias=\"ARC,CRC-16\"\r\n");
  ASSERT_TRUE(ok);
  ASSERT_EQ(ok.entries.size(), 1u);
  EXPECT_EQ(ok.entries[0].name, "CRC-16/ARC");
  EXPECT_TRUE(ok.entries[0].reflect_in);
  EXPECT_EQ(ok.entries[0].check, 0xBB3D);
  const auto missing =
      learn::parse_crc_catalogue("\nwidth=16 poly=0x8005 init=0x0000 refin=true xorout=0 name=\"x\"");
  EXPECT_EQ(missing.status, learn::catalogue_status::bad_field);  // xorout=0 is not hex
  EXPECT_EQ(missing.line, 2u);
  const auto no_refout = learn::parse_crc_catalogue(
      "width=16 poly=0x8005 init=0x0000 refin=true xorout=0x0 check=0x0 name=\"x\"");
  EXPECT_EQ(no_refout.status, learn::catalogue_status::missing_field);
  EXPECT_EQ(no_refout.detail, "refout");
  const auto wide = learn::parse_crc_catalogue(
      "width=6 poly=0x43 init=0x00 refin=true refout=true xorout=0x00 check=0x06 name=\"x\"");
  EXPECT_EQ(wide.status, learn::catalogue_status::out_of_range);
  const auto unknown = learn::parse_crc_catalogue(
      "width=6 poly=0x03 init=0x00 refin=yes refout=true xorout=0x00 check=0x06 name=\"x\"");
  EXPECT_EQ(unknown.status, learn::catalogue_status::bad_field);
  EXPECT_EQ(unknown.detail, "refin=yes");
  EXPECT_EQ(learn::parse_crc_catalogue("width=16 width=16").status, learn::catalogue_status::bad_field);
}

// ---- learning every catalogue CRC, in both group orders ----

TEST(LearnRingCrc, EveryCatalogueCrcInBothGroupOrdersFromAtMostEightFrames) {
  std::mt19937_64 rng(20);
  std::map<std::size_t, int> needed;
  for (const auto& e : catalogue_of_width(16)) {
    for (const auto& layout : {lsf_layout, msf_layout}) {
      const ring::crc16_parameters hidden = parameters_of(e);
      const outcome o = learn_and_validate(hidden, layout, rng);
      ASSERT_EQ(o.learned.status, learn::crc_learn_status::ok) << e.name;
      ASSERT_EQ(o.learned.classes.size(), 1u);
      EXPECT_EQ(o.learned.rejected, 0u);
      const auto& best = o.learned.classes[0].members[0];
      EXPECT_TRUE(same_on_twelve_bytes(best.parameters, hidden, rng)) << e.name;
      // Named after the hidden entry, or after an earlier catalogue entry that is the same function on
      // 12-byte messages.
      ASSERT_FALSE(best.name.empty()) << e.name;
      if (best.name != e.name) {
        const auto& all = learn::crc_catalogue();
        const auto other =
            std::find_if(all.begin(), all.end(), [&](const auto& c) { return c.name == best.name; });
        ASSERT_NE(other, all.end());
        EXPECT_TRUE(same_on_twelve_bytes(parameters_of(*other), hidden, rng)) << e.name << " / " << best.name;
      }
      EXPECT_EQ(o.validation_verified, 100u) << e.name;
      ASSERT_NE(o.frames_needed, 0u) << e.name;  // 0: not within the capture
      ASSERT_LE(o.frames_needed, 8u) << e.name;
      ++needed[o.frames_needed];
    }
  }
  std::string histogram;
  for (const auto& [frames, count] : needed)
    histogram += std::to_string(frames) + ": " + std::to_string(count) + "  ";
  std::printf("frames needed over the catalogue x 2 group orders: %s\n", histogram.c_str());
}

TEST(LearnRingCrc, RandomParametersIncludingMixedReflections) {
  std::mt19937_64 rng(21);
  for (int round = 0; round < 64; ++round) {
    ring::crc16_parameters hidden;
    hidden.polynomial = static_cast<std::uint16_t>(rng() | 1);
    hidden.initial = static_cast<std::uint16_t>(rng());
    hidden.xor_out = static_cast<std::uint16_t>(rng());
    hidden.reflect_in = (round & 1) != 0;
    hidden.reflect_out = (round & 2) != 0;
    const auto& layout = (round & 4) != 0 ? msf_layout : lsf_layout;
    const outcome o = learn_and_validate(hidden, layout, rng);
    ASSERT_EQ(o.learned.status, learn::crc_learn_status::ok) << round;
    EXPECT_TRUE(same_on_twelve_bytes(o.learned.classes[0].members[0].parameters, hidden, rng)) << round;
    EXPECT_EQ(o.validation_verified, 100u) << round;
    EXPECT_NE(o.frames_needed, 0u) << round;
    EXPECT_LE(o.frames_needed, 8u) << round;
    EXPECT_EQ(o.learned.rejected, 0u);
  }
}

TEST(LearnRingCrc, EvenPolynomialsWhenAskedFor) {
  learn::crc_learn_options with_even;
  with_even.even_polynomials = true;
  std::mt19937_64 rng(30);
  for (int round = 0; round < 16; ++round) {
    ring::crc16_parameters hidden;
    hidden.polynomial = static_cast<std::uint16_t>(rng());
    if (round < 8) hidden.polynomial = static_cast<std::uint16_t>(hidden.polynomial & 0xFFFE);
    hidden.initial = static_cast<std::uint16_t>(rng());
    hidden.reflect_in = (round & 1) != 0;
    hidden.reflect_out = (round & 2) != 0;
    const outcome o = learn_and_validate(hidden, lsf_layout, rng, 32, with_even);
    ASSERT_EQ(o.learned.status, learn::crc_learn_status::ok) << round;
    EXPECT_TRUE(same_on_twelve_bytes(o.learned.classes[0].members[0].parameters, hidden, rng)) << round;
    EXPECT_EQ(o.validation_verified, 100u) << round;
  }
  // Without the option an even polynomial is not found.
  const auto frames =
      learn::encode_capture(random_sent(rng, 8), ring::crc16_parameters{0x8004, 0, false, false, 0});
  EXPECT_EQ(learn::learn_ring_crc(frames).status, learn::crc_learn_status::no_candidate);
}

TEST(LearnRingCrc, TheEvenRivalOfAGeneratorDivisibleByXPlusOneNeedsMoreFrames) {
  // CRC-16/XMODEM's generator x^16 + x^12 + x^5 + 1 is (x + 1) A(x) with A = 0xF01F (degree 15). The even
  // generator x A(x) = x^16 + 0xE03E leaves the same remainder mod A, so the two CRCs differ by 0 or A: one
  // linear functional of the message. With even polynomials admitted, each random frame refutes that rival
  // with probability 1/2 only.
  learn::crc_learn_options with_even;
  with_even.even_polynomials = true;
  std::mt19937_64 rng(31);
  int ambiguous_after_four = 0;
  const int rounds = 64;
  for (int round = 0; round < rounds; ++round) {
    const auto frames =
        learn::encode_capture(random_sent(rng, 4), ring::crc16_parameters{0x1021, 0, false, false, 0});
    const auto odd_only = learn::learn_ring_crc(frames);
    const auto all = learn::learn_ring_crc(frames, with_even);
    EXPECT_EQ(odd_only.status, learn::crc_learn_status::ok);
    if (all.status == learn::crc_learn_status::ambiguous) {
      ++ambiguous_after_four;
      ASSERT_EQ(all.classes.size(), 2u);
      const auto rival =
          all.classes[0].members[0].parameters.polynomial == 0x1021 ? all.classes[1] : all.classes[0];
      EXPECT_EQ(rival.members[0].parameters.polynomial, 0xE03E);
    }
  }
  // Three differences: the rival survives with probability 1/8.
  EXPECT_GT(ambiguous_after_four, 2);
  EXPECT_LT(ambiguous_after_four, 20);
}

// ---- how many frames: the mathematics ----

TEST(LearnRingCrc, OneFrameFitsEveryPolynomialAndReflection) {
  std::mt19937_64 rng(22);
  const auto frames = learn::encode_capture(random_sent(rng, 1), ring::crc16_parameters{});
  const auto learned = learn::learn_ring_crc(frames);
  EXPECT_EQ(learned.status, learn::crc_learn_status::too_many_candidates);
  EXPECT_EQ(learned.survivors,
            32768u * 4u);  // every odd polynomial and reflection pair, each with its constant
  EXPECT_TRUE(learned.classes.empty());
  learn::crc_learn_options with_even;
  with_even.even_polynomials = true;
  EXPECT_EQ(learn::learn_ring_crc(frames, with_even).survivors, 65536u * 4u);
}

TEST(LearnRingCrc, TwoFramesLeaveAFewClassesEachExactOnBothFrames) {
  std::mt19937_64 rng(23);
  std::size_t total = 0;
  const int rounds = 20;
  for (int round = 0; round < rounds; ++round) {
    const ring::crc16_parameters hidden{};
    const auto frames = learn::encode_capture(random_sent(rng, 2), hidden);
    const auto learned = learn::learn_ring_crc(frames);
    ASSERT_EQ(learned.status, learn::crc_learn_status::ambiguous);
    EXPECT_EQ(learned.rejected, 0u);
    bool hidden_found = false;
    for (const auto& c : learned.classes) {
      for (const auto& m : c.members) {
        for (const auto& f : frames) EXPECT_TRUE(learn::frame_crc_matches(m.parameters, f));
      }
      hidden_found = hidden_found || same_on_twelve_bytes(c.members[0].parameters, hidden, rng);
    }
    EXPECT_TRUE(hidden_found);
    total += learned.classes.size();
  }
  // About 2^17 / 2^14 = 8 wrong hypotheses survive one difference, plus the right one.
  const double mean = static_cast<double>(total) / rounds;
  EXPECT_GT(mean, 4.0);
  EXPECT_LT(mean, 16.0);
}

TEST(LearnRingCrc, FramesWithTheSameVrAndCountingValuesAlsoSuffice) {
  // A realistic capture: one VR counting up 0, 1, 2, ... (the messages differ in a few low bits only).
  std::mt19937_64 rng(24);
  for (const auto& e : catalogue_of_width(16)) {
    std::vector<learn::sent_variable> sent;
    for (int i = 0; i < 32; ++i) sent.push_back({100, trionet::q32_from_integer(i)});
    const auto frames = learn::encode_capture(sent, parameters_of(e));
    const auto learned = learn::learn_ring_crc(frames);
    ASSERT_EQ(learned.status, learn::crc_learn_status::ok) << e.name;
    EXPECT_TRUE(same_on_twelve_bytes(learned.classes[0].members[0].parameters, parameters_of(e), rng))
        << e.name;
  }
}

// ---- exactness and bad input ----

TEST(LearnRingCrc, ACorruptedFrameLeavesNoCandidate) {
  std::mt19937_64 rng(25);
  auto frames = learn::encode_capture(random_sent(rng, 8), ring::crc16_parameters{0x8005, 0, true, true, 0});
  frames[5][4] ^= 0x10;  // a data bit flipped, the CRC left as it was
  const auto learned = learn::learn_ring_crc(frames);
  EXPECT_EQ(learned.status, learn::crc_learn_status::no_candidate);
  EXPECT_TRUE(learned.classes.empty());
}

TEST(LearnRingCrc, SameMessageWithTwoCrcsLeavesNoCandidate) {
  std::mt19937_64 rng(26);
  auto frames = learn::encode_capture(random_sent(rng, 4), ring::crc16_parameters{});
  frames.push_back(frames[0]);
  frames.back()[12] ^= 1;
  EXPECT_EQ(learn::learn_ring_crc(frames).status, learn::crc_learn_status::no_candidate);
  // The same frame twice carries nothing new and is harmless.
  frames.back() = frames[0];
  EXPECT_EQ(learn::learn_ring_crc(frames).status, learn::crc_learn_status::ok);
}

TEST(LearnRingCrc, RejectsNoFramesAndBytesWithBitSeven) {
  EXPECT_EQ(learn::learn_ring_crc({}).status, learn::crc_learn_status::no_frames);
  std::mt19937_64 rng(27);
  auto frames = learn::encode_capture(random_sent(rng, 4), ring::crc16_parameters{});
  frames[2][7] |= 0x80;
  const auto learned = learn::learn_ring_crc(frames);
  EXPECT_EQ(learned.status, learn::crc_learn_status::bad_frame);
  EXPECT_EQ(learned.bad_frame_index, 2u);
}

TEST(LearnRingCrc, ACrcOverTheDefaultByteOrderIsFoundWithThatLayout) {
  std::mt19937_64 rng(28);
  const ring::variable_layout_parameters canonical_crc{ring::group_order::most_significant_first,
                                                       ring::group_order::most_significant_first,
                                                       ring::crc_input::least_significant_first};
  const ring::crc16_parameters hidden{0x3D65, 0x0000, true, true, 0xFFFF};  // CRC-16/DNP
  const auto sent = random_sent(rng, 8);
  const auto frames = learn::encode_capture(sent, hidden, canonical_crc);
  EXPECT_EQ(learn::learn_ring_crc(frames).status,
            learn::crc_learn_status::no_candidate);  // not over bytes as sent
  learn::crc_learn_options options;
  options.layout = canonical_crc;
  const auto learned = learn::learn_ring_crc(frames, options);
  ASSERT_EQ(learned.status, learn::crc_learn_status::ok);
  EXPECT_EQ(learned.classes[0].members[0].name, "CRC-16/DNP");
  EXPECT_EQ(verified_by_decoder(frames, sent, learned.classes[0].members[0].parameters, canonical_crc), 8u);
}

TEST(LearnRingCrc, WithoutACatalogueTheRepresentativeIsAPlainInitAndXorout) {
  std::mt19937_64 rng(29);
  const ring::crc16_parameters modbus{0x8005, 0xFFFF, true, true, 0x0000};
  const auto frames = learn::encode_capture(random_sent(rng, 6), modbus);
  learn::crc_learn_options options;
  options.catalogue = nullptr;
  const auto learned = learn::learn_ring_crc(frames, options);
  ASSERT_EQ(learned.status, learn::crc_learn_status::ok);
  EXPECT_TRUE(learned.classes[0].members[0].name.empty());
  EXPECT_EQ(learned.classes[0].members[0].parameters, modbus);  // init 0xFFFF, xorout 0 is the first tried
}

// ---- frames from a stream of ring bytes ----

TEST(LearnRingCapture, FindsTheDirectVariableTransfersInAStream) {
  std::vector<std::uint8_t> stream = {0x05, 0x8a};  // stray data, a lone header
  std::uint8_t frame[16];
  ASSERT_TRUE(ring::encode_variable(frame, 3, 200, trionet::q32_from_integer(99)));
  stream.insert(stream.end(), frame, frame + 16);
  ASSERT_TRUE(ring::encode_characters(frame, 2, "HI", 2));
  stream.insert(stream.end(), frame, frame + 4);
  ASSERT_TRUE(ring::encode_variable(frame, 1, 7, -1));
  stream.insert(stream.end(), frame, frame + 16);
  stream.insert(stream.end(), frame, frame + 10);  // cut short
  const auto found = learn::variable_transfers(trionet::byte_view(stream.data(), stream.size()));
  ASSERT_EQ(found.frames.size(), 2u);
  EXPECT_EQ(found.skipped_bytes, 2u + 4u + 10u);
  EXPECT_EQ(found.frames[1][0], 7);
}

TEST(LearnRingCapture, ReadsTheSentList) {
  const auto ok = learn::parse_sent_list("# vr value\n200 99\n  7\t-1.5   # comment\n\n16383 2147483647\n");
  ASSERT_TRUE(ok);
  ASSERT_EQ(ok.sent.size(), 3u);
  EXPECT_EQ(ok.sent[0].vr, 200);
  EXPECT_EQ(ok.sent[0].value, trionet::q32_from_integer(99));
  EXPECT_EQ(ok.sent[1].value, -(std::int64_t{3} << 31));
  EXPECT_EQ(learn::parse_sent_list("200\n").status, learn::sent_list_status::syntax);
  EXPECT_EQ(learn::parse_sent_list("1 2\n200 99 3\n").line, 2u);
  EXPECT_EQ(learn::parse_sent_list("16384 1\n").status, learn::sent_list_status::vr_out_of_range);
  EXPECT_EQ(learn::parse_sent_list("99999999999999999999 1\n").status,
            learn::sent_list_status::vr_out_of_range);
  EXPECT_EQ(learn::parse_sent_list("-1 1\n").status, learn::sent_list_status::syntax);
  EXPECT_EQ(learn::parse_sent_list("1 2147483648\n").status, learn::sent_list_status::value_out_of_range);
  EXPECT_EQ(learn::parse_sent_list("1 nan\n").status, learn::sent_list_status::syntax);
  EXPECT_EQ(learn::parse_sent_list("1 inf\n").status, learn::sent_list_status::syntax);
  EXPECT_EQ(learn::parse_sent_list("1 0x10\n").status, learn::sent_list_status::syntax);
  EXPECT_EQ(learn::parse_sent_list("1 2z\n").status, learn::sent_list_status::syntax);
}
