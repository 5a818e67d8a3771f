// Pieces of `trionet can` shared between its commands (can_cli.cpp, can_live_cli.cpp).
#pragma once

#include <cstdint>
#include <set>
#include <string>
#include <string_view>

#include "cli.hpp"
#include "profile_cli.hpp"
#include "trionet/can.hpp"
#include "trionet/host/candump.hpp"

namespace trionet::cli {

/// `--nodes K` (2..11), else the profile's node count (by default 5). False with `error` set for anything else.
bool parse_node_count(const arguments& parsed, std::uint8_t& out, std::string& error);

/// `--nodes K`, an option table of its own (`can table`), part of every other command's.
const option_list& node_count_option();

/// The options that describe one VR frame (`can encode`, `can send`): --nodes --from --to --vr --value.
const option_list& can_message_options();

/// The frame node --from sends to node --to to set VR(--vr) = --value in an exchange of --nodes controllers.
/// False with `error` saying what is wrong.
bool can_message_frame(const arguments& parsed, can::frame& out, std::string& error);

/// What a frame read from the bus is, for the live commands' counters.
enum class can_frame_class : std::uint8_t {
  vr,           ///< a TN20-17 VR message of the exchange
  vr_error,     ///< a frame on an exchange identifier that is no VR message (bad_dlc, bad_sign, bad_fraction)
  other,        ///< a valid frame that is not the exchange's (foreign identifier, extended, remote, FD, XL ...)
  error_frame,  ///< an error frame: a controller's report, not a frame on the bus
};

/// The event of one CAN frame, as `can decode` prints it: "vr" (id, from, to, vr, negative, int, frac, value)
/// for a TN20-17 VR message of an exchange of `nodes` controllers; "frame" with its `kind` for a valid frame
/// that is no VR message; "error" with the `reason` for a frame on an exchange identifier that is no VR
/// message. The numbers are read in the active profile's byte order. `where(event&)` adds the position.
/// Returns what the frame is.
template <class Where>
can_frame_class append_can_frame_event(std::string& out, std::uint8_t nodes, const host::candump_record& r, Where&& where) {
  const auto other = [&](const char* kind, std::uint32_t id) {
    event e(out, "frame");
    where(e);
    e.text("kind", kind).number("id", id).number("length", r.length);
    if (r.type == host::candump_frame_type::xl) e.number("vcid", r.can_id >> 16U & 0xFFU);
    // A remote request that its kind does not name (an extended or out-of-range identifier): `length` is the
    // DLC it asks for, no data came.
    if (r.type == host::candump_frame_type::classic && (r.can_id & can::frame::remote_flag) != 0 &&
        std::string_view(kind) != "remote") {
      e.boolean("remote", true);
    }
    return r.type == host::candump_frame_type::error ? can_frame_class::error_frame : can_frame_class::other;
  };
  const std::uint32_t id = r.can_id;
  switch (r.type) {
    case host::candump_frame_type::error:
      return other("error_frame", id & can::frame::extended_mask);
    case host::candump_frame_type::fd:
      if ((id & can::frame::extended_flag) == 0 && (id & 0xFFFFFU) > 0x7FFU) return other("bad_identifier", id & 0xFFFFFU);
      return other("fd", id & ((id & can::frame::extended_flag) != 0 ? can::frame::extended_mask : 0xFFFFFU));
    case host::candump_frame_type::xl:
      return other("xl", id & 0x7FFU);
    case host::candump_frame_type::classic:
      break;
  }
  if ((id & can::frame::extended_flag) != 0) return other("extended", id & can::frame::extended_mask);
  if (!r.classic_frame()) return other("bad_identifier", id & ~can::frame::remote_flag);
  const can::frame& frame = r.frame;
  if (frame.remote()) return other("remote", frame.identifier());
  const can::route_result route = can::route_of(nodes, frame.identifier());
  if (!route) return other("foreign_id", frame.identifier());
  const can::decode_result decoded = can::decode_vr_frame(frame, active_profile().can.byte_order);
  if (!decoded) {
    event e(out, "error");
    where(e);
    e.text("reason", can::to_string(decoded.status)).number("id", frame.identifier());
    return can_frame_class::vr_error;
  }
  const can::vr_message& message = decoded.message;
  event e(out, "vr");
  where(e);
  e.number("id", frame.identifier()).number("from", route.value.sender).number("to", route.value.receiver);
  e.number("vr", message.vr).boolean("negative", message.value.negative);
  e.number("int", message.value.integer_part).number("frac", message.value.fraction);
  e.real("value", trionet::to_double(message.value));
  return can_frame_class::vr;
}

/// A frame received from SocketCAN as the fields of a candump record (classic, or an error frame).
host::candump_record candump_record_of(const can::frame& frame, bool error_frame = false);

/// The live commands (can_live_cli.cpp): `trionet can monitor|send|node ...`, and their help text.
int can_monitor_main(const words& args);
int can_send_main(const words& args);
int can_node_main(const words& args);
extern const char* const can_live_usage;
const option_list& can_monitor_options();
const option_list& can_send_options();
const option_list& can_node_options();

}  // namespace trionet::cli
