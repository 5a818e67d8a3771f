// Learning the direct variable transfer's layout (src/learn/ring_layout_learn.hpp) from frames made by the
// library's encoder in every supported layout, and the sent list.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "learn/ring_capture.hpp"
#include "learn/ring_layout_learn.hpp"
#include "trionet/ring.hpp"

namespace ring = trionet::ring;
namespace learn = trionet::learn;

namespace {

constexpr ring::group_order lsf = ring::group_order::least_significant_first;
constexpr ring::group_order msf = ring::group_order::most_significant_first;

std::vector<learn::sent_variable> random_sent(std::mt19937_64& rng, std::size_t count) {
  std::vector<learn::sent_variable> sent;
  for (std::size_t i = 0; i < count; ++i) {
    // Values a program sends: integers and fractions in the Q32.32 range.
    const auto value = static_cast<std::int64_t>(rng() % 2000000) - 1000000;
    sent.push_back({static_cast<std::uint16_t>(rng() % 16384), value * (std::int64_t{1} << (rng() % 32))});
  }
  return sent;
}

}  // namespace

TEST(LearnRingLayout, EveryGroupOrderPairFromFourFrames) {
  std::mt19937_64 rng(50);
  const ring::crc16_parameters kermit{0x1021, 0x0000, true, true, 0x0000};
  for (int round = 0; round < 20; ++round) {
    for (ring::group_order vr : {lsf, msf}) {
      for (ring::group_order value : {lsf, msf}) {
        const ring::variable_layout_parameters layout{vr, value, ring::crc_input::as_sent};
        const auto sent = random_sent(rng, 4);
        const auto frames = learn::encode_capture(sent, kermit, layout);
        const auto learned = learn::learn_layout(frames, sent);
        ASSERT_EQ(learned.status, learn::layout_learn_status::ok) << round;
        EXPECT_EQ(learned.layout.vr, vr);
        EXPECT_EQ(learned.layout.value, value);
        EXPECT_EQ(learned.layout.crc, ring::crc_input::as_sent);
        // With a default pair the two CRC readings are the same bytes; otherwise the CRC, learned both
        // ways from the four frames, fits the bytes as sent only.
        EXPECT_EQ(learned.crc, vr == lsf && value == lsf ? learn::crc_input_finding::same_bytes
                                                         : learn::crc_input_finding::as_sent);
        int fitting = 0;
        for (const auto& o : learned.orders) fitting += o.fits;
        EXPECT_EQ(fitting, 1);
      }
    }
  }
}

TEST(LearnRingLayout, ACrcOverTheDefaultOrderIsRecognisedWithAKnownOrALearnedCrc) {
  std::mt19937_64 rng(51);
  const ring::crc16_parameters crc{};  // CCITT-FALSE
  const ring::variable_layout_parameters layout{msf, lsf, ring::crc_input::least_significant_first};
  const auto sent = random_sent(rng, 4);
  const auto frames = learn::encode_capture(sent, crc, layout);
  const auto learned = learn::learn_layout(frames, sent);
  ASSERT_TRUE(learned);
  EXPECT_EQ(learned.layout, layout);
  EXPECT_EQ(learned.crc, learn::crc_input_finding::least_significant_first);
  learn::layout_learn_options known;
  known.crc = &crc;
  const auto checked = learn::learn_layout(frames, sent, known);
  EXPECT_EQ(checked.layout, layout);
  EXPECT_EQ(checked.crc, learn::crc_input_finding::least_significant_first);
  // A wrong CRC fits neither way.
  const ring::crc16_parameters wrong{0x8005, 0, true, true, 0};
  known.crc = &wrong;
  EXPECT_EQ(learn::learn_layout(frames, sent, known).crc, learn::crc_input_finding::none_fits);
  // Two frames are too few to learn a CRC both ways: the orders are found, the CRC input is not.
  const std::vector<learn::variable_frame> two(frames.begin(), frames.begin() + 2);
  const std::vector<learn::sent_variable> two_sent(sent.begin(), sent.begin() + 2);
  const auto few = learn::learn_layout(two, two_sent);
  ASSERT_TRUE(few);
  EXPECT_NE(few.crc, learn::crc_input_finding::least_significant_first);
  EXPECT_NE(few.crc, learn::crc_input_finding::as_sent);
}

TEST(LearnRingLayout, NoLayoutFitsNamesEachLayoutsFirstContradictingFrame) {
  std::mt19937_64 rng(52);
  auto sent = random_sent(rng, 6);
  const auto frames =
      learn::encode_capture(sent, ring::crc16_parameters{}, {msf, msf, ring::crc_input::as_sent});
  sent[3].value += 1;  // the list says otherwise from frame 3
  const auto learned = learn::learn_layout(frames, sent);
  EXPECT_EQ(learned.status, learn::layout_learn_status::no_layout_fits);
  for (const auto& o : learned.orders) {
    EXPECT_FALSE(o.fits);
    if (o.vr == msf && o.value == msf) {
      EXPECT_EQ(o.first_contradiction, 3u);
    } else {
      EXPECT_EQ(o.first_contradiction, 0u);  // the other readings differ at once
    }
  }
  EXPECT_EQ(learned.crc, learn::crc_input_finding::undecided);
}

TEST(LearnRingLayout, SymmetricFramesAreAmbiguous) {
  // vr 129 has equal groups (1, 1), value 0 is all zero groups: every order reads the same.
  const std::vector<learn::sent_variable> sent = {{129, 0}, {0, 0}};
  const auto frames = learn::encode_capture(sent, ring::crc16_parameters{});
  const auto learned = learn::learn_layout(frames, sent);
  EXPECT_EQ(learned.status, learn::layout_learn_status::ambiguous);
  for (const auto& o : learned.orders) EXPECT_TRUE(o.fits);
}

TEST(LearnRingLayout, CountMismatchBadFrameAndNoFrames) {
  std::mt19937_64 rng(53);
  const auto sent = random_sent(rng, 5);
  auto frames = learn::encode_capture(sent, ring::crc16_parameters{});
  frames.pop_back();
  const auto fewer = learn::learn_layout(frames, sent);
  EXPECT_EQ(fewer.status, learn::layout_learn_status::count_mismatch);
  EXPECT_TRUE(fewer.orders[0].fits);  // the common part still reads as sent in the default layout
  frames[1][3] = 0x80;
  const auto bad = learn::learn_layout(frames, sent);
  EXPECT_EQ(bad.status, learn::layout_learn_status::bad_frame);
  EXPECT_EQ(bad.bad_frame_index, 1u);
  EXPECT_EQ(learn::learn_layout({}, sent).status, learn::layout_learn_status::no_frames);
}

TEST(LearnRingLayout, TheTopGroupMustHoldOnlyTheSignBit) {
  // A frame whose value reads as sent only if X9's bits 6..1 are ignored does not fit.
  const std::vector<learn::sent_variable> sent = {{300, -5}};
  auto frames = learn::encode_capture(sent, ring::crc16_parameters{});
  frames[0][11] |= 0x04;
  const auto learned = learn::learn_layout(frames, sent);
  EXPECT_FALSE(learned.orders[0].fits);
}
