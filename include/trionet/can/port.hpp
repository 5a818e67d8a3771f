// The CAN port: what firmware (a CAN controller driver) or host code (SocketCAN, the bus model) implements so
// that a VR-exchange node can put frames on the bus. Receiving is the other way round: whoever owns the
// controller hands each received frame to `vr_exchange_node::receive`.
#pragma once

#include <cstdint>

#include "trionet/can/frame.hpp"

namespace trionet::can {

/// What became of a frame handed to a port.
enum class transmit_status : std::uint8_t {
  ok,      ///< accepted for transmission (in a mailbox, a queue or already on the bus)
  busy,    ///< no free transmit mailbox or queue slot now; nothing was queued, the caller may retry
  failed,  ///< the controller or driver failed (bus off, I/O error); nothing was queued
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(transmit_status status) noexcept {
  switch (status) {
    case transmit_status::ok:
      return "ok";
    case transmit_status::busy:
      return "busy";
    case transmit_status::failed:
      return "failed";
  }
  return "unknown";
}

/// A CAN transmitter. One virtual call per frame; implementations must not block for long, must not throw,
/// and decide themselves whether they may be called from an ISR (document it on the implementation).
/// Cost: one vtable pointer.
class port {
 public:
  /// Queues `outgoing` for transmission.
  [[nodiscard]] virtual transmit_status send(const frame& outgoing) noexcept = 0;

 protected:
  constexpr port() = default;
  port(const port&) = default;             ///< copyable by implementations only
  port& operator=(const port&) = default;  ///< assignable by implementations only
  ~port() = default;
};

}  // namespace trionet::can
