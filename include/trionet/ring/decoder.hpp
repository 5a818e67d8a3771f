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
// The results (`decode_status`, `frame_error`, `decode_result`) are in ring/decode_result.hpp.
//
// At an end of message the checks run in this order: end-of-message A equals header A (`eom_mismatch`),
// type 1..4 (`unknown_type`), data length for the type (`bad_length`), the fields (`bad_field`), then for
// type 2 the CRC: a CRC error is a message that is otherwise well formed (docs/protocol.md 1.4). Whatever
// the input, the decoder re-synchronises at the next header.
//
// Cost: RAM = the character store (MaxCharacters bytes by default, at least 14) + 10 bytes; per byte O(1),
// no allocation; the per-byte path for message data is one comparison and one store. `push` may be called
// from an ISR. A decoded message's `text` points into the decoder and is valid until the next push.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

#include "trionet/detail/attributes.hpp"
#include "trionet/detail/character_store.hpp"
#include "trionet/detail/crc_holder.hpp"
#include "trionet/ring/bytes.hpp"
#include "trionet/ring/crc.hpp"
#include "trionet/ring/decode_result.hpp"
#include "trionet/ring/message.hpp"
#include "trionet/ring/variable_layout.hpp"
#include "trionet/span.hpp"

namespace trionet::detail {
/// What one byte did to a decoder, in a byte: the `decode_status` in bits 0..2 and, for a frame error, the
/// `frame_error` in bits 3..6. A node handles this and asks for the whole `decode_result` only for a message
/// it takes (`basic_decoder::result`), so the per-byte path never builds one.
using decode_step = std::uint8_t;

/// The status of a step.
constexpr ring::decode_status status_of(decode_step step) noexcept {
  return static_cast<ring::decode_status>(step & 7u);
}
}  // namespace trionet::detail

namespace trionet::ring {

template <class Node, class Decoder, std::size_t ForwardCapacity, std::size_t TransmitCapacity, bool Switchable>
class node;

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
  /// The longest character transfer it accepts.
  static constexpr std::size_t max_characters = MaxCharacters;
  /// The CRC policy of its direct variable transfers (crc.hpp).
  using crc_type = Crc;
  /// The field layout of its direct variable transfers (variable_layout.hpp).
  using layout_type = Layout;

  /// A decoder with a static CRC policy (or a run-time CRC with its default parameters).
  constexpr basic_decoder() = default;
  /// A decoder whose direct variable transfers are checked with `crc` (a CRC chosen at run time).
  constexpr explicit basic_decoder(const Crc& crc) noexcept : detail::crc_holder<Crc>(crc) {}

  /// Feeds one byte. The fast path: a data byte of an open message with room in the store's window.
  [[nodiscard]] TRIONET_ALWAYS_INLINE decode_result push(std::uint8_t byte) noexcept {
    if (TRIONET_LIKELY(is_data(byte)) && at_ != end_) {
      store_.slots()[at_] = byte;
      ++at_;
      return {};
    }
    return result(step_slow(byte));
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
        end_ = at_;
        const detail::decode_step checked = check_variable(p + 1);
        decode_result r;
        r.status = detail::status_of(checked);
        if (r.status == decode_status::frame_error) {
          r.error = static_cast<frame_error>(checked >> 3);
        } else {
          r.msg.type = message_type::variable;
          r.msg.hops = hops_of(*p);
          Layout::read(p + 1, r.msg.vr, r.msg.value);
        }
        p += 16;
        sink(r);
        continue;
      }
      if (state_ == state::in_message) {  // the common case: a run of message data, copied whole
        const std::uint8_t* const run = find_control(p, end);
        store(p, static_cast<std::size_t>(run - p));
        p = run;
        if (p == end) break;
      }
      const detail::decode_step done = step_slow(*p++);
      if (done != 0) sink(result(done));
    }
  }

  /// A header that this decoder does not see (a node forwards it) ends any open message: `interrupted` if a
  /// message was open, else incomplete. Either way the decoder is then between messages.
  [[nodiscard]] decode_result interrupt() noexcept { return result(close(frame_error::interrupted)); }

  /// The line has been idle (docs/protocol.md 1.10): an open message has lost the rest of its bytes, `idle_line`;
  /// else incomplete. Either way the decoder is then between messages (a skipped A = 0 message is over too).
  [[nodiscard]] decode_result line_idle() noexcept { return result(close(frame_error::idle_line)); }

  /// Forgets any open message (e.g. after a link reset), silently.
  void reset() noexcept {
    if (state_ == state::in_message) {
      if (characters()) store_.abort();
      end_ = at_;  // (outside a message end_ == at_ already)
    }
    state_ = state::idle;
  }

  /// True while a message has begun and not ended.
  bool in_message() const noexcept { return state_ == state::in_message; }
  /// True while a message, or a skipped A = 0 message, has begun and not ended.
  bool open() const noexcept { return state_ == state::in_message || state_ == state::skipping; }

 private:
  // ---- for the ring-node core (node.hpp): the decoder of a node's messages, a step at a time ----
  template <class, class, std::size_t, std::size_t, bool>
  friend class node;

  /// Feeds one byte and says what it did in a `decode_step` (see `result` for the details).
  [[nodiscard]] TRIONET_ALWAYS_INLINE detail::decode_step step(std::uint8_t byte) noexcept {
    if (TRIONET_LIKELY(is_data(byte)) && at_ != end_) {
      store_.slots()[at_] = byte;
      ++at_;
      return 0;
    }
    return step_slow(byte);
  }

  /// The whole result of the step just taken (the message, or why it was discarded); `step` must be the
  /// last step's value, and the decoder not fed since. A character message's text is in the store.
  decode_result result(detail::decode_step step) const noexcept {
    decode_result r;
    r.status = detail::status_of(step);
    switch (r.status) {
      case decode_status::incomplete:
        return r;
      case decode_status::frame_error:
        r.error = static_cast<frame_error>(step >> 3);
        return r;
      case decode_status::ok:
      case decode_status::no_room:
      case decode_status::crc_error:
        break;
    }
    r.msg.type = type();
    r.msg.hops = hops_of(header_);
    const std::uint8_t* const payload = store_.slots() + Store::payload_at;
    switch (r.msg.type) {
      case message_type::character:
        if (r.status == decode_status::ok) r.msg.text = store_.text(length());
        break;
      case message_type::variable:
        Layout::read(payload, r.msg.vr, r.msg.value);
        break;
      case message_type::keypad_offset:
        r.msg.offset = payload[0];
        break;
      case message_type::keypad_mode:
        r.msg.mode = payload[0];
        break;
    }
    return r;
  }

  /// The type of the message the last step ended (meaningful for `ok`, `no_room` and `crc_error`).
  message_type type() const noexcept { return static_cast<message_type>(type_of(header_)); }
  /// The data of that message when it is not a character transfer (14 bytes for a variable transfer).
  const std::uint8_t* payload() const noexcept { return store_.slots() + Store::payload_at; }

  /// `interrupt` or `line_idle` (`reason`) as a step: a frame error with that reason if a message was open.
  detail::decode_step close(frame_error reason) noexcept {
    const bool was_open = state_ == state::in_message;
    reset();
    return was_open ? error(reason) : detail::decode_step{0};
  }

  /// True between messages, with nothing to skip or report.
  bool idle() const noexcept { return state_ == state::idle; }

  /// The character store.
  Store& store() noexcept { return store_; }
  /// The character store, read-only.
  const Store& store() const noexcept { return store_; }

  // ---- the decoder itself ----

  enum class state : std::uint8_t { idle, stray, in_message, skipping };

  static constexpr detail::decode_step error(frame_error reason) noexcept {
    return static_cast<detail::decode_step>(static_cast<unsigned>(decode_status::frame_error) |
                                    (static_cast<unsigned>(reason) << 3));
  }
  static constexpr detail::decode_step status(decode_status s) noexcept {
    return static_cast<detail::decode_step>(s);
  }

  bool characters() const noexcept { return type_of(header_) == 1; }
  bool no_room() const noexcept { return (header_ & 0x80u) == 0; }

  // Data bytes of the open message so far (saturating one past its limit).
  std::size_t length() const noexcept { return static_cast<std::uint16_t>(base_ + at_); }
  void set_length(std::size_t length) noexcept { base_ = static_cast<std::uint16_t>(length - at_); }

  // Everything but a data byte with room in the window.
  TRIONET_NOINLINE detail::decode_step step_slow(std::uint8_t byte) noexcept {
    if (is_data(byte)) {
      if (state_ == state::in_message) {  // the window is used up
        if (next_window()) {
          store_.slots()[at_] = byte;
          ++at_;
        } else {
          count(1);
        }
        return 0;
      }
      if (state_ != state::idle) return 0;  // stray data reported once per run; a skipped message
      state_ = state::stray;
      return error(frame_error::stray_data);
    }
    end_ = at_;
    const state was = state_;
    if (type_of(byte) == 0) {  // end of message
      state_ = state::idle;
      if (was == state::in_message) return finish(hops_of(byte));
      return was == state::skipping ? detail::decode_step{0} : error(frame_error::stray_eom);
    }
    if (was == state::in_message && characters()) store_.abort();
    const std::uint8_t hops = hops_of(byte);
    if (hops == 0) {
      state_ = state::skipping;
      return error(was == state::in_message ? frame_error::interrupted : frame_error::zero_hops);
    }
    state_ = state::in_message;
    header_ = byte;  // bit 7 set: room so far
    if (characters()) {
      open_window(store_.begin(), 0);
    } else {
      at_ = static_cast<std::uint16_t>(Store::payload_at);
      end_ = static_cast<std::uint16_t>(Store::payload_at + variable_data_length);
      set_length(0);
    }
    return was == state::in_message ? error(frame_error::interrupted) : detail::decode_step{0};
  }

  // Characters go to the store's windows (up to MaxCharacters), other payloads to its payload slots (up to
  // 14 bytes); past that the decoder only counts, so that the length never wraps. The same as the bytes one
  // at a time, with one copy per window.
  void store(const std::uint8_t* data, std::size_t n) noexcept {
    for (;;) {
      const std::size_t room = std::size_t{end_} - at_;
      const std::size_t k = n < room ? n : room;
      std::memcpy(store_.slots() + at_, data, k);
      at_ = static_cast<std::uint16_t>(at_ + k);
      data += k;
      n -= k;
      if (n == 0) return;
      if (!next_window()) return count(n);
    }
  }

  // The window is used up (at_ == end_): opens the next one if the message may store more characters (true);
  // notes it when the store has no more room.
  bool next_window() noexcept {
    const std::size_t so_far = length();
    if (!characters() || no_room() || so_far >= MaxCharacters) return false;
    const detail::store_window next = store_.next(so_far);
    if (next.first == next.end) {
      header_ = static_cast<std::uint8_t>(header_ & 0x7Fu);  // no room
      return false;
    }
    open_window(next, so_far);
    return true;
  }

  // `n` more data bytes that are not stored: counted, saturating one past the longest legal length.
  void count(std::size_t n) noexcept {
    const std::size_t limit = characters() ? MaxCharacters : variable_data_length;
    const std::size_t counted = length() + n;
    set_length(counted > limit ? limit + 1 : counted);
  }

  // The store's window `w` takes the characters from the `so_far`th on.
  void open_window(detail::store_window w, std::size_t so_far) noexcept {
    at_ = w.first;
    const std::size_t most = w.first + (MaxCharacters - so_far);
    end_ = static_cast<std::uint16_t>(w.end < most ? w.end : most);
    set_length(so_far);
  }

  // The end of message of the open message: its checks, in the order of the file comment.
  detail::decode_step finish(std::uint8_t end_hops) noexcept {
    const detail::decode_step checked = check(end_hops);
    if (characters()) {
      if (checked == status(decode_status::ok)) {
        (void)store_.commit(length());
      } else {
        store_.abort();
      }
    }
    return checked;
  }

  detail::decode_step check(std::uint8_t end_hops) const noexcept {
    if (end_hops != hops_of(header_)) return error(frame_error::eom_mismatch);
    const std::size_t n = length();
    const std::uint8_t* const payload = store_.slots() + Store::payload_at;
    switch (type_of(header_)) {
      case 1:
        if (n == 0 || n > MaxCharacters) return error(frame_error::bad_length);
        return status(no_room() ? decode_status::no_room : decode_status::ok);
      case 2:
        if (n != variable_data_length) return error(frame_error::bad_length);
        return check_variable(payload);
      case 3:
        if (n != 1) return error(frame_error::bad_length);
        return valid_hops(payload[0]) ? status(decode_status::ok) : error(frame_error::bad_field);
      case 4:
        if (n != 1) return error(frame_error::bad_length);
        return payload[0] == keypad_mode_key_on || payload[0] == keypad_mode_key_on_off
                   ? status(decode_status::ok)
                   : error(frame_error::bad_field);
      default:
        return error(frame_error::unknown_type);
    }
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
  detail::decode_step check_variable(const std::uint8_t* data) const noexcept {
    if ((data[Layout::top_group] & 0x7E) != 0) return error(frame_error::bad_field);
    std::uint8_t scratch[variable_crc_length];
    const std::uint16_t crc = crc_of<variable_crc_length>(this->crc(), Layout::crc_bytes(data, scratch));
    if (crc_wire_bits(crc) != static_cast<std::uint16_t>(data[12] | (data[13] << 8))) {
      return status(decode_status::crc_error);
    }
    return status(decode_status::ok);
  }

  std::uint16_t at_ = 0;   // the slot the next data byte goes to
  std::uint16_t end_ = 0;  // the fast path writes while at_ != end_ (equal outside a message)
  std::uint16_t base_ = 0;  // length() - at_ (mod 2^16)
  state state_ = state::idle;
  // The open message's header: its A and type, and bit 7 cleared once a character did not fit (the message
  // is then counted, not stored).
  std::uint8_t header_ = 0;
  Store store_;
};

/// The streaming decoder with its own character buffer of MaxCharacters.
template <std::size_t MaxCharacters = default_max_characters, class Crc = crc16_ccitt_false,
          class Layout = default_variable_layout>
using decoder = basic_decoder<detail::character_buffer<MaxCharacters>, MaxCharacters, Crc, Layout>;

}  // namespace trionet::ring
