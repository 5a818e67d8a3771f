// Pieces of `trionet ring` shared between its commands.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "cli.hpp"
#include "trionet/ring/decoder.hpp"

namespace trionet::cli {

/// Bytes as "91 48 45 90": lower-case hex pairs, what `ring encode` prints and `ring decode` reads.
std::string hex_line(const std::uint8_t* bytes, std::size_t length);

/// The event name of a decoder result: "message", "frame_error", "crc_error" or "no_room".
const char* ring_event_kind(const ring::decode_result& result);

/// The fields of a decoder result after the event's position: `type`, `hops` and the type's fields for a
/// message, `reason` for a frame error, `hops` and `vr` for a CRC error.
void append_ring_event_body(event& e, const ring::decode_result& result);

/// One decoder result as a JSON event line; `where(event&)` adds its position.
template <class Where>
void append_ring_event(std::string& out, const ring::decode_result& result, Where&& where) {
  event e(out, ring_event_kind(result));
  where(e);
  append_ring_event_body(e, result);
}

/// `trionet ring simulate --help`, and its option table.
extern const char* const simulate_usage;
const option_list& ring_simulate_options();

/// `trionet ring simulate ...`.
int ring_simulate_main(const words& args);

}  // namespace trionet::cli

namespace trionet::host {
class ring_network;
}

namespace trionet::cli {

/// `trionet ring simulate ... --interactive`: runs `net` in real time at `bit_rate` (10 bits per byte) until
/// quit, a signal or `max_byte_times`, with its keypads on the terminal (ring_simulate_interactive.cpp).
int ring_simulate_interactive(host::ring_network& net, double bit_rate, std::uint64_t max_byte_times);

}  // namespace trionet::cli
