// TN20-17 VR message codec: docs/protocol.md 2.2's example, rounding and carry edges, and every decode error.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>
#include <string>

#include <trionet/can/vr_codec.hpp>

namespace {

using namespace trionet::can;
using trionet::byte_view;

std::string hex(const std::uint8_t (&bytes)[8]) {
  std::string out;
  char pair[4];
  for (std::uint8_t b : bytes) {
    std::snprintf(pair, sizeof pair, "%02X", b);
    out += pair;
  }
  return out;
}

// docs/protocol.md 2.2: node 1 sends VR(1) = 2.345 to node 4 -> data 01 00 00 00 00 02 0d 7a.
TEST(CanVrCodec, ProtocolExampleVrOneIsTwoPointThreeFourFive) {
  std::uint8_t data[8] = {};
  ASSERT_EQ(encode_vr(1, 2.345, data), encode_status::ok);
  EXPECT_EQ(hex(data), "0100000000020D7A");
  const decode_result back = decode_vr_message(byte_view(data));
  ASSERT_EQ(back.status, decode_status::ok);
  EXPECT_EQ(back.message.vr, 1);
  EXPECT_FALSE(back.message.value.negative);
  EXPECT_EQ(back.message.value.integer_part, 2U);
  EXPECT_EQ(back.message.value.fraction, 3450);
  EXPECT_EQ(to_double(back.message.value), 2.345);
}

// The byte order of the integer part and the fraction is configurable (docs/protocol.md 2.2).
TEST(CanVrCodec, LittleEndianReversesEachNumberOnly) {
  std::uint8_t data[8] = {};
  ASSERT_EQ(encode_vr(1, 2.345, data, byte_order::little_endian), encode_status::ok);
  EXPECT_EQ(hex(data), "0100020000007A0D");
  const decode_result back = decode_vr_message(byte_view(data), byte_order::little_endian);
  ASSERT_EQ(back.status, decode_status::ok);
  EXPECT_EQ(back.message.value.integer_part, 2U);
  EXPECT_EQ(back.message.value.fraction, 3450);
  // Read in the other order, 7A 0D is 31245: not a fraction.
  EXPECT_EQ(decode_vr_message(byte_view(data)).status, decode_status::bad_fraction);
  const vr_message parts{9, vr_value{true, 0x01020304U, 0x0506}};
  ASSERT_EQ(encode_vr_message(parts, data, byte_order::little_endian), encode_status::ok);
  EXPECT_EQ(hex(data), "0901040302010605");
  ASSERT_EQ(encode_vr_message(parts, data, byte_order::big_endian), encode_status::ok);
  EXPECT_EQ(hex(data), "0901010203040506");
  EXPECT_STREQ(to_string(byte_order::little_endian), "little_endian");
  EXPECT_STREQ(to_string(byte_order::big_endian), "big_endian");
}

TEST(CanVrCodec, BothByteOrdersRoundTripRandomParts) {
  std::mt19937 random(31);
  for (byte_order order : {byte_order::big_endian, byte_order::little_endian}) {
    for (int i = 0; i < 2000; ++i) {
      vr_message m;
      m.vr = static_cast<std::uint8_t>(random());
      m.value.integer_part = static_cast<std::uint32_t>(random());
      m.value.fraction = static_cast<std::uint16_t>(random() % 10000);
      m.value.negative = (random() & 1) != 0 && (m.value.integer_part != 0 || m.value.fraction != 0);
      std::uint8_t data[8] = {};
      ASSERT_EQ(encode_vr_message(m, data, order), encode_status::ok);
      const decode_result back = decode_vr_message(byte_view(data), order);
      ASSERT_EQ(back.status, decode_status::ok);
      EXPECT_EQ(back.message.vr, m.vr);
      EXPECT_EQ(back.message.value.negative, m.value.negative);
      EXPECT_EQ(back.message.value.integer_part, m.value.integer_part);
      EXPECT_EQ(back.message.value.fraction, m.value.fraction);
    }
  }
}

struct rounding_case {
  double input;
  bool negative;
  std::uint32_t integer_part;
  std::uint16_t fraction;
};

TEST(CanVrCodec, RoundsToFourDecimalsTiesAwayFromZeroWithCarry) {
  const rounding_case cases[] = {
      {2.345, false, 2, 3450},
      {2.34565, false, 2, 3457},  // protocol 2.2: the decimal tie rounds up although the double is below it
      {2.34564, false, 2, 3456},
      {2.345649, false, 2, 3456},
      {2.345651, false, 2, 3457},
      {-2.34565, true, 2, 3457},  // away from zero
      {0.00005, false, 0, 1},
      {0.00004999, false, 0, 0},
      {0.99995, false, 1, 0},  // carry into the integer part
      {9.99995, false, 10, 0},
      {99999.99995, false, 100000, 0},
      {-0.99995, true, 1, 0},
      {-7.5, true, 7, 5000},
      {0.0, false, 0, 0},
      {-0.0, false, 0, 0},      // zero is sent with sign 0
      {-0.00004, false, 0, 0},  // rounds to zero: sign 0
      {1e-300, false, 0, 0},
      {4294967295.9999, false, 4294967295U, 9999},   // the largest magnitude
      {4294967295.99994, false, 4294967295U, 9999},  // just below its upper tie
      {-4294967295.9999, true, 4294967295U, 9999},
      {65536.0001, false, 65536, 1},
  };
  for (const rounding_case& c : cases) {
    const value_result r = to_vr_value(c.input);
    ASSERT_EQ(r.status, encode_status::ok) << c.input;
    EXPECT_EQ(r.value.negative, c.negative) << c.input;
    EXPECT_EQ(r.value.integer_part, c.integer_part) << c.input;
    EXPECT_EQ(r.value.fraction, c.fraction) << c.input;
  }
}

TEST(CanVrCodec, MagnitudeOfTwoToTheThirtyTwoOrMoreIsAnError) {
  EXPECT_EQ(to_vr_value(4294967295.99995).status, encode_status::too_large);  // one past: carries into 2^32
  EXPECT_EQ(to_vr_value(-4294967295.99995).status, encode_status::too_large);
  EXPECT_EQ(to_vr_value(4294967296.0).status, encode_status::too_large);
  EXPECT_EQ(to_vr_value(-4294967296.0).status, encode_status::too_large);
  EXPECT_EQ(to_vr_value(1e300).status, encode_status::too_large);
  EXPECT_EQ(to_vr_value(std::numeric_limits<double>::infinity()).status, encode_status::too_large);
  EXPECT_EQ(to_vr_value(-std::numeric_limits<double>::infinity()).status, encode_status::too_large);
  EXPECT_EQ(to_vr_value(std::numeric_limits<double>::quiet_NaN()).status, encode_status::not_a_number);
  std::uint8_t data[8] = {9, 9, 9, 9, 9, 9, 9, 9};
  EXPECT_EQ(encode_vr(1, 4294967296.0, data), encode_status::too_large);
  EXPECT_EQ(encode_vr(256, 1.0, data), encode_status::vr_out_of_range);
  EXPECT_EQ(hex(data), "0909090909090909") << "nothing is written on error";
  EXPECT_EQ(encode_vr(255, -4294967295.9999, data), encode_status::ok);
  EXPECT_EQ(hex(data), "FF01FFFFFFFF270F");
}

// Every 5-decimal input, read by strtod as a user's text would be, rounds as the decimal number does.
TEST(CanVrCodec, FiveDecimalInputsRoundAsDecimalsAtEveryMagnitude) {
  std::mt19937_64 random(20001018);
  for (int i = 0; i < 200000; ++i) {
    const unsigned digits = static_cast<unsigned>(random() % 11);  // integer parts of 0..10 digits
    std::uint64_t whole = random() % 4294967296ULL;
    std::uint64_t limit = 1;
    for (unsigned d = 0; d < digits; ++d) limit *= 10;
    whole %= limit;
    std::uint64_t fifth = random() % 100000;      // five decimals
    if (i % 3 == 0) fifth = fifth / 10 * 10 + 5;  // force many ties
    char text[48];
    std::snprintf(text, sizeof text, "%llu.%05llu", static_cast<unsigned long long>(whole),
                  static_cast<unsigned long long>(fifth));
    const double value = std::strtod(text, nullptr);
    const std::uint64_t expected_scaled = (whole * 100000 + fifth + 5) / 10;  // ties away from zero
    const value_result r = to_vr_value(value);
    if (expected_scaled / 10000 > 4294967295ULL) {
      EXPECT_EQ(r.status, encode_status::too_large) << text;
      continue;
    }
    ASSERT_EQ(r.status, encode_status::ok) << text;
    EXPECT_EQ(std::uint64_t{r.value.integer_part} * 10000 + r.value.fraction, expected_scaled) << text;
    const value_result negative = to_vr_value(-value);
    EXPECT_EQ(negative.value.negative, expected_scaled != 0) << text;
    EXPECT_EQ(negative.value.integer_part, r.value.integer_part) << text;
    EXPECT_EQ(negative.value.fraction, r.value.fraction) << text;
  }
}

// Values that are already 4-decimal numbers survive encode -> decode -> to_double unchanged.
TEST(CanVrCodec, FourDecimalValuesRoundTripExactly) {
  std::mt19937_64 random(17);
  for (int i = 0; i < 100000; ++i) {
    const std::uint64_t scaled = random() % (4294967296ULL * 10000);
    char text[48];
    std::snprintf(text, sizeof text, "%s%llu.%04llu", i % 2 ? "-" : "",
                  static_cast<unsigned long long>(scaled / 10000),
                  static_cast<unsigned long long>(scaled % 10000));
    const double value = std::strtod(text, nullptr);
    std::uint8_t data[8] = {};
    ASSERT_EQ(encode_vr(42, value, data), encode_status::ok) << text;
    const decode_result back = decode_vr_message(byte_view(data));
    ASSERT_EQ(back.status, decode_status::ok);
    EXPECT_EQ(to_double(back.message.value), value) << text;
  }
}

TEST(CanVrCodec, PartsEncodeBigEndianWithoutDoubles) {
  std::uint8_t data[8] = {};
  const vr_message message{200, {true, 0x12345678U, 9999}};
  ASSERT_EQ(encode_vr_message(message, data), encode_status::ok);
  EXPECT_EQ(hex(data),
            "C801123456782"
            "70F");
  const decode_result back = decode_vr_message(byte_view(data));
  ASSERT_EQ(back.status, decode_status::ok);
  EXPECT_EQ(back.message.vr, 200);
  EXPECT_TRUE(back.message.value.negative);
  EXPECT_EQ(back.message.value.integer_part, 0x12345678U);
  EXPECT_EQ(back.message.value.fraction, 9999);

  ASSERT_EQ(encode_vr_message(vr_message{3, {true, 0, 0}}, data), encode_status::ok);
  EXPECT_EQ(hex(data), "0300000000000000") << "negative zero is sent with sign 0";

  std::uint8_t untouched[8] = {};
  EXPECT_EQ(encode_vr_message(vr_message{1, {false, 1, 10000}}, untouched),
            encode_status::fraction_out_of_range);
  EXPECT_EQ(hex(untouched), "0000000000000000");
}

TEST(CanVrCodec, DecodeRejectsDlcSignAndFraction) {
  const std::uint8_t good[8] = {1, 0, 0, 0, 0, 2, 0x0D, 0x7A};
  EXPECT_EQ(decode_vr_message(byte_view(good, 7)).status, decode_status::bad_dlc);
  EXPECT_EQ(decode_vr_message(byte_view(good, 0)).status, decode_status::bad_dlc);
  const std::uint8_t nine[9] = {1, 0, 0, 0, 0, 2, 0x0D, 0x7A, 0};
  EXPECT_EQ(decode_vr_message(byte_view(nine)).status, decode_status::bad_dlc);
  const std::uint8_t sign_two[8] = {1, 2, 0, 0, 0, 2, 0x0D, 0x7A};
  EXPECT_EQ(decode_vr_message(byte_view(sign_two)).status, decode_status::bad_sign);
  const std::uint8_t sign_ff[8] = {1, 0xFF, 0, 0, 0, 2, 0x0D, 0x7A};
  EXPECT_EQ(decode_vr_message(byte_view(sign_ff)).status, decode_status::bad_sign);
  const std::uint8_t fraction_10000[8] = {1, 0, 0, 0, 0, 2, 0x27, 0x10};
  EXPECT_EQ(decode_vr_message(byte_view(fraction_10000)).status, decode_status::bad_fraction);
  const std::uint8_t fraction_ffff[8] = {1, 1, 0, 0, 0, 2, 0xFF, 0xFF};
  EXPECT_EQ(decode_vr_message(byte_view(fraction_ffff)).status, decode_status::bad_fraction);
  const std::uint8_t sign_and_fraction[8] = {1, 7, 0, 0, 0, 2, 0xFF, 0xFF};
  EXPECT_EQ(decode_vr_message(byte_view(sign_and_fraction)).status, decode_status::bad_sign) << "wire order";
  const std::uint8_t fraction_9999[8] = {1, 0, 0, 0, 0, 2, 0x27, 0x0F};
  EXPECT_EQ(decode_vr_message(byte_view(fraction_9999)).status, decode_status::ok);
}

TEST(CanVrCodec, EveryEightByteInputIsClassifiedWithoutUndefinedBehaviour) {
  std::mt19937 random(5);
  for (int i = 0; i < 100000; ++i) {
    std::uint8_t data[8];
    for (std::uint8_t& b : data) b = static_cast<std::uint8_t>(random());
    const decode_result r = decode_vr_message(byte_view(data));
    const unsigned fraction = unsigned{data[6]} << 8 | data[7];
    const decode_status expected = data[1] > 1       ? decode_status::bad_sign
                                   : fraction > 9999 ? decode_status::bad_fraction
                                                     : decode_status::ok;
    ASSERT_EQ(r.status, expected);
    if (expected == decode_status::ok) {
      std::uint8_t again[8] = {};
      ASSERT_EQ(encode_vr_message(r.message, again), encode_status::ok);
      const bool negative_zero = data[1] == 1 && r.message.value.integer_part == 0 && fraction == 0;
      if (!negative_zero) {
        EXPECT_EQ(hex(again), hex(data));
      }
    }
  }
}

TEST(CanVrCodec, UsableAtCompileTime) {
  constexpr value_result rounded = to_vr_value(2.34565);
  static_assert(rounded.status == encode_status::ok && rounded.value.fraction == 3457, "constexpr rounding");
  static_assert(to_double(vr_value{true, 1, 5000}) == -1.5, "constexpr conversion");
  EXPECT_EQ(rounded.value.integer_part, 2U);
  EXPECT_TRUE(std::signbit(to_double(vr_value{true, 0, 0}))) << "sign 1 with zero magnitude decodes as -0.0";
}

}  // namespace

TEST(CanVrCodec, Q32ValuesRoundWithIntegersOnly) {
  using trionet::q32_to_decimal;
  const auto check = [](std::int64_t raw, bool negative, std::uint32_t integer, std::uint16_t fraction) {
    const auto v = q32_to_decimal(raw);
    EXPECT_EQ(v.negative, negative) << raw;
    EXPECT_EQ(v.integer_part, integer) << raw;
    EXPECT_EQ(v.fraction, fraction) << raw;
  };
  check(std::int64_t{5} << 31, false, 2, 5000);     // 2.5
  check(-(std::int64_t{5} << 30), true, 1, 2500);   // -1.25
  check((std::int64_t{1} << 32) - 1, false, 1, 0);  // 0.99999999977 carries into 1.0000
  check(-((std::int64_t{1} << 32) - 1), true, 1, 0);
  check(214748, false, 0, 0);               // 0.0000499999: rounds to zero...
  check(-214748, false, 0, 0);              // ... and zero has sign 0
  check(214749, false, 0, 1);               // 0.0000500003: up
  check(INT64_MIN, true, 2147483648u, 0);   // -2^31
  check(INT64_MAX, false, 2147483648u, 0);  // 2^31 - 2^-32 rounds to 2^31
  // Agrees with the double path wherever the double is exact.
  for (std::int64_t raw : {std::int64_t{12345} << 20, -(std::int64_t{98765} << 16), std::int64_t{3} << 30}) {
    const auto from_double = trionet::can::to_vr_value(static_cast<double>(raw) / 4294967296.0);
    ASSERT_EQ(from_double.status, trionet::can::encode_status::ok);
    const auto from_q32 = q32_to_decimal(raw);
    EXPECT_EQ(from_q32.negative, from_double.value.negative);
    EXPECT_EQ(from_q32.integer_part, from_double.value.integer_part);
    EXPECT_EQ(from_q32.fraction, from_double.value.fraction);
  }
}

// The 32-bit arithmetic gives (fraction * 10000 + 2^31) >> 32 exactly: checked against 64-bit arithmetic at
// every rounding boundary (two fractions either side of each k + 1/2 ten-thousandths) and on random values.
TEST(CanVrCodec, Q32FractionRoundingMatchesSixtyFourBitArithmetic) {
  using trionet::q32_to_decimal;
  const auto expect_exact = [](std::uint32_t fraction) {
    const std::uint64_t nearest = (std::uint64_t{fraction} * 10000u + (1ULL << 31U)) >> 32U;
    const auto v = q32_to_decimal(static_cast<std::int64_t>((std::uint64_t{7} << 32U) | fraction));
    const std::uint64_t got = v.integer_part == 8 ? 10000 : v.fraction;  // 10000 carries into the integer
    ASSERT_EQ(got, nearest) << fraction;
  };
  for (std::uint64_t k = 0; k < 10000; ++k) {
    const std::uint64_t boundary = ((2 * k + 1) << 32U) / 20000u;  // floor((k + 1/2) * 2^32 / 10000)
    for (std::uint64_t f = boundary - 2; f <= boundary + 2; ++f) expect_exact(static_cast<std::uint32_t>(f));
  }
  std::mt19937 rng(2017);
  for (int i = 0; i < 1000000; ++i) expect_exact(static_cast<std::uint32_t>(rng()));
  expect_exact(0);
  expect_exact(0xFFFFFFFFu);
}
