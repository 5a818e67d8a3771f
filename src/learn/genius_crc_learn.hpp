// Learning the Genius CRC-6 (docs/protocol.md 3.2) from captured transmissions.
//
// A sample is the data bytes a CRC covers and the 6-bit CRC sent for them: a Stop covers the data bytes
// since the Start, an End of block those since its Start of block. The search tries every 6-bit CRC of the
// Rocksoft/reveng model: polynomial, reflected in and out, init; the first sample then fixes xorout, and the
// others must fit. Candidates that give the same CRC for every message of 1..max_length bytes are one class.
//
// How many samples: polynomial (5 bits, odd), reflections (2), init and xorout (6 + 6) are 19 unknown bits
// and each sample gives 6, so after 3 samples about 2^19 / 2^18 = 2 wrong candidates remain (fewer classes:
// for a generator divisible by x + 1, inits that differ by G / (x + 1) are the same CRC on every length),
// after 4 samples about 2^-5: 3 samples at the least, 4 or 5 usually. Init and xorout are told apart only
// by samples of different lengths (on one length they act as one constant). Cost: 2^5 x 4 x 2^6 CRCs of
// the first sample, the others only for what survives; milliseconds.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "learn/crc_catalogue.hpp"
#include "learn/ring_crc_learn.hpp"
#include "trionet/genius/character.hpp"
#include "trionet/genius/crc6.hpp"
#include "trionet/genius/transmission.hpp"
#include "trionet/span.hpp"

namespace trionet::learn {

/// Bytes a CRC-6 covers and the CRC sent for them.
struct crc6_sample {
  std::vector<std::uint8_t> data;
  std::uint8_t crc = 0;  ///< 0..63
};

/// The CRC samples of a stream of Genius characters, the control characters read in `layout` (the default:
/// docs/protocol.md 3.2): one per Stop (the data since the Start) and one per End of block (the data since
/// its Start of block). Characters outside a well-formed transmission are skipped and counted.
struct sample_extraction {
  std::vector<crc6_sample> stops;
  std::vector<crc6_sample> blocks;
  std::size_t skipped_characters = 0;
};
[[nodiscard]] sample_extraction genius_crc_samples(span<const genius::character> characters,
                                                   const genius::control_layout& layout = genius::control_layout{});

struct crc6_member {
  genius::crc6_parameters parameters;
  std::string name;  ///< the catalogue name, if it is a catalogue entry
};

/// Parameter sets that give the same CRC for every message of 1..max_length bytes.
struct crc6_class {
  std::vector<crc6_member> members;  ///< catalogue entries first
};

struct [[nodiscard]] crc6_learn_result {
  crc_learn_status status = crc_learn_status::no_frames;  ///< no_frames: no sample; bad_frame: a bad sample
  std::vector<crc6_class> classes;
  std::size_t survivors = 0;  ///< parameter sets that fit every sample
  std::size_t samples = 0;
  std::size_t distinct_samples = 0;  ///< of which different from every other (repeats say nothing more)
  std::size_t bad_sample_index = 0;  ///< for bad_frame: no data, or a CRC above 63
  std::size_t rejected = 0;  ///< candidates that failed the final check with crc6_runtime (a bug if not 0)
  explicit operator bool() const noexcept { return status == crc_learn_status::ok; }
};

struct crc6_learn_options {
  std::size_t max_classes = 256;
  /// Classes are equivalence on messages of 1..max_length bytes (a transmission's data and destination).
  std::size_t max_length = 257;
  bool even_polynomials = false;  ///< also polynomials without the x^0 term
  const std::vector<catalogue_entry>* catalogue = &crc_catalogue();
  /// Called during the search with how much of it is done, `done` of `total` (for a progress line,
  /// host::progress); may be empty.
  std::function<void(double done, double total)> progress;
};

/// Finds every CRC-6 that fits `samples`.
[[nodiscard]] crc6_learn_result learn_genius_crc(const std::vector<crc6_sample>& samples,
                                                 const crc6_learn_options& options = {});

}  // namespace trionet::learn
