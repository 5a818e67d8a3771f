// How a codec holds its CRC: nothing for a static policy (an empty class, so the empty base costs no byte and
// every call is the policy's static function), the object itself for one chosen at run time (a profile).
// Shared by the ring (crc.hpp) and Genius (transmission.hpp) codecs.
#pragma once

#include <type_traits>

namespace trionet::detail {

template <class Crc, bool Empty = std::is_empty<Crc>::value>
class crc_holder {
 protected:
  constexpr crc_holder() = default;
  constexpr explicit crc_holder(const Crc& crc) noexcept : crc_(crc) {}
  constexpr const Crc& crc() const noexcept { return crc_; }

 private:
  Crc crc_{};
};
template <class Crc>
class crc_holder<Crc, true> {
 protected:
  constexpr crc_holder() = default;
  constexpr explicit crc_holder(const Crc&) noexcept {}
  static constexpr Crc crc() noexcept { return Crc{}; }
};

}  // namespace trionet::detail
