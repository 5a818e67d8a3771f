// A membrane keypad on the fibre ring (PROTOCOL.md 1.7-1.9).
//
//   local mode (at power-up)          network mode
//   - handles only a keypad offset    - forwards like any node
//     addressed to itself (A = 1)     - each key press: a one-character message to `offset` hops along
//   - drops and counts everything     - keypad mode 0: key ON only; 127: key ON and key OFF
//     else to or through it           - character messages drive the 2 x 20 display
//   - never transmits                 - direct variable transfers are ignored (counted)
//
// Cost (defaults): RAM = forward buffer 16 + transmit queue 16 + decoder 256 + display 45 + state and counters
// = 452 bytes on a 32-bit core (472 on a 64-bit host).
// `receive`/`transmit` may run in an ISR; `press`/`release` from the key-scan context (see transport.hpp).
#pragma once

#include <cstddef>
#include <cstdint>

#include "trionet/ring/bytes.hpp"
#include "trionet/ring/crc.hpp"
#include "trionet/ring/decoder.hpp"
#include "trionet/ring/keypad_codes.hpp"
#include "trionet/ring/keypad_display.hpp"
#include "trionet/ring/link.hpp"
#include "trionet/ring/message.hpp"
#include "trionet/transport.hpp"

namespace trionet::ring {

/// What became of a key press or release.
enum class key_result : std::uint8_t {
  sent,        ///< queued for the node `offset` hops along
  not_sent,    ///< a key OFF in keypad mode 0: nothing to send
  local_mode,  ///< the keypad has no offset yet: nothing is sent (counted)
  queue_full,  ///< no room in the transmit queue (counted)
};

/// The keypad's configurable behaviour (PROTOCOL.md 1.7-1.8 defaults).
struct keypad_config {
  const keypad_codes* codes = &default_keypad_codes;
  std::uint8_t (*key_off_code)(std::uint8_t on) noexcept = default_key_off_code;
};

/// Counters of a keypad; they only ever grow (and wrap at 2^32).
struct keypad_counters {
  std::uint32_t dropped_in_local_mode = 0;  ///< messages to this keypad dropped before its offset arrived
  std::uint32_t display_messages = 0;       ///< character transfers shown on the display
  std::uint32_t variables_ignored = 0;      ///< direct variable transfers (ignored by keypads)
  std::uint32_t frame_errors = 0;           ///< frame errors of PROTOCOL.md 1.4
  std::uint32_t crc_errors = 0;             ///< direct variable transfers that failed their CRC
  std::uint32_t keys_sent = 0;              ///< key characters queued
  std::uint32_t keys_lost = 0;              ///< key presses not sent: local mode or queue full
};

template <std::size_t ForwardCapacity = 16, std::size_t TransmitCapacity = 16,
          std::size_t MaxCharacters = default_max_characters, class Crc = crc16_ccitt_false,
          class Layout = default_variable_layout>
class keypad final : public byte_port {
 public:
  explicit keypad(const keypad_config& config = keypad_config{}) noexcept : config_(config) {
    link_.set_forwarding(false);
  }

  // ---- the link (byte_port) ----

  using byte_port::receive;  // the bulk forms, one byte at a time
  using byte_port::transmit;

  void receive(std::uint8_t byte) noexcept override {
    const route r = link_.receive(byte);
    if (r == route::local) {
      handle(decoder_.push(byte));
    } else if (classify(byte) == byte_class::header) {
      handle(decoder_.interrupt());
    }
  }
  [[nodiscard]] bool transmit(std::uint8_t& byte) noexcept override {
    return network_mode() && link_.transmit(byte);
  }
  [[nodiscard]] bool transmit_pending() const noexcept override {
    return network_mode() && link_.transmit_pending();
  }

  // ---- keys ----

  [[nodiscard]] key_result press(key k) noexcept { return send_key((*config_.codes)[k]); }

  [[nodiscard]] key_result release(key k) noexcept {
    if (mode_ != keypad_mode_key_on_off)
      return network_mode() ? key_result::not_sent : key_result::local_mode;
    return send_key(config_.key_off_code((*config_.codes)[k]));
  }

  // ---- state ----

  bool network_mode() const noexcept { return offset_ != 0; }
  /// Hops to where key presses go (0 in local mode).
  std::uint8_t offset() const noexcept { return offset_; }
  std::uint8_t mode() const noexcept { return mode_; }
  const keypad_display& display() const noexcept { return display_; }
  const keypad_counters& counters() const noexcept { return counters_; }
  const link_counters& forwarding_counters() const noexcept { return link_.counters(); }

 private:
  key_result send_key(std::uint8_t character) noexcept {
    if (!network_mode()) {
      ++counters_.keys_lost;
      return key_result::local_mode;
    }
    const std::uint8_t text[1] = {character};
    if (!link_.queue(message::characters(offset_, byte_view(text, 1)))) {
      ++counters_.keys_lost;
      return key_result::queue_full;
    }
    ++counters_.keys_sent;
    return key_result::sent;
  }

  void handle(const decode_result& r) noexcept {
    switch (r.status) {
      case decode_status::incomplete:
        return;
      case decode_status::frame_error:
        ++counters_.frame_errors;
        return;
      case decode_status::crc_error:
        ++counters_.crc_errors;
        return;
      case decode_status::no_room:
        return;  // cannot happen: the store holds MaxCharacters
      case decode_status::message:
        break;
    }
    if (!network_mode()) {
      if (r.msg.type == message_type::keypad_offset) {
        offset_ = r.msg.offset;
        link_.set_forwarding(true);
      } else {
        ++counters_.dropped_in_local_mode;
      }
      return;
    }
    switch (r.msg.type) {
      case message_type::character:
        display_.write(r.msg.text);
        ++counters_.display_messages;
        return;
      case message_type::variable:
        ++counters_.variables_ignored;
        return;
      case message_type::keypad_offset:
        offset_ = r.msg.offset;
        return;
      case message_type::keypad_mode:
        mode_ = r.msg.mode;
        return;
    }
  }

  keypad_config config_;
  link<ForwardCapacity, TransmitCapacity, Crc, Layout> link_;
  decoder<MaxCharacters, Crc, Layout> decoder_;
  keypad_display display_;
  keypad_counters counters_;
  std::uint8_t offset_ = 0;
  std::uint8_t mode_ = keypad_mode_key_on;
};

}  // namespace trionet::ring
