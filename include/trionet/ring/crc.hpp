// The CRC of a direct variable transfer (docs/protocol.md 1.3), as a policy type.
//
// A CRC policy is any type with
//   static constexpr std::uint16_t initial;                            // register before the first byte
//   static constexpr std::uint16_t update(std::uint16_t, std::uint8_t); // one byte in
//   static constexpr std::uint16_t finish(std::uint16_t);               // reflection and final xor
// or an object with `compute(const std::uint8_t*, std::size_t) const` (a CRC chosen at run time,
// `crc16_runtime`): the encoders and the decoder take such an object as an argument.
// `crc16<>` makes a static policy for any 16-bit CRC of the Rocksoft/reveng model (polynomial, init,
// reflected in and out, final xor): without a table, with a 256-entry table (512 bytes of const data, built
// at compile time), or sliced (four tables, 2 KiB, four bytes per step). The default, `crc16_ccitt_false`,
// is CRC-16/CCITT-FALSE sliced on 64-bit cores (hosts, gateways: the fastest, memory is cheap) and with one
// table on 32-bit and smaller cores (firmware: 512 bytes).
// Only bits 14..8 and 6..0 of the result travel on the ring (two 7-bit data bytes).
// Cost per byte: one table lookup and two shifts (table), about half that (sliced, on runs of 4 bytes), or
// eight shift/xor steps (table-free); the same for reflected CRCs (they shift right instead of left).
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

/// The 16 bits of `value` in reverse order (bit 0 becomes bit 15).
constexpr std::uint16_t reflect16(std::uint16_t value) noexcept {
  std::uint16_t out = 0;
  for (unsigned bit = 0; bit < 16; ++bit) {
    if (((static_cast<unsigned>(value) >> bit) & 1u) != 0)
      out = static_cast<std::uint16_t>(out | (1u << (15 - bit)));
  }
  return out;
}

/// A 16-bit CRC in the Rocksoft/reveng model: polynomial, init and xorout in the usual (non-reflected)
/// notation; RefIn reflects each byte before it enters, RefOut reflects the register before the final xor.
/// A reflected policy keeps its register reflected and shifts right, so it costs the same as a plain one.
/// `initial` is the register before the first byte (reflected when RefIn).
template <std::uint16_t Polynomial, std::uint16_t Initial, std::uint16_t XorOut = 0,
          crc_table Table = crc_table::lookup, bool RefIn = false, bool RefOut = false>
struct crc16 {
  static constexpr std::uint16_t polynomial = Polynomial;  ///< the generator polynomial
  /// The register before the first byte (reflected when RefIn).
  static constexpr std::uint16_t initial = RefIn ? reflect16(Initial) : Initial;
  static constexpr crc_table table_kind = Table;           ///< how it computes
  static constexpr bool reflect_in = RefIn;                ///< bytes enter least significant bit first
  static constexpr bool reflect_out = RefOut;              ///< the register is reflected before the final xor

  /// The register after one more byte, computed bit by bit (no table).
  static constexpr std::uint16_t update_bitwise(std::uint16_t crc, std::uint8_t byte) noexcept {
    if constexpr (RefIn) {
      crc = static_cast<std::uint16_t>(crc ^ byte);
      for (int bit = 0; bit < 8; ++bit) {
        crc = (crc & 1) != 0 ? static_cast<std::uint16_t>((crc >> 1) ^ reflected_polynomial)
                             : static_cast<std::uint16_t>(crc >> 1);
      }
    } else {
      crc = static_cast<std::uint16_t>(crc ^ (byte << 8));
      for (int bit = 0; bit < 8; ++bit) {
        crc = (crc & 0x8000) != 0 ? static_cast<std::uint16_t>((crc << 1) ^ Polynomial)
                                  : static_cast<std::uint16_t>(crc << 1);
      }
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
        tables[k][i] = RefIn ? static_cast<std::uint16_t>((previous >> 8) ^ tables[0][previous & 0xFF])
                             : static_cast<std::uint16_t>((previous << 8) ^ tables[0][previous >> 8]);
      }
    }
    return tables;
  }

  /// The register after one more byte.
  static constexpr std::uint16_t update(std::uint16_t crc, std::uint8_t byte) noexcept {
    if constexpr (Table == crc_table::none) {
      return update_bitwise(crc, byte);
    } else {
      const auto& entries = Table == crc_table::sliced ? slices[0] : table;
      if constexpr (RefIn) {
        return static_cast<std::uint16_t>((crc >> 8) ^ entries[(crc ^ byte) & 0xFF]);
      } else {
        return static_cast<std::uint16_t>((crc << 8) ^ entries[((crc >> 8) ^ byte) & 0xFF]);
      }
    }
  }

  /// The CRC of the bytes taken into the register `crc`.
  static constexpr std::uint16_t finish(std::uint16_t crc) noexcept {
    if constexpr (RefIn != RefOut) crc = reflect16(crc);
    return static_cast<std::uint16_t>(crc ^ XorOut);
  }

  /// The CRC of a whole buffer.
  static constexpr std::uint16_t compute(const std::uint8_t* data, std::size_t size) noexcept {
    std::uint16_t crc = initial;
    std::size_t i = 0;
    if constexpr (Table == crc_table::sliced) {
      // Four bytes per step: only the first two meet the register (a 16-bit CRC), the tables do the rest.
      for (; i + 4 <= size; i += 4) {
        if constexpr (RefIn) {
          crc = static_cast<std::uint16_t>(slices[3][(crc ^ data[i]) & 0xFF] ^
                                           slices[2][((crc >> 8) ^ data[i + 1]) & 0xFF] ^
                                           slices[1][data[i + 2]] ^ slices[0][data[i + 3]]);
        } else {
          crc = static_cast<std::uint16_t>(slices[3][((crc >> 8) ^ data[i]) & 0xFF] ^
                                           slices[2][(crc ^ data[i + 1]) & 0xFF] ^ slices[1][data[i + 2]] ^
                                           slices[0][data[i + 3]]);
        }
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
  static constexpr std::uint16_t reflected_polynomial = reflect16(Polynomial);
  static constexpr std::array<std::uint16_t, 256> table =
      Table == crc_table::lookup ? make_table() : std::array<std::uint16_t, 256>{};
  static constexpr std::array<std::array<std::uint16_t, 256>, 4> slices =
      Table == crc_table::sliced ? make_slices() : std::array<std::array<std::uint16_t, 256>, 4>{};
};

/// The parameters of a 16-bit CRC in the Rocksoft/reveng model, as values (a profile read at run time).
/// The default is the ring's CRC, CRC-16/CCITT-FALSE.
struct crc16_parameters {
  std::uint16_t polynomial = 0x1021;  ///< without the x^16 term, non-reflected notation
  std::uint16_t initial = 0xFFFF;     ///< non-reflected notation
  bool reflect_in = false;            ///< each byte fed least significant bit first
  bool reflect_out = false;           ///< the register reflected before the final XOR
  std::uint16_t xor_out = 0;          ///< XORed into the result

  /// Equal when every parameter is.
  friend constexpr bool operator==(const crc16_parameters& a, const crc16_parameters& b) noexcept {
    return a.polynomial == b.polynomial && a.initial == b.initial && a.reflect_in == b.reflect_in &&
           a.reflect_out == b.reflect_out && a.xor_out == b.xor_out;
  }
  /// Not equal when any parameter differs.
  friend constexpr bool operator!=(const crc16_parameters& a, const crc16_parameters& b) noexcept {
    return !(a == b);
  }
};

/// A 16-bit CRC whose parameters are chosen at run time (host tools reading a profile), with one 256-entry
/// table built by the constructor. Pass it to `encode`, `encode_variable` or a decoder's constructor.
/// Cost: 528 bytes; constructing it builds the table (2048 shift steps); per byte one lookup, as `crc16<>`.
class crc16_runtime {
 public:
  constexpr crc16_runtime() noexcept : crc16_runtime(crc16_parameters{}) {}
  /// A CRC with these parameters; builds the table.
  constexpr explicit crc16_runtime(const crc16_parameters& parameters) noexcept
      : parameters_(parameters),
        initial_(parameters.reflect_in ? reflect16(parameters.initial) : parameters.initial) {
    const std::uint16_t reflected = reflect16(parameters.polynomial);
    for (unsigned i = 0; i < 256; ++i) {
      std::uint16_t crc = static_cast<std::uint16_t>(parameters.reflect_in ? i : i << 8);
      for (int bit = 0; bit < 8; ++bit) {
        if (parameters.reflect_in) {
          crc = (crc & 1) != 0 ? static_cast<std::uint16_t>((crc >> 1) ^ reflected)
                               : static_cast<std::uint16_t>(crc >> 1);
        } else {
          crc = (crc & 0x8000) != 0 ? static_cast<std::uint16_t>((crc << 1) ^ parameters.polynomial)
                                    : static_cast<std::uint16_t>(crc << 1);
        }
      }
      table_[i] = crc;
    }
  }

  /// The parameters it was built with.
  constexpr const crc16_parameters& parameters() const noexcept { return parameters_; }

  /// The CRC of a whole buffer.
  constexpr std::uint16_t compute(const std::uint8_t* data, std::size_t size) const noexcept {
    std::uint16_t crc = initial_;
    if (parameters_.reflect_in) {
      for (std::size_t i = 0; i < size; ++i)
        crc = static_cast<std::uint16_t>((crc >> 8) ^ table_[(crc ^ data[i]) & 0xFF]);
    } else {
      for (std::size_t i = 0; i < size; ++i)
        crc = static_cast<std::uint16_t>((crc << 8) ^ table_[((crc >> 8) ^ data[i]) & 0xFF]);
    }
    if (parameters_.reflect_in != parameters_.reflect_out) crc = reflect16(crc);
    return static_cast<std::uint16_t>(crc ^ parameters_.xor_out);
  }
  /// The CRC of a whole buffer.
  constexpr std::uint16_t compute(byte_view bytes) const noexcept {
    return compute(bytes.data(), bytes.size());
  }

 private:
  crc16_parameters parameters_;
  std::uint16_t initial_;
  std::array<std::uint16_t, 256> table_{};
};

}  // namespace trionet::ring

namespace trionet::detail {
template <class Crc, class = void>
struct is_sliced : std::false_type {};
template <class Crc>
struct is_sliced<Crc, std::void_t<decltype(Crc::table_kind)>>
    : std::bool_constant<Crc::table_kind == ring::crc_table::sliced> {};

template <class Crc, class = void>
struct has_update : std::false_type {};
template <class Crc>
struct has_update<Crc, std::void_t<decltype(Crc::update(std::uint16_t{}, std::uint8_t{}))>> : std::true_type {
};

}  // namespace trionet::detail

namespace trionet::ring {

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

/// The same with a CRC object: a static policy computes exactly as above, a run-time one (`crc16_runtime`)
/// with its `compute`.
template <std::size_t N, class Crc>
constexpr std::uint16_t crc_of(const Crc& crc, const std::uint8_t* data) noexcept {
  if constexpr (detail::has_update<Crc>::value) {
    return crc_of<Crc, N>(data);
  } else {
    return crc.compute(data, N);
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
