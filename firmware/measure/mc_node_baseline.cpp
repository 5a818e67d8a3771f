// The baseline of firmware/programs/mc_node.cpp for scripts/firmware-size: the same ISR and main loop moving
// bytes without the library (and the same integer arithmetic on the position). The image minus this baseline
// is the MC node: link, decoder, encoder, receive buffer, VR writes.
#include <cstddef>
#include <cstdint>

#include "board.hpp"

namespace {

constexpr std::uint32_t core_clock_hz = 48000000;
constexpr std::uint32_t ticks_per_second = 100;

volatile bool tick = false;

volatile std::uint8_t last_byte = 0;
volatile std::size_t bytes_waiting = 0;
volatile std::int64_t position = 0;  // Q32.32
constexpr std::uint8_t fixed_frame[16] = {0x8a, 0x00, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0x88};
std::size_t transmitted = sizeof fixed_frame;  // index of the next byte to send

bool next_byte(std::uint8_t& byte) {
  if (transmitted == sizeof fixed_frame) return false;
  byte = fixed_frame[transmitted++];
  return true;
}

}  // namespace

extern "C" void SysTick_Handler() {
  tick = true;
}

// One received byte and one transmitted byte per interrupt, as a UART at line rate gives them (FIFOs off:
// one byte in the receive register, one place in the transmitter). A byte that is still waiting re-raises
// the interrupt at once.
extern "C" void UART0_IRQHandler() {
  if (board::uart0::rx_ready()) {
    last_byte = board::uart0::read();
    bytes_waiting = bytes_waiting + 1;
  }
  if (board::uart0::tx_ready()) {
    std::uint8_t byte = 0;
    const bool have = next_byte(byte);
    if (have) {
      board::uart0::write(byte);
    } else {
      board::uart0::enable_tx_interrupt(false);  // nothing to send: the main loop switches it on again
    }
  }
}

int main() {
  board::uart0::start();
  board::systick::start(core_clock_hz / ticks_per_second - 1);
  for (;;) {
    if (!tick) {
      board::wait_for_interrupt();
      continue;
    }
    tick = false;
    position = position + 4294967;  // the same application arithmetic as the program's (0.001 in Q32.32)
    if (bytes_waiting != 0) bytes_waiting = 0;
    transmitted = 0;
    board::uart0::enable_tx_interrupt(true);
  }
}
