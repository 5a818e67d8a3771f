// Decimal text to Q32.32 (docs/protocol.md 1.3), exactly: the number the text writes, not the double
// nearest to it, rounded once to the nearest 2^-32, ties away from zero. The `trionet` tool's one reader
// of a value that goes on the ring as Q32.32 (`ring encode var --value`, `ring join`'s `send N VR VALUE`).
// A double has 53 significant bits and Q32.32 has 64, so reading through a double both refused values in
// range (2147483647.99999999977) and moved others (2147483647.5000001). Header-only; host code.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace trionet::host {

/// Why a text has no Q32.32 value.
enum class q32_text_status : std::uint8_t {
  ok,            ///< converted
  not_a_number,  ///< not the text of a finite decimal number (the syntax of parse_real)
  too_long,      ///< longer than max_q32_text characters
  out_of_range,  ///< rounds to a value outside [-2^31, 2^31 - 2^-32]
};

/// A Q32.32 value read from text (`raw` = value * 2^32), or why there is none (`raw` is then 0).
struct q32_text_result {
  q32_text_status status;  ///< `ok`, or why there is no value
  std::int64_t raw;        ///< the value times 2^32
  /// True when `status` is `ok`.
  constexpr explicit operator bool() const noexcept { return status == q32_text_status::ok; }
};

/// The longest text parse_q32 reads: far more digits than a Q32.32 value has (at most 10 whole and 32
/// fraction digits are exact), and a bound on the work (at most 33 passes over the digits).
constexpr std::size_t max_q32_text = 1000;

/// The range of Q32.32 as docs/protocol.md 1.3 writes it, for messages.
constexpr const char* q32_range_text = "[-2147483648, 2147483647.99999999977]";

/// Decimal text ("99", "-2.345", "+1e3", ".5", "2.5E-4") to Q32.32: rounded to the nearest 2^-32, ties away
/// from zero, and out_of_range when the rounded value is outside [-2^31, 2^31 - 2^-32] (raw outside
/// [-2^63, 2^63 - 1]), never wrapped. The syntax is parse_real's: an optional '+' or '-', digits
/// with an optional '.' (at least one digit), an optional exponent ('e' or 'E', an optional sign, digits);
/// nothing else (no blanks, NaN, infinities or hex). Any number of digits up to max_q32_text characters in
/// all, and any exponent: the result is exact (1e-400 is 0, 1e400 out of range).
inline q32_text_result parse_q32(std::string_view text) noexcept {
  if (text.size() > max_q32_text) return {q32_text_status::too_long, 0};
  const auto digit = [&](std::size_t i) { return i < text.size() && text[i] >= '0' && text[i] <= '9'; };
  std::size_t i = 0;
  const bool positive = i < text.size() && text[i] == '+';
  if (positive) ++i;
  const bool negative = !positive && i < text.size() && text[i] == '-';
  if (negative) ++i;
  const std::size_t whole_begin = i;
  while (digit(i)) ++i;
  const std::size_t whole_end = i;
  std::size_t fraction_begin = i;
  std::size_t fraction_end = i;
  if (i < text.size() && text[i] == '.') {
    fraction_begin = ++i;
    while (digit(i)) ++i;
    fraction_end = i;
  }
  if (whole_begin == whole_end && fraction_begin == fraction_end) return {q32_text_status::not_a_number, 0};
  constexpr long long exponent_cap = 1000000000;  // far beyond where the value is 0 or out of range
  long long exponent = 0;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    const bool exponent_negative = i < text.size() && text[i] == '-';
    if (i < text.size() && (text[i] == '-' || text[i] == '+')) ++i;
    if (!digit(i)) return {q32_text_status::not_a_number, 0};
    while (digit(i)) {
      exponent = exponent * 10 + (text[i] - '0');
      if (exponent > exponent_cap) exponent = exponent_cap;
      ++i;
    }
    if (exponent_negative) exponent = -exponent;
  }
  if (i != text.size()) return {q32_text_status::not_a_number, 0};

  // The significant digits, leading zeros left out, and where the point is among them: value =
  // 0.d1d2d3... * 10^point.
  char digits[max_q32_text];
  std::size_t count = 0;
  long long point = static_cast<long long>(whole_end - whole_begin) + exponent;
  for (std::size_t k = whole_begin; k < fraction_end; ++k) {
    if (k == whole_end) continue;  // the '.'
    if (count == 0 && text[k] == '0') {
      --point;
      continue;
    }
    digits[count++] = static_cast<char>(text[k] - '0');
  }
  while (count > 0 && digits[count - 1] == 0) --count;  // trailing zeros change nothing
  if (count == 0) return {q32_text_status::ok, 0};      // zero, with any sign and exponent
  // 10^(point - 1) <= value < 10^point.
  if (point > 10) return {q32_text_status::out_of_range, 0};  // at least 10^10
  if (point < -9) return {q32_text_status::ok, 0};             // below 10^-10 < 2^-33: rounds to 0

  // The whole part (below 10^10, so it fits) and the fraction's digits.
  std::uint64_t whole = 0;
  for (long long k = 0; k < point; ++k) {
    whole = whole * 10 + (k < static_cast<long long>(count) ? static_cast<std::uint64_t>(digits[k]) : 0U);
  }
  if (whole > (std::uint64_t{1} << 31U)) return {q32_text_status::out_of_range, 0};
  char fraction[max_q32_text + 16];
  std::size_t length = 0;
  for (long long k = point; k < 0; ++k) fraction[length++] = 0;  // at most 9 zeros after the point
  for (long long k = point < 0 ? 0 : point; k < static_cast<long long>(count); ++k) fraction[length++] = digits[k];

  // floor(fraction * 2^33), one bit per doubling of the decimal fraction (the carry out of its first digit);
  // then the nearest 2^-32, a tie up: floor((floor(2x) + 1) / 2) = floor(x + 1/2).
  std::uint64_t twice = 0;
  for (int bit = 0; bit < 33; ++bit) {
    int carry = 0;
    for (std::size_t k = length; k-- > 0;) {
      const int doubled = fraction[k] * 2 + carry;
      fraction[k] = static_cast<char>(doubled % 10);
      carry = doubled / 10;
    }
    twice = twice << 1U | static_cast<std::uint64_t>(carry);
    while (length > 0 && fraction[length - 1] == 0) --length;
  }
  const std::uint64_t magnitude = (whole << 32U) + ((twice + 1) >> 1U);  // at most 2^63 + 2^32
  constexpr std::uint64_t two_63 = std::uint64_t{1} << 63U;
  if (negative) {
    if (magnitude > two_63) return {q32_text_status::out_of_range, 0};
    return {q32_text_status::ok, magnitude == two_63 ? INT64_MIN : -static_cast<std::int64_t>(magnitude)};
  }
  if (magnitude >= two_63) return {q32_text_status::out_of_range, 0};
  return {q32_text_status::ok, static_cast<std::int64_t>(magnitude)};
}

}  // namespace trionet::host
