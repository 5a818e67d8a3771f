// The baseline of firmware/programs/keypad_node.cpp for scripts/firmware-size: the same ISR, key scan and
// main loop without the library. The image minus this baseline is the keypad node.
#include <cstddef>
#include <cstdint>

#include "board.hpp"

namespace {

constexpr std::uint32_t core_clock_hz = 48000000;
constexpr std::uint32_t ticks_per_second = 100;
constexpr unsigned key_count = 18;

volatile bool tick = false;
std::uint32_t keys_down = 0;  // the key matrix at the previous scan

volatile std::uint8_t last_byte = 0;
volatile std::uint32_t key_events = 0;

}  // namespace

extern "C" void SysTick_Handler() {
  tick = true;
}

extern "C" void UART0_IRQHandler() {
  while (board::uart0::rx_ready()) {
    last_byte = board::uart0::read();
  }
  std::uint8_t byte = 0;
  while (board::uart0::tx_ready() && (last_byte & 0x80u) != 0) {
    byte = last_byte;
    last_byte = 0;
    board::uart0::write(byte);
  }
  board::uart0::enable_tx_interrupt(false);
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
    const std::uint32_t now = board::keys::pressed();
    const std::uint32_t changed = now ^ keys_down;
    keys_down = now;
    if (changed == 0) continue;
    bool queued = false;
    for (unsigned k = 0; k < key_count; ++k) {
      if ((changed & (1u << k)) == 0) continue;
      key_events = key_events + 1;
      queued = true;
    }
    if (queued) board::uart0::enable_tx_interrupt(true);  // no masking: the ISR switches it off when done
  }
}
