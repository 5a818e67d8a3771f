// The baseline of firmware/programs/can_node.cpp for scripts/firmware-size: the same ISRs and main loop
// moving frames without the library (and the same integer arithmetic on the position). The image minus this
// baseline is the CAN codec + node.
#include <cstdint>

#include "board.hpp"

namespace {

constexpr std::uint32_t core_clock_hz = 48000000;
constexpr std::uint32_t ticks_per_second = 100;

volatile bool tick = false;
volatile std::uint32_t frames_received = 0;

volatile std::uint32_t last_identifier = 0;
volatile std::int64_t position = 0;  // Q32.32

}  // namespace

extern "C" void SysTick_Handler() {
  tick = true;
}

extern "C" void CAN0_RX0_IRQHandler() {
  while (board::can0::rx_pending()) {
    frames_received = frames_received + 1;
    std::uint32_t identifier = 0;
    std::uint8_t length = 0;
    std::uint8_t data[8];
    board::can0::read(identifier, length, data);
    last_identifier = identifier;
  }
}

int main() {
  board::can0::start();
  board::systick::start(core_clock_hz / ticks_per_second - 1);
  for (;;) {
    if (!tick) {
      board::wait_for_interrupt();
      continue;
    }
    tick = false;
    position = position + 4294967;  // the same application arithmetic as below (0.001 in Q32.32)
    if (board::can0::tx_free()) {
      const std::uint8_t zeros[8] = {};
      board::can0::write(20, 8, zeros);
    }
  }
}
