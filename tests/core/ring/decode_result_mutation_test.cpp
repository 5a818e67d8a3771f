// A decode_result is true exactly for `ok` (ring/decode_result.hpp): as it starts (incomplete), for a message
// decoded, and for a frame error, a CRC error and `no_room`.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "support/ring_frames.hpp"
#include "trionet/ring.hpp"

namespace {

namespace ring = trionet::ring;
using trionet::test::chars;

TEST(RingDecodeResult, TrueExactlyForOk) {
  EXPECT_FALSE(ring::decode_result{});
  ring::decode_result r;
  for (const ring::decode_status status : {ring::decode_status::incomplete, ring::decode_status::frame_error,
                                           ring::decode_status::crc_error, ring::decode_status::no_room}) {
    r.status = status;
    EXPECT_FALSE(r) << ring::to_string(status);
  }
  r.status = ring::decode_status::ok;
  EXPECT_TRUE(r);

  ring::decoder<> decoder;
  ring::decode_result last;
  for (const std::uint8_t b : chars(1, "OK")) last = decoder.push(b);
  EXPECT_TRUE(last);
  EXPECT_EQ(std::string(last.msg.text.begin(), last.msg.text.end()), "OK");
  last = decoder.push(ring::make_end_of_message(1));  // stray
  EXPECT_FALSE(last);
}

}  // namespace
