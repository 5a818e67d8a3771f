// Bytes on the fibre ring (docs/protocol.md 1.1-1.2): control/data classification, header and end of message,
// hop counts and BASIC addresses.
//
//          bit  7   6   5   4   3   2   1   0
//   header      1 | A: hops 1..15 | T: type 1..7 |
//   end of msg  1 | A: same hops  |   0   0   0  |
//   data        0 |  7 bits of message information |
//
// Everything here is constexpr, stateless and safe from an ISR.
#pragma once

#include <cstdint>
#include <cstring>
#include <optional>

#include "trionet/detail/attributes.hpp"

namespace trionet::ring {

/// The three classes of byte on the ring, told apart by bit 7 and the type field.
enum class byte_class : std::uint8_t {
  data,            ///< bit 7 clear
  header,          ///< bit 7 set, type field 1..7
  end_of_message,  ///< bit 7 set, type field 0
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(byte_class value) noexcept {
  switch (value) {
    case byte_class::data:
      return "data";
    case byte_class::header:
      return "header";
    case byte_class::end_of_message:
      return "end_of_message";
  }
  return "unknown";
}

constexpr std::uint8_t control_flag = 0x80;  ///< bit 7: set on header and end of message
constexpr std::uint8_t min_hops = 1;         ///< the next node along the ring
constexpr std::uint8_t max_hops = 15;        ///< the fifteenth node along the ring
constexpr int first_basic_address = 10;      ///< BASIC address of the next node (hops 1)
constexpr int last_basic_address = 24;       ///< BASIC address of the fifteenth node (hops 15)

/// The class of a byte: data (bit 7 clear), header (bit 7 set, type field 1..7) or end of message (bit 7 set,
/// type field 0).
constexpr byte_class classify(std::uint8_t byte) noexcept {
  if ((byte & control_flag) == 0) return byte_class::data;
  return (byte & 0x07) != 0 ? byte_class::header : byte_class::end_of_message;
}

/// True for a data byte (bit 7 clear).
constexpr bool is_data(std::uint8_t byte) noexcept {
  return (byte & control_flag) == 0;
}
/// True for hops 1..15.
constexpr bool valid_hops(unsigned hops) noexcept {
  return hops >= min_hops && hops <= max_hops;
}

/// A: the hop count of a header or end of message (0 is possible on the wire and invalid).
constexpr std::uint8_t hops_of(std::uint8_t control_byte) noexcept {
  return static_cast<std::uint8_t>((control_byte >> 3) & 0x0F);
}
/// T: the message type field of a header (0 for an end of message).
constexpr std::uint8_t type_of(std::uint8_t control_byte) noexcept {
  return static_cast<std::uint8_t>(control_byte & 0x07);
}

/// A header byte. Preconditions: hops 1..15, type 1..7 (checked by the encoders, not here).
constexpr std::uint8_t make_header(std::uint8_t hops, std::uint8_t type) noexcept {
  return static_cast<std::uint8_t>(control_flag | ((hops & 0x0F) << 3) | (type & 0x07));
}
/// An end-of-message byte. Precondition: hops 1..15.
constexpr std::uint8_t make_end_of_message(std::uint8_t hops) noexcept {
  return static_cast<std::uint8_t>(control_flag | ((hops & 0x0F) << 3));
}
/// The same control byte (header or end of message) with A - 1, and A = 0 left as it is: what a forwarding
/// node sends (A sits in bits 6..3, so this is one subtraction).
constexpr std::uint8_t decrement_hops(std::uint8_t control_byte) noexcept {
  return static_cast<std::uint8_t>((control_byte & 0x78) != 0 ? control_byte - 0x08 : control_byte);
}
/// The same control byte (header or end of message) with A replaced.
constexpr std::uint8_t with_hops(std::uint8_t control_byte, std::uint8_t hops) noexcept {
  return static_cast<std::uint8_t>((control_byte & 0x87) | ((hops & 0x0F) << 3));
}

/// The first control byte (header or end of message) in [first, last), or `last`: the end of a run of data.
/// Eight bytes at a time where words are 64-bit.
TRIONET_ALWAYS_INLINE inline const std::uint8_t* find_control(const std::uint8_t* first,
                                                              const std::uint8_t* last) noexcept {
#if defined(__GNUC__) && defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
  if constexpr (sizeof(void*) >= 8) {
    const auto controls_at = [](const std::uint8_t* at) {
      std::uint64_t word;
      std::memcpy(&word, at, sizeof word);
      return word & 0x8080808080808080ull;
    };
    if (last - first > 16) {
      do {
        const std::uint64_t controls = controls_at(first);
        if (controls != 0) return first + (__builtin_ctzll(controls) >> 3);  // the lowest address first
        first += 8;
      } while (last - first > 16);
    } else if (last - first < 8) {
      while (first != last && is_data(*first)) ++first;
      return first;
    }
    // 8..16 bytes left (a direct variable transfer's whole frame): their first 8, then their last 8,
    // overlapping what is known to be data, so the first control in them is at or after `first`.
    std::uint64_t controls = controls_at(first);
    if (controls != 0) return first + (__builtin_ctzll(controls) >> 3);
    controls = controls_at(last - 8);
    return controls == 0 ? last : last - 8 + (__builtin_ctzll(controls) >> 3);
  }
#endif
  while (first != last && is_data(*first)) ++first;
  return first;
}

/// BASIC address n (10..24) to hop count (1..15); nothing for any other n.
constexpr std::optional<std::uint8_t> hops_from_basic_address(int basic_address) noexcept {
  if (basic_address < first_basic_address || basic_address > last_basic_address) return std::nullopt;
  return static_cast<std::uint8_t>(basic_address - (first_basic_address - 1));
}
/// Hop count (1..15) to BASIC address (10..24); nothing for any other hop count.
constexpr std::optional<int> basic_address_from_hops(unsigned hops) noexcept {
  if (!valid_hops(hops)) return std::nullopt;
  return static_cast<int>(hops) + (first_basic_address - 1);
}

}  // namespace trionet::ring
