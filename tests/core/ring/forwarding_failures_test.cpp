// A forwarded message that is lost (docs/protocol.md 1.5, 1.10) is counted once by its reason, sets NETSTAT
// bit 1, and `forwards_failed` is the sum of the three reasons; a node's own messages are counted as they go.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "support/ring_frames.hpp"
#include "trionet/ring.hpp"
#include "trionet/vr.hpp"

namespace {

namespace ring = trionet::ring;
using trionet::test::chars;
using trionet::test::drain;
using trionet::test::feed;

// The link at its own pace: each byte received, then everything the node has to send.
template <class Node>
void at_line_rate(Node& node, const std::vector<std::uint8_t>& bytes) {
  for (std::uint8_t b : bytes) {
    node.receive(b);
    (void)drain(node);
  }
}

TEST(RingForwardingFailures, EachLossIsCountedByItsReasonAndForwardsFailedIsTheirSum) {
  trionet::vr_table<16> vr;
  ring::motion_coordinator<> mc(vr);
  EXPECT_EQ(mc.forwarding_counters().forwards_failed(), 0U);

  feed(mc, {ring::make_header(3, 1), 'A'});  // its end of message never comes
  mc.line_idle();
  (void)drain(mc);
  EXPECT_EQ(mc.forwarding_counters().forwards_ended_idle, 1U);
  EXPECT_EQ(mc.forwarding_counters().forwards_failed(), 1U);
  EXPECT_EQ(mc.netstat(), ring::netstat_tx_buffer_error);
  mc.clear_netstat();

  std::vector<std::uint8_t> too_long = {ring::make_header(3, 2)};  // a variable transfer carries 14 bytes
  too_long.insert(too_long.end(), 20, 'v');
  too_long.push_back(ring::make_end_of_message(3));
  at_line_rate(mc, too_long);
  EXPECT_EQ(mc.forwarding_counters().forwards_cut, 1U);
  EXPECT_EQ(mc.forwarding_counters().forwards_failed(), 2U);
  EXPECT_EQ(mc.netstat(), ring::netstat_tx_buffer_error);
  mc.clear_netstat();

  ASSERT_EQ(mc.print(10, "OWN MESSAGE").status, ring::send_status::ok);
  std::uint8_t b = 0;
  ASSERT_TRUE(mc.transmit(b));                    // the own message has begun: forwarding waits
  feed(mc, chars(3, "MORE THAN SIXTEEN BYTES"));  // faster than the line: the forward buffer overflows
  (void)drain(mc);
  EXPECT_EQ(mc.forwarding_counters().forwards_lost, 1U);
  EXPECT_EQ(mc.forwarding_counters().forwards_failed(), 3U);
  EXPECT_EQ(mc.netstat(), ring::netstat_tx_buffer_error);
  EXPECT_EQ(mc.forwarding_counters().forwards_ended_idle, 1U) << "each reason counted once";
  EXPECT_EQ(mc.forwarding_counters().forwards_cut, 1U);
  EXPECT_EQ(mc.forwarding_counters().messages_sent, 1U) << "the own message went out whole";
}

TEST(RingForwardingFailures, ForwardsFailedAddsTheThreeReasons) {
  ring::link_counters c;
  c.forwards_lost = 1;
  c.forwards_cut = 20;
  c.forwards_ended_idle = 300;
  c.messages_forwarded = 4000;
  c.messages_dropped = 50000;
  c.messages_sent = 600000;
  EXPECT_EQ(c.forwards_failed(), 321U);
}

TEST(RingForwardingFailures, OwnMessagesAreCountedWhenTheirEndOfMessageHasGoneOut) {
  trionet::vr_table<16> vr;
  ring::motion_coordinator<> mc(vr);
  ASSERT_EQ(mc.print(11, "ONE").status, ring::send_status::ok);
  ASSERT_EQ(mc.send_variable(12, 7, 1.5), ring::send_status::ok);
  std::uint8_t b = 0;
  ASSERT_TRUE(mc.transmit(b));
  EXPECT_EQ(mc.forwarding_counters().messages_sent, 0U) << "begun, not gone";
  (void)drain(mc);
  EXPECT_EQ(mc.forwarding_counters().messages_sent, 2U);
  EXPECT_EQ(mc.forwarding_counters().messages_forwarded, 0U);
}

}  // namespace
