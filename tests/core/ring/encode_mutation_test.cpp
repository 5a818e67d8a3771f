// Values a caller makes before an encode fills them in (ring/encode.hpp): an encode_result is `ok` with
// nothing written, as the one an encode returns says only what it wrote.
#include <gtest/gtest.h>

#include <cstdint>

#include "trionet/ring/encode.hpp"

namespace {

namespace ring = trionet::ring;

TEST(RingStartingValues, AnEncodeResultIsOkWithNothingWritten) {
  const ring::encode_result r{};
  EXPECT_TRUE(r);
  EXPECT_EQ(r.status, ring::encode_status::ok);
  EXPECT_EQ(r.length, 0U);
}

TEST(RingStartingValues, AnEncodeThatFailsSaysItWroteNothing) {
  std::uint8_t out[4] = {};
  const ring::encode_result r =
      ring::encode_characters(trionet::byte_buffer(out, sizeof out), 1, "TOO LONG", 8);
  EXPECT_EQ(r.status, ring::encode_status::buffer_too_small);
  EXPECT_EQ(r.length, 0U);
}

}  // namespace
