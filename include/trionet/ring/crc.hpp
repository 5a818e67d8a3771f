// The CRC of a direct variable transfer (PROTOCOL.md 1.3), as a policy type.
//
// A CRC policy is any type with
//   static constexpr std::uint16_t initial;                            // register before the first byte
//   static constexpr std::uint16_t update(std::uint16_t, std::uint8_t); // one byte in
//   static constexpr std::uint16_t finish(std::uint16_t);               // final xor
// `crc16<>` makes such a policy for any 16-bit non-reflected polynomial and init, with or without a
// 256-entry table (512 bytes of const data, built at compile time). The default is CRC-16/CCITT-FALSE.
// Only bits 14..8 and 6..0 of the result travel on the ring (two 7-bit data bytes).
// Cost per byte: one table lookup and two shifts (table) or eight shift/xor steps (table-free).
// Stateless; safe from an ISR.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "trionet/span.hpp"

namespace trionet::ring {

/// Whether a CRC policy uses a 256-entry lookup table (faster) or none (smaller).
enum class crc_table : bool { none = false, lookup = true };

template <std::uint16_t Polynomial, std::uint16_t Initial, std::uint16_t XorOut = 0,
          crc_table Table = crc_table::lookup>
struct crc16 {
  static constexpr std::uint16_t polynomial = Polynomial;
  static constexpr std::uint16_t initial = Initial;

  static constexpr std::uint16_t update_bitwise(std::uint16_t crc, std::uint8_t byte) noexcept {
    crc = static_cast<std::uint16_t>(crc ^ (byte << 8));
    for (int bit = 0; bit < 8; ++bit) {
      crc = (crc & 0x8000) != 0 ? static_cast<std::uint16_t>((crc << 1) ^ Polynomial)
                                : static_cast<std::uint16_t>(crc << 1);
    }
    return crc;
  }

  static constexpr std::array<std::uint16_t, 256> make_table() noexcept {
    std::array<std::uint16_t, 256> entries{};
    for (unsigned i = 0; i < 256; ++i) entries[i] = update_bitwise(0, static_cast<std::uint8_t>(i));
    return entries;
  }

  static constexpr std::uint16_t update(std::uint16_t crc, std::uint8_t byte) noexcept {
    if constexpr (Table == crc_table::lookup) {
      return static_cast<std::uint16_t>((crc << 8) ^ table[((crc >> 8) ^ byte) & 0xFF]);
    } else {
      return update_bitwise(crc, byte);
    }
  }

  static constexpr std::uint16_t finish(std::uint16_t crc) noexcept {
    return static_cast<std::uint16_t>(crc ^ XorOut);
  }

  /// The CRC of a whole buffer.
  static constexpr std::uint16_t compute(const std::uint8_t* data, std::size_t size) noexcept {
    if constexpr (Table == crc_table::lookup) {
      // A 32-bit register whose bits above 15 are never read saves truncating after every byte.
      std::uint32_t crc = initial;
      const auto step = [&crc](std::uint8_t byte) { crc = (crc << 8) ^ table[((crc >> 8) ^ byte) & 0xFF]; };
      std::size_t i = 0;
      for (; i + 4 <= size; i += 4) {  // unrolled: a variable transfer's 12 bytes are three rounds
        step(data[i]);
        step(data[i + 1]);
        step(data[i + 2]);
        step(data[i + 3]);
      }
      for (; i < size; ++i) step(data[i]);
      return finish(static_cast<std::uint16_t>(crc));
    } else {
      std::uint16_t crc = initial;
      for (std::size_t i = 0; i < size; ++i) crc = update_bitwise(crc, data[i]);
      return finish(crc);
    }
  }
  static constexpr std::uint16_t compute(byte_view bytes) noexcept {
    return compute(bytes.data(), bytes.size());
  }

 private:
  static constexpr std::array<std::uint16_t, 256> table = make_table();
};

/// The CRC of exactly N bytes with any CRC policy (initial, update, finish): a fixed count the compiler can
/// unroll, as for the 12 bytes of a direct variable transfer.
template <class Crc, std::size_t N>
constexpr std::uint16_t crc_of(const std::uint8_t* data) noexcept {
  std::uint16_t crc = Crc::initial;
  for (std::size_t i = 0; i < N; ++i) crc = Crc::update(crc, data[i]);
  return Crc::finish(crc);
}

/// CRC-16/CCITT-FALSE (poly 0x1021, init 0xFFFF, not reflected, xorout 0), 256-entry table: the default.
using crc16_ccitt_false = crc16<0x1021, 0xFFFF>;
/// The same CRC without a table, for the smallest firmware.
using crc16_ccitt_false_bitwise = crc16<0x1021, 0xFFFF, 0, crc_table::none>;

/// The 14 bits of a CRC that travel on the ring: bits 14..8 and 6..0.
constexpr std::uint16_t crc_wire_bits(std::uint16_t crc) noexcept {
  return static_cast<std::uint16_t>(crc & 0x7F7F);
}

}  // namespace trionet::ring
