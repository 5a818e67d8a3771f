// The results of the CAN part (docs/design.md, "Names"): each is true exactly when its status is `ok`, and
// one without an answer carries none (its identifier, node or channel is 0).
#include <gtest/gtest.h>

#include <cstdint>

#include <trionet/can.hpp>

namespace {

using namespace trionet::can;

TEST(CanResults, IdentifierSchemeAnswersAreTrueOnlyWhenOk) {
  EXPECT_TRUE(base_identifier(5, 1));
  EXPECT_FALSE(base_identifier(5, 6));
  EXPECT_TRUE(receive_channel_of(5, 1, 10));
  EXPECT_FALSE(receive_channel_of(5, 1, 20));
  EXPECT_TRUE(destination_of(5, 1, 5));
  EXPECT_FALSE(destination_of(5, 1, 9));
  EXPECT_TRUE(route_of(5, 40));
  EXPECT_FALSE(route_of(5, 45));
  EXPECT_TRUE(make_node_address(5, 5));
  EXPECT_FALSE(make_node_address(5, 0));
}

TEST(CanResults, AQuestionWithoutAnAnswerCarriesNone) {
  for (std::uint8_t nodes : {std::uint8_t{1}, std::uint8_t{5}, std::uint8_t{12}}) {
    for (std::uint8_t node = 0; node <= 13; ++node) {
      for (std::uint8_t other = 0; other <= 13; ++other) {
        const identifier_result ids[] = {base_identifier(nodes, node), receive_identifier(nodes, node, other),
                                         exchange_identifier(nodes, node, other),
                                         transmit_identifier(nodes, node, other)};
        for (const identifier_result& id : ids) {
          if (!id) {
            EXPECT_EQ(id.identifier, 0U) << int(nodes) << " " << int(node) << " " << int(other);
          }
        }
        const channel_result channels[] = {receive_channel_of(nodes, node, other),
                                           transmit_channel_to(nodes, node, other)};
        for (const channel_result& channel : channels) {
          if (!channel) {
            EXPECT_EQ(channel.channel, 0U) << int(nodes) << " " << int(node) << " " << int(other);
          }
        }
        const route_result route = route_of(nodes, std::uint32_t{node} * 10U + other);
        if (!route) {
          EXPECT_EQ(route.value.sender, 0U);
          EXPECT_EQ(route.value.receiver, 0U);
          EXPECT_EQ(route.value.receive_channel, 0U);
        }
        const node_result destination = destination_of(nodes, node, other);
        if (!destination) {
          EXPECT_EQ(destination.node, 0U);
        }
      }
    }
  }
}

TEST(CanResults, AResultMadeByTheCallerStartsEmpty) {
  EXPECT_EQ(identifier_result{}.identifier, 0U);
  EXPECT_EQ(node_result{}.node, 0U);
  EXPECT_EQ(channel_result{}.channel, 0U);
  const route nowhere{};
  EXPECT_EQ(nowhere.sender, 0U);
  EXPECT_EQ(nowhere.receiver, 0U);
  EXPECT_EQ(nowhere.receive_channel, 0U);
  EXPECT_EQ(receive_result{}.status, receive_status::foreign);
  EXPECT_EQ(receive_result{}.sender, 0U);
  EXPECT_EQ(receive_result{}.receive_channel, 0U);
}

class silent_port final : public port {
 public:
  transmit_status send(const frame&) noexcept override { return transmit_status::ok; }
};

TEST(CanResults, AReceivedFrameIsTrueOnlyWhenItWroteItsVr) {
  silent_port wire;
  trionet::vr_table<8> vrs;
  vr_exchange_node node(make_node_address(5, 1).address, wire, vrs);
  frame f;
  f.id = 10;
  f.dlc = 8;
  f.data[0] = 3;  // VR(3) = 0
  EXPECT_TRUE(node.receive(f));
  f.data[0] = 100;  // past the table
  EXPECT_FALSE(node.receive(f));
  f.id = 20;  // node 2's
  EXPECT_FALSE(node.receive(f));
}

}  // namespace
