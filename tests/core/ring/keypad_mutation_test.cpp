// The keypad's default capacities (keypad.hpp, "Cost (defaults): forward buffer 16 + transmit queue 16"),
// seen from the ring: while nothing is sent, a keypad holds a passing message of 16 bytes whole and loses one
// of 17 (docs/protocol.md 1.5).
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "support/ring_frames.hpp"
#include "trionet/ring.hpp"

namespace {

namespace ring = trionet::ring;
using trionet::test::chars;
using trionet::test::drain;
using trionet::test::feed;
using trionet::test::frame_of;

TEST(RingKeypadCapacity, TheDefaultsAreSixteenBytesEach) {
  static_assert(ring::keypad<>::forward_capacity == 16, "keypad.hpp: forward buffer 16");
  static_assert(ring::keypad<>::transmit_capacity == 16, "keypad.hpp: transmit queue 16");
}

// A message passing through a keypad in network mode, received faster than the keypad sends anything: the
// forward buffer holds it until the transmitter takes it.
TEST(RingKeypadCapacity, AMessageOfSixteenBytesPassesWholeOneOfSeventeenIsLost) {
  ring::keypad<> keypad;
  feed(keypad, frame_of(ring::message::keypad_offset(1, 2)));
  ASSERT_TRUE(keypad.network_mode());

  const std::string fourteen(14, 'F');  // header + 14 characters + end of message = 16 bytes
  const std::vector<std::uint8_t> sixteen_bytes = chars(3, fourteen);
  ASSERT_EQ(sixteen_bytes.size(), 16U);
  feed(keypad, sixteen_bytes);
  EXPECT_EQ(drain(keypad), chars(2, fourteen));
  EXPECT_EQ(keypad.forwarding_counters().forwards_lost, 0U);
  EXPECT_EQ(keypad.forwarding_counters().messages_forwarded, 1U);

  const std::string fifteen(15, 'S');  // 17 bytes: one more than the buffer holds
  feed(keypad, chars(3, fifteen));
  EXPECT_EQ(keypad.forwarding_counters().forwards_lost, 1U);
  EXPECT_NE(drain(keypad), chars(2, fifteen)) << "the message is lost, not forwarded whole";
}

}  // namespace
