// A Motion Coordinator on the fibre ring (docs/protocol.md 1.5-1.6, 1.10): forwards what is not for it, keeps the
// characters sent to it in its receive buffer for KEY# and GET#, writes direct variable transfers into VR()
// through the write policy, and sends PRINT# and SEND messages. The link, the idle line, NETSTAT and the bulk
// paths are the ring-node core's (node.hpp).
//
// Wire it to a UART (see transport.hpp) and call the program-level API from the main loop:
//
//   trionet::vr_table<256> vr;
//   trionet::ring::motion_coordinator<> mc(vr);
//   mc.print(11, "HELLO");              // PRINT #11,"HELLO" (text of any length: split into messages)
//   mc.send_variable(10, 200, 99.0);    // SEND(10,1,200,99)
//   if (mc.key(3)) { auto k = mc.get(3); ... }   // IF KEY#3 THEN GET #3,k
//
// Cost (defaults): RAM = receive buffer 256 + forward buffer 16 + transmit queue 32 + 96 bytes of state and
// counters = 400 bytes on a 32-bit core (448 on a 64-bit host); the VR table and DEFKEY table are the
// caller's. Per received byte O(1). `receive`/`transmit` run on the link side (an ISR), the BASIC calls on
// the program side, with no lock or masking (node.hpp, transport.hpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

#include "trionet/detail/attributes.hpp"
#include "trionet/detail/character_store.hpp"
#include "trionet/detail/single_writer.hpp"
#include "trionet/q32.hpp"
#include "trionet/ring/bytes.hpp"
#include "trionet/ring/crc.hpp"
#include "trionet/ring/decoder.hpp"
#include "trionet/ring/keypad_codes.hpp"
#include "trionet/ring/message.hpp"
#include "trionet/ring/node.hpp"
#include "trionet/span.hpp"
#include "trionet/vr.hpp"

namespace trionet::ring {

/// What became of a PRINT# or SEND call. Anything but `ok` means nothing was queued (but for PRINT#, see
/// `print_result`).
enum class send_status : std::uint8_t {
  ok,                      ///< queued whole
  bad_address,             ///< BASIC address not 10..24
  empty_text,              ///< PRINT# of nothing
  character_out_of_range,  ///< a character above 127
  vr_out_of_range,         ///< vr above 16383
  value_out_of_range,      ///< value outside Q32.32 (or NaN)
  offset_out_of_range,     ///< keypad offset not a BASIC address 10..24
  mode_out_of_range,       ///< keypad mode not 0 or 127
  queue_full,              ///< no room in the transmit queue (NETSTAT bit 0 is set)
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(send_status status) noexcept {
  switch (status) {
    case send_status::ok:
      return "ok";
    case send_status::bad_address:
      return "bad_address";
    case send_status::empty_text:
      return "empty_text";
    case send_status::character_out_of_range:
      return "character_out_of_range";
    case send_status::vr_out_of_range:
      return "vr_out_of_range";
    case send_status::value_out_of_range:
      return "value_out_of_range";
    case send_status::offset_out_of_range:
      return "offset_out_of_range";
    case send_status::mode_out_of_range:
      return "mode_out_of_range";
    case send_status::queue_full:
      return "queue_full";
  }
  return "unknown";
}

/// What became of a PRINT#: `status` as for SEND, and how many characters were queued. A text longer than
/// one message carries is sent as several (docs/protocol.md 1.6); whole messages only, so with `queue_full`
/// `queued` says where to go on from.
struct print_result {
  /// `ok`, or why not all of the text was queued.
  send_status status;
  /// Characters queued (all of them for `ok`).
  std::size_t queued;
  /// True for `ok`.
  constexpr explicit operator bool() const noexcept { return status == send_status::ok; }
};

/// What became of a GET#.
enum class get_status : std::uint8_t {
  ok,           ///< a character was taken
  nothing_yet,  ///< the receive buffer holds no character (the non-blocking form; a blocking wrapper may
                ///< wait)
  bad_channel,  ///< a channel other than 3 or 4
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(get_status status) noexcept {
  switch (status) {
    case get_status::ok:
      return "ok";
    case get_status::nothing_yet:
      return "nothing_yet";
    case get_status::bad_channel:
      return "bad_channel";
  }
  return "unknown";
}

/// GET#: a character, or why there is none.
struct [[nodiscard]] get_result {
  /// `ok`, or why there is no character.
  get_status status;
  /// The character (meaningful for `ok`).
  std::uint8_t value;
  /// True for `ok`.
  constexpr explicit operator bool() const noexcept { return status == get_status::ok; }
};

/// Counters of a Motion Coordinator, as read at one moment; they only ever grow. The wire errors (frame, CRC,
/// receive overflow) wrap at 2^32; the others, traffic and the outcomes of VR writes, at 2^16. (The
/// forwarding counters are the link's: `forwarding_counters()`.)
struct motion_coordinator_counters {
  std::uint32_t frame_errors = 0;        ///< frame errors of docs/protocol.md 1.4 and 1.10 (NETSTAT bit 3)
  std::uint32_t crc_errors = 0;          ///< direct variable transfers that failed their CRC (NETSTAT bit 2)
  std::uint32_t character_messages = 0;  ///< character transfers taken into the receive buffer (2^16)
  std::uint32_t receive_overflows = 0;   ///< character transfers dropped whole: no room (NETSTAT bit 4)
  std::uint32_t variables_written = 0;   ///< direct variable transfers applied to VR() (2^16)
  std::uint32_t variables_refused = 0;   ///< ... refused by the write policy (2^16)
  std::uint32_t variables_out_of_range = 0;        ///< ... to a vr past the VR table (2^16)
  std::uint32_t variables_value_out_of_range = 0;  ///< ... whose value the VR table's type cannot hold (2^16)
  std::uint32_t keypad_messages_ignored = 0;       ///< keypad offset / mode messages sent to this MC (2^16)
  std::uint32_t sends_refused = 0;  ///< PRINT#/SEND calls refused for lack of room (NETSTAT bit 0) (2^16)
};

/// `MaxCharacters` is the character maximum of docs/protocol.md 1.4: the longest character transfer the node
/// accepts, and the bound on messages it forwards. The receive buffer (`ReceiveCapacity`) may be smaller: a
/// message that does not fit is dropped whole (NETSTAT bit 4). `Crc` and `Layout` are the direct variable
/// transfer's CRC policy and field layout (crc.hpp, variable_layout.hpp).
template <std::size_t ReceiveCapacity = 256, std::size_t ForwardCapacity = 16, std::size_t TransmitCapacity = 32,
          std::size_t MaxCharacters = default_max_characters, class Crc = crc16_ccitt_false,
          class Layout = default_variable_layout>
class motion_coordinator final
    : public node<motion_coordinator<ReceiveCapacity, ForwardCapacity, TransmitCapacity, MaxCharacters, Crc, Layout>,
                  basic_decoder<detail::receive_buffer<ReceiveCapacity>, MaxCharacters, Crc, Layout>,
                  ForwardCapacity, TransmitCapacity, false> {
  using core = node<motion_coordinator, basic_decoder<detail::receive_buffer<ReceiveCapacity>, MaxCharacters, Crc, Layout>,
                    ForwardCapacity, TransmitCapacity, false>;
  friend core;

 public:
  /// `vr` receives direct variable transfers (through its write policy, on the link side); `defkey`
  /// translates GET#3.
  explicit motion_coordinator(vr_store& vr, const defkey_table& defkey = default_defkey) noexcept
      : vr_(&vr), defkey_(&defkey) {}
  /// The same with a CRC object (`crc16_runtime`: the CRC of a profile, chosen at run time) for the direct
  /// variable transfers it checks and sends.
  motion_coordinator(vr_store& vr, const defkey_table& defkey, const Crc& crc) noexcept
      : core(crc), vr_(&vr), defkey_(&defkey) {}

  using core::receive;
  using core::transmit;

  // ---- PRINT# and SEND (BASIC addresses 10..24) ----

  /// PRINT \#n,text, without waiting: `text` (each character 0..127) as consecutive character messages, each
  /// as long as fits, as many whole messages as the transmit queue has room for (docs/protocol.md 1.6). If not
  /// all of it fits, the result is `queue_full` with the number of characters queued, and NETSTAT bit 0 is
  /// set; nothing is queued unless every character is valid.
  [[nodiscard]] print_result print(int n, byte_view text) noexcept {
    const send_status checked = check_print(n, text);
    if (checked != send_status::ok) return {checked, 0};
    const std::size_t queued = this->queue_text(hops_of_address(n), text);
    if (queued == text.size()) return {send_status::ok, queued};
    refuse();
    return {send_status::queue_full, queued};
  }
  /// The same with a NUL-terminated text.
  [[nodiscard]] print_result print(int n, const char* text) noexcept { return print(n, c_text(text)); }

  /// BASIC's PRINT \#n,text: waits for room until all of `text` is queued. `wait()` is called whenever the
  /// transmit queue is full; it lets the link run (returns once some bytes may have gone out) and returns
  /// false to give up, which sets NETSTAT bit 0 (docs/protocol.md 1.6). Not for an ISR.
  template <class Wait>
  [[nodiscard]] print_result print_all(int n, byte_view text, Wait&& wait) noexcept(noexcept(wait())) {
    const send_status checked = check_print(n, text);
    if (checked != send_status::ok) return {checked, 0};
    const std::uint8_t hops = hops_of_address(n);
    std::size_t done = 0;
    for (;;) {
      done += this->queue_text(hops, byte_view(text.data() + done, text.size() - done));
      if (done == text.size()) return {send_status::ok, done};
      if (!wait()) {
        refuse();
        return {send_status::queue_full, done};
      }
    }
  }
  /// The same with a NUL-terminated text.
  template <class Wait>
  [[nodiscard]] print_result print_all(int n, const char* text, Wait&& wait) noexcept(noexcept(wait())) {
    return print_all(n, c_text(text), wait);
  }

  /// SEND(n,1,vr,value): a direct variable transfer; `value` is rounded to Q32.32.
  [[nodiscard]] send_status send_variable(int n, std::uint16_t vr, double value) noexcept {
    const q32_result q = q32_from_double(value);
    if (!q) {  // the same order of checks as send_variable_q32: address, vr, then value
      if (!hops_from_basic_address(n)) return send_status::bad_address;
      return vr > max_vr ? send_status::vr_out_of_range : send_status::value_out_of_range;
    }
    return send_variable_q32(n, vr, q.raw);
  }

  /// SEND(n,1,vr,value) with the value already in Q32.32 (value * 2^32): no floating point.
  [[nodiscard]] send_status send_variable_q32(int n, std::uint16_t vr, std::int64_t value) noexcept {
    const auto hops = hops_from_basic_address(n);
    if (!hops) return send_status::bad_address;
    if (vr > max_vr) return send_status::vr_out_of_range;
    return send(message::variable(*hops, vr, value));
  }

  /// SEND(n,2,offset): tells the keypad n where to send its key presses (offset: BASIC address 10..24,
  /// counted from the keypad).
  [[nodiscard]] send_status send_keypad_offset(int n, int offset) noexcept {
    const auto hops = hops_from_basic_address(n);
    if (!hops) return send_status::bad_address;
    const auto offset_hops = hops_from_basic_address(offset);
    if (!offset_hops) return send_status::offset_out_of_range;
    return send(message::keypad_offset(*hops, *offset_hops));
  }

  /// Keypad mode: 0 = key ON only, 127 = key ON and key OFF.
  [[nodiscard]] send_status send_keypad_mode(int n, int mode) noexcept {
    const auto hops = hops_from_basic_address(n);
    if (!hops) return send_status::bad_address;
    if (mode != keypad_mode_key_on && mode != keypad_mode_key_on_off) return send_status::mode_out_of_range;
    return send(message::keypad_mode(*hops, static_cast<std::uint8_t>(mode)));
  }

  // ---- KEY# and GET# (program side) ----

  /// KEY#3 / KEY#4: true if at least one character is waiting; nothing is consumed.
  bool key(int channel) const noexcept {
    return (channel == 3 || channel == 4) && this->character_store().waiting() != 0;
  }

  /// GET#4: the next character raw; GET#3: translated through DEFKEY.
  [[nodiscard]] get_result get(int channel) noexcept {
    if (channel != 3 && channel != 4) return {get_status::bad_channel, 0};
    std::uint8_t c = 0;
    if (!this->character_store().take(c)) return {get_status::nothing_yet, 0};
    return {get_status::ok, channel == 3 ? (*defkey_)[c] : c};
  }

  /// Program side: characters waiting in the receive buffer.
  std::size_t characters_waiting() const noexcept { return this->character_store().waiting(); }

  /// Either side: the counters now (each read whole; not all at one instant), since construction or
  /// `clear_counters`.
  motion_coordinator_counters counters() const noexcept {
    motion_coordinator_counters c;
    c.sends_refused = sends_refused_.load();
    if (this->counters_clearing()) return c;  // the link side's: 0 until it clears them
    c.frame_errors = this->frame_errors();
    c.crc_errors = this->crc_errors();
    c.receive_overflows = receive_overflows_.load();
    c.character_messages = character_messages_.load();
    c.variables_written = variables_[0].load();
    c.variables_refused = variables_[1].load();
    c.variables_out_of_range = variables_[2].load();
    c.variables_value_out_of_range = variables_[3].load();
    c.keypad_messages_ignored = keypad_messages_ignored_.load();
    return c;
  }

 private:
  static byte_view c_text(const char* text) noexcept {
    return byte_view(reinterpret_cast<const std::uint8_t*>(text), std::strlen(text));
  }
  // Precondition: a valid BASIC address.
  static std::uint8_t hops_of_address(int n) noexcept { return static_cast<std::uint8_t>(n - 9); }

  static send_status check_print(int n, byte_view text) noexcept {
    if (!hops_from_basic_address(n)) return send_status::bad_address;
    if (text.empty()) return send_status::empty_text;
    if (find_control(text.begin(), text.end()) != text.end()) return send_status::character_out_of_range;
    return send_status::ok;
  }

  // Program side: an own message could not be put into the transmit queue: NETSTAT bit 0.
  void refuse() noexcept {
    sends_refused_.increment();
    this->raise_tx_timeout();
  }

  // A message whose fields were all checked: queued, or refused for want of room.
  send_status send(const message& m) noexcept {
    const encode_result queued = this->queue(m);
    if (queued) return send_status::ok;
    TRIONET_ASSERT(queued.status == encode_status::buffer_too_small);
    refuse();
    return send_status::queue_full;
  }

  // Program side, in `clear_counters`: the counters it writes.
  void clear_program_counters() noexcept { sends_refused_.store(0); }
  // Link side, before it next counts after `clear_counters`: the counters it writes here.
  void clear_delivery_counters() noexcept {
    character_messages_.store(0);
    for (auto& v : variables_) v.store(0);
    keypad_messages_ignored_.store(0);
    receive_overflows_.store(0);
  }

  // Link side: a message for this node, `ok` or `no_room` (the core has counted errors already), still in the
  // decoder.
  void deliver(detail::decode_step step) noexcept {
    if (detail::status_of(step) == decode_status::no_room) {
      receive_overflows_.increment();
      this->raise_netstat(netstat_rx_overflow);
      return;
    }
    switch (this->delivered_type()) {
      case message_type::character:
        character_messages_.increment();
        return;
      case message_type::variable: {
        std::uint16_t vr = 0;
        std::int64_t value = 0;
        Layout::read(this->delivered_payload(), vr, value);
        const auto written = static_cast<unsigned>(vr_->write(vr, network_value::from_q32(value)));
        // Counted by outcome, the counters in the enum's order (a store that answers outside it: not counted).
        if (written < sizeof variables_ / sizeof variables_[0]) variables_[written].increment();
        return;
      }
      case message_type::keypad_offset:
      case message_type::keypad_mode:
        keypad_messages_ignored_.increment();
        return;
    }
  }

  // Written by the link side:
  detail::single_writer<std::uint16_t> character_messages_;
  // by vr_write_status: written, refused, out_of_range, value_out_of_range
  detail::single_writer<std::uint16_t> variables_[4];
  detail::single_writer<std::uint16_t> keypad_messages_ignored_;
  // Written by the program side:
  detail::single_writer<std::uint16_t> sends_refused_;
  vr_store* vr_;
  const defkey_table* defkey_;
  detail::single_writer<std::uint32_t> receive_overflows_;  // link side
};

}  // namespace trionet::ring
