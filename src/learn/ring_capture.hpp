// Captured direct variable transfers (docs/protocol.md 1.3) as the learners take them: the frames found in a
// stream of ring bytes, the list of what the user's program sent, and captures made with the library's own
// encoder under any CRC and layout (for tests, and to show what a profile sends).
//
// Sent list text: one direct variable transfer per line, "VR VALUE" (VR 0..16383, VALUE a real number in
// the Q32.32 range, rounded as SEND rounds it: to the nearest 2^-32, ties away from zero); blank lines and
// text after '#' are ignored.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "trionet/ring/crc.hpp"
#include "trionet/ring/variable_layout.hpp"
#include "trionet/span.hpp"

namespace trionet::learn {

/// The 14 data bytes of one direct variable transfer (V0 V1 X0..X9 C0 C1).
using variable_frame = std::array<std::uint8_t, 14>;

/// The 14 transmitted CRC bits of a frame, C0 | C1 << 8.
constexpr std::uint16_t transmitted_crc(const variable_frame& frame) noexcept {
  return static_cast<std::uint16_t>(frame[12] | (frame[13] << 8));
}

/// Direct variable transfers in a stream of ring bytes: every header of type 2, 14 data bytes and an end of
/// message with the header's hop count. Anything else (other messages, broken frames) is skipped and counted.
struct frame_extraction {
  std::vector<variable_frame> frames;
  std::size_t skipped_bytes = 0;  ///< bytes that were not part of a well-framed direct variable transfer
};
[[nodiscard]] frame_extraction variable_transfers(byte_view stream);

/// One SEND(n,1,vr,value) of the user's program.
struct sent_variable {
  std::uint16_t vr = 0;
  std::int64_t value = 0;  ///< Q32.32
};

enum class sent_list_status : std::uint8_t {
  ok,
  syntax,              ///< a line that is not "VR VALUE"
  vr_out_of_range,     ///< VR above 16383
  value_out_of_range,  ///< VALUE outside [-2^31, 2^31 - 2^-32]
};

constexpr const char* to_string(sent_list_status status) noexcept {
  switch (status) {
    case sent_list_status::ok:
      return "ok";
    case sent_list_status::syntax:
      return "syntax";
    case sent_list_status::vr_out_of_range:
      return "vr_out_of_range";
    case sent_list_status::value_out_of_range:
      return "value_out_of_range";
  }
  return "unknown";
}

struct [[nodiscard]] sent_list_result {
  sent_list_status status = sent_list_status::ok;
  std::vector<sent_variable> sent;
  std::size_t line = 0;  ///< 1-based line of the error
  explicit operator bool() const noexcept { return status == sent_list_status::ok; }
};

/// Reads a sent list (format at the top of this file). Stops at the first bad line.
[[nodiscard]] sent_list_result parse_sent_list(std::string_view text);

/// The frames (14 data bytes each) the library's encoder makes for `sent` with the CRC `crc` and the layout
/// `layout`. Precondition: every vr <= 16383.
[[nodiscard]] std::vector<variable_frame> encode_capture(const std::vector<sent_variable>& sent,
                                                         const ring::crc16_parameters& crc,
                                                         const ring::variable_layout_parameters& layout = {});

}  // namespace trionet::learn
