// Firmware image (c): a membrane keypad node on the ring.
//
// The PL011 interrupt is the keypad's link (see include/trionet/transport.hpp): received bytes go to
// `keypad.receive` (the keypad offset that puts it in network mode, display text, forwarding), and while the
// transmitter has room it takes bytes from `keypad.transmit`. Every SysTick (10 ms) the main loop reads the
// hardware-scanned key matrix and reports each key that went down or up (`press` / `release`): the keypad's
// program side, with no interrupt masking (transport.hpp).
//
// Its baseline, firmware/measure/keypad_node_baseline.cpp, is the same ISR, key scan and main loop without
// the library: scripts/firmware-size reports the difference, the keypad node.
#include <cstddef>
#include <cstdint>

#include "board.hpp"

#include "trionet/ring/keypad.hpp"

namespace {

constexpr std::uint32_t core_clock_hz = 48000000;
constexpr std::uint32_t ticks_per_second = 100;
constexpr unsigned key_count = 18;

volatile bool tick = false;
std::uint32_t keys_down = 0;  // the key matrix at the previous scan

namespace ring = trionet::ring;
static_assert(key_count == ring::key_count, "the key matrix has one bit per keypad key");

ring::keypad<> node;

}  // namespace

extern "C" void SysTick_Handler() {
  tick = true;
}

extern "C" void UART0_IRQHandler() {
  while (board::uart0::rx_ready()) {
    node.receive(board::uart0::read());
  }
  std::uint8_t byte = 0;
  while (board::uart0::tx_ready()) {
    if (!node.transmit(byte)) {
      board::uart0::enable_tx_interrupt(false);
      break;
    }
    board::uart0::write(byte);
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
    const std::uint32_t now = board::keys::pressed();
    const std::uint32_t changed = now ^ keys_down;
    keys_down = now;
    if (changed == 0) continue;
    bool queued = false;
    for (unsigned k = 0; k < key_count; ++k) {
      if ((changed & (1u << k)) == 0) continue;
      const auto which = static_cast<ring::key>(k);
      if (((now & (1u << k)) != 0 ? node.press(which) : node.release(which)) == ring::key_status::ok) queued = true;
    }
    if (queued) board::uart0::enable_tx_interrupt(true);  // no masking: the ISR switches it off when done
  }
}
