// Learning the CRC of direct variable transfers from captured frames (docs/protocol.md 1.3, docs/profile.md).
//
// A frame's 14 data bytes are V0 V1 X0..X9 C0 C1; the CRC covers 12 bytes and only its bits 14..8 (C1) and
// 6..0 (C0) travel. The search finds every 16-bit CRC of the Rocksoft/reveng model (polynomial, init,
// reflected in and out, final xor) whose 14 transmitted bits match every frame:
//
//   1. For a fixed polynomial and reflections, CRC(m) = out(L(m)) ^ out(A(init)) ^ xorout on 12-byte
//      messages: L is linear in the message, A linear in init, out() the output reflection (a bit
//      permutation). So for two frames CRC(m1) ^ CRC(m2) = out(L(m1 ^ m2)): init and xorout cancel. Every
//      polynomial and the four reflection pairs are checked against the differences of the frames with the
//      first, on the 14 bits that travel, 64 polynomials at a time (bit-sliced registers).
//   2. A survivor's init and xorout are any pair with out(A(init)) ^ xorout equal, on the 14 bits, to the
//      constant the first frame fixes: 2^18 pairs that all give the same C0 C1. They are one class with one
//      representative (a catalogue entry if one fits, else a plain init and xorout).
//   3. Survivors that give the same C0 C1 for every valid frame (7-bit bytes, the value's top group 0 or 1:
//      2^78 messages) are collapsed into one class.
//   4. Every representative is checked against every frame with a full CRC (crc16_runtime).
//
// How many frames. One frame says nothing about the polynomial: every polynomial and reflection pair fits,
// each with its own constant. Each further frame adds one difference, 14 bits against 2^15 x 4 = 2^17
// hypotheses (odd polynomials): after 2 frames about 2^17 / 2^14 = 8 wrong ones remain (rarely none), after
// 3 frames about 2^-11. So 3 frames usually suffice, 2 never reliably. A wrong hypothesis whose difference
// from the right one has rank r (of 14) on the valid frames survives each further random frame with
// probability 2^-r; for most CRCs the closest one has r = 8, but generators that share a large factor with
// another generator have closer ones (in the catalogue: r = 2 for CRC-16/DECT-R, DECT-X and TELEDISK, r = 3
// for OPENSAFETY-B, r = 5 for PROFIBUS), and they need a fourth frame now and then. Frames that differ in
// few bits (one VR counting up) give dependent differences and need more. Measured: docs/profile.md.
// Cost: the first difference through 2^16 registers (odd polynomials, both input reflections), 64 at a time
// (bit-sliced); about a millisecond. One frame alone: every hypothesis is a survivor, about 50 ms.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "learn/crc_catalogue.hpp"
#include "learn/ring_capture.hpp"
#include "trionet/ring/crc.hpp"
#include "trionet/ring/variable_layout.hpp"

namespace trionet::learn {

enum class crc_learn_status : std::uint8_t {
  ok,                   ///< exactly one class of CRCs fits every frame
  ambiguous,            ///< several classes fit: more (or more varied) frames are needed; all are listed
  too_many_candidates,  ///< more than `max_classes` fit (e.g. one or two frames): none is listed
  no_candidate,         ///< no CRC of the model fits every frame (a corrupted frame, or not such a CRC)
  no_frames,            ///< no frame given
  bad_frame,            ///< a data byte with bit 7 set: `bad_frame_index` says which frame
};

constexpr const char* to_string(crc_learn_status status) noexcept {
  switch (status) {
    case crc_learn_status::ok:
      return "ok";
    case crc_learn_status::ambiguous:
      return "ambiguous";
    case crc_learn_status::too_many_candidates:
      return "too_many_candidates";
    case crc_learn_status::no_candidate:
      return "no_candidate";
    case crc_learn_status::no_frames:
      return "no_frames";
    case crc_learn_status::bad_frame:
      return "bad_frame";
  }
  return "unknown";
}

/// One (polynomial, reflections) that fits, with the init and xorout chosen to represent its class.
struct crc16_member {
  ring::crc16_parameters parameters;  ///< representative: every init/xorout pair with the same constant fits
  std::string name;                   ///< the catalogue name when the representative is a catalogue entry
};

/// A class of CRCs that give the same 14 transmitted bits for every valid frame.
struct crc16_class {
  std::vector<crc16_member> members;  ///< one per (polynomial, reflections); the first is the representative
  std::uint16_t constant = 0;         ///< the 14 transmitted bits of the CRC of twelve zero bytes
};

struct [[nodiscard]] crc_learn_result {
  crc_learn_status status = crc_learn_status::no_frames;
  std::vector<crc16_class> classes;  ///< every class that fits (empty for too_many_candidates)
  std::size_t survivors = 0;         ///< (polynomial, reflections) pairs that fit every difference
  std::size_t frames = 0;            ///< frames used
  std::size_t bad_frame_index = 0;   ///< for bad_frame
  std::size_t rejected = 0;          ///< representatives that failed the final check on every frame (a bug if
                                     ///< not 0: they are dropped, never reported)
  constexpr explicit operator bool() const noexcept { return status == crc_learn_status::ok; }
};

struct crc_learn_options {
  /// Which bytes the CRC covers (docs/protocol.md 1.3 decides "as sent"). With another layout the search runs
  /// over the 12 bytes put back in the default order first.
  ring::variable_layout_parameters layout{};
  /// Above this many classes none is listed (status too_many_candidates).
  std::size_t max_classes = 256;
  /// Also consider even polynomials (no x^0 term). A generator without x^0 is x times a degree-15 one; the
  /// CRC's bit 0 then never depends on the message, so no real CRC uses one. Every generator divisible by
  /// x + 1 (24 of the catalogue's 31) has such an even rival that differs from it in one direction only
  /// and survives each frame with probability 1/2: admitting them costs several frames.
  bool even_polynomials = false;
  /// Preferred representatives, named in the report (nullptr: none).
  const std::vector<catalogue_entry>* catalogue = &crc_catalogue();
  /// Called during the search with how much of it is done, `done` of `total` (for a progress line,
  /// host::progress); may be empty.
  std::function<void(double done, double total)> progress;
};

/// Finds every CRC that fits `frames` (see the top of this file). Cost: the search above, then O(frames) per
/// survivor; about a millisecond for typical captures. Host only (it allocates).
[[nodiscard]] crc_learn_result learn_ring_crc(const std::vector<variable_frame>& frames,
                                              const crc_learn_options& options = {});

/// The 14 transmitted bits of the CRC (`parameters`) of a frame's 12 bytes as `layout` says they are
/// covered, compared with its C0 C1.
[[nodiscard]] bool frame_crc_matches(const ring::crc16_parameters& parameters, const variable_frame& frame,
                                     const ring::variable_layout_parameters& layout = {});

/// The last step of a CRC search (ring or Genius): in each class the members the catalogue names first, then
/// the classes whose representative it names; the status from the count (none: `no_candidate`, one: `ok`,
/// more: `ambiguous`).
template <class Result>
void finish_classes(Result& result) {
  for (auto& c : result.classes) {
    std::stable_sort(c.members.begin(), c.members.end(),
                     [](const auto& a, const auto& b) { return !a.name.empty() && b.name.empty(); });
  }
  std::stable_sort(result.classes.begin(), result.classes.end(), [](const auto& a, const auto& b) {
    return !a.members.front().name.empty() && b.members.front().name.empty();
  });
  if (result.classes.empty()) {
    result.status = crc_learn_status::no_candidate;
  } else {
    result.status = result.classes.size() == 1 ? crc_learn_status::ok : crc_learn_status::ambiguous;
  }
}

}  // namespace trionet::learn
