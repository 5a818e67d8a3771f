// The VR codec is constexpr (can/vr_codec.hpp): a message can be encoded and decoded in a constant
// expression, e.g. a table of frames built at compile time in firmware. docs/protocol.md 2.2's example, VR(1)
// = 2.345, is 01 00 00 00 00 02 0D 7A big-endian.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>

#include <trionet/can/vr_codec.hpp>

namespace {

using namespace trionet::can;
using bytes = std::array<std::uint8_t, vr_message_size>;

constexpr bytes encoded(const vr_message& message, byte_order order) {
  std::uint8_t out[vr_message_size] = {};
  const encode_status status = encode_vr_message(message, out, order);
  bytes result{};
  for (std::size_t i = 0; i < vr_message_size; ++i) result[i] = status == encode_status::ok ? out[i] : 0xEE;
  return result;
}

constexpr bool same(const bytes& a, const bytes& b) {  // std::array's == is constexpr from C++20 only
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i] != b[i]) return false;
  }
  return true;
}

constexpr vr_message example{1, {false, 2, 3450}};
constexpr vr_message negative{200, {true, 0x01020304, 9999}};

static_assert(same(encoded(example, byte_order::big_endian), bytes{0x01, 0, 0, 0, 0, 0x02, 0x0D, 0x7A}));
static_assert(same(encoded(example, byte_order::little_endian), bytes{0x01, 0, 0x02, 0, 0, 0, 0x7A, 0x0D}));
static_assert(same(encoded(negative, byte_order::big_endian), bytes{200, 1, 1, 2, 3, 4, 0x27, 0x0F}));
static_assert(same(encoded(negative, byte_order::little_endian), bytes{200, 1, 4, 3, 2, 1, 0x0F, 0x27}));

constexpr decode_result decoded(const bytes& wire, byte_order order) {
  return decode_vr_message(trionet::byte_view(wire.data(), wire.size()), order);
}

static_assert(decoded(bytes{200, 1, 1, 2, 3, 4, 0x27, 0x0F}, byte_order::big_endian)
                  .message.value.integer_part == 0x01020304);
static_assert(
    decoded(bytes{200, 1, 4, 3, 2, 1, 0x0F, 0x27}, byte_order::little_endian).message.value.fraction == 9999);

TEST(CanVrCodecAtCompileTime, TheProtocolExampleInBothByteOrders) {
  // The checks are the static_asserts above; here the same at run time, so a failure also reads as a test.
  EXPECT_EQ(encoded(example, byte_order::big_endian), (bytes{0x01, 0, 0, 0, 0, 0x02, 0x0D, 0x7A}));
  const decode_result back = decoded(encoded(negative, byte_order::little_endian), byte_order::little_endian);
  ASSERT_EQ(back.status, decode_status::ok);
  EXPECT_EQ(back.message.vr, 200);
  EXPECT_TRUE(back.message.value.negative);
  EXPECT_EQ(back.message.value.integer_part, 0x01020304U);
  EXPECT_EQ(back.message.value.fraction, 9999);
}

}  // namespace
