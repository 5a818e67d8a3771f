// The direct variable transfer's CRC (docs/protocol.md 1.3, configurable): the default CRC-16/CCITT-FALSE in
// every table kind, other static policies (reflected or not), the run-time CRC, and a decoder and an encoder
// that take any of them.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <type_traits>
#include <vector>

#include "support/ring_events.hpp"
#include "trionet/ring.hpp"
#include "trionet/vr.hpp"

namespace ring = trionet::ring;
using trionet::byte_view;
using trionet::test::decode_bulk;
using trionet::test::decode_bytewise;

namespace {

// docs/protocol.md 1.3's example frame.
const std::vector<std::uint8_t>& golden = trionet::test::golden_variable_transfer;

constexpr std::uint8_t check_bytes[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};

// The Rocksoft model, one message bit at a time, written independently of crc.hpp: the register holds the
// CRC in non-reflected order throughout; a reflected input feeds each byte's bits least significant first.
std::uint16_t reference_crc(const ring::crc16_parameters& p, const std::uint8_t* data, std::size_t size) {
  unsigned reg = p.initial;
  for (std::size_t i = 0; i < size; ++i) {
    for (int k = 0; k < 8; ++k) {
      const unsigned bit = p.reflect_in ? (data[i] >> k) & 1u : (data[i] >> (7 - k)) & 1u;
      const unsigned top = ((reg >> 15) & 1u) ^ bit;
      reg = (reg << 1) & 0xFFFFu;
      if (top != 0) reg ^= p.polynomial;
    }
  }
  if (p.reflect_out) reg = ring::reflect16(static_cast<std::uint16_t>(reg));
  return static_cast<std::uint16_t>(reg ^ p.xor_out);
}

template <class Crc>
std::uint16_t check_value() {
  return Crc::compute(check_bytes, sizeof check_bytes);
}

// A CRC policy written by hand, with only initial, update and finish.
struct sum16 {
  static constexpr std::uint16_t initial = 0;
  static constexpr std::uint16_t update(std::uint16_t crc, std::uint8_t b) noexcept {
    return static_cast<std::uint16_t>(crc + b);
  }
  static constexpr std::uint16_t finish(std::uint16_t crc) noexcept { return crc; }
};

}  // namespace

TEST(RingGoldenExample, TableFreeCrcGivesTheSameFrame) {
  std::uint8_t frame[16];
  ASSERT_TRUE(
      ring::encode_variable<ring::crc16_ccitt_false_bitwise>(frame, 1, 200, trionet::q32_from_integer(99)));
  EXPECT_EQ(std::vector<std::uint8_t>(frame, frame + 16), golden);
  ring::decoder<256, ring::crc16_ccitt_false_bitwise> d;
  const auto events = decode_bytewise(d, golden);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].status, ring::decode_status::ok);
}

TEST(RingCrc, CheckValueWithTable) {
  const char* check = "123456789";
  EXPECT_EQ(ring::crc16_ccitt_false_table::compute(reinterpret_cast<const std::uint8_t*>(check), 9), 0x29B1);
  EXPECT_EQ(ring::crc16_ccitt_false::compute(reinterpret_cast<const std::uint8_t*>(check), 9), 0x29B1);
}

// The default is sliced on 64-bit cores and one table on 32-bit ones (the firmware build checks the latter).
TEST(RingCrc, DefaultIsSlicedOnSixtyFourBitCores) {
  constexpr bool sixty_four_bit = sizeof(void*) == 8;
  EXPECT_EQ((std::is_same_v<ring::crc16_ccitt_false, ring::crc16_ccitt_false_sliced>), sixty_four_bit);
  EXPECT_EQ((std::is_same_v<ring::crc16_ccitt_false, ring::crc16_ccitt_false_table>), !sixty_four_bit);
}

TEST(RingCrc, CheckValueWithoutTable) {
  const char* check = "123456789";
  EXPECT_EQ(ring::crc16_ccitt_false_bitwise::compute(reinterpret_cast<const std::uint8_t*>(check), 9),
            0x29B1);
}

TEST(RingCrc, CheckValueAtCompileTime) {
  constexpr std::uint8_t check[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  static_assert(ring::crc16_ccitt_false_table::compute(check, 9) == 0x29B1, "table CRC check value");
  static_assert(ring::crc16_ccitt_false_sliced::compute(check, 9) == 0x29B1, "sliced CRC check value");
  static_assert(ring::crc16_ccitt_false_bitwise::compute(check, 9) == 0x29B1, "bitwise CRC check value");
  SUCCEED();
}

TEST(RingCrc, AnotherPolynomialAndInitCanBePluggedIn) {
  // CRC-16/XMODEM (poly 0x1021, init 0) and CRC-16/GENIBUS (init 0xFFFF, xorout 0xFFFF): catalogue check
  // values.
  using xmodem = ring::crc16<0x1021, 0x0000>;
  using genibus = ring::crc16<0x1021, 0xFFFF, 0xFFFF, ring::crc_table::none>;
  const char* check = "123456789";
  const auto* data = reinterpret_cast<const std::uint8_t*>(check);
  EXPECT_EQ(xmodem::compute(data, 9), 0x31C3);
  EXPECT_EQ(genibus::compute(data, 9), 0xD64E);

  // A decoder with another CRC accepts frames encoded with it and rejects default-CRC frames.
  std::uint8_t frame[16];
  ASSERT_TRUE(ring::encode_variable<xmodem>(frame, 1, 200, trionet::q32_from_integer(99)));
  ring::decoder<256, xmodem> d;
  auto events = decode_bytewise(d, std::vector<std::uint8_t>(frame, frame + 16));
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].status, ring::decode_status::ok);
  events = decode_bytewise(d, golden);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].status, ring::decode_status::crc_error);
}

TEST(RingCrc, OnlyFourteenBitsTravel) {
  EXPECT_EQ(ring::crc_wire_bits(0xFFFF), 0x7F7F);
  EXPECT_EQ(ring::crc_wire_bits(0x3EFF), 0x3E7F);
}

TEST(RingCrc, SlicedTablesGiveTheSameCrc) {
  const char* check = "123456789";
  EXPECT_EQ(ring::crc16_ccitt_false_sliced::compute(reinterpret_cast<const std::uint8_t*>(check), 9), 0x29B1);
  static_assert(ring::crc16_ccitt_false_sliced::compute(check_bytes, 9) == 0x29B1, "sliced CRC check value");
  std::mt19937_64 rng(5);
  std::vector<std::uint8_t> bytes(1000);
  for (auto& b : bytes) b = static_cast<std::uint8_t>(rng());
  for (std::size_t length = 0; length <= bytes.size(); length += 1 + length / 7) {
    ASSERT_EQ(ring::crc16_ccitt_false_sliced::compute(bytes.data(), length),
              ring::crc16_ccitt_false::compute(bytes.data(), length))
        << length;
  }
  using xmodem_sliced = ring::crc16<0x1021, 0x0000, 0, ring::crc_table::sliced>;
  EXPECT_EQ(xmodem_sliced::compute(reinterpret_cast<const std::uint8_t*>(check), 9), 0x31C3);
  // A decoder and an encoder with the sliced policy agree with the golden frame.
  std::uint8_t frame[16];
  ASSERT_TRUE(
      ring::encode_variable<ring::crc16_ccitt_false_sliced>(frame, 1, 200, trionet::q32_from_integer(99)));
  EXPECT_EQ(std::vector<std::uint8_t>(frame, frame + 16), golden);
  ring::decoder<256, ring::crc16_ccitt_false_sliced> d;
  const auto events = decode_bulk(d, golden);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].status, ring::decode_status::ok);
}

TEST(RingCrc, HandWrittenPolicyWithTheMinimalInterface) {
  std::uint8_t frame[16];
  ASSERT_TRUE(ring::encode_variable<sum16>(frame, 1, 1, 1));
  ring::decoder<256, sum16> d;
  const auto events = decode_bytewise(d, std::vector<std::uint8_t>(frame, frame + 16));
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].status, ring::decode_status::ok);
  EXPECT_EQ(frame[13], 2);  // V0 + X0 = 1 + 1
}

TEST(RingCrcReflected, CatalogueCheckValuesInEveryTableKind) {
  using arc = ring::crc16<0x8005, 0x0000, 0x0000, ring::crc_table::lookup, true, true>;
  using arc_bitwise = ring::crc16<0x8005, 0x0000, 0x0000, ring::crc_table::none, true, true>;
  using arc_sliced = ring::crc16<0x8005, 0x0000, 0x0000, ring::crc_table::sliced, true, true>;
  EXPECT_EQ(check_value<arc>(), 0xBB3D);  // CRC-16/ARC
  EXPECT_EQ(check_value<arc_bitwise>(), 0xBB3D);
  EXPECT_EQ(check_value<arc_sliced>(), 0xBB3D);
  using x25 = ring::crc16<0x1021, 0xFFFF, 0xFFFF, ring::crc_table::sliced, true, true>;
  EXPECT_EQ(check_value<x25>(), 0x906E);  // CRC-16/IBM-SDLC
  using modbus = ring::crc16<0x8005, 0xFFFF, 0x0000, ring::crc_table::lookup, true, true>;
  EXPECT_EQ(check_value<modbus>(), 0x4B37);  // CRC-16/MODBUS
  using riello = ring::crc16<0x1021, 0xB2AA, 0x0000, ring::crc_table::none, true, true>;
  EXPECT_EQ(check_value<riello>(), 0x63D0);  // CRC-16/RIELLO: a non-symmetric init, reflected
  static_assert(arc_sliced::compute(check_bytes, 9) == 0xBB3D, "constexpr reflected CRC");
  // Unchanged defaults: CCITT-FALSE is still the default and not reflected.
  EXPECT_EQ(check_value<ring::crc16_ccitt_false>(), 0x29B1);
  static_assert(!ring::crc16_ccitt_false::reflect_in && !ring::crc16_ccitt_false::reflect_out, "");
}

TEST(RingCrcReflected, EveryTableKindAndReflectionMatchesTheBitModel) {
  std::mt19937_64 rng(16);
  std::vector<std::uint8_t> data(300);
  for (auto& b : data) b = static_cast<std::uint8_t>(rng());
  const auto check = [&](auto policy, ring::crc16_parameters p) {
    using crc = decltype(policy);
    for (std::size_t length : {0u, 1u, 3u, 4u, 5u, 12u, 13u, 64u, 299u}) {
      ASSERT_EQ(crc::compute(data.data(), length), reference_crc(p, data.data(), length)) << length;
      ASSERT_EQ((ring::crc_of<crc, 12>(data.data())), reference_crc(p, data.data(), 12));
    }
  };
  // Mixed reflections (no catalogue entry has them, the model allows them).
  check(ring::crc16<0x3D65, 0x1234, 0x0F0F, ring::crc_table::lookup, true, false>{},
        {0x3D65, 0x1234, true, false, 0x0F0F});
  check(ring::crc16<0x3D65, 0x1234, 0x0F0F, ring::crc_table::sliced, false, true>{},
        {0x3D65, 0x1234, false, true, 0x0F0F});
  check(ring::crc16<0x3D65, 0x1234, 0x0F0F, ring::crc_table::none, true, false>{},
        {0x3D65, 0x1234, true, false, 0x0F0F});
  check(ring::crc16<0x8BB7, 0xBEEF, 0x0000, ring::crc_table::sliced, true, true>{},
        {0x8BB7, 0xBEEF, true, true, 0x0000});
  check(ring::crc16<0x8BB7, 0xBEEF, 0x0000, ring::crc_table::lookup, false, false>{},
        {0x8BB7, 0xBEEF, false, false, 0x0000});
}

TEST(RingCrcRuntime, MatchesTheBitModelForRandomParameters) {
  std::mt19937_64 rng(17);
  std::vector<std::uint8_t> data(40);
  for (int round = 0; round < 400; ++round) {
    ring::crc16_parameters p;
    p.polynomial = static_cast<std::uint16_t>(rng());
    p.initial = static_cast<std::uint16_t>(rng());
    p.xor_out = static_cast<std::uint16_t>(rng());
    p.reflect_in = (round & 1) != 0;
    p.reflect_out = (round & 2) != 0;
    for (auto& b : data) b = static_cast<std::uint8_t>(rng());
    const ring::crc16_runtime crc(p);
    EXPECT_EQ(crc.parameters(), p);
    const std::size_t length = static_cast<std::size_t>(rng() % data.size());
    ASSERT_EQ(crc.compute(data.data(), length), reference_crc(p, data.data(), length)) << round;
    ASSERT_EQ(ring::crc_of<12>(crc, data.data()), reference_crc(p, data.data(), 12)) << round;
  }
}

TEST(RingCrcRuntime, DefaultIsTheRingCrcAndTheDecoderUsesIt) {
  const ring::crc16_runtime ccitt_false;
  EXPECT_EQ(ccitt_false.compute(check_bytes, 9), 0x29B1);
  // The protocol's example frame (docs/protocol.md 1.3) through a decoder holding a run-time CRC.
  ring::decoder<256, ring::crc16_runtime> d(ccitt_false);
  int messages = 0;
  d.push(byte_view(golden.data(), golden.size()), [&](const ring::decode_result& r) {
    EXPECT_EQ(r.status, ring::decode_status::ok);
    EXPECT_EQ(r.msg.vr, 200);
    EXPECT_EQ(r.msg.value, trionet::q32_from_integer(99));
    ++messages;
  });
  EXPECT_EQ(messages, 1);
  // Another run-time CRC (XMODEM) rejects it; the encoder with that CRC makes a frame it accepts.
  const ring::crc16_runtime xmodem(ring::crc16_parameters{0x1021, 0x0000, false, false, 0x0000});
  ring::decoder<256, ring::crc16_runtime> x(xmodem);
  ring::decode_result last;
  for (std::uint8_t b : golden) last = x.push(b);
  EXPECT_EQ(last.status, ring::decode_status::crc_error);
  std::uint8_t frame[16];
  ASSERT_TRUE(ring::encode_variable(frame, 1, 200, trionet::q32_from_integer(99), xmodem));
  for (std::uint8_t b : frame) last = x.push(b);
  EXPECT_EQ(last.status, ring::decode_status::ok);
  // Byte for byte what the static XMODEM policy sends.
  std::uint8_t expected[16];
  using xmodem_policy = ring::crc16<0x1021, 0x0000>;
  ASSERT_TRUE(ring::encode_variable<xmodem_policy>(expected, 1, 200, trionet::q32_from_integer(99)));
  EXPECT_EQ(0, std::memcmp(frame, expected, 16));
}

TEST(RingCrcRuntime, AStaticPolicyCostsTheDecoderNoRam) {
  EXPECT_EQ(sizeof(ring::decoder<256>), sizeof(ring::decoder<256, ring::crc16_ccitt_false_bitwise>));
  EXPECT_GT(sizeof(ring::decoder<256, ring::crc16_runtime>), sizeof(ring::decoder<256>));
}
