// NETSTAT, a ring node's error register (docs/protocol.md 1.6): its bits. A node's `netstat()` reads them and
// `clear_netstat()` clears them (the register itself is detail/netstat_register.hpp). And the counters of a
// node's link (`forwarding_counters()`), which count what sets NETSTAT bit 1 and the traffic.
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

/// Counters of a node's link, as read at one moment; they only ever grow. The forwarding losses (wire errors)
/// wrap at 2^32, the traffic counts (messages forwarded, dropped, sent) at 2^16.
struct link_counters {
  std::uint32_t forwards_lost = 0;        ///< forwarded messages lost to a full forward buffer
  std::uint32_t forwards_cut = 0;         ///< ... longer than the longest legal message of their type
  std::uint32_t forwards_ended_idle = 0;  ///< ... whose end of message never came: the line went idle
  std::uint32_t messages_forwarded = 0;   ///< headers of messages passed on (A decremented)
  std::uint32_t messages_dropped = 0;     ///< messages dropped while forwarding was off: a keypad in local mode
  std::uint32_t messages_sent = 0;        ///< own messages whose end of message has gone out

  /// Forwarded messages lost for any reason (each sets NETSTAT bit 1).
  constexpr std::uint32_t forwards_failed() const noexcept {
    return forwards_lost + forwards_cut + forwards_ended_idle;
  }
};

}  // namespace trionet::ring
