// Q32.32 from decimals (q32.hpp): a default decimal is 0, and -2^31 is the bottom of the range: -2147483648 is
// in it, anything below it is out of range, however little below.
#include <gtest/gtest.h>

#include <cstdint>

#include "trionet/q32.hpp"

namespace {

using trionet::decimal;
using trionet::q32_from_decimal;
using trionet::q32_status;

TEST(Q32Decimal, ADefaultDecimalIsZero) {
  const decimal zero{};
  EXPECT_FALSE(zero.negative);
  EXPECT_EQ(zero.integer_part, 0u);
  EXPECT_EQ(zero.fraction, 0u);
  const auto q = q32_from_decimal(zero);
  ASSERT_TRUE(q);
  EXPECT_EQ(q.raw, 0);
}

TEST(Q32Decimal, TheBottomOfTheRangeIsMinus2To31AndNothingBelow) {
  const auto bottom = q32_from_decimal(decimal{true, 0x80000000u, 0});
  ASSERT_TRUE(bottom);
  EXPECT_EQ(bottom.raw, INT64_MIN);
  EXPECT_EQ(q32_from_decimal(decimal{true, 0x80000000u, 1}).status, q32_status::out_of_range);  // -2147483648.0001
  EXPECT_EQ(q32_from_decimal(decimal{true, 0x80000000u, 9999}).status, q32_status::out_of_range);
  EXPECT_EQ(q32_from_decimal(decimal{false, 0x80000000u, 0}).status, q32_status::out_of_range);  // 2^31
}

}  // namespace
