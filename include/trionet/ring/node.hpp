// The ring-node core (docs/protocol.md 1.4-1.6, 1.10): what every node on the fibre ring does with its link.
// `motion_coordinator` and `keypad` are this core plus what they do with a message for them (`deliver`).
//
//   link byte -> receive -+-> not for this node: forward buffer (A - 1) ---+
//                         |                                                +-> transmit -> link byte
//                         +-> for this node: decoder -> deliver(message)   |   forwarded bytes first, one
//                                  +-> frame / CRC error: counted          |   message at a time
//   program: PRINT#, SEND, key presses ------------> transmit queue -------+
//   idle line -> line_idle: ends an open message (counted)
//
// Forwarding (1.5, 1.10) is one state machine, `receive_slow` below, over `receiving_`:
//
//   byte            local (between messages,   forwarding (a message       dropping (the rest of a
//                   or one for the node)       passing through, type T)    message not passed on)
//   header A > 1    passed on with A - 1: forwarding T (no room: lost; forwarding off: dropping); any
//                   message open before it has ended
//   header A <= 1   to the decoder: local (A = 0: a frame error there); any message passing through ends
//   data            to the decoder             appended; past the bound    dropped
//                                              of T: cut; no room: lost
//   end of message  to the decoder             passed on with A - 1: local dropped: local
//                                              (no room: lost)
//   idle line       the decoder's open         ended: lost (counted)       local
//                   message: a frame error
//
// A lost message (`forwards_lost`: no room, `forwards_cut`: longer than legal, `forwards_ended_idle`) sets
// NETSTAT bit 1; it is removed whole if none of it has gone out, else cut short (its destination sees a frame
// error), and the rest of it is dropped. The forward buffer (detail/forward_buffer.hpp) takes a data byte of
// a message passing through on its fast path (`receive`: one comparison and one store); the state machine
// takes every other byte.
//
// Capacity rule: bytes arrive at most one per byte-time, so while the node sends an own frame of L bytes at
// most L forwarded bytes arrive. The forward buffer holds at least a direct variable transfer (16 bytes,
// checked at compile time) and the node never queues an own frame longer than it (`max_own_frame`: long
// PRINT# text goes as several messages): forwarded traffic is never lost to the node's own sending.
//
// Two sides, no lock (docs/design.md, "Contexts"; transport.hpp shows the wiring):
//   link side (one interrupt context: the UART ISR, or a host's I/O loop): receive and transmit (per byte and
//     bulk), line_idle, transmit_pending, in_message, forward_backlog, and everything a delivered message
//     does (deliver: the receive buffer, VR() through its vr_store, the keypad's display and mode)
//   program side (one thread context: the main loop or one RTOS task): PRINT#, SEND, GET#, KEY#, key
//     presses, transmit_free, netstat, clear_netstat, clear_counters
//   either side: counters, forwarding_counters (each counter is read whole; not all at one instant)
// The transmit queue is a single-producer, single-consumer queue between them, NETSTAT a netstat register
// (each side writes one byte), and every counter is written by one side only: `clear_counters` clears the
// program side's and raises a flag on which the link side clears its own, before it next counts.
//
// What became of a message is the answer of the byte that ended it (`receive_status`, decode_result.hpp);
// every other byte answers `incomplete`.
//
// Cost: ForwardCapacity + TransmitCapacity bytes, the decoder's RAM and about 40 bytes. Per byte O(1).
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>

#include "trionet/detail/attributes.hpp"
#include "trionet/detail/crc_holder.hpp"
#include "trionet/detail/fifo.hpp"
#include "trionet/detail/forward_buffer.hpp"
#include "trionet/detail/netstat_register.hpp"
#include "trionet/detail/single_writer.hpp"
#include "trionet/ring/bytes.hpp"
#include "trionet/ring/decoder.hpp"
#include "trionet/ring/encode.hpp"
#include "trionet/ring/message.hpp"
#include "trionet/ring/netstat.hpp"
#include "trionet/span.hpp"
#include "trionet/transport.hpp"

namespace trionet::ring {

/// The ring-node core (see the file comment). `Node` (the derived node, CRTP) provides
///   void deliver(detail::decode_step)   // link side: a valid message for it (`ok`), or one with no room
///                                       // (`no_room`), still in the decoder
///   void clear_program_counters()       // program side, in `clear_counters`: the counters it writes
///   void clear_delivery_counters()      // link side: the counters `deliver` writes
/// `Decoder` is a `basic_decoder`, whose CRC policy and layout the node's own direct variable transfers use;
/// `Switchable`: whether forwarding can be turned off (a keypad).
template <class Node, class Decoder, std::size_t ForwardCapacity, std::size_t TransmitCapacity, bool Switchable>
class node : public byte_port,
             private detail::crc_holder<typename Decoder::crc_type>,
             private detail::forwarding_switch<Switchable> {
  using crc_type = typename Decoder::crc_type;
  using layout_type = typename Decoder::layout_type;
  static constexpr std::size_t max_characters = Decoder::max_characters;
  static_assert(ForwardCapacity >= framing_length + variable_data_length && ForwardCapacity < 65535,
                "the forward buffer must hold a whole direct variable transfer (16 bytes): while a node sends "
                "an own frame, as many forwarded bytes arrive as the frame has, and they must not be lost");
  static_assert(TransmitCapacity >= framing_length + 1 && TransmitCapacity <= 32767,
                "the transmit queue must hold at least a one-character message (3 bytes)");

 public:
  /// The longest own frame the node queues, header and end of message included: it fits in the transmit
  /// queue, and the forward buffer can absorb everything that arrives while it is sent.
  static constexpr std::size_t max_own_frame =
      ForwardCapacity < TransmitCapacity ? ForwardCapacity : TransmitCapacity;
  /// The most characters one own character message carries.
  static constexpr std::size_t max_own_characters =
      max_own_frame - framing_length < max_characters ? max_own_frame - framing_length : max_characters;
  /// The transmit queue's capacity in bytes (`transmit_free()` when nothing waits).
  static constexpr std::size_t transmit_capacity = TransmitCapacity;
  /// The forward buffer's capacity in bytes.
  static constexpr std::size_t forward_capacity = ForwardCapacity;

  // ---- the link side (byte_port): per byte, for a UART interrupt ----

  /// Link side: a byte arrived; returns what became of the message it ended (`incomplete`: none). A data byte
  /// of a message passing through takes the forward buffer's fast path (inlined into a caller that knows the
  /// node's type, e.g. the UART interrupt); every other byte the state machine.
  TRIONET_ALWAYS_INLINE receive_status receive(std::uint8_t byte) noexcept final {
    if (TRIONET_LIKELY(is_data(byte)) && TRIONET_LIKELY(forward_.put_fast(byte))) return receive_status::incomplete;
    return receive_slow(byte);
  }
  /// Link side: the next byte to send, if there is one now: forwarded bytes first, then the node's own frames,
  /// never mixing two messages. The next forwarded byte takes the fast path (inlined as `receive` is).
  [[nodiscard]] TRIONET_ALWAYS_INLINE bool transmit(std::uint8_t& byte) noexcept final {
    // The two paths meet in a whole register, so a caller that widens `byte` does not widen it again after
    // the fast path; the general path's result stays in a register too.
    std::size_t next;
    if (TRIONET_LIKELY(forward_.ready())) {
      next = forward_.take();
    } else {
      const int slow = transmit_slow();
      if (slow < 0) return false;
      next = static_cast<std::uint8_t>(slow);
    }
    byte = static_cast<std::uint8_t>(next);
    return true;
  }
  [[nodiscard]] bool transmit_pending() const noexcept final {  ///< Link side: `transmit` would give a byte now.
    return !forward_.empty() || !(forwarding_message() || queue_.empty());  // (parked: the queue has the rest)
  }
  /// Link side: the idle line (docs/protocol.md 1.10): a message open in the decoder is a frame error (NETSTAT
  /// bit 3); a message being forwarded is ended and counted as lost (NETSTAT bit 1), any later byte of it is
  /// stray data, and own messages may be sent. Returns what became of the message it ended.
  receive_status line_idle() noexcept final {
    if (forwarding_message()) {  // (the decoder is between messages: the message's header closed it)
      forward_.close();
      (void)lost(receive_status::forward_ended_idle);
      receiving_ = receiving::local;
      return receive_status::forward_ended_idle;
    }
    receiving_ = receiving::local;
    const detail::decode_step step = decoder_.close(frame_error::idle_line);
    return step == 0 ? receive_status::incomplete : handle(step);
  }
  /// Link side: true while a message has begun on the receive side and not ended (for this node, passing
  /// through it, or being dropped): what `line_idle` would end.
  [[nodiscard]] bool in_message() const noexcept final {
    return receiving_ != receiving::local || decoder_.open();
  }

  // ---- the link side in bulk: a DMA-fed UART, or a host's read() and write() ----

  /// Link side: many received bytes at once: exactly `receive` of each, in order, with the data of a message
  /// passing through copied a run at a time. Returns how many of the bytes ended a message (`receive` did not
  /// answer `incomplete`). Not virtual, so firmware that does not call it does not link it.
  std::size_t receive(byte_view bytes) noexcept {
    const std::uint8_t* p = bytes.begin();
    const std::uint8_t* const end = bytes.end();
    std::size_t ended = 0;
    while (p != end) {
      p = forward_.put_run(p, end);
      if (p != end) ended += receive_slow(*p++) != receive_status::incomplete;
    }
    return ended;
  }
  /// Link side: fills `out` with up to out.size() bytes to send and returns how many: exactly as many calls of
  /// `transmit`, stopping at the first that has none, with forwarded bytes copied a run at a time.
  [[nodiscard]] std::size_t transmit(byte_buffer out) noexcept {
    std::size_t n = 0;
    while (n < out.size()) {
      n += forward_.take_run(out.data() + n, out.size() - n);
      if (n == out.size()) break;
      const int next = transmit_slow();
      if (next < 0) break;
      out[n++] = static_cast<std::uint8_t>(next);
    }
    return n;
  }

  /// Link side: bytes waiting in the forward buffer.
  std::size_t forward_backlog() const noexcept { return forward_.size(); }

  // ---- the program side ----

  /// Program side: NETSTAT, errors since it was last cleared (docs/protocol.md 1.6); cleared only by
  /// `clear_netstat`.
  std::uint8_t netstat() const noexcept { return netstat_.read(); }
  void clear_netstat() noexcept { netstat_.clear(); }  ///< Program side: clears NETSTAT.
  /// Program side: room left in the transmit queue, in bytes (a message takes its data + 2).
  std::size_t transmit_free() const noexcept { return queue_.free(); }
  /// Program side: starts every count of `counters()` and `forwarding_counters()` again from 0 (not NETSTAT).
  /// The link side clears its own counters (one writer each) before it next counts; until then they read 0.
  void clear_counters() noexcept {
    static_cast<Node*>(this)->clear_program_counters();
    clearer_.store(&node::clear_link_counters_of, std::memory_order_relaxed);
    clear_asked_.raise();  // (release: the link side finds the pointer set)
  }

  /// Either side: the forwarding counters now (each read whole; not all at one instant).
  link_counters forwarding_counters() const noexcept {
    link_counters c;
    if (counters_clearing()) return c;
    c.forwards_lost = errors_[0].load();
    c.forwards_cut = errors_[1].load();
    c.forwards_ended_idle = errors_[2].load();
    c.messages_forwarded = messages_forwarded_.load();
    c.messages_dropped = this->dropped();
    c.messages_sent = messages_sent_.load();
    return c;
  }

 protected:
  node() noexcept = default;
  /// A node whose decoder and own frames use `crc` (a CRC object such as `crc16_runtime`).
  explicit node(const crc_type& crc) noexcept : detail::crc_holder<crc_type>(crc), decoder_(crc) {}
  node(const node&) = default;             ///< Copies a node (both sides idle).
  node& operator=(const node&) = default;  ///< Copies a node (both sides idle).
  ~node() = default;

  /// Program side: queues one of the node's own messages whole: `buffer_too_small` if the transmit queue has
  /// no room for all of it or it is longer than `max_own_frame` (nothing is queued), or the message's own field
  /// error.
  [[nodiscard]] encode_result queue(const message& m) noexcept {
    const encode_status checked = detail::check_message(m);
    if (checked != encode_status::ok) return {checked, 0};
    const std::size_t length = frame_length(m);
    if (length > queue_.free() || length > max_own_frame) return {encode_status::buffer_too_small, 0};
    if (m.type == message_type::character) {
      stage_characters(m.hops, m.text);  // straight into the queue: no staging copy of the text
    } else {
      std::uint8_t frame[framing_length + variable_data_length];
      (void)encode<crc_type, layout_type>(frame, m, this->crc());  // checked, and it fits
      queue_.stage(0, frame, length);
      queue_.publish(length);
    }
    return {encode_status::ok, length};
  }
  /// Program side: queues `text` (each character 0..127: checked by the caller) as consecutive character
  /// messages to `hops`, each as long as an own message may be (`max_own_characters`, the last one shorter),
  /// as many whole messages as the transmit queue has room for. Returns how many characters were queued. The
  /// split depends on the text only, so a caller that goes on with the rest later sends the same messages.
  std::size_t queue_text(std::uint8_t hops, byte_view text) noexcept {
    std::size_t done = 0;
    while (done < text.size()) {
      std::size_t n = text.size() - done;
      if (n > max_own_characters) n = max_own_characters;
      if (n + framing_length > queue_.free()) break;
      stage_characters(hops, byte_view(text.data() + done, n));
      done += n;
    }
    return done;
  }
  /// Program side: an own message could not be queued: NETSTAT bit 0.
  void raise_tx_timeout() noexcept { netstat_.raise_tx_timeout(); }
  /// Link side: raises NETSTAT `bits` (1..4).
  void raise_netstat(std::uint8_t bits) noexcept { netstat_.raise(bits); }
  /// Link side: forwarding on (a keypad in network mode) or off (local mode: messages through it are dropped
  /// and counted).
  void set_forwarding(bool forwarding) noexcept {
    static_assert(Switchable, "this node always forwards");
    this->on = forwarding;
  }

  /// Either side: true while the link side's counters read 0: a `clear_counters` it has not carried out yet.
  bool counters_clearing() const noexcept { return clear_asked_.raised(); }
  std::uint32_t frame_errors() const noexcept { return errors_[3].load(); }  ///< So far (link side writes).
  std::uint32_t crc_errors() const noexcept { return errors_[4].load(); }    ///< So far (link side writes).

  /// Link side, in `deliver`: the type of the message delivered (still in the decoder).
  message_type delivered_type() const noexcept { return decoder_.type(); }
  /// Link side, in `deliver`: the data of the message delivered, when it is not a character transfer.
  const std::uint8_t* delivered_payload() const noexcept { return decoder_.payload(); }
  /// Link side, in `deliver`: the whole message delivered by `step`.
  decode_result delivered(detail::decode_step step) const noexcept { return decoder_.result(step); }
  /// The decoder's character store (a Motion Coordinator's receive buffer: the program side reads it).
  auto& character_store() noexcept { return decoder_.store(); }
  /// The decoder's character store, read-only.
  const auto& character_store() const noexcept { return decoder_.store(); }

 private:
  // The receive side's state in one byte: `local` (between messages, or in one for the node: its bytes go to
  // the decoder), `dropping` the rest of a message, or `forward` | T, forwarding a message of type T.
  enum class receiving : std::uint8_t { local = 0, dropping = 1, forward = 0x80 };
  bool forwarding_message() const noexcept { return (static_cast<unsigned>(receiving_) & 0x80u) != 0; }
  std::uint8_t forward_type() const noexcept { return static_cast<std::uint8_t>(receiving_) & 0x07u; }

  // The forwarding bound (docs/protocol.md 1.5): the longest legal data of a message, by its header's type.
  // Type 1 and the reserved types 5..7: the character maximum; 2: a direct variable transfer; 3, 4: one.
  static constexpr std::uint16_t longest_data[8] = {0, max_characters, variable_data_length, 1, 1,
                                                    max_characters, max_characters, max_characters};

  // The state machine (see the file comment): a byte the fast path did not take, and what became of the
  // message it ended (a header that ends one message and loses its own answers for the second).
  TRIONET_NOINLINE receive_status receive_slow(std::uint8_t byte) noexcept {
    if (is_data(byte)) {
      if (receiving_ != receiving::local) return forward_data(byte);
    } else if (type_of(byte) == 0) {  // an end of message
      if (receiving_ != receiving::local) return forward_end(byte);
    } else {
      // A header, counted one way or another, ends the message passing through (cut short: `begin`, `close`).
      count_from_here();
      if (hops_of(byte) > 1 && this->forwarding()) return forward_header(byte);
      if (forwarding_message()) forward_.close();
      if (hops_of(byte) > 1) return drop_header();
      receiving_ = receiving::local;  // for this node (A = 0: the decoder reports it)
    }
    return decode(byte);
  }
  TRIONET_ALWAYS_INLINE receive_status forward_data(std::uint8_t byte) noexcept {
    if (receiving_ == receiving::dropping) return receive_status::incomplete;
    const detail::append_status appended = forward_.append(byte);
    if (appended == detail::append_status::ok) return receive_status::incomplete;
    return lose(appended == detail::append_status::full ? receive_status::forward_lost : receive_status::forward_cut);
  }
  TRIONET_ALWAYS_INLINE receive_status forward_end(std::uint8_t byte) noexcept {
    // (A message being dropped was answered for at its header, or when it was lost.)
    const receive_status ended = !forwarding_message()                 ? receive_status::incomplete
                                 : forward_.end(decrement_hops(byte)) ? receive_status::forwarded
                                                                      : lose(receive_status::forward_lost);
    receiving_ = receiving::local;  // the message has ended, lost or not: nothing of it is left to drop
    return ended;
  }
  TRIONET_ALWAYS_INLINE receive_status forward_header(std::uint8_t byte) noexcept {
    const receive_status ended = passed_header();
    messages_forwarded_.increment();
    receiving_ = static_cast<receiving>(0x80u | type_of(byte));
    if (!forward_.begin(static_cast<std::uint8_t>(byte - 0x08), longest_data[type_of(byte)])) {
      // No room for its header (A > 1: decrement_hops without its check): nothing of it is in the buffer.
      return lost(receive_status::forward_lost);
    }
    return ended;
  }
  receive_status drop_header() noexcept {  // a keypad in local mode
    (void)passed_header();
    receiving_ = receiving::dropping;
    if constexpr (Switchable) this->drops.increment();  // (counted here, `count_from_here` before)
    return receive_status::dropped;
  }
  // The message being forwarded is lost (`outcome`: counted, and answered): what of it is still in the forward
  // buffer goes if none of it has gone out, and the rest of it is dropped.
  receive_status lose(receive_status outcome) noexcept {
    forward_.lose(longest_data[forward_type()]);
    return lost(outcome);
  }
  receive_status lost(receive_status outcome) noexcept {
    count_from_here_cold();
    errors_[static_cast<unsigned>(outcome) - static_cast<unsigned>(receive_status::forward_lost)].increment();
    netstat_.raise(netstat_tx_buffer_error);
    receiving_ = receiving::dropping;
    return outcome;
  }

  // A header passed through the node: it ends any message the node was receiving, and the decoder is then
  // between messages.
  receive_status passed_header() noexcept {
    if (TRIONET_LIKELY(decoder_.idle())) return receive_status::incomplete;
    if (decoder_.in_message()) return handle(decoder_.close(frame_error::interrupted));
    decoder_.reset();  // out of a run of stray data or a skipped A = 0 message: nothing to report
    return receive_status::incomplete;
  }

  // A byte for the node's decoder, and what it completed: errors are counted here, messages go to the node.
  TRIONET_ALWAYS_INLINE receive_status decode(std::uint8_t byte) noexcept {
    const detail::decode_step step = decoder_.step(byte);
    return step == 0 ? receive_status::incomplete : handle(step);  // (0, incomplete: the common case)
  }
  TRIONET_NOINLINE receive_status handle(detail::decode_step step) noexcept {  // (step != 0)
    count_from_here_cold();
    const decode_status status = detail::status_of(step);
    if (status == decode_status::ok || status == decode_status::no_room) {
      static_cast<Node*>(this)->deliver(step);
    } else {  // a frame error or a CRC error: counted in that order, NETSTAT bit 3 or 2
      const unsigned error = static_cast<unsigned>(status) - static_cast<unsigned>(decode_status::frame_error);
      errors_[3 + error].increment();
      netstat_.raise(static_cast<std::uint8_t>(netstat_rx_frame_error >> error));
    }
    return detail::decode_outcome::of(status);
  }

  // Before the link side counts (a header, `handle`, `lost`, an own message's end going out), a
  // `clear_counters` asked for is carried out. The clearing code is reached through a pointer that
  // `clear_counters` sets before it asks, so that firmware that never clears links none of it.
  TRIONET_ALWAYS_INLINE void count_from_here() noexcept {
    if (clear_asked_.waiting()) count_from_here_cold();
  }
  TRIONET_NOINLINE void count_from_here_cold() noexcept {
    if (clear_asked_.raised()) clearer_.load(std::memory_order_relaxed)(*this);  // (acquire: the pointer is set)
  }
  static void clear_link_counters_of(node& self) noexcept { self.clear_link_counters(); }
  static inline std::atomic<void (*)(node&) noexcept> clearer_{nullptr};
  void clear_link_counters() noexcept {
    for (auto& c : errors_) c.store(0);
    messages_forwarded_.store(0);
    messages_sent_.store(0);
    if constexpr (Switchable) this->drops.store(0);
    static_cast<Node*>(this)->clear_delivery_counters();
    clear_asked_.lower();
  }

  // The transmitter's general path: own frames, the wrapped-round part of the forward buffer, message
  // boundaries. The next byte, or -1 for none.
  TRIONET_NOINLINE int transmit_slow() noexcept {
    std::uint8_t byte = 0;
    if (forward_.parked()) {  // in an own frame, which was queued whole
      if (!queue_.pop(byte)) {  // cannot happen
        forward_.unpark();
        return -1;
      }
      if (classify(byte) == byte_class::end_of_message) {
        forward_.unpark();
        count_from_here_cold();
        messages_sent_.increment();
      }
      return byte;
    }
    if (forward_.next_part()) return forward_.take();  // bytes that arrived meanwhile
    // The forward buffer is empty. A forwarded message open on the receive side has gone out so far
    // (cut-through): its next byte has not arrived. Otherwise the transmitter is between messages.
    if (forwarding_message() || !queue_.pop(byte)) return -1;
    forward_.park();
    return byte;
  }

  // Program side: one character message, staged and published whole. Precondition: it fits.
  void stage_characters(std::uint8_t hops, byte_view text) noexcept {
    queue_.stage(0, make_header(hops, static_cast<std::uint8_t>(message_type::character)));
    queue_.stage(1, text.data(), text.size());
    queue_.stage(1 + text.size(), make_end_of_message(hops));
    queue_.publish(text.size() + framing_length);
  }

  // The forward buffer's indices first, then the small members, the buffers last: a Cortex-M0+ reaches the
  // first 32 bytes of the node with one byte load or store, the next ones take an address computation more.
  detail::forward_buffer<ForwardCapacity> forward_;           // link side
  detail::netstat_register netstat_;                          // each side writes one byte
  receiving receiving_ = receiving::local;                    // link side
  detail::request_flag clear_asked_;  // `clear_counters` asked: the program side raises, the link side lowers
  detail::single_writer<std::uint16_t> messages_forwarded_;   // link side
  detail::single_writer<std::uint16_t> messages_sent_;        // link side
  // Link side: the wire errors, each counted by its `receive_status` (in the enum's order): forward_lost,
  // forward_cut, forward_ended_idle, then frame_error, crc_error.
  detail::single_writer<std::uint32_t> errors_[5];
  detail::spsc_fifo<TransmitCapacity> queue_;  // the transmit queue: the program side produces, the link side consumes
  Decoder decoder_;                            // the decoder of messages for this node (link side)
};

}  // namespace trionet::ring
