// The byte port through which a ring node talks to its fibre link.
//
// Pull model, nothing blocks inside the node:
//   - every byte the link's receiver delivers is handed to `receive`;
//   - whenever the link's transmitter can take a byte, it asks `transmit` for one.
//
// On a microcontroller both are called from the UART interrupt (the node's link side), while the program
// (PRINT#, SEND, GET#, KEY#, NETSTAT, VR()) runs in the main loop or one RTOS task (the program side), with
// no lock and no interrupt masking:
//
//   void UART_IRQHandler() {                      // link side
//     while (UART->RX_READY) node.receive(UART->DATA);
//     std::uint8_t byte;
//     while (UART->TX_READY) {
//       if (!node.transmit(byte)) { UART->TX_IRQ_ENABLE = 0; break; }
//       UART->DATA = byte;
//     }
//   }
//   // main loop (program side), after queuing a message (print, send_variable, ...):
//   if (result) UART->TX_IRQ_ENABLE = 1;   // the interrupt switches itself off when nothing is left
//
// On a host, a POSIX file descriptor (a serial port, a pipe or a socket) is pumped the same way:
// bytes from read() go to `receive`, bytes from `transmit` go to write() (see src/host/trionet/host/posix_link.hpp).
//
// The idle line (docs/protocol.md 1.10) is the only notion of time: when the receiver has seen no byte for a while
// (most UARTs raise an idle-line interrupt one character time after the last byte; a host uses a read
// timeout), call `line_idle`, so that a message whose rest was lost does not hold the node:
//
//   void UART_IDLE_IRQHandler() { node.line_idle(); }   // link side too
//
// Concurrency contract (docs/design.md, "Contexts"): every call of `byte_port` belongs to the link side, which
// is one interrupt context (or one thread): `receive`, `transmit` and `line_idle` never run at the same time
// as each other (one ISR, or ISRs of the same priority). The program-level API of each node belongs to the
// program side, one thread context, which the link side may interrupt anywhere: neither side masks the other
// or takes a lock. Which call belongs to which side is listed in ring/node.hpp and can/node.hpp. This works on
// a single-core Cortex-M0+ (loads and stores only) as well as M3/M4, and between two threads on a host.
#pragma once

#include <cstdint>

#include "trionet/ring/decode_result.hpp"

namespace trionet {

/// What a ring node offers its link: the link side of the node. Every call is O(1) (amortised), never
/// blocks and may run in an ISR.
class byte_port {
 public:
  /// A byte arrived from the link; returns what became of the message it ended (`incomplete`: none).
  virtual ring::receive_status receive(std::uint8_t byte) noexcept = 0;
  /// The next byte to send, if there is one now; false leaves `byte` untouched.
  [[nodiscard]] virtual bool transmit(std::uint8_t& byte) noexcept = 0;
  /// True when `transmit` would give a byte: use it to (re-)enable a transmit interrupt.
  [[nodiscard]] virtual bool transmit_pending() const noexcept = 0;
  /// The line has carried no byte for a while: a message open on the receive side has lost its rest and is
  /// ended (counted), and what became of it is returned. Harmless when nothing is open (`incomplete`).
  virtual ring::receive_status line_idle() noexcept = 0;
  /// True while a message has begun on the receive side and not ended (for this node, passing through it,
  /// or being dropped): what `line_idle` would end.
  [[nodiscard]] virtual bool in_message() const noexcept = 0;

 protected:
  byte_port() = default;
  /// Copyable by the implementations only.
  byte_port(const byte_port&) = default;
  /// Copyable by the implementations only.
  byte_port& operator=(const byte_port&) = default;
  ~byte_port() = default;
};

}  // namespace trionet
