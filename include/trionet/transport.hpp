// The byte port through which a ring node talks to its fibre link.
//
// Pull model, nothing blocks inside the node:
//   - every byte the link's receiver delivers is handed to `receive`;
//   - whenever the link's transmitter can take a byte, it asks `transmit` for one.
//
// On a microcontroller both are called from the UART interrupt:
//
//   void UART_IRQHandler() {
//     if (UART->RX_READY) node.receive(UART->DATA);
//     if (UART->TX_EMPTY) {
//       std::uint8_t byte;
//       if (node.transmit(byte)) UART->DATA = byte; else UART->TX_IRQ_ENABLE = 0;
//     }
//   }
//   // main loop, after queuing a message (print, send_variable, ...):
//   if (node.transmit_pending()) UART->TX_IRQ_ENABLE = 1;
//
// On a host, a POSIX file descriptor (a serial port, a pipe or a socket) is pumped the same way:
// bytes from read() go to `receive`, bytes from `transmit` go to write() (see src/posix_link.hpp).
//
// Concurrency: a node is not internally synchronised. Call its port and its program-level API (PRINT#,
// SEND, GET#, ...) from one context, or mask the UART interrupt around program-level calls.
#pragma once

#include <cstddef>
#include <cstdint>

#include "trionet/span.hpp"

namespace trionet {

/// What a ring node offers its link. Every call is O(1) (amortised), never blocks and may run in an ISR.
class byte_port {
 public:
  /// A byte arrived from the link.
  virtual void receive(std::uint8_t byte) noexcept = 0;
  /// The next byte to send, if there is one now; false leaves `byte` untouched.
  [[nodiscard]] virtual bool transmit(std::uint8_t& byte) noexcept = 0;
  /// True when `transmit` would give a byte: use it to (re-)enable a transmit interrupt.
  [[nodiscard]] virtual bool transmit_pending() const noexcept = 0;

  /// Many received bytes at once (a DMA buffer, a read()): the same as `receive` for each, in order.
  /// Nodes override it with a faster path for runs of message data.
  virtual void receive(byte_view bytes) noexcept {
    for (std::uint8_t byte : bytes) receive(byte);
  }
  /// Fills `out` with up to out.size() bytes to send and returns how many: the same bytes as that many
  /// calls of `transmit`, stopping at the first that has none.
  [[nodiscard]] virtual std::size_t transmit(byte_buffer out) noexcept {
    std::size_t n = 0;
    while (n < out.size() && transmit(out[n])) ++n;
    return n;
  }

 protected:
  byte_port() = default;
  byte_port(const byte_port&) = default;
  byte_port& operator=(const byte_port&) = default;
  ~byte_port() = default;
};

}  // namespace trionet
