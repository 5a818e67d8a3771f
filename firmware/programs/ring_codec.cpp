// Firmware image (a): the ring codec alone, encoder + decoder with the table-free CRC.
//
// A ring end point that talks only to its neighbour and echoes what it is sent: the UART receive interrupt
// pushes every byte into a trionet::ring::decoder and, for each valid message, encodes the same message back
// to the next node into the transmit frame; the main loop sends that frame. Frame and CRC errors are counted.
//
// Its baseline, firmware/measure/ring_codec_baseline.cpp, is the same ISR and main loop moving bytes without
// the library: scripts/firmware-size reports the difference, the codec's cost.
#include <cstddef>
#include <cstdint>

#include "board.hpp"

#include "trionet/ring/decoder.hpp"
#include "trionet/ring/encode.hpp"

namespace {

constexpr std::uint8_t reply_hops = 1;  // the next node along the ring

volatile std::uint32_t bytes_received = 0;
volatile bool reply_ready = false;  // set by the ISR with the frame to send, cleared by the main loop
std::size_t reply_length = 0;

namespace ring = trionet::ring;
using crc = ring::crc16_ccitt_false_bitwise;

ring::decoder<ring::default_max_characters, crc> receiver;
std::uint8_t frame[ring::framing_length + ring::default_max_characters];

volatile std::uint32_t frame_errors = 0;
volatile std::uint32_t crc_errors = 0;
volatile std::uint32_t replies_dropped = 0;

void reply(ring::message msg) {
  if (reply_ready) {
    replies_dropped = replies_dropped + 1;
    return;
  }
  msg.hops = reply_hops;
  const ring::encode_result encoded = ring::encode<crc>(frame, msg);
  if (!encoded) return;
  reply_length = encoded.length;
  reply_ready = true;
}

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
    const ring::decode_result result = receiver.push(byte);
    if (result.status == ring::decode_status::ok) {
      reply(result.msg);
    } else if (result.status == ring::decode_status::crc_error) {
      crc_errors = crc_errors + 1;
    } else if (result.status != ring::decode_status::incomplete) {
      frame_errors = frame_errors + 1;  // a frame error, or anything else the decoder discarded
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
