// Learning the layout of direct variable transfers (docs/protocol.md 1.3, variable_layout.hpp) from captured
// frames and the list of what the user's program sent, in order.
//
// The supported layouts: the 7-bit group order of the VR number and of the value, each least or most
// significant group first (four pairs), and whether the CRC covers the 12 bytes as sent or in the default
// order. A pair fits if every frame reads back as the VR and value sent (and the value's top group is 0 or
// 1). One frame with a VR whose two groups differ and a value whose groups are not a palindrome decides the
// pair. Which bytes the CRC covers only matters when an order is not the default; it is decided with the CRC
// if one is given, else by learning the CRC both ways (3 frames or more).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "learn/ring_capture.hpp"
#include "learn/ring_crc_learn.hpp"
#include "trionet/ring/crc.hpp"
#include "trionet/ring/variable_layout.hpp"

namespace trionet::learn {

enum class layout_learn_status : std::uint8_t {
  ok,              ///< exactly one group-order pair fits every frame
  ambiguous,       ///< several pairs fit (the frames read the same either way): more varied values needed
  no_layout_fits,  ///< no supported pair fits: `orders` says where each one is first contradicted
  count_mismatch,  ///< the capture and the sent list differ in length (the pairs are checked on the common
                   ///< part)
  no_frames,       ///< no frame given
  bad_frame,       ///< a data byte with bit 7 set: `bad_frame_index`
};

constexpr const char* to_string(layout_learn_status status) noexcept {
  switch (status) {
    case layout_learn_status::ok:
      return "ok";
    case layout_learn_status::ambiguous:
      return "ambiguous";
    case layout_learn_status::no_layout_fits:
      return "no_layout_fits";
    case layout_learn_status::count_mismatch:
      return "count_mismatch";
    case layout_learn_status::no_frames:
      return "no_frames";
    case layout_learn_status::bad_frame:
      return "bad_frame";
  }
  return "unknown";
}

/// Which bytes the CRC covers, as far as the frames tell.
enum class crc_input_finding : std::uint8_t {
  same_bytes,               ///< both orders are the default: the two readings are the same bytes
  as_sent,                  ///< the CRC fits over the bytes as sent only
  least_significant_first,  ///< the CRC fits over the bytes in the default order only
  both_fit,                 ///< it fits either way (too few or too similar frames)
  none_fits,                ///< it fits neither way: not a CRC of the model, or a wrong CRC given
  undecided,                ///< no layout decided, or too few frames to learn the CRC
};

constexpr const char* to_string(crc_input_finding finding) noexcept {
  switch (finding) {
    case crc_input_finding::same_bytes:
      return "same_bytes";
    case crc_input_finding::as_sent:
      return "as_sent";
    case crc_input_finding::least_significant_first:
      return "least_significant_first";
    case crc_input_finding::both_fit:
      return "both_fit";
    case crc_input_finding::none_fits:
      return "none_fits";
    case crc_input_finding::undecided:
      return "undecided";
  }
  return "unknown";
}

/// How one group-order pair did.
struct order_fit {
  ring::group_order vr = ring::group_order::least_significant_first;
  ring::group_order value = ring::group_order::least_significant_first;
  bool fits = false;
  std::size_t first_contradiction = 0;  ///< index of the first frame that reads otherwise (when !fits)
};

struct [[nodiscard]] layout_learn_result {
  layout_learn_status status = layout_learn_status::no_frames;
  ring::variable_layout_parameters layout{};  ///< the layout found (status ok)
  std::array<order_fit, 4> orders{};  ///< (vr, value) = (lsf, lsf), (lsf, msf), (msf, lsf), (msf, msf)
  crc_input_finding crc = crc_input_finding::undecided;
  std::size_t bad_frame_index = 0;
  explicit operator bool() const noexcept { return status == layout_learn_status::ok; }
};

struct layout_learn_options {
  /// The CRC, if known (a profile's): the CRC input is then checked with it, else it is learned both ways.
  const ring::crc16_parameters* crc = nullptr;
  crc_learn_options crc_learning{};
};

/// Decides the layout from `frames` and the `sent` list (frame i carries sent[i]).
[[nodiscard]] layout_learn_result learn_layout(const std::vector<variable_frame>& frames,
                                               const std::vector<sent_variable>& sent,
                                               const layout_learn_options& options = {});

}  // namespace trionet::learn
