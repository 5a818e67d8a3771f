// The four messages of the fibre ring (docs/protocol.md 1.2-1.3) and their frames.
//
//   character transfer (T=1)      header | c1 c2 ... cn (n >= 1, 7-bit) | end of message
//   direct variable transfer (T=2) header | V0 V1 X0..X9 C0 C1 | end of message
//   keypad offset (T=3)           header | hops 1..15 | end of message
//   keypad mode (T=4)             header | 0 or 127 | end of message
//
//   direct variable transfer payload, each byte 7 bits, least significant group first:
//     V0 = vr bits 6..0      V1 = vr bits 13..7
//     Xk = value bits 7k+6..7k (k = 0..9)   X9 = bit 63 in bit 0, bits 6..1 zero
//     C0 = CRC bits 6..0     C1 = CRC bits 14..8     (CRC over V0..X9 as sent)
#pragma once

#include <cstddef>
#include <cstdint>

#include "trionet/span.hpp"

namespace trionet::ring {

/// Wire message types (T). They differ from the SEND command's type numbers.
enum class message_type : std::uint8_t {
  character = 1,      ///< PRINT#n: one or more 7-bit characters
  variable = 2,       ///< SEND(n,1,vr,value): direct variable transfer
  keypad_offset = 3,  ///< SEND(n,2,offset): puts a keypad in network mode
  keypad_mode = 4,    ///< key ON only (0) or key ON and key OFF (127)
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(message_type value) noexcept {
  switch (value) {
    case message_type::character:
      return "character";
    case message_type::variable:
      return "variable";
    case message_type::keypad_offset:
      return "keypad_offset";
    case message_type::keypad_mode:
      return "keypad_mode";
  }
  return "unknown";
}

constexpr std::size_t variable_data_length = 14;  ///< V0 V1 X0..X9 C0 C1
constexpr std::size_t variable_crc_length = 12;   ///< the CRC covers V0..X9
constexpr std::size_t framing_length = 2;         ///< header and end of message
constexpr std::size_t default_max_characters = 256;  ///< receive buffer of a node
constexpr std::uint16_t max_vr = 16383;  ///< 14 bits
constexpr std::uint8_t keypad_mode_key_on = 0;        ///< keypad mode: key ON only
constexpr std::uint8_t keypad_mode_key_on_off = 127;  ///< keypad mode: key ON and key OFF

/// One decoded or to-be-encoded message. Which fields mean something depends on `type`; the others are 0.
/// `text` is a view: in a decoded message it points into the decoder and is valid until its next push.
struct message {           // (largest fields first: 24 bytes on a 32-bit core, 32 on a 64-bit one)
  std::int64_t value = 0;  ///< variable: Q32.32 value (value / 2^32)
  byte_view text;          ///< character: the characters, each 0..127
  std::uint16_t vr = 0;    ///< variable: VR number 0..16383
  message_type type = message_type::character;  ///< T: which message
  std::uint8_t hops = 0;    ///< A: hops from the sender to the receiver, 1..15
  std::uint8_t offset = 0;  ///< keypad offset: hops from the keypad to where it sends its keys, 1..15
  std::uint8_t mode = 0;    ///< keypad mode: 0 or 127

  /// A character transfer (PRINT#) of `text`.
  static constexpr message characters(std::uint8_t hops, byte_view text) noexcept {
    message m;
    m.type = message_type::character;
    m.hops = hops;
    m.text = text;
    return m;
  }
  /// A direct variable transfer: VR(vr) = value (Q32.32).
  static constexpr message variable(std::uint8_t hops, std::uint16_t vr, std::int64_t value) noexcept {
    message m;
    m.type = message_type::variable;
    m.hops = hops;
    m.vr = vr;
    m.value = value;
    return m;
  }
  /// A keypad offset: where the keypad sends its keys.
  static constexpr message keypad_offset(std::uint8_t hops, std::uint8_t offset) noexcept {
    message m;
    m.type = message_type::keypad_offset;
    m.hops = hops;
    m.offset = offset;
    return m;
  }
  /// A keypad mode: 0 (key ON) or 127 (key ON and OFF).
  static constexpr message keypad_mode(std::uint8_t hops, std::uint8_t mode) noexcept {
    message m;
    m.type = message_type::keypad_mode;
    m.hops = hops;
    m.mode = mode;
    return m;
  }
};

/// The whole frame length of a message, header and end of message included (0 for an unknown type).
constexpr std::size_t frame_length(const message& m) noexcept {
  switch (m.type) {
    case message_type::character:
      return framing_length + m.text.size();
    case message_type::variable:
      return framing_length + variable_data_length;
    case message_type::keypad_offset:
    case message_type::keypad_mode:
      return framing_length + 1;
  }
  return 0;
}

}  // namespace trionet::ring
