// NETSTAT, a ring node's error register (docs/protocol.md 1.6): its bits. A node's `netstat()` reads them and
// `clear_netstat()` clears them (the register itself is detail/netstat_register.hpp).
#pragma once

#include <cstdint>

namespace trionet::ring {

/// NETSTAT bits (docs/protocol.md 1.6).
enum netstat_bit : std::uint8_t {
  netstat_tx_timeout = 1,       ///< an own message could not be put into the transmit queue
  netstat_tx_buffer_error = 2,  ///< a forwarded message was lost (buffer full, too long, or the line idle)
  netstat_rx_crc_error = 4,     ///< a direct variable transfer failed its CRC
  netstat_rx_frame_error = 8,   ///< an incomplete or corrupt message was received
  netstat_rx_overflow = 16,     ///< a character transfer did not fit in the receive buffer (extension)
};

/// The bit's name, as spelled in `netstat_bit`.
constexpr const char* to_string(netstat_bit bit) noexcept {
  switch (bit) {
    case netstat_tx_timeout:
      return "netstat_tx_timeout";
    case netstat_tx_buffer_error:
      return "netstat_tx_buffer_error";
    case netstat_rx_crc_error:
      return "netstat_rx_crc_error";
    case netstat_rx_frame_error:
      return "netstat_rx_frame_error";
    case netstat_rx_overflow:
      return "netstat_rx_overflow";
  }
  return "unknown";
}

}  // namespace trionet::ring
