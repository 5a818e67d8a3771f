// What the streaming ring decoder (ring/decoder.hpp) reports for a pushed byte: `decode_status`, the reason of a
// frame error (`frame_error`), their names (`to_string`) and the `decode_result` that carries them with the
// message. A node's counters and NETSTAT bits (ring/node.hpp) are made from these, and so is what a node's
// `receive` answers for a byte (`receive_status`).
#pragma once

#include <cstdint>

#include "trionet/detail/status_map.hpp"
#include "trionet/ring/message.hpp"

namespace trionet::ring {

/// What one pushed byte completed. As for every streaming push, "nothing yet" is 0 and `ok` follows: the
/// per-byte path returns `incomplete` almost always, and a zero result is the cheapest to make.
enum class decode_status : std::uint8_t {
  incomplete,   ///< nothing to report yet
  ok,           ///< a valid message: see `decode_result::msg`
  frame_error,  ///< a message or byte was discarded: see `decode_result::error`
  crc_error,    ///< a direct variable transfer failed its CRC; `msg.hops` and `msg.vr` are as received
  no_room,      ///< a valid character transfer that the character store had no room for (discarded whole;
                ///< only with a store smaller than MaxCharacters, e.g. a node's receive buffer)
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(decode_status status) noexcept {
  switch (status) {
    case decode_status::incomplete:
      return "incomplete";
    case decode_status::ok:
      return "ok";
    case decode_status::frame_error:
      return "frame_error";
    case decode_status::crc_error:
      return "crc_error";
    case decode_status::no_room:
      return "no_room";
  }
  return "unknown";
}

/// What became of the message that a byte received by a node ended (a node's `receive` and `line_idle`; its
/// counters count each outcome). The decoder's outcomes for a message for the node keep their names and order
/// here (from `incomplete` to `no_room`); the outcomes of a message passing through the node follow.
enum class receive_status : std::uint8_t {
  incomplete,          ///< the byte ended no message
  ok,                  ///< a valid message for the node, delivered (what the node did with it: its counters)
  frame_error,         ///< a message for the node discarded: a frame error (NETSTAT bit 3)
  crc_error,           ///< a direct variable transfer for the node failed its CRC (NETSTAT bit 2)
  no_room,             ///< a valid character transfer for the node with no room in its receive buffer, dropped
                       ///< whole (NETSTAT bit 4)
  forwarded,           ///< the end of message of a message passing through went on (`messages_forwarded`
                       ///< counted it at its header)
  dropped,             ///< a message to or through a node that does not forward it now (a keypad in local
                       ///< mode), dropped at its header (`messages_dropped`)
  forward_lost,        ///< a message passing through lost: no room in the forward buffer (NETSTAT bit 1)
  forward_cut,         ///< ... longer than the longest legal message of its type (NETSTAT bit 1)
  forward_ended_idle,  ///< ... its end of message never came: the line went idle (`line_idle`; NETSTAT bit 1)
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(receive_status status) noexcept {
  switch (status) {
    case receive_status::incomplete:
      return "incomplete";
    case receive_status::ok:
      return "ok";
    case receive_status::frame_error:
      return "frame_error";
    case receive_status::crc_error:
      return "crc_error";
    case receive_status::no_room:
      return "no_room";
    case receive_status::forwarded:
      return "forwarded";
    case receive_status::dropped:
      return "dropped";
    case receive_status::forward_lost:
      return "forward_lost";
    case receive_status::forward_cut:
      return "forward_cut";
    case receive_status::forward_ended_idle:
      return "forward_ended_idle";
  }
  return "unknown";
}

/// Why a frame was discarded (`none` unless the status is `frame_error`).
enum class frame_error : std::uint8_t {
  none,          ///< no frame error
  stray_data,    ///< data bytes outside any message (one report per run)
  stray_eom,     ///< end of message with no open message
  interrupted,   ///< a header arrived before the open message's end of message
  eom_mismatch,  ///< end of message A differs from the header's
  bad_length,    ///< data length wrong for the type (or longer than the capacity)
  bad_field,     ///< a field out of range: offset, mode, or X9 bits 6..1
  unknown_type,  ///< message type 5..7
  zero_hops,     ///< header with A = 0
  idle_line,     ///< the line went idle before the open message's end of message (docs/protocol.md 1.10)
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(frame_error error) noexcept {
  switch (error) {
    case frame_error::none:
      return "none";
    case frame_error::stray_data:
      return "stray_data";
    case frame_error::stray_eom:
      return "stray_eom";
    case frame_error::interrupted:
      return "interrupted";
    case frame_error::eom_mismatch:
      return "eom_mismatch";
    case frame_error::bad_length:
      return "bad_length";
    case frame_error::bad_field:
      return "bad_field";
    case frame_error::unknown_type:
      return "unknown_type";
    case frame_error::zero_hops:
      return "zero_hops";
    case frame_error::idle_line:
      return "idle_line";
  }
  return "unknown";
}

/// What a pushed byte completed: a message, or why one was discarded.
struct [[nodiscard]] decode_result {
  /// What the byte completed (`incomplete`: nothing yet).
  decode_status status = decode_status::incomplete;
  /// Why the frame was discarded, for `frame_error`.
  frame_error error = frame_error::none;
  message msg;  ///< meaningful for `ok`; `hops` and `vr` also for `crc_error`
  /// True for `ok`: `msg` is a valid message.
  constexpr explicit operator bool() const noexcept { return status == decode_status::ok; }
};

}  // namespace trionet::ring

namespace trionet::detail {
/// The decoder's outcomes as a node's `receive_status`.
using decode_outcome =
    status_map<ring::decode_status::incomplete, ring::decode_status::no_room, ring::receive_status::incomplete>;
}  // namespace trionet::detail
