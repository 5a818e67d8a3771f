// What the Genius transmission parser counts (genius/transmission.hpp): every character it is given lands in
// exactly one count, a framing error while it is already waiting for the next Start included; and when two
// control layouts are the same layout.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include <trionet/genius/transmission.hpp>

namespace {

using namespace trionet::genius;

std::vector<character> encoded(const transmission& t) {
  std::vector<character> out(64);
  const encode_result r = encode_transmission(trionet::span<character>(out.data(), out.size()), t);
  EXPECT_TRUE(r);
  out.resize(r.length);
  return out;
}

const std::uint8_t two_bytes[] = {0x11, 0x22};
const segment one_segment[] = {{false, 0, two_bytes}};
const transmission from_sba_4{4, true, 0, one_segment};  // a broadcast: Start, 2 data, Stop

TEST(GeniusTransmissionCounts, AFramingErrorWhileWaitingForAStartIsSkippedAndCounted) {
  transmission_parser<> parser;
  const std::vector<character> characters = encoded(from_sba_4);
  ASSERT_EQ(characters.size(), 4U);
  EXPECT_EQ(parser.push(characters[0]), parse_status::in_progress);
  EXPECT_EQ(parser.push_framing_error(), parse_status::framing_error);
  EXPECT_EQ(parser.push(characters[2]), parse_status::skipped);
  EXPECT_EQ(parser.push_framing_error(), parse_status::skipped) << "nothing open: nothing more is lost";
  EXPECT_EQ(parser.push(characters[3]), parse_status::skipped);
  EXPECT_EQ(parser.count(parse_status::framing_error), 1U);
  EXPECT_EQ(parser.count(parse_status::skipped), 3U);
  EXPECT_EQ(parser.errors(), 1U);

  for (const character c : characters) (void)parser.push(c);  // the next transmission is read whole
  EXPECT_EQ(parser.count(parse_status::ok), 1U);
  EXPECT_EQ(parser.count(parse_status::skipped), 3U);
  parser.clear_counters();
  EXPECT_EQ(parser.count(parse_status::ok), 0U);
  EXPECT_EQ(parser.count(parse_status::skipped), 0U);
  EXPECT_EQ(parser.errors(), 0U);
}

TEST(GeniusTransmissionCounts, LayoutsAreEqualOnlyWhenEveryTagAndThePositionAre) {
  const control_layout standard{};
  EXPECT_TRUE(standard == control_layout{});
  EXPECT_FALSE(standard != control_layout{});
  control_layout other = standard;
  other.start = 1;
  other.stop = 0;
  EXPECT_FALSE(standard == other) << "start and stop swapped";
  other = standard;
  other.start_of_block = 3;
  other.end_of_block = 2;
  EXPECT_FALSE(standard == other) << "the block tags swapped";
  other = standard;
  other.position = tag_position::low;
  EXPECT_FALSE(standard == other) << "the tag at the other end";
  EXPECT_TRUE(standard != other);
}

}  // namespace
