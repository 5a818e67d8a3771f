// A Motion Coordinator on the fibre ring (PROTOCOL.md 1.5-1.6): forwards what is not for it, keeps the
// characters sent to it in its receive buffer for KEY# and GET#, writes direct variable transfers into VR()
// through the write policy, and sends PRINT# and SEND messages.
//
// Wire it to a UART (see transport.hpp) and call the program-level API from the main loop:
//
//   trionet::vr_table<256> vr;
//   trionet::ring::motion_coordinator<> mc(vr);
//   mc.print(11, "HELLO");              // PRINT #11,"HELLO"
//   mc.send_variable(10, 200, 99.0);    // SEND(10,1,200,99)
//   if (mc.key(3)) { auto k = mc.get(3); ... }   // IF KEY#3 THEN GET #3,k
//
// Cost (defaults): RAM = receive buffer 256 + forward buffer 32 + transmit queue 32 + 128 bytes of state and
// counters = 448 bytes on a 32-bit core (464 on a 64-bit host); the VR table and DEFKEY table are the
// caller's. Per received byte O(1). `receive`/`transmit` may run in an ISR; see transport.hpp for sharing
// with the main loop.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

#include "trionet/attributes.hpp"
#include "trionet/fifo.hpp"
#include "trionet/ring/bytes.hpp"
#include "trionet/ring/crc.hpp"
#include "trionet/ring/decoder.hpp"
#include "trionet/ring/keypad_codes.hpp"
#include "trionet/ring/link.hpp"
#include "trionet/ring/message.hpp"
#include "trionet/ring/q32.hpp"
#include "trionet/span.hpp"
#include "trionet/transport.hpp"
#include "trionet/vr.hpp"

namespace trionet::ring {

/// NETSTAT bits (PROTOCOL.md 1.6).
enum netstat_bit : std::uint8_t {
  netstat_tx_timeout = 1,       ///< an own message could not be put into the transmit queue
  netstat_tx_buffer_error = 2,  ///< a forwarded message was lost (forward buffer overflow)
  netstat_rx_crc_error = 4,     ///< a direct variable transfer failed its CRC
  netstat_rx_frame_error = 8,   ///< an incomplete or corrupt message was received
  netstat_rx_overflow = 16,     ///< a character transfer did not fit in the receive buffer (extension)
};

/// What became of a PRINT# or SEND call. Anything but `queued` means nothing was queued.
enum class send_result : std::uint8_t {
  queued,
  bad_address,             ///< BASIC address not 10..24
  empty_text,              ///< PRINT# of nothing
  character_out_of_range,  ///< a character above 127
  vr_out_of_range,         ///< vr above 16383
  value_out_of_range,      ///< value outside Q32.32 (or NaN)
  offset_out_of_range,     ///< keypad offset not a BASIC address 10..24
  mode_out_of_range,       ///< keypad mode not 0 or 127
  queue_full,              ///< no room in the transmit queue (NETSTAT bit 0 is set)
};

constexpr const char* to_string(send_result result) noexcept {
  switch (result) {
    case send_result::queued:
      return "queued";
    case send_result::bad_address:
      return "bad_address";
    case send_result::empty_text:
      return "empty_text";
    case send_result::character_out_of_range:
      return "character_out_of_range";
    case send_result::vr_out_of_range:
      return "vr_out_of_range";
    case send_result::value_out_of_range:
      return "value_out_of_range";
    case send_result::offset_out_of_range:
      return "offset_out_of_range";
    case send_result::mode_out_of_range:
      return "mode_out_of_range";
    case send_result::queue_full:
      return "queue_full";
  }
  return "unknown";
}

/// GET#: a character, or nothing yet (the non-blocking form; a blocking wrapper may wait on `key`).
struct get_result {
  enum class status : std::uint8_t { ok, nothing_yet, bad_channel } status;
  std::uint8_t value;
  constexpr explicit operator bool() const noexcept { return status == status::ok; }
};

/// Counters of a Motion Coordinator; they only ever grow (and wrap at 2^32).
/// (The forwarding counters are the link's: `forwarding_counters()`.)
struct motion_coordinator_counters {
  std::uint32_t character_messages = 0;      ///< character transfers taken into the receive buffer
  std::uint32_t receive_overflows = 0;       ///< character transfers dropped whole: no room (NETSTAT bit 4)
  std::uint32_t variables_written = 0;       ///< direct variable transfers applied to VR()
  std::uint32_t variables_refused = 0;       ///< ... refused by the write policy
  std::uint32_t variables_out_of_range = 0;  ///< ... to a vr past the VR table
  std::uint32_t crc_errors = 0;    ///< direct variable transfers that failed their CRC (NETSTAT bit 2)
  std::uint32_t frame_errors = 0;  ///< frame errors of PROTOCOL.md 1.4 (NETSTAT bit 3)
  std::uint32_t keypad_messages_ignored = 0;  ///< keypad offset / mode messages sent to this MC
  std::uint32_t sends_refused = 0;            ///< PRINT#/SEND calls refused for lack of room (NETSTAT bit 0)
};

/// The receive buffer as the decoder's character store: a message's characters are staged at its end and
/// kept only if the whole message is valid and fits (all or nothing).
template <std::size_t Capacity>
class receive_buffer {
 public:
  void begin() noexcept { staged_ = 0; }
  bool put(std::uint8_t c) noexcept {
    if (!fifo_.push(c)) return false;
    ++staged_;  // at most Capacity <= 65535
    return true;
  }
  std::size_t put(const std::uint8_t* c, std::size_t n) noexcept {
    const std::size_t pushed = fifo_.push(c, n);
    staged_ = static_cast<std::uint16_t>(staged_ + pushed);
    return pushed;
  }
  byte_view commit() noexcept {  // the characters may wrap round the buffer: no contiguous view
    staged_ = 0;
    return {};
  }
  void abort() noexcept {
    fifo_.drop_back(staged_);
    staged_ = 0;
  }

  /// Characters of whole messages waiting to be read.
  std::size_t waiting() const noexcept { return fifo_.size() - staged_; }
  bool take(std::uint8_t& c) noexcept { return waiting() != 0 && fifo_.pop(c); }

 private:
  byte_fifo<Capacity> fifo_;
  std::uint16_t staged_ = 0;
};

template <std::size_t ReceiveCapacity = 256, std::size_t ForwardCapacity = 32,
          std::size_t TransmitCapacity = 32, class Crc = crc16_ccitt_false,
          class Layout = default_variable_layout>
class motion_coordinator final : public byte_port {
 public:
  /// `vr` receives direct variable transfers (through its write policy); `defkey` translates GET#3.
  explicit motion_coordinator(vr_store& vr, const defkey_table& defkey = default_defkey) noexcept
      : vr_(&vr), defkey_(&defkey) {}

  // ---- the link (byte_port) ----

  void receive(std::uint8_t byte) noexcept override {
    const route r = link_.receive(byte);
    if (r == route::local) {
      handle(decoder_.push(byte));
      return;
    }
    if (r == route::lost) netstat_ |= netstat_tx_buffer_error;
    if (classify(byte) == byte_class::header) handle(decoder_.interrupt());
  }
  /// Many received bytes at once (a DMA buffer, a read()): the same as `receive` for each, in order, with
  /// runs of message data copied whole. Not virtual, so firmware that does not call it does not link it.
  void receive(byte_view bytes) noexcept { receive_bytes(bytes); }
  [[nodiscard]] bool transmit(std::uint8_t& byte) noexcept override { return link_.transmit(byte); }
  /// Fills `out` with up to out.size() bytes to send and returns how many: the same bytes as that many calls
  /// of `transmit`, stopping at the first that has none.
  [[nodiscard]] std::size_t transmit(byte_buffer out) noexcept {
    return link_.transmit(out.data(), out.size());
  }
  [[nodiscard]] bool transmit_pending() const noexcept override { return link_.transmit_pending(); }

  /// A DMA-fed node's receive-and-forward in one call: exactly `receive(in)` then `transmit(out)` (returns
  /// how many bytes of `out` to send). When the forward buffer is empty and the node is between its own
  /// messages, the bytes it forwards are written straight into `out`: one copy instead of two.
  [[nodiscard]] std::size_t relay(byte_view in, byte_buffer out) noexcept {
    if (!link_.straight_through(in.size(), out.size())) return receive_then_transmit(in, out);
    auto straight = link_type::straight_buffer(out.data());
    receive_bytes(in, straight);
    return link_.transmit_after(straight, out.data(), out.size());
  }

  // ---- PRINT# and SEND (BASIC addresses 10..24) ----

  /// PRINT #n,text: a character transfer of `text` (each character 0..127).
  [[nodiscard]] send_result print(int n, byte_view text) noexcept {
    const auto hops = hops_from_basic_address(n);
    if (!hops) return send_result::bad_address;
    return queue(message::characters(*hops, text));
  }
  [[nodiscard]] send_result print(int n, const char* text) noexcept {
    return print(n, byte_view(reinterpret_cast<const std::uint8_t*>(text), std::strlen(text)));
  }

  /// SEND(n,1,vr,value): a direct variable transfer; `value` is rounded to Q32.32.
  [[nodiscard]] send_result send_variable(int n, std::uint16_t vr, double value) noexcept {
    const q32_result q = q32_from_double(value);
    if (!q) {  // the same order of checks as send_variable_q32: address, vr, then value
      if (!hops_from_basic_address(n)) return send_result::bad_address;
      return vr > max_vr ? send_result::vr_out_of_range : send_result::value_out_of_range;
    }
    return send_variable_q32(n, vr, q.raw);
  }

  /// SEND(n,1,vr,value) with the value already in Q32.32 (value * 2^32): no floating point.
  [[nodiscard]] send_result send_variable_q32(int n, std::uint16_t vr, std::int64_t value) noexcept {
    const auto hops = hops_from_basic_address(n);
    if (!hops) return send_result::bad_address;
    if (vr > max_vr) return send_result::vr_out_of_range;
    return queue(message::variable(*hops, vr, value));
  }

  /// SEND(n,2,offset): tells the keypad n where to send its key presses (offset: BASIC address 10..24,
  /// counted from the keypad).
  [[nodiscard]] send_result send_keypad_offset(int n, int offset) noexcept {
    const auto hops = hops_from_basic_address(n);
    if (!hops) return send_result::bad_address;
    const auto offset_hops = hops_from_basic_address(offset);
    if (!offset_hops) return send_result::offset_out_of_range;
    return queue(message::keypad_offset(*hops, *offset_hops));
  }

  /// Keypad mode: 0 = key ON only, 127 = key ON and key OFF.
  [[nodiscard]] send_result send_keypad_mode(int n, int mode) noexcept {
    const auto hops = hops_from_basic_address(n);
    if (!hops) return send_result::bad_address;
    if (mode != keypad_mode_key_on && mode != keypad_mode_key_on_off) return send_result::mode_out_of_range;
    return queue(message::keypad_mode(*hops, static_cast<std::uint8_t>(mode)));
  }

  /// Room left in the transmit queue, in bytes (a message takes its data + 2).
  std::size_t transmit_free() const noexcept { return link_.transmit_free(); }

  // ---- KEY# and GET# ----

  /// KEY#3 / KEY#4: true if at least one character is waiting; nothing is consumed.
  bool key(int channel) const noexcept {
    return (channel == 3 || channel == 4) && decoder_.store().waiting() != 0;
  }

  /// GET#4: the next character raw; GET#3: translated through DEFKEY.
  [[nodiscard]] get_result get(int channel) noexcept {
    if (channel != 3 && channel != 4) return {get_result::status::bad_channel, 0};
    std::uint8_t c = 0;
    if (!decoder_.store().take(c)) return {get_result::status::nothing_yet, 0};
    return {get_result::status::ok, channel == 3 ? (*defkey_)[c] : c};
  }

  /// Characters waiting in the receive buffer.
  std::size_t characters_waiting() const noexcept { return decoder_.store().waiting(); }

  // ---- NETSTAT and counters ----

  std::uint8_t netstat() const noexcept { return netstat_; }
  void clear_netstat() noexcept { netstat_ = 0; }

  const motion_coordinator_counters& counters() const noexcept { return counters_; }
  const link_counters& forwarding_counters() const noexcept { return link_.counters(); }

  std::size_t forward_backlog() const noexcept { return link_.forward_backlog(); }

 private:
  send_result queue(const message& m) noexcept {
    const encode_result queued = link_.queue(m);
    switch (queued.error) {
      case encode_error::none:
        return send_result::queued;
      case encode_error::buffer_too_small:
        netstat_ |= netstat_tx_timeout;
        ++counters_.sends_refused;
        return send_result::queue_full;
      case encode_error::empty_text:
        return send_result::empty_text;
      case encode_error::character_out_of_range:
        return send_result::character_out_of_range;
      case encode_error::vr_out_of_range:
        return send_result::vr_out_of_range;
      case encode_error::offset_out_of_range:
        return send_result::offset_out_of_range;
      case encode_error::mode_out_of_range:
        return send_result::mode_out_of_range;
      case encode_error::hops_out_of_range:
      case encode_error::unknown_type:
        break;
    }
    return send_result::bad_address;
  }

  // The bulk receive: traffic through the node a run at a time (into the forward buffer, or the stand-in
  // given), bytes for the node to the decoder (out of line, so that the forwarding loop stays small).
  template <class... Straight>
  TRIONET_ALWAYS_INLINE void receive_bytes(byte_view bytes, Straight&... straight) noexcept {
    const std::uint8_t* p = bytes.begin();
    const std::uint8_t* const end = bytes.end();
    for (;;) {
      const auto passed = link_.receive_passing(p, end, straight...);
      if (passed.events != 0) passed_events(passed.events);
      p = passed.stop;
      if (p == end) return;
      p = receive_local(p, end);
    }
  }

  // `relay` when it cannot go straight through (out of line, so that the straight path stays small).
  TRIONET_NOINLINE std::size_t receive_then_transmit(byte_view in, byte_buffer out) noexcept {
    receive(in);
    return transmit(out);
  }

  // What happened to traffic through the node: a header (it ends any message the node was receiving, and the
  // decoder is then between messages) or a lost forwarded message.
  void passed_events(std::uint8_t events) noexcept {
    if ((events & link_type::passing::header) != 0) {
      if (decoder_.in_message()) {
        end_local_message();
      } else {
        decoder_.reset();  // out of a run of stray data or a skipped A = 0 message: nothing to report
      }
    }
    if ((events & link_type::passing::lost) != 0) netstat_ |= netstat_tx_buffer_error;
  }

  // A header through the node ended the message the node was receiving.
  TRIONET_NOINLINE void end_local_message() noexcept { handle(decoder_.interrupt()); }

  // Bytes for the node at `p`: one control byte, or a run of message data for the decoder. Returns the next.
  TRIONET_NOINLINE const std::uint8_t* receive_local(const std::uint8_t* p,
                                                     const std::uint8_t* end) noexcept {
    if (!is_data(*p)) {  // a control byte for the node (it never goes to the forward buffer)
      receive(*p);
      return p + 1;
    }
    const std::uint8_t* const run = find_control(p, end);
    const auto n = static_cast<std::size_t>(run - p);
    (void)link_.receive_data(p, n);  // route::local: counted
    decoder_.push(byte_view(p, n), [this](const decode_result& result) { handle(result); });
    return run;
  }

  void handle(const decode_result& r) noexcept {
    switch (r.status) {
      case decode_status::incomplete:
        return;
      case decode_status::frame_error:
        ++counters_.frame_errors;
        netstat_ |= netstat_rx_frame_error;
        return;
      case decode_status::crc_error:
        ++counters_.crc_errors;
        netstat_ |= netstat_rx_crc_error;
        return;
      case decode_status::no_room:
        ++counters_.receive_overflows;
        netstat_ |= netstat_rx_overflow;
        return;
      case decode_status::message:
        break;
    }
    switch (r.msg.type) {
      case message_type::character:
        ++counters_.character_messages;
        return;
      case message_type::variable:
        switch (vr_->write(r.msg.vr, network_value::from_q32(r.msg.value))) {
          case vr_write::written:
            ++counters_.variables_written;
            return;
          case vr_write::refused:
            ++counters_.variables_refused;
            return;
          case vr_write::out_of_range:
          case vr_write::value_out_of_range:
            ++counters_.variables_out_of_range;
            return;
        }
        return;
      case message_type::keypad_offset:
      case message_type::keypad_mode:
        ++counters_.keypad_messages_ignored;
        return;
    }
  }

  using link_type = link<ForwardCapacity, TransmitCapacity, Crc, Layout>;
  link_type link_;
  basic_decoder<receive_buffer<ReceiveCapacity>, ReceiveCapacity, Crc, Layout> decoder_;
  vr_store* vr_;
  const defkey_table* defkey_;
  motion_coordinator_counters counters_;
  std::uint8_t netstat_ = 0;
};

}  // namespace trionet::ring
