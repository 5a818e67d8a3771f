// GE Genius bus characters: the 11-bit serial format (docs/protocol.md 3.1) and a bit-stream receiver.
//
// One character on the wire, first bit on the left, characters back to back with no gap:
//
//   wire bit:   0       1      2    3    4    5    6    7    8    9     10
//            +-----+---------+----+----+----+----+----+----+----+----+------+
//            |start| control | d0 | d1 | d2 | d3 | d4 | d5 | d6 | d7 | stop |
//            |  0  | 1 = ctl |  data byte, least significant bit first | 1    |
//            +-----+---------+----+----+----+----+----+----+----+----+------+
//
// Bit numbering in a `std::uint16_t` word: bit i of the word is wire bit i. So the start bit is bit 0,
// the control bit is bit 1, data bit k is bit k + 2 (the byte sits in bits 9..2), the stop bit is bit 10,
// and bits 15..11 are 0. Shifting the word out least significant bit first reproduces the wire order.
// Example: data character 0xA5 = 0x400 | 0xA5 << 2 = 0x694; control character 0x04 = 0x412.
#pragma once

#include <cstdint>

namespace trionet::genius {

/// One Genius character: a data byte and the control flag (true: control character, false: data).
/// Cost: two bytes. A plain value; any context may use it.
struct character {
  std::uint8_t byte = 0;  ///< the 8 data bits
  bool control = false;   ///< the control bit

  /// Same byte and same control flag.
  friend constexpr bool operator==(character a, character b) noexcept {
    return a.byte == b.byte && a.control == b.control;
  }
  /// Not `a == b`.
  friend constexpr bool operator!=(character a, character b) noexcept { return !(a == b); }
};

/// A data character carrying `byte`.
[[nodiscard]] constexpr character data_character(std::uint8_t byte) noexcept {
  return character{byte, false};
}
/// A control character carrying `byte` (see transmission.hpp for the control layouts).
[[nodiscard]] constexpr character control_character(std::uint8_t byte) noexcept {
  return character{byte, true};
}

constexpr unsigned character_bits = 11;            ///< bits per character on the wire
constexpr std::uint16_t start_bit_mask = 0x001;    ///< wire bit 0, always 0
constexpr std::uint16_t control_bit_mask = 0x002;  ///< wire bit 1, 1 = control character
constexpr std::uint16_t stop_bit_mask = 0x400;     ///< wire bit 10, always 1
constexpr std::uint16_t word_mask = 0x7ff;         ///< the 11 bits a word may use

/// The 11-bit word of `c` (numbering above). Cost: a few instructions; ISR-safe.
[[nodiscard]] constexpr std::uint16_t encode_character(character c) noexcept {
  return static_cast<std::uint16_t>(stop_bit_mask | (static_cast<unsigned>(c.byte) << 2u) |
                                    (c.control ? control_bit_mask : 0u));
}

// A character as one 9-bit UART word (docs/protocol.md 3.4), what a device's UART sends and receives: bit 0
// is the control bit, bits 8..1 the data byte. A UART sends bit 0 first, between its own start and stop
// bits, so the wire order is start, control, data least significant bit first, stop, as drawn above:
//
//   UART word bit:  8   7   6   5   4   3   2   1   0
//                   d7  d6  d5  d4  d3  d2  d1  d0  control
//
// The 11-bit word above is the UART word shifted up by one, with the stop bit added.

constexpr std::uint16_t uart_word_mask = 0x1ff;  ///< the 9 bits a UART word uses

/// `c` as a 9-bit UART word. Cost: a few instructions; ISR-safe.
[[nodiscard]] constexpr std::uint16_t to_uart_word(character c) noexcept {
  return static_cast<std::uint16_t>((static_cast<unsigned>(c.byte) << 1u) | (c.control ? 1u : 0u));
}
/// The character of a 9-bit UART word (bits above bit 8 are ignored). Cost: a few instructions; ISR-safe.
[[nodiscard]] constexpr character from_uart_word(std::uint16_t word) noexcept {
  return character{static_cast<std::uint8_t>((word >> 1u) & 0xffu), (word & 1u) != 0};
}
/// The 11-bit wire word (numbering above) of a 9-bit UART word: start 0, the UART word, stop 1.
[[nodiscard]] constexpr std::uint16_t wire_word(std::uint16_t uart_word) noexcept {
  return static_cast<std::uint16_t>(stop_bit_mask | ((uart_word & uart_word_mask) << 1u));
}

/// What a received 11-bit word or bit sequence turned out to be.
enum class character_status : std::uint8_t {
  ok,               ///< a well-formed character
  start_bit_not_0,  ///< framing error: wire bit 0 was 1 (reported first when both bits are wrong)
  stop_bit_not_1,   ///< framing error: wire bit 10 was 0
  not_11_bits,      ///< the word has bits above bit 10 set: not an 11-bit word at all
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(character_status value) noexcept {
  switch (value) {
    case character_status::ok:
      return "ok";
    case character_status::start_bit_not_0:
      return "start_bit_not_0";
    case character_status::stop_bit_not_1:
      return "stop_bit_not_1";
    case character_status::not_11_bits:
      return "not_11_bits";
  }
  return "unknown";
}

/// The result of decoding one word: `value` is meaningful only when `status` is ok.
struct [[nodiscard]] character_result {
  character_status status = character_status::ok;  ///< `ok`, or what is wrong with the word
  character value{};                               ///< the character
  /// True when `status` is `ok`.
  constexpr explicit operator bool() const noexcept { return status == character_status::ok; }
};

/// Decodes an 11-bit word (numbering above), classifying framing errors. Total: any word is classified.
/// Cost: a few instructions; ISR-safe.
[[nodiscard]] constexpr character_result decode_character(std::uint16_t word) noexcept {
  character_result result;
  if ((word & ~word_mask) != 0) {
    result.status = character_status::not_11_bits;
  } else if ((word & start_bit_mask) != 0) {
    result.status = character_status::start_bit_not_0;
  } else if ((word & stop_bit_mask) == 0) {
    result.status = character_status::stop_bit_not_1;
  }
  result.value.byte = static_cast<std::uint8_t>((word >> 2) & 0xffu);
  result.value.control = (word & control_bit_mask) != 0;
  return result;
}

/// What one bit pushed into a `bit_receiver` completed.
/// As for every streaming push, "nothing yet" is 0 and `ok` follows.
enum class bit_status : std::uint8_t {
  nothing_yet,      ///< no character finished with this bit (idle line, or inside a character)
  ok,               ///< a character finished: see `bit_receiver::last()`
  start_bit_not_0,  ///< framing error: a start bit was due (see `expect_next_character`) but the line was 1
  stop_bit_not_1,   ///< framing error: the 11th bit of a character was 0
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(bit_status value) noexcept {
  switch (value) {
    case bit_status::nothing_yet:
      return "nothing_yet";
    case bit_status::ok:
      return "ok";
    case bit_status::start_bit_not_0:
      return "start_bit_not_0";
    case bit_status::stop_bit_not_1:
      return "stop_bit_not_1";
  }
  return "unknown";
}

/// Receives a Genius bit stream one bit at a time (one call per bit period, the line level as sampled).
///
/// Line model: the idle line is 1, so when the receiver is idle a 0 bit is a start bit (a 1->0
/// transition from the idle level, also right after reset). The next 10 bits are the control bit, the 8
/// data bits and the stop bit. A stop bit of 0 is a framing error; the receiver then waits for the line to
/// return to 1 and re-synchronises on the next 1->0 transition.
///
/// Start-bit errors: on an idle line a 1 is just idle, so a missing start bit can only be seen when a
/// character is known to be due. Inside a transmission characters follow each other with no gap, so the
/// caller that knows a transmission is still open (`transmission_receiver` does) calls
/// `expect_next_character()` after a character: the very next bit must then be 0, and a 1 is reported as
/// `start_bit_not_0`. The line is then at 1, so the next 0 is again a start bit.
///
/// Cost: 20 bytes (state and three counters); O(1) per bit; no allocation. ISR-safe (one object per
/// line, not shared between contexts without the caller's locking).
class bit_receiver {
 public:
  /// Feeds the next bit (true = 1). See `bit_status`.
  [[nodiscard]] bit_status push(bool bit) noexcept {
    switch (state_) {
      case state::idle:
        if (!bit) begin_character();
        return bit_status::nothing_yet;
      case state::start_due:
        if (!bit) {
          begin_character();
          return bit_status::nothing_yet;
        }
        state_ = state::idle;
        ++start_bit_errors_;
        return bit_status::start_bit_not_0;
      case state::receiving:
        return receive(bit);
      case state::resync:
        if (bit) state_ = state::idle;
        return bit_status::nothing_yet;
    }
    return bit_status::nothing_yet;
  }

  /// Declares that the next bit is the start bit of a character that follows the last one without a gap.
  /// Has effect only between characters (after `push` returned `ok`); otherwise ignored.
  void expect_next_character() noexcept {
    if (state_ == state::idle) state_ = state::start_due;
  }

  /// The character completed by the last `push` that returned `ok`.
  [[nodiscard]] character last() const noexcept { return last_; }
  /// True while a character is being received (a start bit was seen, the stop bit not yet).
  [[nodiscard]] bool receiving() const noexcept { return state_ == state::receiving; }

  /// Characters received whole (counters only grow, and wrap).
  [[nodiscard]] std::uint32_t characters() const noexcept { return characters_; }
  /// Framing errors `start_bit_not_0`.
  [[nodiscard]] std::uint32_t start_bit_errors() const noexcept { return start_bit_errors_; }
  /// Framing errors `stop_bit_not_1`.
  [[nodiscard]] std::uint32_t stop_bit_errors() const noexcept { return stop_bit_errors_; }

  /// Back to an idle line; counters are kept.
  void reset() noexcept {
    state_ = state::idle;
    shift_ = 0;
    count_ = 0;
  }
  /// Clears the counters.
  void clear_counters() noexcept { characters_ = start_bit_errors_ = stop_bit_errors_ = 0; }

 private:
  enum class state : std::uint8_t { idle, start_due, receiving, resync };

  void begin_character() noexcept {
    state_ = state::receiving;
    shift_ = 0;  // wire bit 0 (the start bit) is 0
    count_ = 1;
  }

  bit_status receive(bool bit) noexcept {
    if (bit) shift_ = static_cast<std::uint16_t>(shift_ | (1u << count_));
    ++count_;
    if (count_ < character_bits) return bit_status::nothing_yet;
    const character_result result = decode_character(shift_);
    if (result.status != character_status::ok) {
      // Only the stop bit can be wrong here: the start bit was seen as 0 and the word has 11 bits.
      state_ = state::resync;
      ++stop_bit_errors_;
      return bit_status::stop_bit_not_1;
    }
    state_ = state::idle;
    last_ = result.value;
    ++characters_;
    return bit_status::ok;
  }

  state state_ = state::idle;
  std::uint8_t count_ = 0;
  std::uint16_t shift_ = 0;
  character last_{};
  std::uint32_t characters_ = 0;
  std::uint32_t start_bit_errors_ = 0;
  std::uint32_t stop_bit_errors_ = 0;
};

}  // namespace trionet::genius
