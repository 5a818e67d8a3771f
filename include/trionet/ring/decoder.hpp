// The streaming ring decoder: validates messages at their destination (docs/protocol.md 1.4).
//
// The caller owns the decoder and feeds it bytes; it never blocks, allocates or reads a clock.
//
//   byte in      state            result
//   header A>0   any              begins a message; `interrupted` if one was open, else incomplete
//   header A=0   any              `interrupted` if a message was open, else `zero_hops`; then skips to
//                                  that message's end of message or the next header
//   data         in a message     stored (up to the capacity; a longer message is counted, not stored)
//   data         outside          `stray_data` once per run of such bytes
//   end of msg   in a message     the message, a frame error, or a CRC error
//   end of msg   outside          `stray_eom` (none when it closes a skipped A=0 message)
//   line idle    in a message     `idle_line` (docs/protocol.md 1.10: the rest of the message is lost)
//
// At an end of message the checks run in this order: end-of-message A equals header A (`eom_mismatch`),
// type 1..4 (`unknown_type`), data length for the type (`bad_length`), the fields (`bad_field`), then for
// type 2 the CRC: a CRC error is a message that is otherwise well formed (docs/protocol.md 1.4). Whatever
// the input, the decoder re-synchronises at the next header.
//
// Cost: RAM = the character store (MaxCharacters bytes by default) + 14 bytes + 3 words; per byte O(1),
// no allocation. `push` may be called from an ISR. A decoded message's `text` points into the decoder and is
// valid until the next push.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

#include "trionet/attributes.hpp"
#include "trionet/ring/bytes.hpp"
#include "trionet/ring/crc.hpp"
#include "trionet/ring/message.hpp"
#include "trionet/ring/variable_layout.hpp"
#include "trionet/span.hpp"

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

/// Why a frame was discarded (`none` unless the status is `frame_error`).
enum class frame_error : std::uint8_t {
  none,
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

struct [[nodiscard]] decode_result {
  decode_status status = decode_status::incomplete;
  frame_error error = frame_error::none;
  message msg;  ///< meaningful for `ok`; `hops` and `vr` also for `crc_error`
  constexpr explicit operator bool() const noexcept { return status == decode_status::ok; }
};

/// The default character store: a plain array of N characters, so a decoded message's `text` is contiguous.
///
/// A character store receives the characters of a character transfer while it arrives and keeps them only
/// if the message turns out valid:
///   void begin();                  // a character transfer begins
///   bool put(std::uint8_t c);      // one more character; false if there is no room
///   std::size_t put(const std::uint8_t* c, std::size_t n);  // many: how many fitted (a prefix)
///   byte_view commit();            // the message is valid: keep it (view of it, or empty if not contiguous)
///   void abort();                  // the message is discarded: forget what `put` took since `begin`
/// A node can stage characters straight into its receive buffer this way, so no message is held twice.
template <std::size_t N>
class character_buffer {
 public:
  void begin() noexcept { length_ = 0; }
  bool put(std::uint8_t c) noexcept {
    if (length_ == N) return false;
    data_[length_++] = c;
    return true;
  }
  std::size_t put(const std::uint8_t* c, std::size_t n) noexcept {
    if (n > N - length_) n = N - length_;
    std::memcpy(data_ + length_, c, n);
    length_ += n;
    return n;
  }
  byte_view commit() noexcept { return byte_view(data_, length_); }
  void abort() noexcept { length_ = 0; }

 private:
  std::uint8_t data_[N] = {};
  std::size_t length_ = 0;
};

/// The decoder with its character store as a template parameter (see `decoder` for the common case).
/// `Crc` and `Layout` are the direct variable transfer's CRC (crc.hpp) and field layout
/// (variable_layout.hpp). A static CRC policy costs no RAM; a CRC chosen at run time (`crc16_runtime`) is
/// passed to the constructor and held by the decoder.
template <class Store, std::size_t MaxCharacters = default_max_characters, class Crc = crc16_ccitt_false,
          class Layout = default_variable_layout>
class basic_decoder : private detail::crc_holder<Crc> {
  static_assert(MaxCharacters >= 1 && MaxCharacters < 65535,
                "a character transfer holds 1..65534 characters");

 public:
  static constexpr std::size_t max_characters = MaxCharacters;

  constexpr basic_decoder() = default;
  constexpr explicit basic_decoder(const Crc& crc) noexcept : detail::crc_holder<Crc>(crc) {}

  /// Feeds one byte.
  [[nodiscard]] decode_result push(std::uint8_t byte) noexcept {
    if (is_data(byte)) {
      switch (state_) {
        case state::in_message:
          store(byte);
          return {};
        case state::idle:
          state_ = state::stray;
          return error(frame_error::stray_data);
        case state::stray:
        case state::skipping:
          return {};
      }
      return {};
    }
    if (type_of(byte) == 0) {  // end of message
      const state was = state_;
      state_ = state::idle;
      if (was == state::in_message) return finish(hops_of(byte));
      if (was == state::skipping) return {};
      return error(frame_error::stray_eom);
    }
    const bool was_open = state_ == state::in_message;
    if (was_open && type_ == 1) store_.abort();
    const std::uint8_t hops = hops_of(byte);
    if (hops == 0) {
      state_ = state::skipping;
      return error(was_open ? frame_error::interrupted : frame_error::zero_hops);
    }
    state_ = state::in_message;
    hops_ = hops;
    type_ = type_of(byte);
    length_ = 0;
    no_room_ = false;
    if (type_ == 1) store_.begin();
    return was_open ? error(frame_error::interrupted) : decode_result{};
  }

  /// Feeds many bytes; calls `sink(const decode_result&)` for every result that is not `incomplete`, in
  /// order: exactly the results that pushing the bytes one at a time would give.
  template <class Sink>
  void push(byte_view bytes, Sink&& sink) noexcept(noexcept(sink(decode_result{}))) {
    const std::uint8_t* p = bytes.begin();
    const std::uint8_t* const end = bytes.end();
    while (p != end) {
      if (state_ != state::in_message && end - p >= 16 && is_whole_variable_transfer(p)) {
        // A whole direct variable transfer in the buffer: checked in place, as the bytes one by one would be.
        state_ = state::idle;
        const decode_result result = check_variable(hops_of(*p), p + 1);
        p += 16;
        sink(result);
        continue;
      }
      if (state_ == state::in_message) {  // the common case: a run of message data, copied whole
        const std::uint8_t* const run = find_control(p, end);
        store(p, static_cast<std::size_t>(run - p));
        p = run;
        if (p == end) break;
      }
      const decode_result result = push(*p++);
      if (result.status != decode_status::incomplete) sink(result);
    }
  }

  /// A header that this decoder does not see (a node forwards it) ends any open message: `interrupted` if a
  /// message was open, else incomplete. Either way the decoder is then between messages.
  [[nodiscard]] decode_result interrupt() noexcept {
    const bool was_open = state_ == state::in_message;
    state_ = state::idle;
    if (!was_open) return {};
    if (type_ == 1) store_.abort();
    return error(frame_error::interrupted);
  }

  /// The line has been idle (docs/protocol.md 1.10): an open message has lost the rest of its bytes, `idle_line`;
  /// else incomplete. Either way the decoder is then between messages (a skipped A = 0 message is over too).
  [[nodiscard]] decode_result line_idle() noexcept {
    const bool was_open = state_ == state::in_message;
    state_ = state::idle;
    if (!was_open) return {};
    if (type_ == 1) store_.abort();
    return error(frame_error::idle_line);
  }

  /// Forgets any open message (e.g. after a link reset), silently.
  void reset() noexcept { (void)interrupt(); }

  /// True while a message has begun and not ended.
  bool in_message() const noexcept { return state_ == state::in_message; }
  /// True while a message, or a skipped A = 0 message, has begun and not ended.
  bool open() const noexcept { return state_ == state::in_message || state_ == state::skipping; }

  Store& store() noexcept { return store_; }
  const Store& store() const noexcept { return store_; }

 private:
  enum class state : std::uint8_t { idle, stray, in_message, skipping };

  // Characters go to the store (up to MaxCharacters), other payloads to `payload_` (up to 14 bytes); past
  // that the decoder only notes that the message is too long, so `length_` never wraps.
  void store(std::uint8_t byte) noexcept {
    if (type_ == 1) {
      if (length_ < MaxCharacters) {
        if (!no_room_ && !store_.put(byte)) no_room_ = true;
        ++length_;
      } else {
        length_ = MaxCharacters + 1;
      }
    } else if (length_ < variable_data_length) {
      payload_[length_++] = byte;
    } else {
      length_ = variable_data_length + 1;
    }
  }

  // The same as `store(byte)` for each of `n` data bytes, with one copy.
  void store(const std::uint8_t* data, std::size_t n) noexcept {
    const std::size_t limit = type_ == 1 ? MaxCharacters : variable_data_length;
    const std::size_t room = length_ < limit ? limit - length_ : 0;
    const std::size_t take = n < room ? n : room;
    if (type_ == 1) {
      if (!no_room_ && take != 0 && store_.put(data, take) != take) no_room_ = true;
    } else if (take != 0) {
      std::memcpy(payload_ + length_, data, take);
    }
    length_ = static_cast<std::uint16_t>(n > room ? limit + 1 : length_ + take);
  }

  // Out of line: one copy of the result set-up instead of one per error (smaller firmware).
  TRIONET_NOINLINE static decode_result error(frame_error reason) noexcept {
    decode_result result;
    result.status = decode_status::frame_error;
    result.error = reason;
    return result;
  }

  decode_result finish(std::uint8_t end_hops) noexcept {
    const decode_result result = check(end_hops);
    if (type_ == 1) {
      if (result.status == decode_status::ok) {
        decode_result committed = result;
        committed.msg.text = store_.commit();
        return committed;
      }
      store_.abort();
    }
    return result;
  }

  decode_result check(std::uint8_t end_hops) const noexcept {
    if (end_hops != hops_) return error(frame_error::eom_mismatch);
    if (type_ > 4) return error(frame_error::unknown_type);
    decode_result result;
    result.status = decode_status::ok;
    result.msg.type = static_cast<message_type>(type_);
    result.msg.hops = hops_;
    switch (result.msg.type) {
      case message_type::character:
        if (length_ == 0 || length_ > MaxCharacters) return error(frame_error::bad_length);
        if (no_room_) result.status = decode_status::no_room;
        return result;
      case message_type::variable:
        if (length_ != variable_data_length) return error(frame_error::bad_length);
        return check_variable(hops_, payload_);
      case message_type::keypad_offset:
        if (length_ != 1) return error(frame_error::bad_length);
        if (!valid_hops(payload_[0])) return error(frame_error::bad_field);
        result.msg.offset = payload_[0];
        return result;
      case message_type::keypad_mode:
        if (length_ != 1) return error(frame_error::bad_length);
        if (payload_[0] != keypad_mode_key_on && payload_[0] != keypad_mode_key_on_off) {
          return error(frame_error::bad_field);
        }
        result.msg.mode = payload_[0];
        return result;
    }
    return error(frame_error::unknown_type);
  }

  // Header A = hops (not 0), type 2; 14 data bytes; end of message with the same A.
  static bool is_whole_variable_transfer(const std::uint8_t* p) noexcept {
    if (type_of(p[0]) != 2 || p[15] != make_end_of_message(hops_of(p[0])) || hops_of(p[0]) == 0 ||
        is_data(p[0])) {
      return false;
    }
    return find_control(p + 1, p + 15) == p + 15;
  }

  // The checks of a direct variable transfer whose 14 data bytes are well framed: the value's top group (X9 by
  // default) must have bits 6..1 zero whatever the CRC; a CRC error is an otherwise well-formed message.
  decode_result check_variable(std::uint8_t hops, const std::uint8_t* data) const noexcept {
    decode_result result;
    result.status = decode_status::ok;
    result.msg.type = message_type::variable;
    result.msg.hops = hops;
    Layout::read(data, result.msg.vr, result.msg.value);
    std::uint8_t scratch[variable_crc_length];
    const std::uint16_t crc = crc_of<variable_crc_length>(this->crc(), Layout::crc_bytes(data, scratch));
    if (crc_wire_bits(crc) != static_cast<std::uint16_t>(data[12] | (data[13] << 8))) {
      result.status = decode_status::crc_error;  // if it is otherwise well formed
    }
    if ((data[Layout::top_group] & 0x7E) != 0) return error(frame_error::bad_field);
    return result;
  }

  state state_ = state::idle;
  std::uint8_t hops_ = 0;
  std::uint8_t type_ = 0;
  bool no_room_ = false;
  std::uint16_t length_ = 0;  // data bytes so far, saturating one past the limit
  std::uint8_t payload_[variable_data_length] = {};
  Store store_;
};

/// The streaming decoder with its own character buffer of MaxCharacters.
template <std::size_t MaxCharacters = default_max_characters, class Crc = crc16_ccitt_false,
          class Layout = default_variable_layout>
using decoder = basic_decoder<character_buffer<MaxCharacters>, MaxCharacters, Crc, Layout>;

}  // namespace trionet::ring
