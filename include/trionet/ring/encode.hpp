// Ring encoders: a message into a caller-provided buffer (docs/protocol.md 1.2-1.3).
// Every encoder checks all fields and the room first and writes nothing unless the whole frame fits:
// on error the buffer is untouched. Cost: O(frame length), no allocation; safe from an ISR.
#pragma once

#include <cstddef>
#include <cstdint>

#include "trionet/detail/attributes.hpp"
#include "trionet/ring/bytes.hpp"
#include "trionet/ring/crc.hpp"
#include "trionet/ring/message.hpp"
#include "trionet/ring/variable_layout.hpp"
#include "trionet/span.hpp"

namespace trionet::ring {

/// What became of an encode (misuse of the API; on anything but `ok` nothing was written).
enum class encode_status : std::uint8_t {
  ok,                      ///< encoded
  buffer_too_small,        ///< the frame does not fit in the buffer
  hops_out_of_range,       ///< hops not 1..15
  empty_text,              ///< a character transfer needs at least one character
  character_out_of_range,  ///< a character above 127
  vr_out_of_range,         ///< vr above 16383
  offset_out_of_range,     ///< keypad offset not 1..15
  mode_out_of_range,       ///< keypad mode not 0 or 127
  unknown_type,            ///< message type not 1..4
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(encode_status status) noexcept {
  switch (status) {
    case encode_status::ok:
      return "ok";
    case encode_status::buffer_too_small:
      return "buffer_too_small";
    case encode_status::hops_out_of_range:
      return "hops_out_of_range";
    case encode_status::empty_text:
      return "empty_text";
    case encode_status::character_out_of_range:
      return "character_out_of_range";
    case encode_status::vr_out_of_range:
      return "vr_out_of_range";
    case encode_status::offset_out_of_range:
      return "offset_out_of_range";
    case encode_status::mode_out_of_range:
      return "mode_out_of_range";
    case encode_status::unknown_type:
      return "unknown_type";
  }
  return "unknown";
}

/// The outcome of an encode: `length` bytes were written (0 unless `ok`).
struct [[nodiscard]] encode_result {
  encode_status status = encode_status::ok;  ///< `ok`, or why nothing was written
  std::size_t length = 0;                    ///< bytes written
  /// True when `status` is `ok`.
  constexpr explicit operator bool() const noexcept { return status == encode_status::ok; }
};

}  // namespace trionet::ring

namespace trionet::detail {

/// Checks a message's fields (not the buffer). The first problem found, or `ok`.
constexpr ring::encode_status check_message(const ring::message& m) noexcept {
  if (!ring::valid_hops(m.hops)) return ring::encode_status::hops_out_of_range;
  switch (m.type) {
    case ring::message_type::character:
      if (m.text.empty()) return ring::encode_status::empty_text;
      for (std::uint8_t c : m.text) {
        if (!ring::is_data(c)) return ring::encode_status::character_out_of_range;
      }
      return ring::encode_status::ok;
    case ring::message_type::variable:
      return m.vr <= ring::max_vr ? ring::encode_status::ok : ring::encode_status::vr_out_of_range;
    case ring::message_type::keypad_offset:
      return ring::valid_hops(m.offset) ? ring::encode_status::ok : ring::encode_status::offset_out_of_range;
    case ring::message_type::keypad_mode:
      return m.mode == ring::keypad_mode_key_on || m.mode == ring::keypad_mode_key_on_off
                 ? ring::encode_status::ok
                 : ring::encode_status::mode_out_of_range;
  }
  return ring::encode_status::unknown_type;
}

/// Writes the 14 data bytes of a direct variable transfer (V0 V1 X0..X9 C0 C1) in the layout `Layout`, with
/// the CRC `crc` (a static policy, or a `crc16_runtime`). Precondition: vr <= 16383.
template <class Crc, class Layout>
constexpr void write_variable_data(std::uint8_t* out, std::uint16_t vr, std::int64_t value,
                                   const Crc& crc) noexcept {
  TRIONET_ASSERT(vr <= ring::max_vr);
  Layout::write(out, vr, value);
  std::uint8_t scratch[ring::variable_crc_length] = {};
  const std::uint16_t sum = ring::crc_of<ring::variable_crc_length>(crc, Layout::crc_bytes(out, scratch));
  out[12] = static_cast<std::uint8_t>(sum & 0x7F);
  out[13] = static_cast<std::uint8_t>((sum >> 8) & 0x7F);
}

}  // namespace trionet::detail

namespace trionet::ring {

/// Encodes any message. On success returns its frame length; on error writes nothing.
template <class Crc = crc16_ccitt_false, class Layout = default_variable_layout>
constexpr encode_result encode(byte_buffer out, const message& m, const Crc& crc = Crc{}) noexcept {
  const encode_status status = detail::check_message(m);
  if (status != encode_status::ok) return {status, 0};
  const std::size_t length = frame_length(m);
  if (out.size() < length) return {encode_status::buffer_too_small, 0};
  std::uint8_t* p = out.data();
  *p++ = make_header(m.hops, static_cast<std::uint8_t>(m.type));
  switch (m.type) {
    case message_type::character:
      for (std::uint8_t c : m.text) *p++ = c;
      break;
    case message_type::variable:
      detail::write_variable_data<Crc, Layout>(p, m.vr, m.value, crc);
      p += variable_data_length;
      break;
    case message_type::keypad_offset:
      *p++ = m.offset;
      break;
    case message_type::keypad_mode:
      *p++ = m.mode;
      break;
  }
  *p = make_end_of_message(m.hops);
  return {encode_status::ok, length};
}

/// PRINT#: a character transfer of `text` (each character 0..127, at least one).
constexpr encode_result encode_characters(byte_buffer out, std::uint8_t hops, byte_view text) noexcept {
  return encode(out, message::characters(hops, text));
}
/// PRINT#: the same, for `length` characters at `text`.
inline encode_result encode_characters(byte_buffer out, std::uint8_t hops, const char* text,
                                       std::size_t length) noexcept {
  return encode_characters(out, hops, byte_view(reinterpret_cast<const std::uint8_t*>(text), length));
}

/// SEND(n,1,vr,value): a direct variable transfer of a Q32.32 value (see trionet/q32.hpp).
template <class Crc = crc16_ccitt_false, class Layout = default_variable_layout>
constexpr encode_result encode_variable(byte_buffer out, std::uint8_t hops, std::uint16_t vr,
                                        std::int64_t value, const Crc& crc = Crc{}) noexcept {
  return encode<Crc, Layout>(out, message::variable(hops, vr, value), crc);
}

/// SEND(n,2,offset): a keypad offset; `offset` is a hop count 1..15 (BASIC offset - 9).
constexpr encode_result encode_keypad_offset(byte_buffer out, std::uint8_t hops,
                                             std::uint8_t offset) noexcept {
  return encode(out, message::keypad_offset(hops, offset));
}

/// Keypad mode: 0 = key ON only, 127 = key ON and key OFF.
constexpr encode_result encode_keypad_mode(byte_buffer out, std::uint8_t hops, std::uint8_t mode) noexcept {
  return encode(out, message::keypad_mode(hops, mode));
}

}  // namespace trionet::ring
