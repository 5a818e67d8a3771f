// TN20-17 identifier scheme: the note's three tables and examples, and the scheme both ways for 2..11 nodes.
#include <gtest/gtest.h>

#include <set>

#include <trionet/can/identifiers.hpp>

namespace {

using namespace trionet::can;

// "Node Base address / Rx #1 .. Rx #4", copied from the note.
constexpr std::uint16_t note_receive_table[5][5] = {
    {10, 10, 11, 12, 13}, {20, 20, 21, 22, 23}, {30, 30, 31, 32, 33},
    {40, 40, 41, 42, 43}, {50, 50, 51, 52, 53},
};

// "Node Base address / Tx #5 .. Tx #8", copied from the note.
constexpr std::uint16_t note_transmit_table[5][5] = {
    {10, 20, 30, 40, 50}, {20, 31, 41, 51, 10}, {30, 42, 52, 11, 21},
    {40, 53, 12, 22, 32}, {50, 13, 23, 33, 43},
};

// "Node / Received FROM node Rx #1..#4 / Transmit TO node Tx #5..#8", copied from the note.
constexpr std::uint8_t note_connection_table[5][9] = {
    {1, 2, 3, 4, 5, 2, 3, 4, 5}, {2, 1, 3, 4, 5, 3, 4, 5, 1}, {3, 1, 2, 4, 5, 4, 5, 1, 2},
    {4, 1, 2, 3, 5, 5, 1, 2, 3}, {5, 1, 2, 3, 4, 1, 2, 3, 4},
};

TEST(CanTn2017Tables, ReceiveIdentifierTableForFiveNodes) {
  for (const auto& row : note_receive_table) {
    const std::uint8_t node = static_cast<std::uint8_t>(row[0] / 10);
    const identifier_result base = base_identifier(5, node);
    ASSERT_EQ(base.status, scheme_status::ok);
    EXPECT_EQ(base.identifier, row[0]);
    for (std::uint8_t channel = 1; channel <= 4; ++channel) {
      const identifier_result id = receive_identifier(5, node, channel);
      ASSERT_EQ(id.status, scheme_status::ok);
      EXPECT_EQ(id.identifier, row[channel]) << "node " << int{node} << " Rx #" << int{channel};
    }
  }
}

TEST(CanTn2017Tables, TransmitIdentifierTableForFiveNodes) {
  for (const auto& row : note_transmit_table) {
    const std::uint8_t node = static_cast<std::uint8_t>(row[0] / 10);
    for (std::uint8_t channel = 5; channel <= 8; ++channel) {
      const identifier_result id = transmit_identifier(5, node, channel);
      ASSERT_EQ(id.status, scheme_status::ok);
      EXPECT_EQ(id.identifier, row[channel - 4]) << "node " << int{node} << " Tx #" << int{channel};
    }
  }
}

TEST(CanTn2017Tables, VirtualConnectionsTableForFiveNodes) {
  for (const auto& row : note_connection_table) {
    const std::uint8_t node = row[0];
    for (std::uint8_t channel = 1; channel <= 4; ++channel) {
      const identifier_result id = receive_identifier(5, node, channel);
      const route_result route = route_of(5, id.identifier);
      ASSERT_EQ(route.status, scheme_status::ok);
      EXPECT_EQ(route.value.sender, row[channel]) << "node " << int{node} << " Rx #" << int{channel};
      EXPECT_EQ(route.value.receiver, node);
      EXPECT_EQ(route.value.receive_channel, channel);
    }
    for (std::uint8_t channel = 5; channel <= 8; ++channel) {
      const node_result destination = destination_of(5, node, channel);
      ASSERT_EQ(destination.status, scheme_status::ok);
      EXPECT_EQ(destination.node, row[channel]) << "node " << int{node} << " Tx #" << int{channel};
    }
  }
}

// "for node 1 to send to node 4 it must place the message in message buffer 7 (address 40). Node 4 then picks
// up the message from message buffer 1."
TEST(CanTn2017Examples, NodeOneToNodeFourUsesBufferSevenAddressFortyReceivedOnBufferOne) {
  EXPECT_EQ(transmit_channel_to(5, 1, 4).channel, 7);
  EXPECT_EQ(transmit_identifier(5, 1, 7).identifier, 40);
  EXPECT_EQ(exchange_identifier(5, 1, 4).identifier, 40);
  EXPECT_EQ(receive_channel_of(5, 4, 40).channel, 1);
}

// "for node 5 to send to node 2, it puts the message in buffer 6 (address 23) and node 2 picks up the message
// from buffer 4."
TEST(CanTn2017Examples, NodeFiveToNodeTwoUsesBufferSixAddressTwentyThreeReceivedOnBufferFour) {
  EXPECT_EQ(transmit_channel_to(5, 5, 2).channel, 6);
  EXPECT_EQ(transmit_identifier(5, 5, 6).identifier, 23);
  EXPECT_EQ(exchange_identifier(5, 5, 2).identifier, 23);
  EXPECT_EQ(receive_channel_of(5, 2, 23).channel, 4);
}

// docs/protocol.md 2.1: "node 2 channel 5 -> 31, node 4 channel 6 -> 12"; channel 5 of node 5 goes to node 1.
TEST(CanTn2017Examples, ProtocolChannelExamplesAndTheRing) {
  EXPECT_EQ(transmit_identifier(5, 2, 5).identifier, 31);
  EXPECT_EQ(transmit_identifier(5, 4, 6).identifier, 12);
  EXPECT_EQ(destination_of(5, 5, 5).node, 1);
  static_assert(exchange_identifier(5, 1, 4).identifier == 40, "usable at compile time");
  static_assert(route_of(5, 23).value.sender == 5, "usable at compile time");
}

TEST(CanIdentifierScheme, BothWaysForEveryNodeCountFromTwoToEleven) {
  for (std::uint8_t n = min_node_count; n <= max_node_count; ++n) {
    std::set<std::uint16_t> identifiers;
    for (std::uint8_t sender = 1; sender <= n; ++sender) {
      std::set<std::uint8_t> destinations;
      for (std::uint8_t receiver = 1; receiver <= n; ++receiver) {
        if (sender == receiver) continue;
        const identifier_result id = exchange_identifier(n, sender, receiver);
        ASSERT_EQ(id.status, scheme_status::ok);
        EXPECT_LE(id.identifier, max_standard_identifier);
        identifiers.insert(id.identifier);
        const route_result route = route_of(n, id.identifier);
        ASSERT_EQ(route.status, scheme_status::ok);
        EXPECT_EQ(route.value.sender, sender);
        EXPECT_EQ(route.value.receiver, receiver);
        EXPECT_EQ(receive_identifier(n, receiver, route.value.receive_channel).identifier, id.identifier);
        const channel_result channel = transmit_channel_to(n, sender, receiver);
        ASSERT_EQ(channel.status, scheme_status::ok);
        EXPECT_GE(channel.channel, first_transmit_channel);
        EXPECT_LE(channel.channel, n + 3);
        EXPECT_EQ(destination_of(n, sender, channel.channel).node, receiver);
        EXPECT_EQ(transmit_identifier(n, sender, channel.channel).identifier, id.identifier);
      }
      for (std::uint8_t channel = 5; channel <= n + 3; ++channel) {
        destinations.insert(destination_of(n, sender, channel).node);
      }
      EXPECT_EQ(destinations.size(), n - 1U) << "every transmit channel reaches a different node";
      EXPECT_EQ(destinations.count(sender), 0U);
    }
    EXPECT_EQ(identifiers.size(), std::size_t{n} * (n - 1U)) << "identifiers are unique";
    for (std::uint32_t id = 0; id <= 0x7FF; ++id) {
      const route_result route = route_of(n, id);
      if (identifiers.count(static_cast<std::uint16_t>(id)) != 0) continue;
      EXPECT_EQ(route.status, scheme_status::not_exchange_identifier) << "n " << int{n} << " id " << id;
    }
  }
}

TEST(CanIdentifierScheme, NotExchangeIdentifiers) {
  EXPECT_EQ(route_of(5, 9).status, scheme_status::not_exchange_identifier);   // below node 1
  EXPECT_EQ(route_of(5, 14).status, scheme_status::not_exchange_identifier);  // node 1 has only 4 channels
  EXPECT_EQ(route_of(5, 54).status, scheme_status::not_exchange_identifier);
  EXPECT_EQ(route_of(5, 60).status, scheme_status::not_exchange_identifier);               // no node 6 of 5
  EXPECT_EQ(route_of(5, 0x80000028U).status, scheme_status::not_exchange_identifier);      // extended frame
  EXPECT_EQ(route_of(5, 0x40000028U).status, scheme_status::not_exchange_identifier);      // remote frame
  EXPECT_EQ(receive_channel_of(5, 3, 40).status, scheme_status::not_exchange_identifier);  // node 4's
  EXPECT_EQ(route_of(11, 119).value.sender, 10);
  EXPECT_EQ(route_of(11, 110).value.sender, 1);
}

TEST(CanIdentifierScheme, MisuseIsReportedWithAReason) {
  EXPECT_EQ(exchange_identifier(1, 1, 2).status, scheme_status::bad_node_count);
  EXPECT_EQ(exchange_identifier(12, 1, 2).status, scheme_status::bad_node_count);
  EXPECT_EQ(route_of(12, 10).status, scheme_status::bad_node_count);
  EXPECT_EQ(exchange_identifier(5, 0, 2).status, scheme_status::bad_node);
  EXPECT_EQ(exchange_identifier(5, 1, 6).status, scheme_status::bad_node);
  EXPECT_EQ(exchange_identifier(5, 3, 3).status, scheme_status::same_node);
  EXPECT_EQ(transmit_channel_to(5, 3, 3).status, scheme_status::same_node);
  EXPECT_EQ(destination_of(5, 1, 4).status, scheme_status::bad_channel);
  EXPECT_EQ(destination_of(5, 1, 9).status, scheme_status::bad_channel);
  EXPECT_EQ(destination_of(2, 1, 6).status, scheme_status::bad_channel);
  EXPECT_EQ(destination_of(2, 1, 5).node, 2);
  EXPECT_EQ(receive_identifier(5, 1, 0).status, scheme_status::bad_channel);
  EXPECT_EQ(receive_identifier(5, 1, 5).status, scheme_status::bad_channel);
  EXPECT_EQ(base_identifier(5, 6).status, scheme_status::bad_node);
}

}  // namespace

TEST(CanIdentifiers, EveryStandardIdentifierRoutesAsTheDivisionSays) {
  for (std::uint8_t n = 2; n <= 11; ++n) {
    for (std::uint32_t id = 0; id <= 0x7FF; ++id) {
      const auto r = trionet::can::route_of(n, id);
      const std::uint32_t receiver = id / 10, channel = id % 10 + 1;
      const bool ours = receiver >= 1 && receiver <= n && channel < n;
      ASSERT_EQ(r.status == trionet::can::scheme_status::ok, ours) << int{n} << " " << id;
      if (ours) {
        ASSERT_EQ(r.value.receiver, receiver);
        ASSERT_EQ(r.value.receive_channel, channel);
      }
    }
  }
}
