// The workloads shared by the Google Benchmark programs and the callgrind instruction counter, so that the
// timed figures and the instruction counts are about the same bytes.
//
//   character stream   header(A,1) | 200 characters | EOM(A)   back to back
//   variable stream    header(A,2) | V0 V1 X0..X9 C0 C1 | EOM(A) back to back (16 bytes, valid CRC)
//
// Host-side only (std::vector); the library under test allocates nothing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "trionet/can/frame.hpp"
#include "trionet/can/vr_codec.hpp"
#include "trionet/ring/encode.hpp"
#include "trionet/ring/motion_coordinator.hpp"

namespace trionet::bench {

/// Characters per message in the character streams.
constexpr std::size_t characters_per_message = 200;
/// Messages per stream: long enough that the stream is many times the decoder's state, short enough to stay
/// in L1/L2.
constexpr std::size_t messages_per_stream = 16;

/// Bytes per call of a node's bulk `receive(byte_view)`, as a UART DMA or a read() might deliver them; the
/// node's bulk `transmit(byte_buffer)` is then given room for twice that. Below the default forward buffer
/// (32 bytes), so cut-through forwarding never overflows.
constexpr std::size_t dma_chunk = 16;

/// Bytes per read() and write() of a host's POSIX link (src/host/posix_link.cpp).
constexpr std::size_t host_chunk = 256;
/// A Motion Coordinator as a host runs it on a POSIX link: a forward buffer that holds a whole read().
using host_mc = ring::motion_coordinator<256, 4096, 256>;

/// A deterministic generator (xorshift32), so every run measures the same bytes.
class pseudo_random {
 public:
  std::uint32_t next() noexcept {
    state_ ^= state_ << 13U;
    state_ ^= state_ >> 17U;
    state_ ^= state_ << 5U;
    return state_;
  }

 private:
  std::uint32_t state_ = 2463534242U;
};

/// `messages` character transfers of `characters_per_message` printable characters, to `hops`.
inline std::vector<std::uint8_t> character_stream(std::uint8_t hops,
                                                  std::size_t messages = messages_per_stream) {
  std::vector<std::uint8_t> stream;
  pseudo_random random;
  std::uint8_t text[characters_per_message];
  std::uint8_t frame[characters_per_message + ring::framing_length];
  for (std::size_t m = 0; m < messages; ++m) {
    for (std::uint8_t& c : text) c = static_cast<std::uint8_t>(0x20 + random.next() % 0x5F);
    const ring::encode_result encoded = ring::encode_characters(frame, hops, byte_view(text));
    stream.insert(stream.end(), frame, frame + encoded.length);
  }
  return stream;
}

/// `messages` direct variable transfers (varied VR numbers and values, valid CRC) to `hops`.
inline std::vector<std::uint8_t> variable_stream(std::uint8_t hops,
                                                 std::size_t messages = messages_per_stream) {
  std::vector<std::uint8_t> stream;
  pseudo_random random;
  std::uint8_t frame[ring::variable_data_length + ring::framing_length];
  for (std::size_t m = 0; m < messages; ++m) {
    const auto vr = static_cast<std::uint16_t>(random.next() % 200);
    const auto value = static_cast<std::int64_t>((std::uint64_t{random.next()} << 20U) ^ random.next());
    const ring::encode_result encoded = ring::encode_variable(frame, hops, vr, value);
    stream.insert(stream.end(), frame, frame + encoded.length);
  }
  return stream;
}

/// `size` pseudo-random bytes (for the CRC over long buffers).
inline std::vector<std::uint8_t> random_bytes(std::size_t size) {
  std::vector<std::uint8_t> bytes(size);
  pseudo_random random;
  for (std::uint8_t& b : bytes) b = static_cast<std::uint8_t>(random.next());
  return bytes;
}

/// `count` CAN frames of node 2 of 5 to node 1 (identifier 10), each a valid VR message.
inline std::vector<can::frame> vr_frames(std::size_t count) {
  std::vector<can::frame> frames(count);
  pseudo_random random;
  for (can::frame& f : frames) {
    can::vr_message message;
    message.vr = static_cast<std::uint8_t>(random.next());
    message.value.negative = (random.next() & 1U) != 0;
    message.value.integer_part = random.next();
    message.value.fraction = static_cast<std::uint16_t>(random.next() % 10000);
    (void)can::encode_vr_message(message, f.data);
    f.id = 10;
    f.dlc = can::vr_message_size;
  }
  return frames;
}

}  // namespace trionet::bench
