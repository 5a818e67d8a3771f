// Firmware image (a): the ring codec alone, encoder + decoder with the table-free CRC.
//
// A ring end point that talks only to its neighbour: the UART receive interrupt pushes every byte into a
// trionet::ring::decoder; a message for this node (a variable or a character transfer) is handed to the main
// loop, which encodes it back to the next node. Frame and CRC errors are counted.
//
// Built twice (see CMakeLists.txt): normally, and with TRIONET_FIRMWARE_BASELINE=1, where the same ISR and
// main loop move bytes without the library. The difference between the two images is the codec's cost.
#include <cstddef>
#include <cstdint>

#include "board.hpp"

#if !TRIONET_FIRMWARE_BASELINE
#include "trionet/ring/decoder.hpp"
#include "trionet/ring/encode.hpp"
#endif

namespace {

constexpr std::uint8_t reply_hops = 1;  // the next node along the ring

volatile std::uint32_t bytes_received = 0;
volatile bool reply_ready = false;  // set by the ISR, cleared by the main loop

#if TRIONET_FIRMWARE_BASELINE
volatile std::uint8_t last_byte = 0;
constexpr std::uint8_t fixed_frame[16] = {0x8a, 0x48, 0x01, 0, 0, 0, 0, 0x30, 0x0c, 0, 0, 0, 0, 0x7f, 0x3e, 0x88};
#else
namespace ring = trionet::ring;
using crc = ring::crc16_ccitt_false_bitwise;

ring::decoder<ring::default_max_characters, crc> receiver;

// The reply the ISR hands to the main loop (owned by the ISR while reply_ready is false).
ring::message_type reply_type = ring::message_type::character;
std::uint16_t reply_vr = 0;
std::int64_t reply_value = 0;
std::uint8_t reply_text[ring::default_max_characters];
std::size_t reply_length = 0;

volatile std::uint32_t frame_errors = 0;
volatile std::uint32_t crc_errors = 0;
volatile std::uint32_t replies_dropped = 0;

std::uint8_t frame[ring::framing_length + ring::default_max_characters];

void accept(const ring::message& msg) {
  if (reply_ready) {
    replies_dropped = replies_dropped + 1;
    return;
  }
  reply_type = msg.type;
  if (msg.type == ring::message_type::variable) {
    reply_vr = msg.vr;
    reply_value = msg.value;
  } else if (msg.type == ring::message_type::character) {
    reply_length = msg.text.size();
    for (std::size_t i = 0; i < reply_length; ++i) reply_text[i] = msg.text[i];
  } else {
    return;  // keypad messages mean nothing to this end point
  }
  reply_ready = true;
}
#endif

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
#if TRIONET_FIRMWARE_BASELINE
    last_byte = byte;
    if ((byte & 0x87u) == 0x80u) reply_ready = true;  // an end of message
#else
    const ring::decode_result result = receiver.push(byte);
    switch (result.status) {
      case ring::decode_status::incomplete: break;
      case ring::decode_status::message: accept(result.msg); break;
      case ring::decode_status::frame_error: frame_errors = frame_errors + 1; break;
      case ring::decode_status::crc_error: crc_errors = crc_errors + 1; break;
    }
#endif
  }
}

int main() {
  board::uart0::start();
  for (;;) {
    if (!reply_ready) {
      board::wait_for_interrupt();
      continue;
    }
#if TRIONET_FIRMWARE_BASELINE
    send(fixed_frame, sizeof fixed_frame);
#else
    const ring::encode_result encoded =
        reply_type == ring::message_type::variable
            ? ring::encode_variable<crc>(frame, reply_hops, reply_vr, reply_value)
            : ring::encode_characters(frame, reply_hops, trionet::byte_view(reply_text, reply_length));
    if (encoded) send(frame, encoded.length);
#endif
    reply_ready = false;
  }
}
