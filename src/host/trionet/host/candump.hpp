// candump text (can-utils) for the host side: read and write classic CAN frames as
//
//   log form      (1700000000.123456) can0 028#0100000000020D7A      candump -L, canplayer input
//   compact form  028#0100000000020D7A                               cansend argument
//
// Identifier: 3 hex digits (11-bit, at most 7FF) or 8 hex digits (29-bit, at most 1FFFFFFF). Data: 0 to 8
// bytes as pairs of hex digits, optionally separated by '.', either case on input, upper case on output. A
// remote frame is `028#R` or `028#R8` (R and a length digit). CAN FD (`##`) and the `_` DLC suffix are not
// classic TN20-17 frames and are syntax errors. Leading and trailing blanks (and a trailing CR) are ignored.
// The log form may end with a direction flag, ` R` (received) or ` T` (sent), as `candump -L -x` and asc2log
// write it; it is read and dropped.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include <trionet/can/frame.hpp>

namespace trionet::host {

/// One candump line: a frame, and for the log form its timestamp and interface.
struct candump_record {
  bool has_timestamp = false;      ///< log form; false for the compact form
  std::uint64_t seconds = 0;       ///< timestamp, whole seconds
  std::uint32_t microseconds = 0;  ///< timestamp, 0..999999
  std::string interface_name;      ///< "can0"; empty for the compact form
  can::frame frame{};
};

/// Whether a line is candump text. The CLI reports every reason as `syntax`.
enum class candump_status : std::uint8_t {
  ok,
  empty,           ///< nothing but blanks
  timestamp,       ///< "(seconds.micros)" malformed
  interface_name,  ///< no interface name after the timestamp
  identifier,      ///< not 3 or 8 hex digits, or out of range
  separator,       ///< no '#' after the identifier, or "##" (CAN FD)
  data,            ///< odd hex digits, a non-hex character, more than 8 bytes, or a bad remote length
  trailing,        ///< text after the frame
};

/// A parsed line, or why it is not one.
struct [[nodiscard]] candump_result {
  candump_status status = candump_status::ok;
  candump_record record{};
  explicit operator bool() const noexcept { return status == candump_status::ok; }
};

/// Parses one line in either form.
[[nodiscard]] candump_result parse_candump_line(std::string_view line);

/// The compact form of `frame`: "028#0100000000020D7A" (upper-case hex).
[[nodiscard]] std::string format_candump_frame(const can::frame& frame);

/// The record as a line: the log form "(1700000000.123456) can0 028#..." if it has a timestamp (interface
/// "can0" when the record names none), else the compact form.
[[nodiscard]] std::string format_candump_line(const candump_record& record);

/// The enumerator's name ("identifier"), for messages.
[[nodiscard]] const char* to_string(candump_status status);

}  // namespace trionet::host
