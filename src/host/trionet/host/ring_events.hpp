// The events of a stream of ring bytes, as every front end reports them (`trionet ring decode`, `ring monitor`,
// the Python package's `trionet.ring.Decoder`): what each decoder result is called, its fields in order, and
// the byte of the stream it is about. One place, so that the tool's JSON and the other front ends cannot
// drift apart. Header-only; host code.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <utility>

#include "trionet/q32.hpp"
#include "trionet/ring/bytes.hpp"
#include "trionet/ring/decoder.hpp"
#include "trionet/span.hpp"

namespace trionet::host {

/// The event name of a decoder result: "message", "frame_error", "crc_error" or "no_room".
constexpr const char* ring_event_kind(const ring::decode_result& result) noexcept {
  return result.status == ring::decode_status::ok ? "message" : ring::to_string(result.status);
}

/// The name of a message's type in events: "char", "var", "offset" or "mode".
constexpr const char* ring_event_type(ring::message_type type) noexcept {
  switch (type) {
    case ring::message_type::character:
      return "char";
    case ring::message_type::variable:
      return "var";
    case ring::message_type::keypad_offset:
      return "offset";
    case ring::message_type::keypad_mode:
      return "mode";
  }
  return "unknown";
}

/// Characters of a Q32.32 value's "raw" field: "0x" and 16 lower-case hex digits.
constexpr std::size_t ring_raw_length = 18;

/// The "raw" field of a direct variable transfer: the Q32.32 value's 64 bits as "0x" and 16 hex digits.
inline std::string_view ring_raw_text(std::int64_t value, char (&text)[ring_raw_length]) noexcept {
  static constexpr char digits[] = "0123456789abcdef";
  const auto bits = static_cast<std::uint64_t>(trionet::q32_to_raw(value));
  text[0] = '0';
  text[1] = 'x';
  for (unsigned i = 0; i < 16; ++i) text[2 + i] = digits[bits >> (60U - 4U * i) & 0xFU];
  return std::string_view(text, ring_raw_length);
}

/// Gives the fields of a decoder result (after the event's position) to `out`, in order:
///   message      type, hops, then text (char); vr, raw, value (var); offset (offset); mode (mode)
///   frame_error  reason
///   crc_error    hops, vr
///   no_room      hops
/// through `out.name(key, std::string_view)` for the program's own names (type, reason, raw),
/// `out.text(key, std::string_view)` for characters from the wire (escape them), `out.number(key,
/// std::uint64_t)` and `out.real(key, double)`.
template <class Fields>
void ring_event_fields(Fields& out, const ring::decode_result& result) {
  const ring::message& m = result.msg;
  if (result.status == ring::decode_status::frame_error) {
    out.name("reason", ring::to_string(result.error));
    return;
  }
  if (result.status != ring::decode_status::ok) {  // crc_error, no_room
    out.number("hops", m.hops);
    if (result.status == ring::decode_status::crc_error) out.number("vr", m.vr);
    return;
  }
  out.name("type", ring_event_type(m.type));
  out.number("hops", m.hops);
  switch (m.type) {
    case ring::message_type::character:
      out.text("text", std::string_view(reinterpret_cast<const char*>(m.text.data()), m.text.size()));
      return;
    case ring::message_type::variable: {
      char raw[ring_raw_length];
      out.number("vr", m.vr);
      out.name("raw", ring_raw_text(m.value, raw));
      out.real("value", trionet::q32_to_double(m.value));
      return;
    }
    case ring::message_type::keypad_offset:
      out.number("offset", m.offset);
      return;
    case ring::message_type::keypad_mode:
      out.number("mode", m.mode);
      return;
  }
}

/// A decoder over a stream of bytes that knows where each byte is: every result comes with the position it
/// is about, the first byte of its message, or the byte itself for a result about one byte (stray data,
/// a stray end of message, a zero-hops header). `Decoder` is a ring decoder (`ring::decoder<>` or one with the
/// same `push` calls). Each `sink(const ring::decode_result&, std::uint64_t position)` call gets a result that
/// is valid until the next push (a character message's text is in the decoder).
template <class Decoder>
class ring_event_stream {
 public:
  template <class... Arguments>
  explicit ring_event_stream(Arguments&&... arguments) : decoder_(std::forward<Arguments>(arguments)...) {}

  /// One byte at position `at`.
  template <class Sink>
  void push(std::uint8_t byte, std::uint64_t at, Sink&& sink) {
    const bool header = !ring::is_data(byte) && ring::type_of(byte) != 0;
    const std::uint64_t message_at = start_;
    if (header) start_ = at;
    const ring::decode_result r = decoder_.push(byte);
    if (r.status == ring::decode_status::incomplete) return;
    const bool about_this_byte = r.status == ring::decode_status::frame_error &&
                                 (r.error == ring::frame_error::stray_data || r.error == ring::frame_error::stray_eom ||
                                  r.error == ring::frame_error::zero_hops);
    sink(r, about_this_byte ? at : message_at);
  }

  /// Many bytes, the first at position `at`: runs of data go to the decoder whole (its fast path); only a run
  /// outside a message gives a result (stray_data), and that is about the run's first byte.
  template <class Sink>
  void push(const std::uint8_t* first, const std::uint8_t* last, std::uint64_t at, Sink&& sink) {
    while (first != last) {
      const std::uint8_t* run = ring::find_control(first, last);
      if (run != first) {
        const std::uint64_t run_at = at;
        decoder_.push(byte_view(first, static_cast<std::size_t>(run - first)),
                      [&](const ring::decode_result& r) { sink(r, run_at); });
        at += static_cast<std::uint64_t>(run - first);
        first = run;
        if (first == last) break;
      }
      push(*first++, at++, sink);
    }
  }

  /// True when a message is open (at the end of the input: an "unfinished" event), with the position of
  /// its first byte.
  [[nodiscard]] bool unfinished(std::uint64_t& position) const {
    if (!decoder_.in_message()) return false;
    position = start_;
    return true;
  }

  /// The decoder.
  Decoder& decoder() noexcept { return decoder_; }

 private:
  Decoder decoder_;
  std::uint64_t start_ = 0;
};

}  // namespace trionet::host
