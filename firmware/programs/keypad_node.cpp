// Firmware image (c): a membrane keypad node on the ring.
//
// TRIONET_FIRMWARE_PLACEHOLDER: the ring keypad node (include/trionet/ring/ node and include/trionet/transport.hpp)
// has not landed yet. Until it does, this image is only the skeleton every ring image shares (UART receive
// ISR, main loop); it is built normally and as its baseline, and scripts/firmware-size reports it as a
// placeholder. To fill it: create the node over a vr_table<64> named `vr` and call the node `node`, push every
// received byte into it from UART0_IRQHandler, and drain its transmit side to the UART in the main loop.
#include <cstdint>

#include "board.hpp"

namespace {

volatile std::uint32_t bytes_received = 0;
volatile std::uint8_t last_byte = 0;

}  // namespace

extern "C" void UART0_IRQHandler() {
  while (board::uart0::rx_ready()) {
    last_byte = board::uart0::read();
    bytes_received = bytes_received + 1;
  }
}

int main() {
  board::uart0::start();
  for (;;) board::wait_for_interrupt();
}
