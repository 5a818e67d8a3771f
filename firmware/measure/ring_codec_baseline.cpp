// The baseline of firmware/programs/ring_codec.cpp for scripts/firmware-size: the same ISR and main loop
// moving bytes without the library. The image minus this baseline is the codec's cost.
#include <cstddef>
#include <cstdint>

#include "board.hpp"

namespace {

constexpr std::uint8_t reply_hops = 1;  // the next node along the ring

volatile std::uint32_t bytes_received = 0;
volatile bool reply_ready = false;  // set by the ISR with the frame to send, cleared by the main loop
std::size_t reply_length = 0;

volatile std::uint8_t last_byte = 0;
constexpr std::uint8_t frame[16] = {0x8a, 0x48, 0x01, 0, 0, 0, 0, 0x30, 0x0c, 0, 0, 0, 0, 0x7f, 0x3e, 0x88};

void send(const std::uint8_t* bytes, std::size_t length) {
  for (std::size_t i = 0; i < length; ++i) {
    while (!board::uart0::tx_ready()) {
    }
    board::uart0::write(bytes[i]);
  }
}

}  // namespace

extern "C" void UART0_IRQHandler() {
  while (board::uart0::rx_ready()) {
    const std::uint8_t byte = board::uart0::read();
    bytes_received = bytes_received + 1;
    last_byte = byte;
    if ((byte & 0x87u) == 0x80u && !reply_ready) {  // an end of message
      reply_length = sizeof frame;
      reply_ready = true;
    }
  }
}

int main() {
  board::uart0::start();
  for (;;) {
    if (!reply_ready) {
      board::wait_for_interrupt();
      continue;
    }
    send(frame, reply_length);
    reply_ready = false;
  }
}
