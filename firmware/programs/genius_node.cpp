// Firmware image (e): a Genius device, an I/O block at SBA 5 on a 153.6 kbaud standard bus.
//
// The link side is two interrupts at one priority (include/trionet/genius/device.hpp,
// platform/genius_link.hpp): the 9-bit USART's (a word or a framing error received, a start bit detected on
// the line) and SysTick as the device's one-shot timer, counted in bit times. The main loop is the program
// side: whenever the block's 32 inputs change it makes them its turn data (a broadcast sent at every turn
// until changed), and it puts the outputs the bus controller sends it (a block of 4 bytes) on the output
// port.
//
// The image's baseline (firmware/measure/genius_node_baseline.cpp) has the same start-up, vector table,
// handlers and main loop moving words without the library: scripts/firmware-size reports the difference.
#include <cstdint>

#include "board.hpp"
#include "genius_link.hpp"
#include "trionet/genius/device.hpp"

namespace {

namespace genius = trionet::genius;

constexpr std::uint32_t core_clock_hz = 48000000;
constexpr std::uint32_t baud = 153600;
constexpr std::uint32_t cycles_per_bit = core_clock_hz / baud;  // 312

// The board's side of the link driver.
struct hardware {
  static firmware::uart_events uart_events() noexcept {
    const std::uint32_t isr = board::usart9::isr();
    firmware::uart_events events;
    events.received = (isr & board::usart9::isr_rx_not_empty) != 0;
    events.framing_error = (isr & board::usart9::isr_framing_error) != 0;
    events.start_bit = (isr & board::usart9::isr_start_bit) != 0;
    board::usart9::icr() = isr & (board::usart9::isr_framing_error | board::usart9::isr_start_bit);
    return events;
  }
  static std::uint16_t uart_read() noexcept {
    return static_cast<std::uint16_t>(board::usart9::rdr() & genius::uart_word_mask);
  }
  static void uart_write(std::uint16_t word) noexcept { board::usart9::tdr() = word; }
  // RXNE comes at the middle of the stop bit: a timer from the end of the character adds half a bit.
  static void timer_start(std::uint32_t ticks, bool from_end_of_character) noexcept {
    board::systick::start_once(ticks * cycles_per_bit + (from_end_of_character ? cycles_per_bit / 2 : 0));
  }
  static void timer_stop() noexcept { board::systick::stop(); }
};

// Default capacities; the CRC-6 computed bitwise (no 256-byte table), the smallest configuration.
using genius_device = genius::device<32, 96, 16, 2, genius::crc6_g704_bitwise>;
genius_device node(5, genius::bit_timing(genius::rate::standard_153k6));
using link = firmware::genius_link<genius_device, hardware>;

}  // namespace

extern "C" void UART0_IRQHandler() {
  link::uart_interrupt(node);
}
extern "C" void SysTick_Handler() {
  link::timer_interrupt(node);
}

int main() {
  board::usart9::start(core_clock_hz, baud);
  node.deliver_broadcasts_from(0);  // only its outputs (a block) and transmissions directed to it
  link::power_on(node);
  std::uint32_t inputs = ~board::gpio::inputs();
  for (;;) {
    const std::uint32_t now = board::gpio::inputs();
    if (now != inputs) {
      inputs = now;
      const std::uint8_t bytes[4] = {static_cast<std::uint8_t>(now), static_cast<std::uint8_t>(now >> 8),
                                     static_cast<std::uint8_t>(now >> 16),
                                     static_cast<std::uint8_t>(now >> 24)};
      static_cast<void>(node.set_turn_data(trionet::byte_view(bytes, 4)));
    }
    std::uint8_t data[genius_device::delivery_capacity];  // the longest delivery fits: none stays
    const genius::delivery_result got = node.read(trionet::byte_buffer(data, sizeof data));
    if (got && got.kind == genius::delivery_kind::block && got.length == 4) {
      board::gpio::set_outputs(data[0] | static_cast<std::uint32_t>(data[1]) << 8 |
                               static_cast<std::uint32_t>(data[2]) << 16 |
                               static_cast<std::uint32_t>(data[3]) << 24);
    }
    if (!node.deliveries_waiting()) board::wait_for_interrupt();
  }
}
