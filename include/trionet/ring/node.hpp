// The core that every node on the fibre ring shares (docs/protocol.md 1.4-1.6, 1.10): the link (decrement and
// forward, forwarded traffic first, the forwarding bound), the destination's decoder, the idle line, NETSTAT
// and the receive-side counters, and the bulk paths for DMA-fed links. `motion_coordinator` and `keypad` are
// this core plus what they do with a message for them (`deliver`).
//
//   link byte -> receive -+-> link: not for this node -> forward buffer --+
//                         |                                               +-> transmit -> link byte
//                         +-> decoder: for this node -> deliver(message)  |
//                                  +-> frame / CRC error: counted         |
//   program: PRINT#, SEND, key presses --------------> transmit queue ----+
//   idle line --> line_idle: ends an open message in the decoder and in the link (counted)
//
// Two sides, no lock (docs/design.md, "Contexts"; transport.hpp shows the wiring):
//   link side (one interrupt context: the UART ISR, or a host's I/O loop)
//     receive (per byte and bulk), transmit (per byte and bulk), relay, line_idle, transmit_pending,
//     in_message, forward_backlog; and everything that a delivered message does (deliver: the receive
//     buffer, VR() through its vr_store, the keypad's display and mode)
//   program side (one thread context: the main loop or one RTOS task)
//     PRINT#, SEND, GET#, KEY#, key presses, transmit_free, netstat, clear_netstat
//   either side: counters, forwarding_counters (each counter is read whole; not all at one instant)
// The link side may interrupt the program side at any instruction; neither masks the other. The buffers
// between them are single-producer, single-consumer queues (the transmit queue, the receive buffer), NETSTAT
// is a `netstat_register`, and every counter is written by one side only.
//
// Cost: the link's and the decoder's RAM plus 8 bytes of counters. Per byte O(1); a data byte of a message
// passing through takes the link's fast path. The bulk forms copy runs of message data whole.
#pragma once

#include <cstddef>
#include <cstdint>

#include "trionet/attributes.hpp"
#include "trionet/ring/bytes.hpp"
#include "trionet/ring/decoder.hpp"
#include "trionet/ring/link.hpp"
#include "trionet/ring/netstat.hpp"
#include "trionet/single_writer.hpp"
#include "trionet/span.hpp"
#include "trionet/transport.hpp"

namespace trionet::ring {

/// The ring-node core. `Node` (the derived node, CRTP) provides
///   void deliver(decode_step)   // a valid message for it (`ok`), or one with no room (`no_room`), still in
///                               // the decoder
/// which runs on the link side. Every message ends with its end of message, a control byte, which the node
/// takes one at a time in the bulk paths too: so messages are delivered only there. `Decoder` is a
/// `basic_decoder`; `Link` a `detail::link`.
template <class Node, class Decoder, class Link>
class node : public byte_port {
 public:
  // ---- the link side (byte_port): per byte, for a UART interrupt ----

  /// Link side: a byte arrived. A data byte of a message passing through takes the fast path (inlined into
  /// a caller that knows the node's type, e.g. the UART interrupt).
  TRIONET_ALWAYS_INLINE void receive(std::uint8_t byte) noexcept final {
    if (TRIONET_LIKELY(is_data(byte))) {
      if (TRIONET_LIKELY(link_.forward_fast(byte))) return;
#if !defined(__OPTIMIZE_SIZE__)  // the next steps on hosts; with -Os straight to the general paths (size)
      if (link_.local_data(byte) && decoder_.take(byte)) return;  // a data byte of a message for the node
      return receive_next_data(byte);
    }
    receive_next_control(byte);
#else
      return receive_data_general(byte);
    }
    receive_control_general(byte);
#endif
  }
  /// Link side: the next byte to send, if there is one now. The next forwarded byte takes the fast path
  /// (inlined as `receive` is).
  [[nodiscard]] TRIONET_ALWAYS_INLINE bool transmit(std::uint8_t& byte) noexcept final {
    return link_.transmit(byte);
  }
  /// Link side: true when `transmit` would give a byte now.
  [[nodiscard]] bool transmit_pending() const noexcept final { return link_.transmit_pending(); }

  /// Link side: the idle line (docs/protocol.md 1.10): a message open in the decoder is a frame error
  /// (NETSTAT bit 3); a message being forwarded is ended and counted as lost (NETSTAT bit 1); the node's own
  /// messages may then be sent.
  void line_idle() noexcept final {
    (void)link_.line_idle();
    handle(decoder_.close(frame_error::idle_line));
  }
  /// Link side: true while a message has begun on the receive side and not ended.
  [[nodiscard]] bool in_message() const noexcept final { return link_.passing_message() || decoder_.open(); }

  // ---- the link side in bulk: a DMA-fed UART or a host ----

  /// Link side: many received bytes at once (a DMA buffer, a read()): the same as `receive` for each, in
  /// order, with runs of message data copied whole. Not virtual, so firmware that does not call it does not
  /// link it.
  void receive(byte_view bytes) noexcept { receive_bytes(bytes); }
  /// Link side: fills `out` with up to out.size() bytes to send and returns how many: the same bytes as that
  /// many calls of `transmit`, stopping at the first that has none.
  [[nodiscard]] std::size_t transmit(byte_buffer out) noexcept { return link_.transmit(out.data(), out.size()); }

  /// Link side: a DMA-fed node's receive-and-forward in one call: exactly `receive(in)` then `transmit(out)`
  /// (returns how many bytes of `out` to send). When the forward buffer is empty and the node is between its
  /// own messages, the bytes it forwards are written straight into `out`: one copy instead of two.
  [[nodiscard]] std::size_t relay(byte_view in, byte_buffer out) noexcept {
    if (!link_.straight_through(in.size(), out.size())) return receive_then_transmit(in, out);
    auto straight = Link::straight_buffer(out.data());
    receive_bytes(in, straight);
    return link_.transmit_after(straight, out.data(), out.size());
  }

  /// Link side: bytes waiting in the forward buffer.
  std::size_t forward_backlog() const noexcept { return link_.forward_backlog(); }

  // ---- the program side ----

  /// Program side: NETSTAT, errors since it was last cleared (docs/protocol.md 1.6); cleared only by
  /// `clear_netstat`.
  std::uint8_t netstat() const noexcept { return link_.netstat().read(); }
  /// Program side: clears NETSTAT.
  void clear_netstat() noexcept { link_.netstat().clear(); }
  /// Program side: room left in the transmit queue, in bytes (a message takes its data + 2).
  std::size_t transmit_free() const noexcept { return link_.transmit_free(); }

  /// Either side: the link's counters now.
  link_counters forwarding_counters() const noexcept { return link_.counters(); }

  /// The longest own frame the node sends, header and end of message included (docs/protocol.md 1.5: the
  /// forward buffer absorbs what arrives meanwhile).
  static constexpr std::size_t max_own_frame = Link::max_own_frame;
  /// The transmit queue's capacity in bytes (`transmit_free()` when nothing waits).
  static constexpr std::size_t transmit_capacity = Link::transmit_capacity;
  /// The forward buffer's capacity in bytes.
  static constexpr std::size_t forward_capacity = Link::forward_capacity;

 protected:
  node() noexcept = default;
  /// A node whose decoder and link use `crc` (a CRC object such as `crc16_runtime`).
  template <class Crc>
  explicit node(const Crc& crc) noexcept : link_(crc), decoder_(crc) {}
  /// Copies a node (both sides idle).
  node(const node&) = default;
  /// Copies a node (both sides idle).
  node& operator=(const node&) = default;
  ~node() = default;

  /// Frame errors so far (link side writes).
  std::uint32_t frame_errors() const noexcept { return frame_errors_.load(); }
  /// CRC errors so far (link side writes).
  std::uint32_t crc_errors() const noexcept { return crc_errors_.load(); }

  Link link_;  ///< the link (forward buffer, transmit queue, NETSTAT, its counters)

 private:
  single_writer<std::uint32_t> frame_errors_;  // link side
  single_writer<std::uint32_t> crc_errors_;    // link side

 protected:
  Decoder decoder_;  ///< the decoder of messages for this node (link side)

 private:
#if !defined(__OPTIMIZE_SIZE__)
  // The next steps (hosts): the common bytes of traffic through the node, each in a function whose common
  // path saves no register (the rest goes on to the general paths, tail calls).
  TRIONET_NOINLINE void receive_next_data(std::uint8_t byte) noexcept {
    if (link_.renew(byte) || link_.next_data(byte)) return;
    receive_data_general(byte);
  }
  TRIONET_NOINLINE void receive_next_control(std::uint8_t byte) noexcept {
    if (!link_.next_control(byte)) return receive_control_general(byte);
    if (type_of(byte) != 0) passed_header();
  }
#endif
  // The general paths: a data byte that the fast path refused, and a header or end of message.
  TRIONET_NOINLINE void receive_data_general(std::uint8_t byte) noexcept {
    if (link_.route_data(byte) == byte_route::local) decode(byte);
  }
  TRIONET_NOINLINE void receive_control_general(std::uint8_t byte) noexcept {
    const byte_route r = link_.route_control(byte);
    if (r == byte_route::local) {
      decode(byte);
    } else if (type_of(byte) != 0) {
      passed_header();
    }
  }
  // A byte for the node's decoder.
  TRIONET_FAST_PATH void decode(std::uint8_t byte) noexcept { handle(decoder_.step(byte)); }

  // What a step of the decoder completed: errors are counted here, messages go to the node.
  void handle(decode_step step) noexcept {
    if (step != 0) completed(step);  // 0: incomplete, the common case
  }
  TRIONET_NOINLINE void completed(decode_step step) noexcept {
    const decode_status status = status_of(step);
    if (status == decode_status::ok || status == decode_status::no_room) {
      static_cast<Node*>(this)->deliver(step);
    } else {
      count_error(status);
    }
  }
  // A message for the node that the decoder discarded: a CRC error, else a frame error (the only other
  // status of a completed step).
  void count_error(decode_status status) noexcept {
    if (status == decode_status::crc_error) {
      crc_errors_.increment();
      link_.netstat().raise(netstat_rx_crc_error);
    } else {
      frame_errors_.increment();
      link_.netstat().raise(netstat_rx_frame_error);
    }
  }

  // The bulk receive: traffic through the node a run at a time (into the forward buffer, or the stand-in
  // given), bytes for the node to the decoder (out of line, so that the forwarding loop stays small).
  template <class... Straight>
  TRIONET_ALWAYS_INLINE void receive_bytes(byte_view bytes, Straight&... straight) noexcept {
    const std::uint8_t* p = bytes.begin();
    const std::uint8_t* const end = bytes.end();
    for (;;) {
      const auto passed = link_.receive_passing(p, end, straight...);
      if (passed.header) passed_header();
      p = passed.stop;
      if (TRIONET_LIKELY(p == end)) return;
      p = receive_local(p, end);
    }
  }

  // `relay` when it cannot go straight through (out of line, so that the straight path stays small).
  TRIONET_NOINLINE std::size_t receive_then_transmit(byte_view in, byte_buffer out) noexcept {
    receive(in);
    return transmit(out);
  }

  // A header passed through the node: it ends any message the node was receiving, and the decoder is then
  // between messages.
  TRIONET_ALWAYS_INLINE void passed_header() noexcept {
    if (TRIONET_LIKELY(decoder_.idle())) return;
    passed_header_slow();
  }
  TRIONET_NOINLINE void passed_header_slow() noexcept {
    if (decoder_.in_message()) {
      end_local_message();
    } else {
      decoder_.reset();  // out of a run of stray data or a skipped A = 0 message: nothing to report
    }
  }

  // A header through the node ended the message the node was receiving.
  void end_local_message() noexcept { handle(decoder_.close(frame_error::interrupted)); }

  // Bytes for the node at `p`: one control byte, or a run of message data for the decoder. Returns the next.
  TRIONET_NOINLINE const std::uint8_t* receive_local(const std::uint8_t* p, const std::uint8_t* end) noexcept {
    if (!is_data(*p)) {  // a control byte for the node (it never goes to the forward buffer)
      receive_control_general(*p);
      return p + 1;
    }
    const std::uint8_t* const run = find_control(p, end);
    const auto n = static_cast<std::size_t>(run - p);
    (void)link_.receive_data(p, n);  // byte_route::local
    // Data alone completes no message (its end of message is a control byte, above): the decoder can only
    // report stray data here.
    decoder_.push(byte_view(p, n), [this](const decode_result& result) { count_error(result.status); });
    return run;
  }

};

}  // namespace trionet::ring
