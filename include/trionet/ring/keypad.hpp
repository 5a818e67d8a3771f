// A membrane keypad on the fibre ring (docs/protocol.md 1.7-1.9).
//
//   local mode (at power-up)          network mode
//   - handles only a keypad offset    - forwards like any node
//     addressed to itself (A = 1)     - each key press: a one-character message to `offset` hops along
//   - drops and counts everything     - keypad mode 0: key ON only; 127: key ON and key OFF
//     else to or through it           - character messages drive the 2 x 20 display
//   - never transmits                 - direct variable transfers are ignored (counted)
//
// The link, the idle line, NETSTAT and the bulk paths are the ring-node core's (node.hpp).
// Cost (defaults): RAM = forward buffer 16 + transmit queue 16 + decoder 256 + display 45 + state and counters
// = about 400 bytes on a 32-bit core.
// Sides (node.hpp): `receive`/`transmit`/`line_idle` are the link side (the UART interrupt), and so is the
// display (a message for the keypad writes it: read it there too); `press`/`release` are the program side
// (the key-scan context); `network_mode`, `offset`, `mode` and the counters may be read on either side.
#pragma once

#include <cstddef>
#include <cstdint>

#include "trionet/ring/bytes.hpp"
#include "trionet/ring/crc.hpp"
#include "trionet/ring/decoder.hpp"
#include "trionet/ring/keypad_codes.hpp"
#include "trionet/ring/keypad_display.hpp"
#include "trionet/ring/message.hpp"
#include "trionet/ring/node.hpp"
#include "trionet/detail/single_writer.hpp"

namespace trionet::ring {

/// What became of a key press or release.
enum class key_status : std::uint8_t {
  ok,               ///< queued for the node `offset` hops along
  nothing_to_send,  ///< a key OFF in keypad mode 0: nothing to send
  local_mode,       ///< the keypad has no offset yet: nothing is sent (counted)
  queue_full,       ///< no room in the transmit queue (counted)
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(key_status status) noexcept {
  switch (status) {
    case key_status::ok:
      return "ok";
    case key_status::nothing_to_send:
      return "nothing_to_send";
    case key_status::local_mode:
      return "local_mode";
    case key_status::queue_full:
      return "queue_full";
  }
  return "unknown";
}

/// The keypad's configurable behaviour (docs/protocol.md 1.7-1.8 defaults).
struct keypad_config {
  /// The code each key sends (docs/protocol.md 1.8).
  const keypad_codes* codes = &default_keypad_codes;
  /// The code sent when a key is released, from the code it sent when pressed.
  std::uint8_t (*key_off_code)(std::uint8_t on) noexcept = default_key_off_code;
  /// What the display does with control characters (docs/protocol.md 1.9).
  display_model display{};
};

/// Counters of a keypad, as read at one moment; they only ever grow. The wire errors (frame, CRC) wrap at 2^32;
/// the others, traffic and keys, at 2^16 (docs/design.md, "Results and counters").
struct keypad_counters {
  std::uint32_t frame_errors = 0;           ///< frame errors of docs/protocol.md 1.4 and 1.10 (NETSTAT bit 3)
  std::uint32_t crc_errors = 0;             ///< direct variable transfers that failed their CRC (NETSTAT bit 2)
  std::uint32_t dropped_in_local_mode = 0;  ///< messages to this keypad dropped before its offset arrived (2^16)
  std::uint32_t display_messages = 0;       ///< character transfers shown on the display (2^16)
  std::uint32_t variables_ignored = 0;      ///< direct variable transfers (ignored by keypads) (2^16)
  std::uint32_t keys_sent = 0;              ///< key characters queued (2^16)
  std::uint32_t keys_lost = 0;              ///< key presses not sent: local mode or queue full (2^16)
};

/// A membrane keypad on the ring (see the file comment): the ring-node core (node.hpp) with the keypad's
/// messages, keys and display. `Crc` and `Layout` are the direct variable transfer's CRC policy and field
/// layout (crc.hpp, variable_layout.hpp).
template <std::size_t ForwardCapacity = 16, std::size_t TransmitCapacity = 16,
          std::size_t MaxCharacters = default_max_characters, class Crc = crc16_ccitt_false,
          class Layout = default_variable_layout>
class keypad final : public node<keypad<ForwardCapacity, TransmitCapacity, MaxCharacters, Crc, Layout>,
                                  decoder<MaxCharacters, Crc, Layout>, ForwardCapacity, TransmitCapacity, true> {
  using core = node<keypad, decoder<MaxCharacters, Crc, Layout>, ForwardCapacity, TransmitCapacity, true>;
  friend core;

 public:
  /// A keypad in local mode (not forwarding) until its keypad offset arrives (docs/protocol.md 1.7).
  explicit keypad(const keypad_config& config = keypad_config{}) noexcept
      : config_(config), display_(config.display) {
    this->set_forwarding(false);
  }
  /// The same with a CRC object (`crc16_runtime`: the CRC of a profile, chosen at run time) for the direct
  /// variable transfers it checks.
  keypad(const keypad_config& config, const Crc& crc) noexcept
      : core(crc), config_(config), display_(config.display) {
    this->set_forwarding(false);
  }

  using core::receive;
  using core::transmit;

  // ---- keys (program side) ----

  /// Program side: a key went down: its character goes to the node `offset` hops along.
  [[nodiscard]] key_status press(key k) noexcept { return send_key((*config_.codes)[k]); }

  /// Program side: a key came up: its key OFF character is sent in keypad mode 127.
  [[nodiscard]] key_status release(key k) noexcept {
    if (mode_.load() != keypad_mode_key_on_off)
      return network_mode() ? key_status::nothing_to_send : key_status::local_mode;
    return send_key(config_.key_off_code((*config_.codes)[k]));
  }

  // ---- state ----

  /// Either side: true once a keypad offset has arrived.
  bool network_mode() const noexcept { return offset_.load() != 0; }
  /// Either side: hops to where key presses go (0 in local mode).
  std::uint8_t offset() const noexcept { return offset_.load(); }
  /// Either side: keypad mode, 0 (key ON only) or 127 (key ON and key OFF).
  std::uint8_t mode() const noexcept { return mode_.load(); }
  /// Link side: the 2 x 20 display.
  const keypad_display& display() const noexcept { return display_; }

  /// Either side: the counters now (each read whole; not all at one instant), since construction or
  /// `clear_counters`.
  keypad_counters counters() const noexcept {
    keypad_counters c;
    c.keys_sent = keys_sent_.load();
    c.keys_lost = keys_lost_.load();
    if (this->counters_clearing()) return c;  // the link side's: 0 until it clears them
    c.frame_errors = this->frame_errors();
    c.crc_errors = this->crc_errors();
    c.dropped_in_local_mode = dropped_in_local_mode_.load();
    c.display_messages = display_messages_.load();
    c.variables_ignored = variables_ignored_.load();
    return c;
  }

 private:
  key_status send_key(std::uint8_t character) noexcept {
    const std::uint8_t offset = offset_.load();
    if (offset == 0) {
      keys_lost_.increment();
      return key_status::local_mode;
    }
    const std::uint8_t text[1] = {character};
    if (!this->queue(message::characters(offset, byte_view(text, 1)))) {
      keys_lost_.increment();
      this->raise_tx_timeout();
      return key_status::queue_full;
    }
    keys_sent_.increment();
    return key_status::ok;
  }

  // Program side, in `clear_counters`: the counters it writes.
  void clear_program_counters() noexcept {
    keys_sent_.store(0);
    keys_lost_.store(0);
  }
  // Link side, before it next counts after `clear_counters`: the counters it writes here.
  void clear_delivery_counters() noexcept {
    dropped_in_local_mode_.store(0);
    display_messages_.store(0);
    variables_ignored_.store(0);
  }

  // A message for this keypad (the core has counted errors already). In local mode the link forwards nothing
  // and the keypad never transmits: the transmit queue stays empty because keys are refused.
  // Link side: a message for this keypad, still in the decoder.
  void deliver(detail::decode_step step) noexcept { deliver(this->delivered(step)); }
  // Link side.
  void deliver(const decode_result& r) noexcept {
    if (r.status != decode_status::ok) return;  // no_room cannot happen: the store holds MaxCharacters
    if (!network_mode()) {
      if (r.msg.type == message_type::keypad_offset) {
        offset_.store(r.msg.offset);
        this->set_forwarding(true);
      } else {
        dropped_in_local_mode_.increment();
      }
      return;
    }
    switch (r.msg.type) {
      case message_type::character:
        display_.write(r.msg.text);
        display_messages_.increment();
        return;
      case message_type::variable:
        variables_ignored_.increment();
        return;
      case message_type::keypad_offset:
        offset_.store(r.msg.offset);
        return;
      case message_type::keypad_mode:
        mode_.store(r.msg.mode);
        return;
    }
  }

  keypad_config config_;
  keypad_display display_;  // link side
  detail::single_writer<std::uint8_t> offset_;  // link side
  detail::single_writer<std::uint8_t> mode_{keypad_mode_key_on};  // link side
  detail::single_writer<std::uint16_t> dropped_in_local_mode_;  // link side
  detail::single_writer<std::uint16_t> display_messages_;       // link side
  detail::single_writer<std::uint16_t> variables_ignored_;      // link side
  detail::single_writer<std::uint16_t> keys_sent_;              // program side
  detail::single_writer<std::uint16_t> keys_lost_;              // program side
};

}  // namespace trionet::ring
