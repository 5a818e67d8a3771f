// TN20-17 VR message codec: one VR() value in the 8 data bytes of a CAN frame (docs/protocol.md 2.2).
//
//   byte    0        1        2        3        4        5        6        7
//       +--------+--------+--------+--------+--------+--------+--------+--------+
//       |   VR   |  sign  |  integer part of |value|, uint32   | fraction, uint16|
//       | 0..255 | 0 or 1 |  big-endian: MSB first ... LSB    | BE, 0..9999     |
//       +--------+--------+--------+--------+--------+--------+--------+--------+
//   sign: 0 = zero or positive, 1 = negative; any other value is an error.
//   fraction: ten-thousandths of the magnitude (the note's "4 decimal places"); 10000..65535 is an error.
//   Example, VR(1) = 2.345:   01 | 00 | 00 00 00 02 | 0D 7A      (2 and 3450/10000)
//   The byte order of the two numbers is a decision (configurable, `byte_order`): big-endian by default;
//   little-endian gives 01 | 00 | 02 00 00 00 | 7A 0D for the same value.
//
// Two ways in: from a double (`encode_vr`, rounding to 4 decimals) or from the parts directly
// (`encode_vr_message` with a `vr_message`), for firmware that keeps fixed-point values and wants no double
// arithmetic (`trionet::q32_to_decimal` gives the parts of a Q32.32 value). Decoding gives the parts
// (`decode_vr_message`, or `decode_vr_frame` for a whole frame) and, if wanted, a double (`to_double`, in
// trionet/q32.hpp with the other decimal conversions).
//
// Rounding from a double. The magnitude is rounded to 4 decimals, ties away from zero, with carry into the
// integer part (0.99995 -> 1.0000). A decimal tie such as 2.34565 is not representable in binary: the double
// nearest to it is 2.34564999999999987..., and rounding that exact binary value would give 2.3456. The spec
// (2.34565 -> 2.3457) means the decimal number the user wrote, so this codec rounds the decimal that the
// double stands for: it builds the 5-decimal tie point t = (100000 i + 10 q + 5) / 100000 between the two
// candidates q and q + 1 ten-thousandths (numerator exact in a double, division correctly rounded, so t is
// the double nearest to the decimal tie) and rounds up when |value| >= t. Below 2^32 two different 5-decimal
// numbers are always more than one unit in the last place apart, so a double equal to t is exactly the double
// that the decimal tie reads as: the result equals rounding the value's shortest decimal representation, ties
// away from zero. (This relies on IEEE 754 double arithmetic without excess precision; x87 builds need
// -ffloat-store or SSE2.) A magnitude of 2^32 or more, or one that rounds up to 2^32, is an error, as are NaN
// and infinities.
//
// Cost: constexpr, O(1), no state, no allocation. Any context may call these functions (an ISR too, if it may
// use the FPU for the double-based calls; the parts-based calls use integers only).
#pragma once

#include <cstdint>

#include "trionet/can/frame.hpp"
#include "trionet/q32.hpp"
#include "trionet/span.hpp"

namespace trionet::can {

/// Bytes in a VR message: the frame's DLC must be exactly this.
constexpr std::uint8_t vr_message_size = 8;
/// Largest VR number a message carries (one byte).
constexpr std::uint16_t max_message_vr = 255;

/// The order of the bytes of the integer part (bytes 2..5) and of the fraction (bytes 6..7).
enum class byte_order : std::uint8_t {
  big_endian,     ///< most significant byte first (the default, docs/protocol.md 2.2)
  little_endian,  ///< least significant byte first
};

/// A byte order fixed at compile time, for a node's `Order` parameter (node.hpp): the node then holds no
/// byte order and its code has no choice to make (on a Cortex-M0+, 92 bytes less code than a node whose
/// byte order is chosen at run time).
template <byte_order Order>
struct fixed_byte_order {
  /// The order.
  static constexpr byte_order value = Order;
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(byte_order order) noexcept {
  switch (order) {
    case byte_order::big_endian:
      return "big_endian";
    case byte_order::little_endian:
      return "little_endian";
  }
  return "unknown";
}

/// A value as the message carries it: sign, integer part of the magnitude, fraction in ten-thousandths
/// (0..9999). The same decimal that trionet/q32.hpp converts to and from Q32.32.
using vr_value = decimal;

/// One decoded or to-be-encoded message: VR(vr) = value.
struct vr_message {
  std::uint8_t vr = 0;  ///< the VR number, 0..255
  vr_value value{};     ///< its value
};

/// What became of an encode (API misuse is reported to the caller; on anything but `ok` nothing is written).
enum class encode_status : std::uint8_t {
  ok,                     ///< encoded
  vr_out_of_range,        ///< vr > 255
  not_a_number,           ///< the value is NaN
  too_large,              ///< |value| is 2^32 or more (infinities included), or rounds up to 2^32
  fraction_out_of_range,  ///< a parts-based fraction > 9999
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(encode_status status) noexcept {
  switch (status) {
    case encode_status::ok:
      return "ok";
    case encode_status::vr_out_of_range:
      return "vr_out_of_range";
    case encode_status::not_a_number:
      return "not_a_number";
    case encode_status::too_large:
      return "too_large";
    case encode_status::fraction_out_of_range:
      return "fraction_out_of_range";
  }
  return "unknown";
}

/// Whether 8 bytes from the wire are a VR message (bad wire data: classify, count, drop).
enum class decode_status : std::uint8_t {
  ok,            ///< a VR message
  bad_dlc,       ///< the frame does not carry exactly 8 data bytes
  bad_sign,      ///< byte 1 is neither 0 nor 1
  bad_fraction,  ///< bytes 6..7 exceed 9999
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(decode_status status) noexcept {
  switch (status) {
    case decode_status::ok:
      return "ok";
    case decode_status::bad_dlc:
      return "bad_dlc";
    case decode_status::bad_sign:
      return "bad_sign";
    case decode_status::bad_fraction:
      return "bad_fraction";
  }
  return "unknown";
}

/// A rounded value, or why there is none.
struct [[nodiscard]] value_result {
  encode_status status = encode_status::ok;  ///< `ok`, or why there is no value
  vr_value value{};                          ///< the value rounded to 4 decimals
  /// True when `status` is `ok`.
  constexpr explicit operator bool() const noexcept { return status == encode_status::ok; }
};

/// A decoded message, or why there is none.
struct [[nodiscard]] decode_result {
  decode_status status = decode_status::ok;  ///< `ok`, or why the bytes are not a message
  vr_message message{};                      ///< the message
  /// True when `status` is `ok`.
  constexpr explicit operator bool() const noexcept { return status == decode_status::ok; }
};

/// `value` rounded to 4 decimals, ties away from zero, as sign, integer part and fraction (see the header
/// comment for how decimal ties are honoured). Zero, and anything that rounds to zero, has sign 0.
[[nodiscard]] constexpr value_result to_vr_value(double value) noexcept {
  if (value != value) return {encode_status::not_a_number, {}};
  const bool negative = value < 0.0;
  const double magnitude = negative ? -value : value;
  constexpr double two_to_32 = 4294967296.0;
  if (!(magnitude < two_to_32)) return {encode_status::too_large, {}};
  const auto whole = static_cast<std::uint32_t>(magnitude);         // floor: magnitude >= 0
  const double remainder = magnitude - static_cast<double>(whole);  // exact (Sterbenz)
  auto ten_thousandths = static_cast<std::uint32_t>(remainder * 10000.0);
  if (ten_thousandths > vr_value::max_fraction)
    ten_thousandths = vr_value::max_fraction;  // rounded up to 10000
  // The decimal tie between ten_thousandths and ten_thousandths + 1, correctly rounded to a double.
  const std::uint64_t tie_numerator =
      std::uint64_t{whole} * 100000U + std::uint64_t{ten_thousandths} * 10U + 5U;
  const double tie = static_cast<double>(tie_numerator) / 100000.0;
  std::uint64_t scaled = std::uint64_t{whole} * vr_value::scale + ten_thousandths;
  if (magnitude >= tie) ++scaled;
  if (scaled / vr_value::scale > UINT32_MAX) return {encode_status::too_large, {}};  // carried into 2^32
  vr_value out;
  out.negative = negative && scaled != 0;
  out.integer_part = static_cast<std::uint32_t>(scaled / vr_value::scale);
  out.fraction = static_cast<std::uint16_t>(scaled % vr_value::scale);
  return {encode_status::ok, out};
}

}  // namespace trionet::can

namespace trionet::detail {

// Byte i (0 = first on the wire) of an n-byte number in `order`.
constexpr std::uint8_t number_byte(std::uint32_t number, unsigned n, unsigned i, can::byte_order order) noexcept {
  const unsigned shift = 8U * (order == can::byte_order::big_endian ? n - 1U - i : i);
  return static_cast<std::uint8_t>(number >> shift);
}

// The n-byte number at `at` in `order`.
constexpr std::uint32_t read_number(const std::uint8_t* at, unsigned n, can::byte_order order) noexcept {
  std::uint32_t number = 0;
  for (unsigned i = 0; i < n; ++i) {
    const unsigned shift = 8U * (order == can::byte_order::big_endian ? n - 1U - i : i);
    number |= std::uint32_t{at[i]} << shift;
  }
  return number;
}

}  // namespace trionet::detail

namespace trionet::can {

/// Writes `message` into the 8 data bytes `out`, its numbers in `order`. A negative zero is sent with sign 0.
/// Nothing is written on error (fraction > 9999).
[[nodiscard]] constexpr encode_status encode_vr_message(const vr_message& message,
                                                        std::uint8_t (&out)[vr_message_size],
                                                        byte_order order = byte_order::big_endian) noexcept {
  const vr_value& value = message.value;
  if (value.fraction > vr_value::max_fraction) return encode_status::fraction_out_of_range;
  const bool negative = value.negative && (value.integer_part != 0 || value.fraction != 0);
  out[0] = message.vr;
  out[1] = negative ? 1 : 0;
  for (unsigned i = 0; i < 4; ++i) out[2 + i] = detail::number_byte(value.integer_part, 4, i, order);
  for (unsigned i = 0; i < 2; ++i) out[6 + i] = detail::number_byte(value.fraction, 2, i, order);
  return encode_status::ok;
}

/// Encodes VR(vr) = value, rounded to 4 decimals, into the 8 data bytes `out`, its numbers in `order`.
/// Nothing is written on error.
[[nodiscard]] constexpr encode_status encode_vr(std::uint16_t vr, double value,
                                                std::uint8_t (&out)[vr_message_size],
                                                byte_order order = byte_order::big_endian) noexcept {
  if (vr > max_message_vr) return encode_status::vr_out_of_range;
  const value_result rounded = to_vr_value(value);
  if (!rounded) return rounded.status;
  return encode_vr_message(vr_message{static_cast<std::uint8_t>(vr), rounded.value}, out, order);
}

/// Decodes the data bytes of a frame, its numbers in `order`; `payload.size()` is the frame's data length
/// (DLC), which must be 8. Checks in wire order: length, sign, fraction.
[[nodiscard]] constexpr decode_result decode_vr_message(byte_view payload,
                                                        byte_order order = byte_order::big_endian) noexcept {
  if (payload.size() != vr_message_size) return {decode_status::bad_dlc, {}};
  if (payload[1] > 1) return {decode_status::bad_sign, {}};
  const auto fraction = static_cast<std::uint16_t>(detail::read_number(payload.data() + 6, 2, order));
  if (fraction > vr_value::max_fraction) return {decode_status::bad_fraction, {}};
  vr_message message;
  message.vr = payload[0];
  message.value.negative = payload[1] == 1;
  message.value.integer_part = detail::read_number(payload.data() + 2, 4, order);
  message.value.fraction = fraction;
  return {decode_status::ok, message};
}

/// Decodes a frame's data as a VR message, its numbers in `order`. A remote frame carries no data
/// (`bad_dlc`); a DLC of 9..15 is not exactly 8 and is also `bad_dlc`. The identifier is not looked at (see
/// `route_of`).
[[nodiscard]] constexpr decode_result decode_vr_frame(const frame& received,
                                                      byte_order order = byte_order::big_endian) noexcept {
  if (received.remote() || received.dlc != vr_message_size) return {decode_status::bad_dlc, {}};
  return decode_vr_message(received.payload(), order);
}

}  // namespace trionet::can
