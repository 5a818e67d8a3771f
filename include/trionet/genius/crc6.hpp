// CRC-6 for Genius transmissions (docs/protocol.md 3.2), as a policy type.
//
// The default is CRC-6/G-704: poly 0x03 (x^6 + x + 1), init 0, reflected in and out, xorout 0; its check
// value over the ASCII bytes "123456789" is 0x06. Any other 6-bit CRC in the Rocksoft/reveng model is one
// alias away, e.g. `crc6<0x19, 0x00, true, true, 0x00>` is CRC-6/DARC.
//
// A CRC policy is any type with these members (the transmission encoder and parser use only these), static
// for a compile-time policy (`crc6`), const member functions for one chosen at run time (`crc6_runtime`):
//   register_type begin();                       the register before the first byte
//   register_type update(register_type, byte);   the register after one more byte
//   std::uint8_t  finish(register_type);         the 6-bit CRC (0..63) of the bytes so far
#pragma once

#include <cstddef>
#include <cstdint>

#include "trionet/span.hpp"

namespace trionet::genius {

namespace detail {

constexpr std::uint8_t reflect6(std::uint8_t value) noexcept {
  std::uint8_t out = 0;
  for (unsigned i = 0; i < 6; ++i) {
    if (((static_cast<unsigned>(value) >> i) & 1u) != 0)
      out = static_cast<std::uint8_t>(out | (1u << (5 - i)));
  }
  return out;
}

// Eight shift steps of a register whose 8 bits were already XORed with the next byte. The whole byte
// leaves the register in those 8 steps (the CRC itself is only 6 bits), so a 256-entry table indexed by
// (register XOR byte) is exact.
template <std::uint8_t Poly, bool RefIn>
constexpr std::uint8_t crc6_shift8(std::uint8_t value) noexcept {
  unsigned reg = value;
  for (int step = 0; step < 8; ++step) {
    if constexpr (RefIn) {
      reg = (reg & 1u) ? (reg >> 1) ^ reflect6(Poly) : reg >> 1;
    } else {
      reg = (reg & 0x80u) ? ((reg << 1) ^ (static_cast<unsigned>(Poly) << 2)) & 0xffu : (reg << 1) & 0xffu;
    }
  }
  return static_cast<std::uint8_t>(reg);
}

template <std::uint8_t Poly, bool RefIn>
struct crc6_table {
  struct lookup {
    std::uint8_t entries[256];
  };
  static constexpr lookup make() noexcept {
    lookup built{};
    for (unsigned i = 0; i < 256; ++i)
      built.entries[i] = crc6_shift8<Poly, RefIn>(static_cast<std::uint8_t>(i));
    return built;
  }
};

template <std::uint8_t Poly, bool RefIn>
inline constexpr typename crc6_table<Poly, RefIn>::lookup crc6_table_v = crc6_table<Poly, RefIn>::make();

}  // namespace detail

/// A 6-bit CRC with the given parameters. `Poly`, `Init` and `XorOut` are 6-bit values in the usual
/// (non-reflected) notation. `Table` selects a 256-byte table built at compile time (one lookup per byte)
/// or the bitwise loop (8 shift steps per byte, no table).
/// Cost: `update` is O(1) (table) or 8 steps (bitwise); no state beyond the one-byte register; no
/// allocation. ISR-safe.
template <std::uint8_t Poly, std::uint8_t Init, bool RefIn, bool RefOut, std::uint8_t XorOut,
          bool Table = true>
struct crc6 {
  static_assert(Poly < 64 && Init < 64 && XorOut < 64, "CRC-6 parameters are 6-bit values");

  /// The working register: with RefIn the 6 bits sit reflected in bits 5..0, otherwise in bits 7..2.
  using register_type = std::uint8_t;

  /// The register before the first byte.
  [[nodiscard]] static constexpr register_type begin() noexcept {
    return RefIn ? detail::reflect6(Init) : static_cast<register_type>(Init << 2);
  }

  /// The register after one more byte.
  [[nodiscard]] static constexpr register_type update(register_type reg, std::uint8_t byte) noexcept {
    const auto index = static_cast<std::uint8_t>(reg ^ byte);
    if constexpr (Table) {
      return detail::crc6_table_v<Poly, RefIn>.entries[index];
    } else {
      return detail::crc6_shift8<Poly, RefIn>(index);
    }
  }

  /// The CRC-6 (0..63) of the bytes taken into `reg`.
  [[nodiscard]] static constexpr std::uint8_t finish(register_type reg) noexcept {
    // Reflected in and out: the register already holds the CRC's bits in output order (reflecting twice).
    if constexpr (RefIn && RefOut) return static_cast<std::uint8_t>(reg ^ XorOut);
    const std::uint8_t normal = RefIn ? detail::reflect6(reg) : static_cast<std::uint8_t>(reg >> 2);
    const std::uint8_t out = RefOut ? detail::reflect6(normal) : normal;
    return static_cast<std::uint8_t>(out ^ XorOut);
  }

  /// The CRC of `bytes` in one call.
  [[nodiscard]] static constexpr std::uint8_t compute(byte_view bytes) noexcept {
    register_type reg = begin();
    for (std::uint8_t byte : bytes) reg = update(reg, byte);
    return finish(reg);
  }
};

/// The parameters of a 6-bit CRC as values (a profile read at run time), in the usual (non-reflected)
/// notation. The default is the Genius CRC, CRC-6/G-704.
struct crc6_parameters {
  std::uint8_t polynomial = 0x03;  ///< without the x^6 term
  std::uint8_t initial = 0x00;    ///< the register's value before the first byte
  bool reflect_in = true;         ///< each byte fed least significant bit first
  bool reflect_out = true;        ///< the register reflected before the final XOR
  std::uint8_t xor_out = 0x00;    ///< XORed into the result

  /// Equal when every parameter is.
  friend constexpr bool operator==(const crc6_parameters& a, const crc6_parameters& b) noexcept {
    return a.polynomial == b.polynomial && a.initial == b.initial && a.reflect_in == b.reflect_in &&
           a.reflect_out == b.reflect_out && a.xor_out == b.xor_out;
  }
  /// Not equal when any parameter differs.
  friend constexpr bool operator!=(const crc6_parameters& a, const crc6_parameters& b) noexcept {
    return !(a == b);
  }
};

/// A 6-bit CRC whose parameters are chosen at run time (host tools reading a profile), bitwise: 8 steps a
/// byte, no table. Values above 6 bits are masked. Cost: 5 bytes; no allocation.
class crc6_runtime {
 public:
  constexpr crc6_runtime() noexcept = default;
  /// A CRC with these parameters; values above 6 bits are masked.
  constexpr explicit crc6_runtime(const crc6_parameters& parameters) noexcept
      : parameters_{static_cast<std::uint8_t>(parameters.polynomial & 0x3f),
                    static_cast<std::uint8_t>(parameters.initial & 0x3f), parameters.reflect_in,
                    parameters.reflect_out, static_cast<std::uint8_t>(parameters.xor_out & 0x3f)} {}

  /// The parameters, as masked to 6 bits.
  [[nodiscard]] constexpr const crc6_parameters& parameters() const noexcept { return parameters_; }

  // The members of a CRC policy, as member functions: the transmission encoder and parser take this CRC as
  // an object.

  /// The working register: the 6 bits in non-reflected order, in bits 5..0.
  using register_type = std::uint8_t;

  /// The register before the first byte.
  [[nodiscard]] constexpr register_type begin() const noexcept { return parameters_.initial; }

  /// The register after one more byte: fed most significant bit first, or least significant first when
  /// reflected in.
  [[nodiscard]] constexpr register_type update(register_type reg, std::uint8_t byte) const noexcept {
    unsigned value = reg;
    for (unsigned k = 0; k < 8; ++k) {
      const unsigned bit = parameters_.reflect_in ? (static_cast<unsigned>(byte) >> k) & 1u
                                                  : (static_cast<unsigned>(byte) >> (7 - k)) & 1u;
      const unsigned top = ((value >> 5) & 1u) ^ bit;
      value = (value << 1) & 0x3fu;
      if (top != 0) value ^= parameters_.polynomial;
    }
    return static_cast<register_type>(value);
  }

  /// The CRC-6 (0..63) of the bytes taken into `reg`.
  [[nodiscard]] constexpr std::uint8_t finish(register_type reg) const noexcept {
    const std::uint8_t out = parameters_.reflect_out ? detail::reflect6(reg) : reg;
    return static_cast<std::uint8_t>(out ^ parameters_.xor_out);
  }

  /// The CRC (0..63) of `bytes`.
  [[nodiscard]] constexpr std::uint8_t compute(byte_view bytes) const noexcept {
    register_type reg = begin();
    for (std::uint8_t byte : bytes) reg = update(reg, byte);
    return finish(reg);
  }

 private:
  crc6_parameters parameters_{};
};

/// The default Genius CRC (docs/protocol.md 3.2, configurable): CRC-6/G-704.
using crc6_g704 = crc6<0x03, 0x00, true, true, 0x00>;
/// The same CRC computed bitwise, without the 256-byte table (for tight flash).
using crc6_g704_bitwise = crc6<0x03, 0x00, true, true, 0x00, false>;

}  // namespace trionet::genius
