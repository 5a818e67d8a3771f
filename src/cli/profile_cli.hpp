// The profile in effect (docs/profile.md): `--profile FILE`, taken by the dispatcher for every command, and
// what the commands that encode or decode ring frames build from it; `trionet profile ...`.
#pragma once

#include <cstdint>
#include <string>

#include "cli.hpp"
#include "learn/profile.hpp"
#include "learn/profile_decoder.hpp"
#include "trionet/ring/decoder.hpp"
#include "trionet/ring/encode.hpp"

namespace trionet::cli {

/// The profile every command uses: the one `--profile FILE` named, else the default (docs/protocol.md's
/// decisions).
const learn::profile& active_profile();

/// True when `--profile FILE` named the active profile.
bool profile_given();

/// Takes `--profile FILE` out of `args` (anywhere before "--") and makes it the active profile. Returns
/// exit_ok, or the exit status after printing the problem: 1 if the file cannot be read, 2 for a second
/// --profile, a missing FILE or a profile that is not valid (the message names the key, line and column).
int take_profile_option(words& args);

/// How a command uses the ring's character capacities of the profile.
enum class ring_capacity_use : std::uint8_t {
  text_limit,      ///< encoders: `max_characters` up to 256 limits the text, a larger one cannot be decoded
  decoder,         ///< decoders and keypads, built for 256: `max_characters` must be 256
  receive_buffer,  ///< Motion Coordinators: `max_characters` and `receive_buffer` must be 256
};

/// Exit 2 with a message naming the field, its value and what the tool supports when the active profile
/// asks for a ring character capacity the command cannot honour (its decoders and nodes are built for 256,
/// a compile-time capacity); else exit_ok. `command` names the command for the message ("ring decode").
int check_ring_capacities(const std::string& command, ring_capacity_use use);

/// Reads a profile file. False with `error` set; `io` says whether reading failed (else the content is bad).
bool read_profile_file(const std::string& path, learn::profile& out, std::string& error, bool& io);

/// Writes `p` as JSON to `path` ("-": standard output). Returns the exit status (1 if writing failed).
int write_profile_file(const learn::profile& p, const std::string& path);

/// A ring decoder with the active profile's CRC and variable layout (chosen at run time), for the tool's
/// decoders: the same calls as `ring::decoder<>`.
class profile_decoder : public learn::profile_decoder {
 public:
  profile_decoder() : learn::profile_decoder(active_profile().ring) {}
};

/// Encodes `m` with the active profile's CRC and variable layout.
ring::encode_result encode_with_profile(byte_buffer out, const ring::message& m);

/// `trionet profile ...`: the part's table (profile_cli.cpp).
extern const part profile_part;

}  // namespace trionet::cli
