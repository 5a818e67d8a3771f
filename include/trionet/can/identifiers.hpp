// TN20-17 identifier scheme: which 11-bit CAN identifier carries a VR from one controller to another
// (docs/protocol.md 2.1).
//
// Node k = 1..N has base identifier 10k. Its receive channel r = 1..N-1 (message buffer r) listens on
// identifier 10k + r - 1 and hears the r-th other node in ascending order. Its transmit channel 4 + c
// (c = 1..N-1, message buffers 5..N+3) sends to node ((k - 1 + c) mod N) + 1, so channel 5 is the next node
// round the ring. A frame from node s to node d therefore has identifier 10d + rank(s) - 1, where rank(s) is
// s's position among the nodes other than d. For N = 5 this reproduces the note's tables:
//
//   node  base   Rx #1..#4           Tx #5..#8
//    1     10    10 11 12 13         20 30 40 50
//    2     20    20 21 22 23         31 41 51 10
//    3     30    30 31 32 33         42 52 11 21
//    4     40    40 41 42 43         53 12 22 32
//    5     50    50 51 52 53         13 23 33 43
//
// The note stops at 5 controllers; the scheme generalises unchanged to 2..11 (the receive channel must stay a
// single decimal digit of the identifier), and the node count is a parameter of every function here.
// Lowest identifier wins arbitration, so traffic to node 1 has the highest priority.
//
// Cost: every function is constexpr, O(1), no state, no allocation; any context, ISR included, may call them.
#pragma once

#include <cstdint>

namespace trionet::can {

/// Node counts the scheme supports: 2..5 as in the note, generalised up to 11. 5 is the note's default.
constexpr std::uint8_t min_node_count = 2;
constexpr std::uint8_t max_node_count = 11;     ///< the most controllers
constexpr std::uint8_t default_node_count = 5;  ///< the note's node count

/// The first transmit channel number (message buffer 5 in the note).
constexpr std::uint8_t first_transmit_channel = 5;

/// Largest 11-bit standard identifier.
constexpr std::uint32_t max_standard_identifier = 0x7FF;

/// Whether an identifier-scheme question has an answer.
enum class scheme_status : std::uint8_t {
  ok,                       ///< answered
  bad_node_count,           ///< node count outside 2..11
  bad_node,                 ///< a node number outside 1..N
  same_node,                ///< sender and receiver are the same node
  bad_channel,              ///< a receive channel outside 1..N-1 or a transmit channel outside 5..N+3
  not_exchange_identifier,  ///< the identifier is not a receive identifier of any node of this exchange
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(scheme_status status) noexcept {
  switch (status) {
    case scheme_status::ok:
      return "ok";
    case scheme_status::bad_node_count:
      return "bad_node_count";
    case scheme_status::bad_node:
      return "bad_node";
    case scheme_status::same_node:
      return "same_node";
    case scheme_status::bad_channel:
      return "bad_channel";
    case scheme_status::not_exchange_identifier:
      return "not_exchange_identifier";
  }
  return "unknown";
}

/// An identifier, or why there is none.
struct [[nodiscard]] identifier_result {
  scheme_status status = scheme_status::ok;  ///< `ok`, or why there is no identifier
  std::uint16_t identifier = 0;              ///< the 11-bit identifier
  /// True when `status` is `ok`.
  constexpr explicit operator bool() const noexcept { return status == scheme_status::ok; }
};

/// A node number, or why there is none.
struct [[nodiscard]] node_result {
  scheme_status status = scheme_status::ok;  ///< `ok`, or why there is no node
  std::uint8_t node = 0;                     ///< the node, 1..N
  /// True when `status` is `ok`.
  constexpr explicit operator bool() const noexcept { return status == scheme_status::ok; }
};

/// A channel number (receive 1..N-1 or transmit 5..N+3), or why there is none.
struct [[nodiscard]] channel_result {
  scheme_status status = scheme_status::ok;  ///< `ok`, or why there is no channel
  std::uint8_t channel = 0;                  ///< the channel number
  /// True when `status` is `ok`.
  constexpr explicit operator bool() const noexcept { return status == scheme_status::ok; }
};

/// What an exchange identifier means: who sent it, who receives it, and on which receive channel.
struct route {
  std::uint8_t sender = 0;           ///< the sending node, 1..N
  std::uint8_t receiver = 0;         ///< the receiving node, 1..N
  std::uint8_t receive_channel = 0;  ///< the receiver's channel for it, 1..N-1
};

/// A route, or why the identifier is not one.
struct [[nodiscard]] route_result {
  scheme_status status = scheme_status::ok;  ///< `ok`, or why the identifier has no route
  route value{};                             ///< the route
  /// True when `status` is `ok`.
  constexpr explicit operator bool() const noexcept { return status == scheme_status::ok; }
};

/// True if the exchange supports `node_count` controllers (2..11).
[[nodiscard]] constexpr bool valid_node_count(std::uint8_t node_count) noexcept {
  return node_count >= min_node_count && node_count <= max_node_count;
}

}  // namespace trionet::can

namespace trionet::detail {
[[nodiscard]] constexpr can::scheme_status check_node(std::uint8_t node_count, std::uint8_t node) noexcept {
  if (!can::valid_node_count(node_count)) return can::scheme_status::bad_node_count;
  if (node < 1 || node > node_count) return can::scheme_status::bad_node;
  return can::scheme_status::ok;
}
}  // namespace trionet::detail

namespace trionet::can {

/// Node k's base identifier, 10k (also its receive channel 1 identifier).
[[nodiscard]] constexpr identifier_result base_identifier(std::uint8_t node_count,
                                                          std::uint8_t node) noexcept {
  const scheme_status status = detail::check_node(node_count, node);
  if (status != scheme_status::ok) return {status, 0};
  return {scheme_status::ok, static_cast<std::uint16_t>(10U * node)};
}

/// The identifier node `node` listens on with receive channel `receive_channel` (1..N-1): 10k + r - 1.
[[nodiscard]] constexpr identifier_result receive_identifier(std::uint8_t node_count, std::uint8_t node,
                                                             std::uint8_t receive_channel) noexcept {
  const scheme_status status = detail::check_node(node_count, node);
  if (status != scheme_status::ok) return {status, 0};
  if (receive_channel < 1 || receive_channel >= node_count) return {scheme_status::bad_channel, 0};
  return {scheme_status::ok, static_cast<std::uint16_t>(10U * node + receive_channel - 1U)};
}

/// The identifier of a frame from `sender` to `receiver`: 10 * receiver + rank of sender among the others
/// - 1.
[[nodiscard]] constexpr identifier_result exchange_identifier(std::uint8_t node_count, std::uint8_t sender,
                                                              std::uint8_t receiver) noexcept {
  scheme_status status = detail::check_node(node_count, sender);
  if (status == scheme_status::ok) status = detail::check_node(node_count, receiver);
  if (status != scheme_status::ok) return {status, 0};
  if (sender == receiver) return {scheme_status::same_node, 0};
  const auto rank = static_cast<std::uint8_t>(sender < receiver ? sender : sender - 1);
  return receive_identifier(node_count, receiver, rank);
}

/// Who sends and who receives a frame with `identifier`, or `not_exchange_identifier` (for a standard
/// identifier that no node of this exchange listens on, and for any value above 0x7FF, flags included).
[[nodiscard]] constexpr route_result route_of(std::uint8_t node_count, std::uint32_t identifier) noexcept {
  if (!valid_node_count(node_count)) return {scheme_status::bad_node_count, {}};
  if (identifier > max_standard_identifier) return {scheme_status::not_exchange_identifier, {}};
  // identifier / 10 as a multiply and shift, exact for identifiers up to 0x7FF (no division routine on a
  // core without a divider).
  const std::uint32_t receiver = (identifier * 6554U) >> 16U;
  const std::uint32_t receive_channel = identifier - receiver * 10U + 1U;
  if (receiver < 1 || receiver > node_count || receive_channel >= node_count) {
    return {scheme_status::not_exchange_identifier, {}};
  }
  const std::uint32_t sender = receive_channel < receiver ? receive_channel : receive_channel + 1U;
  return {scheme_status::ok,
          {static_cast<std::uint8_t>(sender), static_cast<std::uint8_t>(receiver),
           static_cast<std::uint8_t>(receive_channel)}};
}

/// The receive channel (1..N-1) on which `node` hears `identifier`, or `not_exchange_identifier` if the
/// identifier is not one of that node's receive identifiers.
[[nodiscard]] constexpr channel_result receive_channel_of(std::uint8_t node_count, std::uint8_t node,
                                                          std::uint32_t identifier) noexcept {
  const scheme_status status = detail::check_node(node_count, node);
  if (status != scheme_status::ok) return {status, 0};
  const route_result found = route_of(node_count, identifier);
  if (!found || found.value.receiver != node) {
    return {scheme_status::not_exchange_identifier, 0};
  }
  return {scheme_status::ok, found.value.receive_channel};
}

/// The node that `sender`'s transmit channel (5..N+3) sends to: ((sender - 1 + channel - 4) mod N) + 1.
[[nodiscard]] constexpr node_result destination_of(std::uint8_t node_count, std::uint8_t sender,
                                                   std::uint8_t transmit_channel) noexcept {
  const scheme_status status = detail::check_node(node_count, sender);
  if (status != scheme_status::ok) return {status, 0};
  if (transmit_channel < first_transmit_channel || transmit_channel > node_count + 3U) {
    return {scheme_status::bad_channel, 0};
  }
  const unsigned step = transmit_channel - (first_transmit_channel - 1U);
  const unsigned ahead = sender - 1U + step;  // < 2N: one subtraction is the modulo
  return {scheme_status::ok,
          static_cast<std::uint8_t>((ahead >= node_count ? ahead - node_count : ahead) + 1U)};
}

/// The transmit channel (5..N+3) with which `sender` reaches `destination`.
[[nodiscard]] constexpr channel_result transmit_channel_to(std::uint8_t node_count, std::uint8_t sender,
                                                           std::uint8_t destination) noexcept {
  scheme_status status = detail::check_node(node_count, sender);
  if (status == scheme_status::ok) status = detail::check_node(node_count, destination);
  if (status != scheme_status::ok) return {status, 0};
  if (sender == destination) return {scheme_status::same_node, 0};
  const unsigned distance =
      destination + node_count - unsigned{sender};  // 1..2N-1: one subtraction is the modulo
  const unsigned step = distance >= node_count ? distance - node_count : distance;  // 1..N-1
  return {scheme_status::ok, static_cast<std::uint8_t>(first_transmit_channel - 1U + step)};
}

/// The identifier that `sender`'s transmit channel (5..N+3) puts on the bus (the note's second table).
[[nodiscard]] constexpr identifier_result transmit_identifier(std::uint8_t node_count, std::uint8_t sender,
                                                              std::uint8_t transmit_channel) noexcept {
  const node_result destination = destination_of(node_count, sender, transmit_channel);
  if (!destination) return {destination.status, 0};
  return exchange_identifier(node_count, sender, destination.node);
}

}  // namespace trionet::can
