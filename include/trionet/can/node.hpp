// A TN20-17 VR-exchange node: one Motion Coordinator's side of the exchange (docs/protocol.md 2.1, 2.2).
//
// Sending: `send_to_node` (by destination node) or `send_on_channel` (by transmit channel 5..N+3, as the
// note's `send_vr` routine does) encodes VR(vr) = value and hands one frame to the `port`. Receiving: the
// owner of the CAN controller passes every received frame to `receive`. A frame on one of this node's receive
// identifiers is decoded and written to VR(vr) through the `vr_store` hook, the same write policy the ring
// node uses. Anything else is not an error to the caller: foreign frames (not ours) and malformed frames (by
// reason) are dropped and counted, as are writes the policy refused or that fall outside the VR table.
#pragma once

#include <cstdint>
#include <type_traits>

#include "trionet/can/frame.hpp"
#include "trionet/can/identifiers.hpp"
#include "trionet/can/port.hpp"
#include "trionet/can/vr_codec.hpp"
#include "trionet/detail/single_writer.hpp"
#include "trionet/detail/status_map.hpp"
#include "trionet/vr.hpp"

namespace trionet::can {

/// Which node of how many: a checked pair, made by `make_node_address`. Default: node 1 of 5.
/// Cost: 2 bytes.
class node_address {
 public:
  constexpr node_address() noexcept = default;
  /// The number of nodes on the bus (docs/protocol.md 2.1).
  [[nodiscard]] constexpr std::uint8_t node_count() const noexcept { return node_count_; }
  /// This node's number, 1 .. node_count().
  [[nodiscard]] constexpr std::uint8_t node() const noexcept { return node_; }

 private:
  constexpr node_address(std::uint8_t node_count, std::uint8_t node) noexcept
      : node_count_(node_count), node_(node) {}
  friend constexpr struct address_result make_node_address(std::uint8_t, std::uint8_t) noexcept;

  std::uint8_t node_count_ = default_node_count;
  std::uint8_t node_ = 1;
};

/// A node address, or why the pair is invalid (`bad_node_count`, `bad_node`).
struct [[nodiscard]] address_result {
  /// `ok`, or why the pair is invalid.
  scheme_status status = scheme_status::ok;
  /// The address (meaningful for `ok`).
  node_address address{};
  /// True for `ok`.
  constexpr explicit operator bool() const noexcept { return status == scheme_status::ok; }
};

/// Checks that `node` is 1..node_count and node_count is 2..11.
[[nodiscard]] constexpr address_result make_node_address(std::uint8_t node_count,
                                                         std::uint8_t node) noexcept {
  const scheme_status status = detail::check_node(node_count, node);
  if (status != scheme_status::ok) return {status, {}};
  return {scheme_status::ok, node_address(node_count, node)};
}

/// What became of a send request. Everything but `ok` means no frame was queued. The encoder's failures
/// (`encode_status`) and the port's (`transmit_status`, as `port_*`) keep their names and order here.
enum class send_status : std::uint8_t {
  ok,                     ///< the port queued the frame
  no_such_node,           ///< destination outside 1..N
  own_node,               ///< destination is this node
  no_such_channel,        ///< transmit channel outside 5..N+3
  vr_out_of_range,        ///< vr > 255
  not_a_number,           ///< value is NaN
  too_large,              ///< |value| rounds to 2^32 or more
  fraction_out_of_range,  ///< parts-based fraction > 9999
  port_busy,              ///< the port had no room (counted in `send_busy`)
  port_failed,            ///< the port failed (counted in `send_failed`)
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(send_status status) noexcept {
  switch (status) {
    case send_status::ok:
      return "ok";
    case send_status::no_such_node:
      return "no_such_node";
    case send_status::own_node:
      return "own_node";
    case send_status::no_such_channel:
      return "no_such_channel";
    case send_status::vr_out_of_range:
      return "vr_out_of_range";
    case send_status::not_a_number:
      return "not_a_number";
    case send_status::too_large:
      return "too_large";
    case send_status::fraction_out_of_range:
      return "fraction_out_of_range";
    case send_status::port_busy:
      return "port_busy";
    case send_status::port_failed:
      return "port_failed";
  }
  return "unknown";
}

/// What became of a received frame. Only `ok` changed a VR. The VR store's outcomes (`vr_write_status`) and
/// the decoder's (`decode_status`) keep their names and order here; each has its counter in `node_counters`.
enum class receive_status : std::uint8_t {
  ok,                  ///< VR(vr) now holds the value
  refused,             ///< the write policy refused the vr
  out_of_range,        ///< vr is past the end of the VR table
  value_out_of_range,  ///< the VR table's value type cannot hold the value (a Q32.32 table)
  foreign,             ///< not one of this node's receive identifiers (or an extended or remote frame)
  bad_dlc,             ///< ours, but not exactly 8 data bytes
  bad_sign,            ///< ours, but the sign byte is not 0 or 1
  bad_fraction,        ///< ours, but the fraction exceeds 9999
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(receive_status status) noexcept {
  switch (status) {
    case receive_status::ok:
      return "ok";
    case receive_status::refused:
      return "refused";
    case receive_status::out_of_range:
      return "out_of_range";
    case receive_status::value_out_of_range:
      return "value_out_of_range";
    case receive_status::foreign:
      return "foreign";
    case receive_status::bad_dlc:
      return "bad_dlc";
    case receive_status::bad_sign:
      return "bad_sign";
    case receive_status::bad_fraction:
      return "bad_fraction";
  }
  return "unknown";
}

/// A received frame's fate, and for frames on our identifiers, who sent it on which receive channel and what
/// it said (`message` is meaningful for ok, refused, out_of_range and value_out_of_range;
/// `to_double(message.value)` gives the value as a double).
struct receive_result {
  /// The frame's fate.
  receive_status status = receive_status::foreign;
  /// The node that sent it (frames on our identifiers).
  std::uint8_t sender = 0;
  /// The receive channel it came in on.
  std::uint8_t receive_channel = 0;
  /// What it said (see above for the statuses it is meaningful for).
  vr_message message{};
  /// True for `ok`.
  constexpr explicit operator bool() const noexcept { return status == receive_status::ok; }
};

/// Counts since construction or `clear_counters`, as read at one moment. Each wraps at 2^32.
struct node_counters {
  std::uint32_t sent = 0;                ///< frames the port queued
  std::uint32_t send_busy = 0;           ///< frames the port had no room for
  std::uint32_t send_failed = 0;         ///< frames the port failed to take
  std::uint32_t written = 0;             ///< VR writes applied
  std::uint32_t refused = 0;             ///< VR writes the policy refused
  std::uint32_t out_of_range = 0;        ///< VR writes past the end of the VR table
  std::uint32_t value_out_of_range = 0;  ///< VR writes whose value the VR table's type cannot hold
  std::uint32_t foreign = 0;             ///< frames not for this node
  std::uint32_t bad_dlc = 0;             ///< frames for this node with DLC != 8
  std::uint32_t bad_sign = 0;            ///< frames for this node with a sign byte other than 0 or 1
  std::uint32_t bad_fraction = 0;        ///< frames for this node with a fraction > 9999

  /// All malformed frames for this node, whatever the reason.
  [[nodiscard]] constexpr std::uint32_t malformed() const noexcept {
    return bad_dlc + bad_sign + bad_fraction;
  }
};

}  // namespace trionet::can

namespace trionet::detail {

// Where a node keeps its byte order: nothing when it is fixed at compile time (`fixed_byte_order`), one byte
// when it is chosen at run time (`byte_order`).
template <class Order>
class order_holder {
 protected:
  constexpr order_holder() noexcept = default;
  static constexpr can::byte_order held_order() noexcept { return Order::value; }
};

template <>
class order_holder<can::byte_order> {
 protected:
  constexpr order_holder() noexcept = default;
  constexpr explicit order_holder(can::byte_order order) noexcept : order_(order) {}
  constexpr can::byte_order held_order() const noexcept { return order_; }

 private:
  can::byte_order order_ = can::byte_order::big_endian;
};

}  // namespace trionet::detail

namespace trionet::can {

/// One controller on the exchange. Holds its address, a reference to its port and VR store, and counters.
/// Cost: 11 counters and their values at the last clear (88 bytes), two pointers and a 2-byte address
/// (100 bytes on a 32-bit MCU); `send_*` and `receive` are O(1) with one virtual call each (port or store).
///
/// Sides, with no lock and no interrupt masking (docs/design.md, "Contexts"): `receive` is the receive side
/// (the CAN receive ISR: the `vr_store` is written there, e.g. a `vr_table`); `send_*`, `counters` and
/// `clear_counters` are the program side (one thread context; the port decides whether it may be called from
/// an ISR instead). Each counter is written by one side only: `clear_counters` does not touch the receive
/// side's, it notes their values, and `counters` reports the counts since. Two contexts must not both send
/// (or both receive) at once.
///
/// `Order` is the byte order of the messages' numbers (vr_codec.hpp): `byte_order` (the `vr_exchange_node`
/// alias) when it is chosen at run time, passed to the constructor (default big-endian);
/// `fixed_byte_order<...>` when it is fixed at compile time, as firmware that knows its network may prefer
/// (smaller code; the same RAM on a 32-bit MCU, where the run-time order's byte sits in padding).
template <class Order = byte_order>
class basic_vr_exchange_node : private detail::order_holder<Order> {
 public:
  /// constexpr, so that a node defined at namespace scope in firmware is constant-initialized (no start-up
  /// code).
  constexpr basic_vr_exchange_node(node_address address, port& port, vr_store& store) noexcept
      : address_(address), port_(&port), store_(&store) {}
  /// The same with the byte order of the messages' numbers, for a node whose order is chosen at run time.
  template <class O = Order, std::enable_if_t<std::is_same_v<O, byte_order>, int> = 0>
  constexpr basic_vr_exchange_node(node_address address, port& port, vr_store& store, byte_order order) noexcept
      : detail::order_holder<Order>(order), address_(address), port_(&port), store_(&store) {}

  /// Which node of how many this is.
  [[nodiscard]] node_address address() const noexcept { return address_; }
  /// The byte order of the numbers in the messages it sends and receives.
  [[nodiscard]] constexpr byte_order order() const noexcept { return this->held_order(); }
  /// Program side: the counts since construction or `clear_counters` (each read whole; not all at one
  /// instant).
  [[nodiscard]] node_counters counters() const noexcept {
    node_counters c;
    c.sent = sends_[0].load() - cleared_.sent;
    c.send_busy = sends_[1].load() - cleared_.send_busy;
    c.send_failed = sends_[2].load() - cleared_.send_failed;
    c.written = writes_[0].load() - cleared_.written;
    c.refused = writes_[1].load() - cleared_.refused;
    c.out_of_range = writes_[2].load() - cleared_.out_of_range;
    c.value_out_of_range = writes_[3].load() - cleared_.value_out_of_range;
    c.foreign = foreign_.load() - cleared_.foreign;
    c.bad_dlc = malformed_[0].load() - cleared_.bad_dlc;
    c.bad_sign = malformed_[1].load() - cleared_.bad_sign;
    c.bad_fraction = malformed_[2].load() - cleared_.bad_fraction;
    return c;
  }
  /// Program side: starts every count again from 0.
  void clear_counters() noexcept {
    const node_counters now = counters();
    cleared_.sent += now.sent;
    cleared_.send_busy += now.send_busy;
    cleared_.send_failed += now.send_failed;
    cleared_.written += now.written;
    cleared_.refused += now.refused;
    cleared_.out_of_range += now.out_of_range;
    cleared_.value_out_of_range += now.value_out_of_range;
    cleared_.foreign += now.foreign;
    cleared_.bad_dlc += now.bad_dlc;
    cleared_.bad_sign += now.bad_sign;
    cleared_.bad_fraction += now.bad_fraction;
  }

  /// Sends VR(vr) = value (rounded to 4 decimals) to node `destination`.
  [[nodiscard]] send_status send_to_node(std::uint8_t destination, std::uint16_t vr, double value) noexcept {
    const send_status checked = check_destination(destination);
    if (checked != send_status::ok) return checked;
    frame out;
    const encode_status encoded = encode_vr(vr, value, out.data, order());
    if (encoded != encode_status::ok) return encode_failure::of(encoded);
    return transmit(identifier_to(destination), out);
  }

  /// Sends `message` (parts, no double arithmetic) to node `destination`.
  [[nodiscard]] send_status send_to_node(std::uint8_t destination, const vr_message& message) noexcept {
    const send_status checked = check_destination(destination);
    if (checked != send_status::ok) return checked;
    frame out;
    const encode_status encoded = encode_vr_message(message, out.data, order());
    if (encoded != encode_status::ok) return encode_failure::of(encoded);
    return transmit(identifier_to(destination), out);
  }

  /// Sends VR(vr) = value through transmit channel 5..N+3 (channel 5 is the next node round the ring).
  [[nodiscard]] send_status send_on_channel(std::uint8_t transmit_channel, std::uint16_t vr,
                                            double value) noexcept {
    const node_result destination = destination_of(address_.node_count(), address_.node(), transmit_channel);
    if (!destination) return send_status::no_such_channel;
    return send_to_node(destination.node, vr, value);
  }

  /// Sends `message` through transmit channel 5..N+3.
  [[nodiscard]] send_status send_on_channel(std::uint8_t transmit_channel,
                                            const vr_message& message) noexcept {
    const node_result destination = destination_of(address_.node_count(), address_.node(), transmit_channel);
    if (!destination) return send_status::no_such_channel;
    return send_to_node(destination.node, message);
  }

  /// Receive side: accepts one frame from the bus: if it is on one of this node's receive identifiers, decodes
  /// it and writes VR(vr) through the store; otherwise classifies and counts it. Never fails.
  receive_result receive(const frame& received) noexcept {
    receive_result result;
    // This node's receive identifiers are 10k .. 10k + N - 2 (docs/protocol.md 2.1): one unsigned comparison
    // also rejects identifiers below them and any with the extended or remote flag set. (`route_of` answers
    // the same for any identifier; a test checks that they agree.)
    const std::uint8_t k = address_.node();
    const std::uint32_t offset = received.id - 10U * k;
    if (offset >= address_.node_count() - 1U) {
      foreign_.increment();
      result.status = receive_status::foreign;
      return result;
    }
    result.receive_channel = static_cast<std::uint8_t>(offset + 1U);
    result.sender = static_cast<std::uint8_t>(result.receive_channel < k ? offset + 1U : offset + 2U);
    const decode_result decoded = decode_vr_frame(received, order());
    if (decoded.status != decode_status::ok) {  // counted by reason: the counters are in the enum's order
      malformed_[static_cast<unsigned>(decoded.status) - 1U].increment();
      result.status = decode_failure::of(decoded.status);
      return result;
    }
    result.message = decoded.message;
    const vr_value& v = decoded.message.value;
    vr_write_status written = store_->write(decoded.message.vr,
                                            network_value::from_decimal(v.negative, v.integer_part, v.fraction));
    // A store that answers outside the enum is read as the last outcome, as it always has been.
    if (static_cast<unsigned>(written) > static_cast<unsigned>(vr_write_status::value_out_of_range)) {
      written = vr_write_status::value_out_of_range;
    }
    writes_[static_cast<unsigned>(written)].increment();  // the counters are in the enum's order
    result.status = write_outcome::of(written);
    return result;
  }

 private:
  // The statuses of the codec, the port and the VR store as outcomes of a send or a receive.
  using encode_failure =
      detail::status_map<encode_status::vr_out_of_range, encode_status::fraction_out_of_range,
                         send_status::vr_out_of_range>;
  using port_failure = detail::status_map<transmit_status::busy, transmit_status::failed, send_status::port_busy>;
  using decode_failure =
      detail::status_map<decode_status::bad_dlc, decode_status::bad_fraction, receive_status::bad_dlc>;
  using write_outcome =
      detail::status_map<vr_write_status::ok, vr_write_status::value_out_of_range, receive_status::ok>;

  // Whether this node may send to `destination`: one of the other nodes 1..N.
  [[nodiscard]] send_status check_destination(std::uint8_t destination) const noexcept {
    if (destination < 1 || destination > address_.node_count()) return send_status::no_such_node;
    return destination == address_.node() ? send_status::own_node : send_status::ok;
  }

  // The identifier of a frame from this node to `destination` (checked): 10d + rank - 1, where rank is this
  // node's place among the nodes other than d (what `exchange_identifier` gives, without re-checking this
  // node's own, already valid, address).
  [[nodiscard]] std::uint16_t identifier_to(std::uint8_t destination) const noexcept {
    const std::uint8_t k = address_.node();
    const unsigned rank = k < destination ? k : k - 1U;
    return static_cast<std::uint16_t>(10U * destination + rank - 1U);
  }

  [[nodiscard]] send_status transmit(std::uint16_t identifier, frame& out) noexcept {
    out.id = identifier;
    out.dlc = vr_message_size;
    transmit_status sent = port_->send(out);
    // A port that answers outside the enum is read as a failure, as it always has been.
    if (static_cast<unsigned>(sent) > static_cast<unsigned>(transmit_status::failed)) sent = transmit_status::failed;
    sends_[static_cast<unsigned>(sent)].increment();  // the counters are in the enum's order
    return sent == transmit_status::ok ? send_status::ok : port_failure::of(sent);
  }

  node_address address_;
  port* port_;
  vr_store* store_;
  // Written by the program side:
  detail::single_writer<std::uint32_t> sends_[3];  // by transmit_status: sent, send_busy, send_failed
  node_counters cleared_{};  // every count at the last clear_counters (program side only)
  // Written by the receive side:
  detail::single_writer<std::uint32_t> writes_[4];  // by vr_write_status: written .. value_out_of_range
  detail::single_writer<std::uint32_t> foreign_;
  detail::single_writer<std::uint32_t> malformed_[3];  // by decode_status: bad_dlc, bad_sign, bad_fraction
};

/// A node whose byte order is chosen at run time (the constructor's last argument; default big-endian).
using vr_exchange_node = basic_vr_exchange_node<>;

}  // namespace trionet::can
