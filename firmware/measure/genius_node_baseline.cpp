// The baseline of firmware/programs/genius_node.cpp for scripts/firmware-size: the same start-up, vector
// table, USART and SysTick access, handlers and main loop, moving words without the library. The image minus
// this baseline is what the Genius device costs.
#include <cstdint>

#include "board.hpp"

namespace {

constexpr std::uint32_t core_clock_hz = 48000000;
constexpr std::uint32_t baud = 153600;
constexpr std::uint32_t cycles_per_bit = core_clock_hz / baud;

volatile std::uint32_t last_word = 0;
volatile std::uint32_t turn_data = 0;

}  // namespace

extern "C" void UART0_IRQHandler() {
  const std::uint32_t isr = board::usart9::isr();
  board::usart9::icr() = isr & (board::usart9::isr_framing_error | board::usart9::isr_start_bit);
  if ((isr & board::usart9::isr_rx_not_empty) != 0) {
    last_word = board::usart9::rdr() & 0x1FFu;
    if ((isr & board::usart9::isr_framing_error) == 0) board::systick::start_once(2 * cycles_per_bit);
  }
  if ((isr & board::usart9::isr_start_bit) != 0) board::systick::stop();
}

extern "C" void SysTick_Handler() {
  board::systick::stop();
  board::usart9::tdr() = turn_data & 0x1FFu;
}

int main() {
  board::usart9::start(core_clock_hz, baud);
  board::systick::start_once(86 * cycles_per_bit);
  std::uint32_t inputs = ~board::gpio::inputs();
  for (;;) {
    const std::uint32_t now = board::gpio::inputs();
    if (now != inputs) {
      inputs = now;
      turn_data = now;
    }
    board::gpio::set_outputs(last_word);
    board::wait_for_interrupt();
  }
}
