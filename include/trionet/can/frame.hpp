// A classic CAN data frame as the VR exchange sees it: identifier, data length code and up to 8 data bytes.
//
// The identifier word follows the Linux SocketCAN convention so that host adapters convert without surprises:
//
//   bit  31        30        29..11            10..0
//      +---------+---------+-----------------+-------------------------+
//      |extended | remote  | extended id     | 11-bit standard id      |
//      |  flag   |  flag   | (high bits)     | (TN20-17 uses only this)|
//      +---------+---------+-----------------+-------------------------+
//
// TN20-17 uses standard (11-bit) data frames only; a frame with either flag set is never an exchange frame.
// Cost: 16 bytes (4 + 1 + 8 + padding); plain data, copyable, usable from an ISR.
#pragma once

#include <cstdint>

#include "trionet/span.hpp"

namespace trionet::can {

/// One classic CAN frame: `id` (11-bit standard identifier plus the flags below), `dlc` (data length code;
/// 0..8 carry that many bytes, 9..15 mean 8 bytes on classic CAN), `data` (only the first min(dlc, 8) bytes
/// are meaningful).
struct frame {
  static constexpr std::uint32_t extended_flag = 0x80000000U;  ///< 29-bit identifier (CAN_EFF_FLAG)
  static constexpr std::uint32_t remote_flag = 0x40000000U;    ///< remote transmission request (CAN_RTR_FLAG)
  static constexpr std::uint32_t extended_mask = 0x1FFFFFFFU;  ///< bits of a 29-bit identifier
  static constexpr std::uint32_t standard_mask = 0x7FFU;       ///< bits of an 11-bit identifier

  std::uint32_t id = 0;       ///< identifier and flags, as Linux's can_id
  std::uint8_t dlc = 0;       ///< data length code, 0..15
  std::uint8_t data[8] = {};  ///< the data bytes

  /// True for a 29-bit identifier.
  [[nodiscard]] constexpr bool extended() const noexcept { return (id & extended_flag) != 0; }
  /// True for a remote frame (no data bytes on the wire).
  [[nodiscard]] constexpr bool remote() const noexcept { return (id & remote_flag) != 0; }
  /// The identifier without flags.
  [[nodiscard]] constexpr std::uint32_t identifier() const noexcept {
    return id & (extended() ? extended_mask : standard_mask);
  }
  /// Number of data bytes on the wire: min(dlc, 8), 0 for a remote frame.
  [[nodiscard]] constexpr std::uint8_t data_length() const noexcept {
    if (remote()) return 0;
    return dlc > 8 ? std::uint8_t{8} : dlc;
  }
  /// The data bytes on the wire.
  [[nodiscard]] constexpr byte_view payload() const noexcept { return byte_view(data, data_length()); }
};

/// Two frames are equal if identifier word, DLC and the bytes on the wire are equal.
[[nodiscard]] constexpr bool operator==(const frame& a, const frame& b) noexcept {
  if (a.id != b.id || a.dlc != b.dlc) return false;
  for (std::uint8_t i = 0; i < a.data_length(); ++i) {
    if (a.data[i] != b.data[i]) return false;
  }
  return true;
}
/// Not `a == b`.
[[nodiscard]] constexpr bool operator!=(const frame& a, const frame& b) noexcept {
  return !(a == b);
}

}  // namespace trionet::can
