// Q32.32 fixed point, the value of a direct variable transfer on the ring (docs/protocol.md 1.3), and the
// decimal with four places that the CAN VR exchange carries (docs/protocol.md 2.2): the one home of both and
// of the conversions between them, used by the ring, the CAN codec and VR().
//
// A 64-bit two's-complement number r stands for r / 2^32, so the range is [-2^31, 2^31 - 2^-32] in steps of
// 2^-32. Every conversion is constexpr, uses no floating-point library call and is ISR-safe. The decimal <->
// Q32.32 conversions use 32-bit integer arithmetic only (no division or 64-bit multiply routine on a core
// without them); the double conversions are a software routine on a core without an FPU.
#pragma once

#include <cstdint>

namespace trionet {

/// Why a number has no Q32.32 value.
enum class q32_status : std::uint8_t {
  ok,                     ///< converted
  out_of_range,           ///< outside [-2^31, 2^31 - 2^-32] after rounding
  not_a_number,           ///< NaN
  fraction_out_of_range,  ///< a decimal's fraction above 9999 ten-thousandths
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(q32_status status) noexcept {
  switch (status) {
    case q32_status::ok:
      return "ok";
    case q32_status::out_of_range:
      return "out_of_range";
    case q32_status::not_a_number:
      return "not_a_number";
    case q32_status::fraction_out_of_range:
      return "fraction_out_of_range";
  }
  return "unknown";
}

/// A Q32.32 value (`raw` = value * 2^32), or why there is none (`raw` is then 0).
struct [[nodiscard]] q32_result {
  q32_status status;  ///< `ok`, or why there is no value
  std::int64_t raw;   ///< the value times 2^32
  /// True when `status` is `ok`.
  constexpr explicit operator bool() const noexcept { return status == q32_status::ok; }
};

constexpr double q32_one = 4294967296.0;  ///< 2^32: the raw value of 1.0

/// A real number to Q32.32: rounded to the nearest 2^-32, ties away from zero. Out of range is an error,
/// never wrapped or saturated.
[[nodiscard]] constexpr q32_result q32_from_double(double value) noexcept {
  if (value != value) return {q32_status::not_a_number, 0};
  const double scaled = value * q32_one;           // exact: a power-of-two scale
  constexpr double limit = 9223372036854775808.0;  // 2^63
  if (!(scaled >= -limit && scaled < limit)) return {q32_status::out_of_range, 0};
  auto whole = static_cast<std::int64_t>(scaled);               // truncates toward zero, exact in range
  const double fraction = scaled - static_cast<double>(whole);  // exact: |scaled| < 2^52 when non-zero
  if (fraction >= 0.5) {
    if (whole == INT64_MAX) return {q32_status::out_of_range, 0};
    ++whole;
  } else if (fraction <= -0.5) {
    if (whole == INT64_MIN) return {q32_status::out_of_range, 0};
    --whole;
  }
  return {q32_status::ok, whole};
}

/// A whole number to Q32.32 (always in range).
constexpr std::int64_t q32_from_integer(std::int32_t value) noexcept {
  return static_cast<std::int64_t>(static_cast<std::uint64_t>(static_cast<std::int64_t>(value)) << 32);
}

/// 64 raw bits, as carried on the wire, to the signed Q32.32 number (two's complement).
constexpr std::int64_t q32_from_raw(std::uint64_t bits) noexcept {
  return bits <= static_cast<std::uint64_t>(INT64_MAX) ? static_cast<std::int64_t>(bits)
                                                       : -static_cast<std::int64_t>(~bits) - 1;
}
/// The 64 raw bits of a Q32.32 number.
constexpr std::uint64_t q32_to_raw(std::int64_t raw) noexcept {
  return static_cast<std::uint64_t>(raw);
}

/// Q32.32 to double: exact while |value| < 2^21, else rounded to 53 significant bits.
constexpr double q32_to_double(std::int64_t raw) noexcept {
  return static_cast<double>(raw) / q32_one;
}

/// A decimal with four places: sign, integer part of the magnitude, fraction in ten-thousandths (the CAN
/// VR exchange's "4 decimal places"). A sign with a zero magnitude is allowed (-0).
struct decimal {
  static constexpr std::uint16_t max_fraction = 9999;  ///< largest fraction, in ten-thousandths
  static constexpr std::uint32_t scale = 10000;        ///< ten-thousandths per unit

  bool negative = false;           ///< the sign (true with a zero magnitude is -0)
  std::uint32_t integer_part = 0;  ///< the integer part of the magnitude
  std::uint16_t fraction = 0;  ///< ten-thousandths, 0..9999
};

/// A decimal as the double nearest to it (exact decimal numerator, one rounding). Sign with a zero magnitude
/// gives -0.0.
[[nodiscard]] constexpr double to_double(const decimal& value) noexcept {
  // integer * 10000 + fraction < 2^53 is exact, so this is the correctly rounded decimal.
  const std::uint64_t scaled = std::uint64_t{value.integer_part} * decimal::scale + value.fraction;
  const double magnitude = static_cast<double>(scaled) / static_cast<double>(decimal::scale);
  return value.negative ? -magnitude : magnitude;
}

/// A decimal to Q32.32, rounded to the nearest 2^-32 (ties away from zero), with 32-bit integer arithmetic
/// only. `out_of_range` outside [-2^31, 2^31 - 2^-32]; `fraction_out_of_range` for a fraction above 9999.
[[nodiscard]] constexpr q32_result q32_from_decimal(const decimal& value) noexcept {
  if (value.fraction > decimal::max_fraction) return {q32_status::fraction_out_of_range, 0};
  if (value.integer_part > 0x80000000u) return {q32_status::out_of_range, 0};
  // (t * 2^32 + 5000) / 10000 with 2^32 = 429496 * 10000 + 7296, so the part left to divide is
  // n = t * 7296 + 5000 < 2^27. floor(n / 10000) in 32-bit arithmetic only (no division or 64-bit multiply
  // routine on a core without them): (n >> 11) * 13422 >> 16 is within one of it, then one correction.
  const std::uint32_t n = static_cast<std::uint32_t>(value.fraction) * 7296u + 5000u;
  std::uint32_t quotient = ((n >> 11) * 13422u) >> 16;
  if (quotient * 10000u > n) {
    --quotient;
  } else if (n - quotient * 10000u >= 10000u) {
    ++quotient;
  }
  const std::uint32_t fraction = static_cast<std::uint32_t>(value.fraction) * 429496u + quotient;
  const std::uint64_t magnitude = (static_cast<std::uint64_t>(value.integer_part) << 32) | fraction;
  if (!value.negative) {
    if (value.integer_part == 0x80000000u) return {q32_status::out_of_range, 0};  // 2^31 and above
    return {q32_status::ok, static_cast<std::int64_t>(magnitude)};
  }
  if (value.integer_part == 0x80000000u && fraction != 0)
    return {q32_status::out_of_range, 0};  // below -2^31
  return {q32_status::ok,
          value.integer_part == 0x80000000u ? INT64_MIN : -static_cast<std::int64_t>(magnitude)};
}

/// A Q32.32 value rounded to four decimals, ties away from zero, with 32-bit integer arithmetic only
/// (for firmware without floating point). Always in range; zero, and anything that rounds to zero, has no
/// sign.
[[nodiscard]] constexpr decimal q32_to_decimal(std::int64_t raw) noexcept {
  const bool negative = raw < 0;
  const std::uint64_t magnitude =
      negative ? ~static_cast<std::uint64_t>(raw) + 1U : static_cast<std::uint64_t>(raw);
  auto integer = static_cast<std::uint32_t>(magnitude >> 32U);  // at most 2^31
  // (fraction * 10000 + 2^31) / 2^32: the nearest ten-thousandth, a tie rounded up (away from zero). In
  // 32-bit pieces, fraction = high * 2^16 + low, so that no 64-bit multiply routine is needed on a core
  // without one.
  const auto fraction = static_cast<std::uint32_t>(magnitude);
  const std::uint32_t low = (fraction & 0xFFFFU) * decimal::scale + 0x80000000U;  // < 2^32
  auto ten_thousandths = ((fraction >> 16U) * decimal::scale + (low >> 16U)) >> 16U;
  if (ten_thousandths == decimal::scale) {
    ten_thousandths = 0;
    ++integer;
  }
  decimal out;
  out.negative = negative && (integer != 0 || ten_thousandths != 0);
  out.integer_part = integer;
  out.fraction = static_cast<std::uint16_t>(ten_thousandths);
  return out;
}

}  // namespace trionet
