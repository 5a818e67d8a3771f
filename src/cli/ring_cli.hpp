// Pieces of `trionet ring` shared between its commands.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "trionet/ring/decoder.hpp"

namespace trionet::cli {

/// Hex text to bytes; whitespace between (and inside) bytes is optional. False with `error` naming the
/// first offending character.
bool parse_hex_bytes(const std::string& text, std::vector<std::uint8_t>& bytes, std::string& error);

/// One decoder result as the JSON object `trionet ring decode` prints.
std::string ring_result_json(const ring::decode_result& result);

/// `trionet ring simulate ...`.
int ring_simulate_main(const std::vector<std::string>& args);

}  // namespace trionet::cli

namespace trionet::host {
class ring_network;
}

namespace trionet::cli {

/// `trionet ring simulate ... --interactive`: runs `net` in real time at `bit_rate` (10 bits per byte) until
/// quit, a signal or `max_byte_times`, with its keypads on the terminal (ring_simulate_interactive.cpp).
int ring_simulate_interactive(host::ring_network& net, double bit_rate, std::uint64_t max_byte_times);

}  // namespace trionet::cli
