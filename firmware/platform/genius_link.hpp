// The link driver of a Genius device (include/trionet/genius/device.hpp) on a 9-bit UART and a one-shot
// timer: the two interrupt handlers' bodies, the same for every board. `Hardware` gives the board's side:
//
//   struct Hardware {
//     static uart_events uart_events() noexcept;            // what the UART interrupt is for (flags cleared)
//     static std::uint16_t uart_read() noexcept;            // the word received (9 bits, bit 0 the control
//     bit) static void uart_write(std::uint16_t word) noexcept;  // a word to send static void
//     timer_start(std::uint32_t ticks, bool from_end_of_character) noexcept;  // one shot static void
//     timer_stop() noexcept;
//   };
//
// Both handlers must run at one priority (they are the device's link side, docs/design.md "Contexts"); the
// program side is the main loop. A timer armed after a received word runs from the END of that character:
// `timer_start` is told so, and a UART that reports a word before the end of its stop bit adds the rest.
#pragma once

#include <cstdint>

#include "trionet/genius/device.hpp"

namespace firmware {

/// What a UART interrupt reports, in the order it happened: a word (or a framing error) received, then a
/// start bit detected on the line (the next character's, when both are pending: an interrupt is served well
/// within one character time).
struct uart_events {
  bool received = false;       ///< a word is in the receive register
  bool framing_error = false;  ///< ... and its stop bit was 0
  bool start_bit = false;      ///< a start bit was detected on the line (the device's own included)
};

template <class Device, class Hardware>
class genius_link {
 public:
  /// At power-up, with the UART and the timer ready.
  static void power_on(Device& node) noexcept { apply(node, node.power_on(), false); }

  /// The UART interrupt's body.
  static void uart_interrupt(Device& node) noexcept {
    const uart_events events = Hardware::uart_events();
    if (events.received) {
      const std::uint16_t word = Hardware::uart_read();
      apply(node, events.framing_error ? node.framing_error() : node.receive(word), true);
    }
    if (events.start_bit) apply(node, node.start_bit(), false);
  }

  /// The timer interrupt's body.
  static void timer_interrupt(Device& node) noexcept {
    Hardware::timer_stop();  // one shot
    apply(node, node.timer_expired(), false);
  }

 private:
  static void apply(Device& node, trionet::genius::link_request request, bool from_end) noexcept {
    if (request.timer == trionet::genius::timer_action::arm) Hardware::timer_start(request.ticks, from_end);
    if (request.timer == trionet::genius::timer_action::cancel) Hardware::timer_stop();
    std::uint16_t word = 0;
    if (request.transmit && node.transmit(word)) Hardware::uart_write(word);
  }
};

}  // namespace firmware
