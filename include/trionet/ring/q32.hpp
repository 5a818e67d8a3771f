// Q32.32 fixed point: the value of a direct variable transfer (PROTOCOL.md 1.3).
// A 64-bit two's-complement number r stands for r / 2^32, so the range is [-2^31, 2^31 - 2^-32] in
// steps of 2^-32. Conversions are constexpr, use no floating-point library call and are ISR-safe
// (on a core without an FPU the double arithmetic is a software routine).
#pragma once

#include <cstdint>

namespace trionet::ring {

enum class q32_error : std::uint8_t {
  none,
  out_of_range,  ///< outside [-2^31, 2^31 - 2^-32] after rounding
  not_a_number,  ///< NaN
};

struct q32_result {
  std::int64_t raw;
  q32_error error;
  constexpr explicit operator bool() const noexcept { return error == q32_error::none; }
};

constexpr double q32_one = 4294967296.0;  ///< 2^32: the raw value of 1.0

/// A real number to Q32.32: rounded to the nearest 2^-32, ties away from zero. Out of range is an error,
/// never wrapped or saturated.
[[nodiscard]] constexpr q32_result q32_from_double(double value) noexcept {
  if (value != value) return {0, q32_error::not_a_number};
  const double scaled = value * q32_one;           // exact: a power-of-two scale
  constexpr double limit = 9223372036854775808.0;  // 2^63
  if (!(scaled >= -limit && scaled < limit)) return {0, q32_error::out_of_range};
  auto whole = static_cast<std::int64_t>(scaled);               // truncates toward zero, exact in range
  const double fraction = scaled - static_cast<double>(whole);  // exact: |scaled| < 2^52 when non-zero
  if (fraction >= 0.5) {
    if (whole == INT64_MAX) return {0, q32_error::out_of_range};
    ++whole;
  } else if (fraction <= -0.5) {
    if (whole == INT64_MIN) return {0, q32_error::out_of_range};
    --whole;
  }
  return {whole, q32_error::none};
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

}  // namespace trionet::ring
