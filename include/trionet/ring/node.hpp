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
// Cost: the link's and the decoder's RAM plus 7 bytes of NETSTAT and the node's counters. Per byte O(1);
// the bulk forms copy runs of message data whole. `receive`, `transmit`, `relay` and `line_idle` may run in
// an ISR.
#pragma once

#include <cstddef>
#include <cstdint>

#include "trionet/attributes.hpp"
#include "trionet/ring/bytes.hpp"
#include "trionet/ring/decoder.hpp"
#include "trionet/ring/link.hpp"
#include "trionet/span.hpp"
#include "trionet/transport.hpp"

namespace trionet::ring {

/// NETSTAT bits (docs/protocol.md 1.6).
enum netstat_bit : std::uint8_t {
  netstat_tx_timeout = 1,       ///< an own message could not be put into the transmit queue
  netstat_tx_buffer_error = 2,  ///< a forwarded message was lost (buffer full, too long, or the line idle)
  netstat_rx_crc_error = 4,     ///< a direct variable transfer failed its CRC
  netstat_rx_frame_error = 8,   ///< an incomplete or corrupt message was received
  netstat_rx_overflow = 16,     ///< a character transfer did not fit in the receive buffer (extension)
};

constexpr const char* to_string(netstat_bit bit) noexcept {
  switch (bit) {
    case netstat_tx_timeout:
      return "netstat_tx_timeout";
    case netstat_tx_buffer_error:
      return "netstat_tx_buffer_error";
    case netstat_rx_crc_error:
      return "netstat_rx_crc_error";
    case netstat_rx_frame_error:
      return "netstat_rx_frame_error";
    case netstat_rx_overflow:
      return "netstat_rx_overflow";
  }
  return "unknown";
}

/// NETSTAT: errors since it was last cleared (docs/protocol.md 1.6). The link side raises bits, the program side
/// reads and clears them, and each byte here is written by one side only: a raised bit is a bit in which
/// `raised_` differs from `cleared_`, and clearing makes them equal. Bit 0 (TX timeout) is the program side's
/// own. An error raised while NETSTAT is being cleared may be cleared with it.
class netstat_register {
 public:
  /// Link side: sets `bits` (not bit 0).
  void raise(std::uint8_t bits) noexcept {
    raised_ = static_cast<std::uint8_t>(raised_ ^ (bits & ~(raised_ ^ cleared_)));
  }
  /// Program side: sets bit 0.
  void raise_tx_timeout() noexcept { program_ = netstat_tx_timeout; }
  std::uint8_t read() const noexcept { return static_cast<std::uint8_t>((raised_ ^ cleared_) | program_); }
  void clear() noexcept {
    cleared_ = raised_;
    program_ = 0;
  }

 private:
  std::uint8_t raised_ = 0;
  std::uint8_t cleared_ = 0;
  std::uint8_t program_ = 0;
};

/// The ring-node core. `Node` (the derived node, CRTP) provides
///   void deliver(const decode_result&)   // a valid message for it (`message`), or one with no room (`no_room`)
/// `Counters` has at least `frame_errors` and `crc_errors`; `Decoder` is a `basic_decoder`; `Link` a
/// `detail::link`.
template <class Node, class Counters, class Decoder, class Link>
class node : public byte_port {
 public:
  // ---- the link (byte_port): per byte, for a UART interrupt ----

  void receive(std::uint8_t byte) noexcept final {
    const byte_route r = link_.receive(byte);
    if (r == byte_route::local) {
      handle(decoder_.push(byte));
      return;
    }
    if (classify(byte) == byte_class::header) handle(decoder_.interrupt());
  }
  [[nodiscard]] bool transmit(std::uint8_t& byte) noexcept final { return link_.transmit(byte); }
  [[nodiscard]] bool transmit_pending() const noexcept final { return link_.transmit_pending(); }

  /// The idle line (docs/protocol.md 1.10): a message open in the decoder is a frame error (NETSTAT bit 3); a
  /// message being forwarded is ended and counted as lost (NETSTAT bit 1); the node's own messages may then
  /// be sent.
  void line_idle() noexcept final {
    (void)link_.line_idle();
    handle(decoder_.line_idle());
  }
  [[nodiscard]] bool in_message() const noexcept final { return link_.passing_message() || decoder_.open(); }

  // ---- the link in bulk: a DMA-fed UART or a host ----

  /// Many received bytes at once (a DMA buffer, a read()): the same as `receive` for each, in order, with
  /// runs of message data copied whole. Not virtual, so firmware that does not call it does not link it.
  void receive(byte_view bytes) noexcept { receive_bytes(bytes); }
  /// Fills `out` with up to out.size() bytes to send and returns how many: the same bytes as that many calls
  /// of `transmit`, stopping at the first that has none.
  [[nodiscard]] std::size_t transmit(byte_buffer out) noexcept { return link_.transmit(out.data(), out.size()); }

  /// A DMA-fed node's receive-and-forward in one call: exactly `receive(in)` then `transmit(out)` (returns
  /// how many bytes of `out` to send). When the forward buffer is empty and the node is between its own
  /// messages, the bytes it forwards are written straight into `out`: one copy instead of two.
  [[nodiscard]] std::size_t relay(byte_view in, byte_buffer out) noexcept {
    if (!link_.straight_through(in.size(), out.size())) return receive_then_transmit(in, out);
    auto straight = Link::straight_buffer(out.data());
    receive_bytes(in, straight);
    return link_.transmit_after(straight, out.data(), out.size());
  }

  // ---- state ----

  /// NETSTAT: errors since it was last cleared (docs/protocol.md 1.6); cleared only by `clear_netstat`.
  /// Bit 1 (a forwarded message lost) is read off the link's counters, so the forwarding paths never touch it.
  std::uint8_t netstat() const noexcept {
    const bool forward_lost = link_.counters().forwards_failed() != forwards_failed_at_clear_;
    return static_cast<std::uint8_t>(netstat_.read() | (forward_lost ? netstat_tx_buffer_error : 0));
  }
  void clear_netstat() noexcept {
    netstat_.clear();
    forwards_failed_at_clear_ = link_.counters().forwards_failed();
  }

  const Counters& counters() const noexcept { return counters_; }
  const link_counters& forwarding_counters() const noexcept { return link_.counters(); }
  /// Bytes waiting in the forward buffer.
  std::size_t forward_backlog() const noexcept { return link_.forward_backlog(); }
  /// Room left in the transmit queue, in bytes (a message takes its data + 2).
  std::size_t transmit_free() const noexcept { return link_.transmit_free(); }

  /// The longest own frame the node sends, header and end of message included (docs/protocol.md 1.5: the forward
  /// buffer absorbs what arrives meanwhile).
  static constexpr std::size_t max_own_frame = Link::max_own_frame;

 protected:
  node() noexcept = default;
  /// A node whose decoder and link use `crc` (a CRC object such as `crc16_runtime`).
  template <class Crc>
  explicit node(const Crc& crc) noexcept : link_(crc), decoder_(crc) {}
  node(const node&) = default;
  node& operator=(const node&) = default;
  ~node() = default;

  Link link_;
  Decoder decoder_;
  Counters counters_{};
  netstat_register netstat_;
  std::uint32_t forwards_failed_at_clear_ = 0;  // the link's forwards_failed() when NETSTAT was cleared

 private:
  void handle(const decode_result& r) noexcept {
    switch (r.status) {
      case decode_status::incomplete:
        return;
      case decode_status::frame_error:
        ++counters_.frame_errors;
        netstat_.raise(netstat_rx_frame_error);
        return;
      case decode_status::crc_error:
        ++counters_.crc_errors;
        netstat_.raise(netstat_rx_crc_error);
        return;
      case decode_status::no_room:
      case decode_status::ok:
        static_cast<Node*>(this)->deliver(r);
        return;
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
      if (p == end) return;
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
  void passed_header() noexcept {
    if (decoder_.in_message()) {
      end_local_message();
    } else {
      decoder_.reset();  // out of a run of stray data or a skipped A = 0 message: nothing to report
    }
  }

  // A header through the node ended the message the node was receiving.
  TRIONET_NOINLINE void end_local_message() noexcept { handle(decoder_.interrupt()); }

  // Bytes for the node at `p`: one control byte, or a run of message data for the decoder. Returns the next.
  TRIONET_NOINLINE const std::uint8_t* receive_local(const std::uint8_t* p, const std::uint8_t* end) noexcept {
    if (!is_data(*p)) {  // a control byte for the node (it never goes to the forward buffer)
      receive(*p);
      return p + 1;
    }
    const std::uint8_t* const run = find_control(p, end);
    const auto n = static_cast<std::size_t>(run - p);
    (void)link_.receive_data(p, n);  // byte_route::local: counted
    decoder_.push(byte_view(p, n), [this](const decode_result& result) { handle(result); });
    return run;
  }
};

}  // namespace trionet::ring
