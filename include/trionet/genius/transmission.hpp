// Genius transmissions (docs/protocol.md 3.2): control characters, an encoder into caller buffers, a
// streaming parser with error reasons, and a bits-to-transmissions receiver.
//
// Control characters (control bit 1). The bit layout is this library's decision (GE does not publish it):
//
//                      7   6   5   4   3   2   1   0
//                    +---+---+---+-------------------+
//   Start            | 0 | 0 | B |  sender SBA 0..31 |   B = 1 broadcast, 0 directed
//                    +---+---+---+-------------------+
//   Stop             | 0 | 1 |  CRC-6 of the transmission|
//                    +---+---+---+-------------------+
//   Start of block   | 1 | 0 | 0 | destination SBA   |   bit 5 = 1 is an unknown control character
//                    +---+---+---+-------------------+
//   End of block     | 1 | 1 |  CRC-6 of the block   |
//                    +---+---+-----------------------+
//
// That layout is the default `control_layout` (configurable): which 2-bit tag marks each control character
// and whether the tag is in bits 7..6 (the fields in bits 5..0, as drawn) or in bits 1..0 (the same fields
// in bits 7..2). Any other layout of these four characters is one of these 24 x 2.
//
// A transmission, characters back to back (c: = control character):
//
//   c:Start | [destination SBA] | data ... | { c:Start of block | data ... | c:End of block | data ... } |
//   c:Stop
//             directed only      plain data   zero or more blocks, in any order with plain data
//
// CRCs (Decision, see docs/genius.md): the End of block CRC covers the data bytes of the data characters
// since its Start of block. The Stop CRC covers the data bytes of every data character since the Start:
// the destination SBA of a directed transmission, plain data and the data inside blocks. The SBAs carried
// in control characters are not covered.
//
// Rules (Decisions where docs/protocol.md 3.2 is silent): at least one data character per transmission (the
// destination SBA counts); every block holds at least one data character; blocks do not nest; in a
// directed transmission the destination SBA (0..31) comes right after the Start, before any block.
#pragma once

#include <cstddef>
#include <cstdint>

#include "trionet/detail/crc_holder.hpp"
#include "trionet/genius/character.hpp"
#include "trionet/genius/crc6.hpp"
#include "trionet/span.hpp"

namespace trionet::genius {

/// The highest Serial Bus Address.
constexpr std::uint8_t max_sba = 31;

/// The four control characters (by their tag, see `control_layout`), plus `unknown` for a Start of block with
/// the top field bit set.
enum class control_kind : std::uint8_t {
  start,           ///< starts a transmission (default tag 00)
  stop,            ///< ends a transmission (default tag 01)
  start_of_block,  ///< starts a block (default tag 10, top field bit 0)
  end_of_block,    ///< ends a block (default tag 11)
  unknown,         ///< a Start of block with the top field bit set
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(control_kind value) noexcept {
  switch (value) {
    case control_kind::start:
      return "start";
    case control_kind::stop:
      return "stop";
    case control_kind::start_of_block:
      return "start_of_block";
    case control_kind::end_of_block:
      return "end_of_block";
    case control_kind::unknown:
      return "unknown";
  }
  return "unknown";
}

/// Where a control character's 2-bit tag sits in its byte.
enum class tag_position : std::uint8_t {
  high,  ///< bits 7..6, the fields in bits 5..0 (the default)
  low,   ///< bits 1..0, the fields in bits 7..2
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(tag_position value) noexcept {
  switch (value) {
    case tag_position::high:
      return "high";
    case tag_position::low:
      return "low";
  }
  return "unknown";
}

/// The bit layout of the control characters (docs/protocol.md 3.2: a decision, configurable). The 6 field
/// bits are the same in every layout: Start = B (bit 5) and the sender SBA (bits 4..0); Stop and End of
/// block = the CRC-6; Start of block = 0 (bit 5) and the destination SBA.
struct control_layout {
  std::uint8_t start = 0;                      ///< the tag of Start, 0..3
  std::uint8_t stop = 1;                       ///< the tag of Stop
  std::uint8_t start_of_block = 2;             ///< the tag of Start of block
  std::uint8_t end_of_block = 3;               ///< the tag of End of block
  tag_position position = tag_position::high;  ///< where the tag sits

  /// True when the four tags are 0..3 and all different. An invalid layout encodes and decodes
  /// consistently but cannot tell some characters apart (a tag shared by two kinds reads as the first of
  /// start, stop, start of block, end of block).
  [[nodiscard]] constexpr bool valid() const noexcept {
    const unsigned seen =
        1U << (start & 7U) | 1U << (stop & 7U) | 1U << (start_of_block & 7U) | 1U << (end_of_block & 7U);
    return seen == 0xFU;
  }

  /// Equal when every tag and the tag position are.
  friend constexpr bool operator==(const control_layout& a, const control_layout& b) noexcept {
    return a.start == b.start && a.stop == b.stop && a.start_of_block == b.start_of_block &&
           a.end_of_block == b.end_of_block && a.position == b.position;
  }
  /// Not equal when any differs.
  friend constexpr bool operator!=(const control_layout& a, const control_layout& b) noexcept {
    return !(a == b);
  }
};

/// The fields of a control character's byte. Only the fields of its `kind` are meaningful.
struct control_fields {
  control_kind kind = control_kind::unknown;  ///< which control character
  std::uint8_t sba = 0;                       ///< Start: sender; Start of block: destination
  bool broadcast = false;                     ///< Start only
  std::uint8_t crc = 0;                       ///< Stop and End of block
};

namespace detail {

constexpr std::uint8_t control_byte(const control_layout& layout, std::uint8_t tag,
                                    unsigned fields) noexcept {
  const unsigned field_bits = fields & 0x3fU;
  const unsigned tag_bits = tag & 3U;
  return static_cast<std::uint8_t>(layout.position == tag_position::high ? (tag_bits << 6U) | field_bits
                                                                         : (field_bits << 2U) | tag_bits);
}

}  // namespace detail

/// Reads a control character's byte in `layout`. Total. Cost: a few instructions; ISR-safe.
[[nodiscard]] constexpr control_fields read_control(
    std::uint8_t byte, const control_layout& layout = control_layout{}) noexcept {
  const bool high = layout.position == tag_position::high;
  const auto tag = static_cast<std::uint8_t>(high ? byte >> 6U : byte & 3U);
  const auto field_bits = static_cast<std::uint8_t>(high ? byte & 0x3fU : byte >> 2U);
  control_fields fields;
  if (tag == layout.start) {
    fields.kind = control_kind::start;
    fields.broadcast = (field_bits & 0x20u) != 0;
    fields.sba = static_cast<std::uint8_t>(field_bits & 0x1fu);
  } else if (tag == layout.stop) {
    fields.kind = control_kind::stop;
    fields.crc = field_bits;
  } else if (tag == layout.start_of_block) {
    fields.kind = (field_bits & 0x20u) != 0 ? control_kind::unknown : control_kind::start_of_block;
    fields.sba = static_cast<std::uint8_t>(field_bits & 0x1fu);
  } else if (tag == layout.end_of_block) {
    fields.kind = control_kind::end_of_block;
    fields.crc = field_bits;
  }
  return fields;
}

/// Control character constructors, in `layout`. Out-of-range arguments are masked to their field (the
/// encoder checks ranges before it gets here).
[[nodiscard]] constexpr character start_character(std::uint8_t sender, bool broadcast,
                                                  const control_layout& layout = control_layout{}) noexcept {
  return control_character(
      detail::control_byte(layout, layout.start, (broadcast ? 0x20u : 0u) | (sender & 0x1fu)));
}
/// Stop carrying the transmission's CRC-6.
[[nodiscard]] constexpr character stop_character(std::uint8_t crc,
                                                 const control_layout& layout = control_layout{}) noexcept {
  return control_character(detail::control_byte(layout, layout.stop, crc));
}
/// Start of block to SBA `destination`.
[[nodiscard]] constexpr character start_of_block_character(
    std::uint8_t destination, const control_layout& layout = control_layout{}) noexcept {
  return control_character(detail::control_byte(layout, layout.start_of_block, destination & 0x1fu));
}
/// End of block carrying the block's CRC-6.
[[nodiscard]] constexpr character end_of_block_character(
    std::uint8_t crc, const control_layout& layout = control_layout{}) noexcept {
  return control_character(detail::control_byte(layout, layout.end_of_block, crc));
}
/// A control character of no known kind in `layout` (a Start of block with the top field bit set). A parser
/// abandons an open transmission on it (`unknown_control`): e.g. what to put where a character was lost.
[[nodiscard]] constexpr character unknown_control_character(
    const control_layout& layout = control_layout{}) noexcept {
  return control_character(detail::control_byte(layout, layout.start_of_block, 0x20u));
}

/// A run of data characters: plain data (`block` false) or a block to `destination`.
struct segment {
  bool block = false;            ///< a block (with its own CRC) rather than plain data
  std::uint8_t destination = 0;  ///< blocks only
  byte_view data;                ///< the data bytes, at least one
};

/// A transmission as the application sees it. `destination` is used only when `broadcast` is false.
struct transmission {
  std::uint8_t sender = 0;       ///< the sender's SBA, 0..31
  bool broadcast = true;         ///< to every device, or directed to `destination`
  std::uint8_t destination = 0;  ///< directed: the receiver's SBA, 0..31
  span<const segment> segments;  ///< plain data and blocks, in order
};

/// What became of an encode (misuse of the API; on anything but `ok` nothing was written).
enum class encode_status : std::uint8_t {
  ok,                        ///< encoded
  buffer_too_small,          ///< the caller's buffer is shorter than the transmission
  sender_out_of_range,       ///< sender SBA > 31
  destination_out_of_range,  ///< directed destination or a block's destination > 31
  empty_transmission,        ///< no data character at all (a broadcast with no data)
  empty_block,               ///< a block with no data
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(encode_status value) noexcept {
  switch (value) {
    case encode_status::ok:
      return "ok";
    case encode_status::buffer_too_small:
      return "buffer_too_small";
    case encode_status::sender_out_of_range:
      return "sender_out_of_range";
    case encode_status::destination_out_of_range:
      return "destination_out_of_range";
    case encode_status::empty_transmission:
      return "empty_transmission";
    case encode_status::empty_block:
      return "empty_block";
  }
  return "unknown";
}

/// The outcome of an encode: `length` characters were written (or would be, for `encoded_length`).
struct [[nodiscard]] encode_result {
  encode_status status = encode_status::ok;  ///< `ok`, or why nothing was written
  std::size_t length = 0;                    ///< characters written
  /// True when `status` is `ok`.
  constexpr explicit operator bool() const noexcept { return status == encode_status::ok; }
};

/// Validates `t` and returns the number of characters it encodes to (buffer_too_small never occurs).
/// Cost: O(number of segments); no allocation; ISR-safe.
[[nodiscard]] constexpr encode_result encoded_length(const transmission& t) noexcept {
  if (t.sender > max_sba) return {encode_status::sender_out_of_range, 0};
  std::size_t length = 2;  // Start and Stop
  std::size_t data_characters = 0;
  if (!t.broadcast) {
    if (t.destination > max_sba) return {encode_status::destination_out_of_range, 0};
    ++length;
    ++data_characters;
  }
  for (const segment& s : t.segments) {
    if (s.block) {
      if (s.destination > max_sba) return {encode_status::destination_out_of_range, 0};
      if (s.data.empty()) return {encode_status::empty_block, 0};
      length += 2;
    }
    length += s.data.size();
    data_characters += s.data.size();
  }
  if (data_characters == 0) return {encode_status::empty_transmission, 0};
  return {encode_status::ok, length};
}

namespace detail {

template <class Crc, class Emit>
constexpr void emit_transmission(const Crc& crc, const control_layout& layout, const transmission& t,
                                 Emit&& emit) noexcept {
  typename Crc::register_type stop_crc = crc.begin();
  emit(start_character(t.sender, t.broadcast, layout));
  if (!t.broadcast) {
    emit(data_character(t.destination));
    stop_crc = crc.update(stop_crc, t.destination);
  }
  for (const segment& s : t.segments) {
    typename Crc::register_type block_crc = crc.begin();
    if (s.block) emit(start_of_block_character(s.destination, layout));
    for (std::uint8_t byte : s.data) {
      emit(data_character(byte));
      stop_crc = crc.update(stop_crc, byte);
      block_crc = crc.update(block_crc, byte);
    }
    if (s.block) emit(end_of_block_character(crc.finish(block_crc), layout));
  }
  emit(stop_character(crc.finish(stop_crc), layout));
}

}  // namespace detail

/// Encodes `t` as characters into `out`, with the CRC-6 `crc` (a static policy by default, or a
/// `crc6_runtime` chosen at run time) and the control characters in `layout`. On any error nothing is
/// written. Cost: O(characters); no allocation; ISR-safe.
template <class Crc = crc6_g704>
[[nodiscard]] constexpr encode_result encode_transmission(
    span<character> out, const transmission& t, const Crc& crc = Crc{},
    const control_layout& layout = control_layout{}) noexcept {
  const encode_result result = encoded_length(t);
  if (!result) return result;
  if (out.size() < result.length) return {encode_status::buffer_too_small, result.length};
  std::size_t at = 0;
  detail::emit_transmission(crc, layout, t, [&](character c) { out[at++] = c; });
  return result;
}

/// Encodes `t` as 11-bit words (numbering in character.hpp) into `out`, with the CRC-6 `crc` and the
/// control layout `layout` as above. On any error nothing is written.
/// Cost: O(characters); no allocation; ISR-safe.
template <class Crc = crc6_g704>
[[nodiscard]] constexpr encode_result encode_transmission(
    span<std::uint16_t> out, const transmission& t, const Crc& crc = Crc{},
    const control_layout& layout = control_layout{}) noexcept {
  const encode_result result = encoded_length(t);
  if (!result) return result;
  if (out.size() < result.length) return {encode_status::buffer_too_small, result.length};
  std::size_t at = 0;
  detail::emit_transmission(crc, layout, t, [&](character c) { out[at++] = encode_character(c); });
  return result;
}

/// What one character pushed into a `transmission_parser` did. Every value from
/// `data_outside_transmission` on is a wire error: it is counted, the transmission being received (if
/// any) is discarded whole, and the parser skips characters until the next Start. As for every streaming
/// push, "nothing yet" (`in_progress`) is 0 and `ok` follows.
enum class parse_status : std::uint8_t {
  in_progress,  ///< accepted; the transmission continues
  ok,           ///< a Stop with a matching CRC: `transmission_parser::received()` holds the transmission
  skipped,      ///< ignored while looking for a Start after an error (counted, not an error itself)
  data_outside_transmission,     ///< a data character with no transmission open
  control_outside_transmission,  ///< a Stop, Start of block or End of block with no transmission open
  start_inside_transmission,   ///< a Start before the Stop: the old transmission is lost, the new one begins
  unknown_control,             ///< a control character of no known kind (Start of block with bit 5 set)
  destination_out_of_range,    ///< a directed transmission's first data character is not 0..31
  missing_destination,         ///< a directed transmission has a Start of block before its destination
  block_not_closed,            ///< a Start of block or Stop inside an open block
  end_of_block_outside_block,  ///< an End of block with no block open
  empty_block,                 ///< an End of block right after its Start of block
  empty_transmission,          ///< a Stop with no data character since the Start
  block_crc_mismatch,          ///< an End of block whose CRC-6 does not match the block
  stop_crc_mismatch,           ///< a Stop whose CRC-6 does not match the transmission
  overflow,                    ///< more data bytes or segments than the parser's capacity
  framing_error,               ///< the character layer reported a framing error (`push_framing_error`)
};

/// Number of `parse_status` values (for counter arrays).
constexpr std::size_t parse_status_count = static_cast<std::size_t>(parse_status::framing_error) + 1;

/// True for the statuses that are wire errors.
[[nodiscard]] constexpr bool is_error(parse_status status) noexcept {
  return static_cast<std::uint8_t>(status) >=
         static_cast<std::uint8_t>(parse_status::data_outside_transmission);
}

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(parse_status value) noexcept {
  switch (value) {
    case parse_status::in_progress:
      return "in_progress";
    case parse_status::ok:
      return "ok";
    case parse_status::skipped:
      return "skipped";
    case parse_status::data_outside_transmission:
      return "data_outside_transmission";
    case parse_status::control_outside_transmission:
      return "control_outside_transmission";
    case parse_status::start_inside_transmission:
      return "start_inside_transmission";
    case parse_status::unknown_control:
      return "unknown_control";
    case parse_status::destination_out_of_range:
      return "destination_out_of_range";
    case parse_status::missing_destination:
      return "missing_destination";
    case parse_status::block_not_closed:
      return "block_not_closed";
    case parse_status::end_of_block_outside_block:
      return "end_of_block_outside_block";
    case parse_status::empty_block:
      return "empty_block";
    case parse_status::empty_transmission:
      return "empty_transmission";
    case parse_status::block_crc_mismatch:
      return "block_crc_mismatch";
    case parse_status::stop_crc_mismatch:
      return "stop_crc_mismatch";
    case parse_status::overflow:
      return "overflow";
    case parse_status::framing_error:
      return "framing_error";
  }
  return "unknown";
}

/// Streaming parser: push characters one at a time; a complete, CRC-checked transmission is reported by
/// `ok`, and `received()` then views it (valid until the next push). The destination SBA of a
/// directed transmission is reported in `transmission::destination`, not in the segments. Consecutive
/// plain data characters form one segment.
///
/// Capacities: `DataCapacity` data bytes (destination SBA excluded) and `SegmentCapacity` segments per
/// transmission; a longer transmission is reported as `overflow` and skipped up to the next Start, so the
/// parser never loses sync. `Crc` is the CRC-6 policy (crc6.hpp): a static policy (`crc6<...>`, held as
/// nothing) or `crc6_runtime` (held as its 5 bytes, passed to the constructor).
///
/// Cost: DataCapacity + 2 * SegmentCapacity * (2 + 2 pointers) bytes plus counters: 752 bytes for the
/// defaults on a 32-bit target, 1160 on 64-bit. O(1) per character, O(segments) on a Stop. No allocation.
/// ISR-safe (one parser per line; the caller owns it).
template <std::size_t DataCapacity = 256, std::size_t SegmentCapacity = 16, class Crc = crc6_g704>
class transmission_parser : private trionet::detail::crc_holder<Crc> {
  static_assert(DataCapacity > 0 && SegmentCapacity > 0, "capacities must be at least 1");

 public:
  /// A parser with the default CRC object (for a static policy, the policy itself).
  transmission_parser() noexcept = default;
  /// A parser that checks with `crc` (e.g. a `crc6_runtime` from a profile) and reads control characters in
  /// `layout`.
  explicit transmission_parser(const Crc& crc, const control_layout& layout = control_layout{}) noexcept
      : trionet::detail::crc_holder<Crc>(crc), layout_(layout) {}

  /// Feeds the next character. See `parse_status`.
  [[nodiscard]] parse_status push(character c) noexcept {
    if (c.control) return push_control(read_control(c.byte, layout_));
    return push_data(c.byte);
  }

  /// Reports a framing error from the character layer: the open transmission, if any, is lost.
  parse_status push_framing_error() noexcept {
    if (!open_ && resync_) {
      ++counts_[static_cast<std::size_t>(parse_status::skipped)];
      return parse_status::skipped;
    }
    return fail(parse_status::framing_error);
  }

  /// The last complete transmission. Valid after `push` returned `ok`, until the next push.
  [[nodiscard]] const transmission& received() const noexcept { return received_; }
  /// True between a Start and the end of its transmission (Stop or error).
  [[nodiscard]] bool in_transmission() const noexcept { return open_; }

  /// How many times `push` returned `status` since the counters were last cleared.
  [[nodiscard]] std::uint32_t count(parse_status status) const noexcept {
    return counts_[static_cast<std::size_t>(status)];
  }
  /// Total wire errors.
  [[nodiscard]] std::uint32_t errors() const noexcept {
    std::uint32_t total = 0;
    for (std::size_t i = 0; i < parse_status_count; ++i) {
      if (is_error(static_cast<parse_status>(i))) total += counts_[i];
    }
    return total;
  }
  /// Sets every count to 0.
  void clear_counters() noexcept {
    for (auto& n : counts_) n = 0;
  }
  /// Forgets any open transmission; the next character is parsed as if the line had just come up.
  void reset() noexcept {
    open_ = false;
    resync_ = false;
  }

  static constexpr std::size_t data_capacity = DataCapacity;        ///< data bytes a transmission may hold
  static constexpr std::size_t segment_capacity = SegmentCapacity;  ///< segments it may hold

 private:
  struct stored_segment {
    bool block;
    std::uint8_t destination;
    std::size_t offset;
    std::size_t length;
  };

  parse_status fail(parse_status status) noexcept {
    open_ = false;
    resync_ = true;
    ++counts_[static_cast<std::size_t>(status)];
    return status;
  }

  parse_status accept(parse_status status) noexcept {
    ++counts_[static_cast<std::size_t>(status)];
    return status;
  }

  parse_status outside(parse_status error) noexcept {
    if (resync_) {
      ++counts_[static_cast<std::size_t>(parse_status::skipped)];
      return parse_status::skipped;
    }
    return fail(error);
  }

  parse_status push_control(const control_fields& f) noexcept {
    if (f.kind == control_kind::start) {
      const bool interrupted = open_;
      open_ = true;
      resync_ = false;
      in_block_ = false;
      broadcast_ = f.broadcast;
      need_destination_ = !f.broadcast;
      sender_ = f.sba;
      destination_ = 0;
      data_characters_ = 0;
      used_ = 0;
      segments_ = 0;
      stop_crc_ = this->crc().begin();
      if (interrupted) return accept(parse_status::start_inside_transmission);
      return accept(parse_status::in_progress);
    }
    if (!open_) return outside(parse_status::control_outside_transmission);
    switch (f.kind) {
      case control_kind::start_of_block:
        if (need_destination_) return fail(parse_status::missing_destination);
        if (in_block_) return fail(parse_status::block_not_closed);
        if (segments_ == SegmentCapacity) return fail(parse_status::overflow);
        stored_[segments_++] = stored_segment{true, f.sba, used_, 0};
        in_block_ = true;
        block_crc_ = this->crc().begin();
        return accept(parse_status::in_progress);
      case control_kind::end_of_block:
        if (!in_block_) return fail(parse_status::end_of_block_outside_block);
        if (stored_[segments_ - 1].length == 0) return fail(parse_status::empty_block);
        if (this->crc().finish(block_crc_) != f.crc) return fail(parse_status::block_crc_mismatch);
        in_block_ = false;
        return accept(parse_status::in_progress);
      case control_kind::stop:
        if (in_block_) return fail(parse_status::block_not_closed);
        if (data_characters_ == 0) return fail(parse_status::empty_transmission);
        if (this->crc().finish(stop_crc_) != f.crc) return fail(parse_status::stop_crc_mismatch);
        complete();
        return accept(parse_status::ok);
      default:
        return fail(parse_status::unknown_control);
    }
  }

  parse_status push_data(std::uint8_t byte) noexcept {
    if (!open_) return outside(parse_status::data_outside_transmission);
    stop_crc_ = this->crc().update(stop_crc_, byte);
    ++data_characters_;
    if (need_destination_) {
      if (byte > max_sba) return fail(parse_status::destination_out_of_range);
      destination_ = byte;
      need_destination_ = false;
      return accept(parse_status::in_progress);
    }
    if (used_ == DataCapacity) return fail(parse_status::overflow);
    if (in_block_) {
      block_crc_ = this->crc().update(block_crc_, byte);
    } else if (segments_ == 0 || stored_[segments_ - 1].block) {
      if (segments_ == SegmentCapacity) return fail(parse_status::overflow);
      stored_[segments_++] = stored_segment{false, 0, used_, 0};
    }
    data_[used_++] = byte;
    ++stored_[segments_ - 1].length;
    return accept(parse_status::in_progress);
  }

  void complete() noexcept {
    open_ = false;
    for (std::size_t i = 0; i < segments_; ++i) {
      const stored_segment& s = stored_[i];
      views_[i] = segment{s.block, s.destination, byte_view(data_ + s.offset, s.length)};
    }
    received_ = transmission{sender_, broadcast_, destination_, span<const segment>(views_, segments_)};
  }

  std::uint8_t data_[DataCapacity] = {};
  stored_segment stored_[SegmentCapacity] = {};
  segment views_[SegmentCapacity] = {};
  transmission received_{};
  std::size_t used_ = 0;
  std::size_t segments_ = 0;
  std::size_t data_characters_ = 0;
  typename Crc::register_type stop_crc_{};   // set by each Start
  typename Crc::register_type block_crc_{};  // set by each Start of block
  std::uint8_t sender_ = 0;
  std::uint8_t destination_ = 0;
  bool broadcast_ = true;
  bool open_ = false;
  bool resync_ = false;
  bool in_block_ = false;
  bool need_destination_ = false;
  std::uint32_t counts_[parse_status_count] = {};
  control_layout layout_{};
};

/// What one bit did in a `transmission_receiver`: the character layer's status and, when that completed a
/// character or reported a framing error, what the transmission parser made of it.
struct [[nodiscard]] bit_result {
  bit_status status = bit_status::nothing_yet;     ///< what the bit completed
  parse_status parse = parse_status::in_progress;  ///< meaningful only when `status` is not nothing_yet
  /// True when the bit completed a character (`status` is `ok`).
  constexpr explicit operator bool() const noexcept { return status == bit_status::ok; }
};

/// Bits in, transmissions out: a `bit_receiver` feeding a `transmission_parser`. While a transmission is
/// open it tells the bit receiver that the next character follows without a gap, so a missing start bit
/// inside a transmission is a framing error (`start_bit_not_0`). A framing error discards the open
/// transmission. Cost: the two parts; O(1) per bit (O(segments) on a Stop). ISR-safe.
template <std::size_t DataCapacity = 256, std::size_t SegmentCapacity = 16, class Crc = crc6_g704>
class transmission_receiver {
 public:
  /// A receiver with the default CRC object (for a static policy, the policy itself).
  transmission_receiver() noexcept = default;
  /// A receiver whose parser checks with `crc` (e.g. a `crc6_runtime` from a profile) and reads control
  /// characters in `layout`.
  explicit transmission_receiver(const Crc& crc, const control_layout& layout = control_layout{}) noexcept
      : parser_(crc, layout) {}

  /// Takes the next bit from the line (1 = idle level); see `bit_result`.
  [[nodiscard]] bit_result push(bool bit) noexcept {
    bit_result result;
    result.status = bits_.push(bit);
    switch (result.status) {
      case bit_status::nothing_yet:
        break;
      case bit_status::ok:
        result.parse = parser_.push(bits_.last());
        if (parser_.in_transmission()) bits_.expect_next_character();
        break;
      case bit_status::start_bit_not_0:
      case bit_status::stop_bit_not_1:
        result.parse = parser_.push_framing_error();
        break;
    }
    return result;
  }

  /// The character layer, with its counters.
  [[nodiscard]] const bit_receiver& bits() const noexcept { return bits_; }
  /// The transmission layer: counters and the last transmission received.
  [[nodiscard]] const transmission_parser<DataCapacity, SegmentCapacity, Crc>& parser() const noexcept {
    return parser_;
  }

 private:
  bit_receiver bits_;
  transmission_parser<DataCapacity, SegmentCapacity, Crc> parser_;
};

}  // namespace trionet::genius
