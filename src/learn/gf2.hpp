// Small pieces of GF(2) arithmetic shared by the CRC learners: bit reversal and a linear-system solver.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace trionet::learn {

/// The 8 bits of `value` in reverse order.
constexpr std::uint8_t reflect_bits8(std::uint8_t value) noexcept {
  unsigned out = 0;
  for (unsigned bit = 0; bit < 8; ++bit) out |= ((static_cast<unsigned>(value) >> bit) & 1u) << (7 - bit);
  return static_cast<std::uint8_t>(out);
}

/// The low `width` bits of `value` in reverse order.
constexpr std::uint16_t reflect_bits(std::uint16_t value, unsigned width) noexcept {
  unsigned out = 0;
  for (unsigned bit = 0; bit < width; ++bit)
    out |= ((static_cast<unsigned>(value) >> bit) & 1u) << (width - 1 - bit);
  return static_cast<std::uint16_t>(out);
}

/// The 16 bits of `value` in reverse order, two table lookups.
inline std::uint16_t reflect_bits16(std::uint16_t value) noexcept {
  static constexpr auto table = [] {
    std::array<std::uint8_t, 256> t{};
    for (unsigned i = 0; i < 256; ++i) t[i] = reflect_bits8(static_cast<std::uint8_t>(i));
    return t;
  }();
  return static_cast<std::uint16_t>(table[value & 0xFF] << 8 | table[value >> 8]);
}

/// Solves x1 v1 ^ x2 v2 ^ ... = target over GF(2) for vectors of up to Bits bits, tracking each vector's
/// label (a bit mask of which unknowns made it): `solve` gives the labels' XOR of one solution.
template <unsigned Bits>
class gf2_solver {
 public:
  /// Adds a vector with its label.
  void add(std::uint16_t vector, std::uint16_t label) noexcept {
    for (unsigned bit = Bits; bit-- > 0;) {
      if (((static_cast<unsigned>(vector) >> bit) & 1u) == 0) continue;
      if (!used_[bit]) {
        used_[bit] = true;
        vectors_[bit] = vector;
        labels_[bit] = label;
        return;
      }
      vector = static_cast<std::uint16_t>(vector ^ vectors_[bit]);
      label = static_cast<std::uint16_t>(label ^ labels_[bit]);
    }
  }
  /// True, with the solution's label, if `target` is a combination of the vectors added.
  bool solve(std::uint16_t target, std::uint16_t& label) const noexcept {
    label = 0;
    for (unsigned bit = Bits; bit-- > 0;) {
      if (((static_cast<unsigned>(target) >> bit) & 1u) == 0) continue;
      if (!used_[bit]) return false;
      target = static_cast<std::uint16_t>(target ^ vectors_[bit]);
      label = static_cast<std::uint16_t>(label ^ labels_[bit]);
    }
    return true;
  }

 private:
  std::array<std::uint16_t, Bits> vectors_{};
  std::array<std::uint16_t, Bits> labels_{};
  std::array<bool, Bits> used_{};
};

}  // namespace trionet::learn
