// candump text (can-utils) for the host side (docs/protocol.md 2.3). Lines read:
//
//   log       (1700000000.123456) can0 028#0100000000020D7A [R|T]   candump -l/-L (-N: 9 fraction digits,
//                                                                   -x, asc2log, python-can: the direction)
//   compact   028#0100000000020D7A                                  cansend's argument
//   screen    [(TIMESTAMP)]  can0  [RX - -]  028   [8]  01 00 00 00 00 02 0D 7A ['ascii']   candump's default
//             [(TIMESTAMP)]  can0  123   [0]  remote request                               (-t, -x, -a, -b, -8)
//
// FRAME follows can-utils' own parser (`parse_canframe`) exactly: 3 identifier digits (standard), 8 (extended,
// or an error frame when bit 29 is set) or 5 (CAN XL VCID and priority); `#R[LEN][_D]` a remote frame;
// `##F` a CAN FD frame with flags digit F; `#FF:SS:AAAAAAAA#` a CAN XL header; then data bytes as hex pairs,
// each optionally preceded by one '.'; `_D` (D = 9..F) after 8 classic data bytes. Like can-utils, the parser
// stops reading the frame after its last data byte (8, 64 or 2048) or after a remote frame's length.
//
// Written: `candump -L` log lines and compact frames, as can-utils writes them (upper-case hex).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <trionet/can/frame.hpp>

namespace trionet::host {

/// Lines longer than this are not read (`candump_status::too_long`); can-utils' own tools stop at about
/// 6350 characters.
constexpr std::size_t candump_max_line_length = 8192;

/// SocketCAN's error-frame flag in an identifier word (CAN_ERR_FLAG).
constexpr std::uint32_t can_error_flag = 0x20000000U;

/// Which text form a line had.
enum class candump_form : std::uint8_t {
  log,      ///< (TIMESTAMP) IFACE FRAME [R|T]
  compact,  ///< FRAME alone
  screen,   ///< candump's default output
};

constexpr const char* to_string(candump_form form) noexcept {
  switch (form) {
    case candump_form::log:
      return "log";
    case candump_form::compact:
      return "compact";
    case candump_form::screen:
      return "screen";
  }
  return "unknown";
}

/// What kind of CAN frame a line holds.
enum class candump_frame_type : std::uint8_t {
  classic,  ///< a classic (CAN 2.0) data or remote frame
  error,    ///< an error frame: the error flag, bit 29, set in an 8-digit identifier (also after `##`)
  fd,       ///< a CAN FD frame (`##`)
  xl,       ///< a CAN XL frame
};

constexpr const char* to_string(candump_frame_type type) noexcept {
  switch (type) {
    case candump_frame_type::classic:
      return "classic";
    case candump_frame_type::error:
      return "error";
    case candump_frame_type::fd:
      return "fd";
    case candump_frame_type::xl:
      return "xl";
  }
  return "unknown";
}

/// One candump line.
struct candump_record {
  candump_form form = candump_form::compact;  ///< the line's form
  std::string timestamp;           ///< the text between the parentheses, as written; empty if none
  bool has_timestamp = false;      ///< `timestamp` is SECONDS.FRACTION, read into the next two fields
  std::uint64_t seconds = 0;       ///< timestamp, whole seconds
  std::uint32_t nanoseconds = 0;   ///< timestamp, 0..999999999
  std::uint8_t fraction_digits = 0;  ///< digits after the point as written (6; 9 with candump -N)
  std::string interface_name;      ///< "can0"; empty for the compact form
  char direction = 0;              ///< 'R' received or 'T' sent, where the line says; else 0
  candump_frame_type type = candump_frame_type::classic;  ///< what the frame is
  /// The identifier word as can-utils builds it: the digits' value with SocketCAN's flags (bit 31 extended,
  /// 30 remote, 29 error). CAN XL: VCID << 16 | priority.
  std::uint32_t can_id = 0;
  std::uint16_t length = 0;   ///< data bytes: classic 0..8 (remote: the length asked for), FD 0..64, XL 0..2048
  std::uint8_t len8_dlc = 0;  ///< a classic frame of 8 bytes: the DLC 9..15 given as `_D`; else 0
  std::uint8_t flags = 0;     ///< CAN FD: the flags digit; CAN XL: the flags byte
  std::uint8_t sdt = 0;       ///< CAN XL: the SDU type
  std::uint32_t af = 0;       ///< CAN XL: the acceptance field
  /// classic: the frame (identifier word with the extended and remote flags, DLC, data); error: the error
  /// class bits as identifier, the length as DLC and the data; FD and XL: the first 8 data bytes.
  can::frame frame{};
  /// Every data byte as written on the line (classic 0..8, FD 0..64, XL 0..2048; none for a remote frame).
  std::vector<std::uint8_t> data;

  /// True for a classic frame whose identifier fits its format (standard 0..7FF, or extended): `frame` is
  /// then the frame as SocketCAN would carry it.
  [[nodiscard]] bool classic_frame() const noexcept {
    return type == candump_frame_type::classic &&
           ((can_id & can::frame::extended_flag) != 0 || (can_id & ~can::frame::remote_flag) <= 0x7FFU);
  }
};

/// Whether a line is candump text, and if not, where it goes wrong.
enum class candump_status : std::uint8_t {
  ok,
  empty,           ///< nothing but blanks
  too_long,        ///< longer than candump_max_line_length
  timestamp,       ///< "(...)" is neither SECONDS.FRACTION (1..9 fraction digits, at most 18446744073.709551615 s:
                   ///< 64-bit nanoseconds) nor candump -t A's date
  interface_name,  ///< no interface name, or nothing after it
  identifier,      ///< no '#' after 3, 5 or 8 characters, or those are not hex digits, or 5 (a CAN XL VCID and
                   ///< priority) before a remote or CAN FD frame
  fd_flags,        ///< `##` not followed by a hex digit
  xl_header,       ///< a CAN XL header that is not FF:SS:AAAAAAAA# (one must follow a 5-digit identifier)
  data,            ///< a data byte that is not two hex digits (screen: fewer bytes than the length says)
  length,          ///< screen form: the length is not [N], {N}, [NN] or [NNNN], or is out of range
  trailing,        ///< text after the frame (other than a direction R or T, or candump's ASCII column)
};

constexpr const char* to_string(candump_status status) noexcept {
  switch (status) {
    case candump_status::ok:
      return "ok";
    case candump_status::empty:
      return "empty";
    case candump_status::too_long:
      return "too_long";
    case candump_status::timestamp:
      return "timestamp";
    case candump_status::interface_name:
      return "interface_name";
    case candump_status::identifier:
      return "identifier";
    case candump_status::fd_flags:
      return "fd_flags";
    case candump_status::xl_header:
      return "xl_header";
    case candump_status::data:
      return "data";
    case candump_status::length:
      return "length";
    case candump_status::trailing:
      return "trailing";
  }
  return "unknown";
}

/// A parsed line, or why it is not one.
struct [[nodiscard]] candump_result {
  candump_status status = candump_status::ok;  ///< `ok` or the first problem
  candump_record record{};                     ///< meaningful when ok
  explicit operator bool() const noexcept { return status == candump_status::ok; }
};

/// Parses one line in any form into `out`, reusing its strings (no allocation per line once they have
/// grown). Leading and trailing blanks and a CR are ignored; the line ends at a NUL, as for can-utils.
[[nodiscard]] candump_status parse_candump_line(std::string_view line, candump_record& out);

/// Parses one line in any form.
[[nodiscard]] candump_result parse_candump_line(std::string_view line);

/// Parses a compact frame (FRAME above, as `cansend` takes it) into the frame fields of `out`.
[[nodiscard]] candump_status parse_candump_frame(std::string_view text, candump_record& out);

/// The compact form of `frame`: "028#0100000000020D7A" (upper-case hex; `_D` for a DLC of 9..15).
[[nodiscard]] std::string format_candump_frame(const can::frame& frame);

/// The record as a line: the log form "(1700000000.123456) can0 028#..." (9 fraction digits if it was
/// read with 9, interface "can0" when the record names none, the direction if any) when it has a numeric
/// timestamp, else the compact form.
[[nodiscard]] std::string format_candump_line(const candump_record& record);

}  // namespace trionet::host
