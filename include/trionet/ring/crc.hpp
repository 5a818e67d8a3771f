// The CRC of a direct variable transfer (docs/protocol.md 1.3), as a policy type.
//
// A CRC policy is any type with
//   static constexpr std::uint16_t initial;                            // register before the first byte
//   static constexpr std::uint16_t update(std::uint16_t, std::uint8_t); // one byte in
//   static constexpr std::uint16_t finish(std::uint16_t);               // final xor
// `crc16<>` makes such a policy for any 16-bit non-reflected polynomial and init: without a table, with a
// 256-entry table (512 bytes of const data, built at compile time), or sliced (four tables, 2 KiB, four bytes
// per step). The default, `crc16_ccitt_false`, is CRC-16/CCITT-FALSE sliced on 64-bit cores (hosts, gateways:
// the fastest, memory is cheap) and with one table on 32-bit and smaller cores (firmware: 512 bytes).
// Only bits 14..8 and 6..0 of the result travel on the ring (two 7-bit data bytes).
// Cost per byte: one table lookup and two shifts (table), about half that (sliced, on runs of 4 bytes), or
// eight shift/xor steps (table-free).
// Stateless; safe from an ISR.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "trionet/span.hpp"

namespace trionet::ring {

/// How a CRC policy computes: no table (smallest), one 256-entry table (512 bytes, the default), or four
/// tables (2 KiB) that take four bytes per step ("slicing by 4": fastest on long buffers and on hosts).
enum class crc_table : std::uint8_t {
  none = 0,    ///< bit by bit, no table
  lookup = 1,  ///< one 256-entry table
  sliced = 2,  ///< four tables, four bytes per step
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(crc_table value) noexcept {
  switch (value) {
    case crc_table::none:
      return "none";
    case crc_table::lookup:
      return "lookup";
    case crc_table::sliced:
      return "sliced";
  }
  return "unknown";
}

template <std::uint16_t Polynomial, std::uint16_t Initial, std::uint16_t XorOut = 0,
          crc_table Table = crc_table::lookup>
/// A CRC policy (see above) for the 16-bit polynomial `Polynomial`, not reflected, with register `Initial`
/// before the first byte and `XorOut` applied at the end, computed as `Table` says.
struct crc16 {
  static constexpr std::uint16_t polynomial = Polynomial;  ///< the generator polynomial
  static constexpr std::uint16_t initial = Initial;        ///< the register before the first byte
  static constexpr crc_table table_kind = Table;           ///< how it computes

  /// The register after one more byte, computed bit by bit (no table).
  static constexpr std::uint16_t update_bitwise(std::uint16_t crc, std::uint8_t byte) noexcept {
    crc = static_cast<std::uint16_t>(crc ^ (byte << 8));
    for (int bit = 0; bit < 8; ++bit) {
      crc = (crc & 0x8000) != 0 ? static_cast<std::uint16_t>((crc << 1) ^ Polynomial)
                                : static_cast<std::uint16_t>(crc << 1);
    }
    return crc;
  }

  /// The 256-entry table of the byte-at-a-time method.
  static constexpr std::array<std::uint16_t, 256> make_table() noexcept {
    std::array<std::uint16_t, 256> entries{};
    for (unsigned i = 0; i < 256; ++i) entries[i] = update_bitwise(0, static_cast<std::uint8_t>(i));
    return entries;
  }

  /// Table k: the effect of a byte followed by k zero bytes (table 0 is the byte-at-a-time table).
  static constexpr std::array<std::array<std::uint16_t, 256>, 4> make_slices() noexcept {
    std::array<std::array<std::uint16_t, 256>, 4> tables{};
    tables[0] = make_table();
    for (std::size_t k = 1; k < 4; ++k) {
      for (unsigned i = 0; i < 256; ++i) {
        const std::uint16_t previous = tables[k - 1][i];
        tables[k][i] = static_cast<std::uint16_t>((previous << 8) ^ tables[0][previous >> 8]);
      }
    }
    return tables;
  }

  /// The register after one more byte.
  static constexpr std::uint16_t update(std::uint16_t crc, std::uint8_t byte) noexcept {
    if constexpr (Table == crc_table::sliced) {
      return static_cast<std::uint16_t>((crc << 8) ^ slices[0][((crc >> 8) ^ byte) & 0xFF]);
    } else if constexpr (Table == crc_table::lookup) {
      return static_cast<std::uint16_t>((crc << 8) ^ table[((crc >> 8) ^ byte) & 0xFF]);
    } else {
      return update_bitwise(crc, byte);
    }
  }

  /// The CRC of the bytes taken into the register `crc`.
  static constexpr std::uint16_t finish(std::uint16_t crc) noexcept {
    return static_cast<std::uint16_t>(crc ^ XorOut);
  }

  /// The CRC of a whole buffer.
  static constexpr std::uint16_t compute(const std::uint8_t* data, std::size_t size) noexcept {
    std::uint16_t crc = initial;
    std::size_t i = 0;
    if constexpr (Table == crc_table::sliced) {
      // Four bytes per step: only the first two meet the register (a 16-bit CRC), the tables do the rest.
      for (; i + 4 <= size; i += 4) {
        crc = static_cast<std::uint16_t>(slices[3][((crc >> 8) ^ data[i]) & 0xFF] ^
                                         slices[2][(crc ^ data[i + 1]) & 0xFF] ^ slices[1][data[i + 2]] ^
                                         slices[0][data[i + 3]]);
      }
    }
    for (; i < size; ++i) crc = update(crc, data[i]);
    return finish(crc);
  }
  /// The CRC of a whole buffer.
  static constexpr std::uint16_t compute(byte_view bytes) noexcept {
    return compute(bytes.data(), bytes.size());
  }

 private:
  static constexpr std::array<std::uint16_t, 256> table =
      Table == crc_table::lookup ? make_table() : std::array<std::uint16_t, 256>{};
  static constexpr std::array<std::array<std::uint16_t, 256>, 4> slices =
      Table == crc_table::sliced ? make_slices() : std::array<std::array<std::uint16_t, 256>, 4>{};
};

namespace detail {
template <class Crc, class = void>
struct is_sliced : std::false_type {};
template <class Crc>
struct is_sliced<Crc, std::void_t<decltype(Crc::table_kind)>>
    : std::bool_constant<Crc::table_kind == crc_table::sliced> {};
}  // namespace detail

/// The CRC of exactly N bytes with any CRC policy (initial, update, finish): a fixed count the compiler can
/// unroll, as for the 12 bytes of a direct variable transfer.
template <class Crc, std::size_t N>
constexpr std::uint16_t crc_of(const std::uint8_t* data) noexcept {
  if constexpr (detail::is_sliced<Crc>::value) {
    return Crc::compute(data, N);
  } else {
    std::uint16_t crc = Crc::initial;
    for (std::size_t i = 0; i < N; ++i) crc = Crc::update(crc, data[i]);
    return Crc::finish(crc);
  }
}

/// CRC-16/CCITT-FALSE (poly 0x1021, init 0xFFFF, not reflected, xorout 0) with one 256-entry table (512 B).
using crc16_ccitt_false_table = crc16<0x1021, 0xFFFF>;
/// The same CRC without a table, for the smallest firmware.
using crc16_ccitt_false_bitwise = crc16<0x1021, 0xFFFF, 0, crc_table::none>;
/// The same CRC four bytes per step with 2 KiB of tables, for hosts and gateways.
using crc16_ccitt_false_sliced = crc16<0x1021, 0xFFFF, 0, crc_table::sliced>;
/// The default CRC of the ring (docs/protocol.md 1.3): sliced where pointers are 64-bit (hosts and gateways,
/// where 2 KiB of tables cost nothing and it is the fastest), one table elsewhere (32-bit cores: firmware,
/// 512 B). Every form gives the same CRC; pass another policy to a node or the codec to choose for yourself.
using crc16_ccitt_false =
    std::conditional_t<(UINTPTR_MAX > 0xFFFFFFFFu), crc16_ccitt_false_sliced, crc16_ccitt_false_table>;

/// The 14 bits of a CRC that travel on the ring: bits 14..8 and 6..0.
constexpr std::uint16_t crc_wire_bits(std::uint16_t crc) noexcept {
  return static_cast<std::uint16_t>(crc & 0x7F7F);
}

}  // namespace trionet::ring
