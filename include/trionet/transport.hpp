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
// bytes from read() go to `receive`, bytes from `transmit` go to write() (see src/host/trionet/host/posix_link.hpp).
//
// The idle line (docs/protocol.md 1.10) is the only notion of time: when the receiver has seen no byte for a while
// (most UARTs raise an idle-line interrupt one character time after the last byte; a host uses a read
// timeout), call `line_idle`, so that a message whose rest was lost does not hold the node:
//
//   void UART_IDLE_IRQHandler() { node.line_idle(); }
//
// Concurrency: a node is not internally synchronised. Call its port and its program-level API (PRINT#,
// SEND, GET#, ...) from one context, or mask the UART interrupt around program-level calls.
#pragma once

#include <cstdint>

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
  /// The line has carried no byte for a while: a message open on the receive side has lost its rest and is
  /// ended (counted). Harmless when nothing is open.
  virtual void line_idle() noexcept = 0;
  /// True while a message has begun on the receive side and not ended (for this node, passing through it,
  /// or being dropped): what `line_idle` would end.
  [[nodiscard]] virtual bool in_message() const noexcept = 0;

 protected:
  byte_port() = default;
  byte_port(const byte_port&) = default;
  byte_port& operator=(const byte_port&) = default;
  ~byte_port() = default;
};

}  // namespace trionet
