// What a keypad counts and flags (docs/protocol.md 1.6-1.8): a key press with no room in the transmit queue
// sets NETSTAT bit 0, a direct variable transfer to it is checked with its CRC (one chosen at run time too)
// and ignored when valid, a CRC error sets bit 2.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "support/ring_frames.hpp"
#include "trionet/ring.hpp"

namespace {

namespace ring = trionet::ring;
using trionet::test::drain;
using trionet::test::feed;
using trionet::test::frame_of;

constexpr std::int64_t one = std::int64_t{1} << 32;

TEST(RingKeypadErrors, AKeyWithNoRoomInTheTransmitQueueSetsNetstatBitZero) {
  ring::keypad<> keypad;  // a transmit queue of 16 bytes: five one-character messages
  feed(keypad, frame_of(ring::message::keypad_offset(1, 1)));
  ASSERT_TRUE(keypad.network_mode());
  for (int i = 0; i < 5; ++i) ASSERT_EQ(keypad.press(ring::key::digit_1), ring::key_status::ok) << i;
  EXPECT_EQ(keypad.netstat(), 0);
  EXPECT_EQ(keypad.press(ring::key::digit_2), ring::key_status::queue_full);
  EXPECT_EQ(keypad.netstat(), ring::netstat_tx_timeout);
  EXPECT_EQ(keypad.counters().keys_sent, 5U);
  EXPECT_EQ(keypad.counters().keys_lost, 1U);
  keypad.clear_netstat();
  EXPECT_EQ(keypad.netstat(), 0);
  EXPECT_EQ(drain(keypad).size(), 15U) << "the five keys that fitted go out";
  EXPECT_EQ(keypad.press(ring::key::digit_3), ring::key_status::ok) << "room again";
}

TEST(RingKeypadErrors, AKeyInLocalModeIsLostWithoutANetstatBit) {
  ring::keypad<> keypad;
  EXPECT_EQ(keypad.press(ring::key::digit_1), ring::key_status::local_mode);
  EXPECT_EQ(keypad.release(ring::key::digit_1), ring::key_status::local_mode);
  EXPECT_EQ(keypad.counters().keys_lost, 1U) << "a release sends nothing, so loses nothing";
  EXPECT_EQ(keypad.netstat(), 0) << "no message was refused: there was none to send";
}

TEST(RingKeypadErrors, DirectVariableTransfersToAKeypadAreCheckedAndIgnored) {
  ring::keypad<> keypad;
  feed(keypad, frame_of(ring::message::keypad_offset(1, 1)));
  std::vector<std::uint8_t> transfer = frame_of(ring::message::variable(1, 9, one));
  feed(keypad, transfer);
  EXPECT_EQ(keypad.counters().variables_ignored, 1U);
  EXPECT_EQ(keypad.counters().crc_errors, 0U);
  transfer[13] ^= 0x01;  // C0
  feed(keypad, transfer);
  EXPECT_EQ(keypad.counters().variables_ignored, 1U);
  EXPECT_EQ(keypad.counters().crc_errors, 1U);
  EXPECT_EQ(keypad.netstat(), ring::netstat_rx_crc_error);
}

// A profile's CRC is known only at run time (`crc16_runtime`): the keypad checks the transfers to it with
// that.
TEST(RingKeypadErrors, AKeypadBuiltWithARunTimeCrcChecksWithIt) {
  const ring::crc16_runtime xmodem(ring::crc16_parameters{0x1021, 0x0000, false, false, 0x0000});
  ring::keypad<16, 16, ring::default_max_characters, ring::crc16_runtime> keypad(ring::keypad_config{},
                                                                                 xmodem);
  feed(keypad, frame_of(ring::message::keypad_offset(1, 1)));
  ASSERT_TRUE(keypad.network_mode());

  std::vector<std::uint8_t> with_xmodem(16);
  ASSERT_TRUE(ring::encode_variable<ring::crc16_runtime>(
      trionet::byte_buffer(with_xmodem.data(), with_xmodem.size()), 1, 9, one, xmodem));
  feed(keypad, with_xmodem);
  EXPECT_EQ(keypad.counters().variables_ignored, 1U);
  EXPECT_EQ(keypad.counters().crc_errors, 0U);

  feed(keypad, frame_of(ring::message::variable(1, 9, one)));  // the default CRC: not this network's
  EXPECT_EQ(keypad.counters().variables_ignored, 1U);
  EXPECT_EQ(keypad.counters().crc_errors, 1U);
  EXPECT_EQ(keypad.netstat(), ring::netstat_rx_crc_error);

  std::vector<std::uint8_t> passing = with_xmodem;  // to the node after it: forwarded unchecked, A - 1
  passing.front() = ring::with_hops(passing.front(), 2);
  passing.back() = ring::with_hops(passing.back(), 2);
  feed(keypad, passing);
  std::vector<std::uint8_t> expected = with_xmodem;
  EXPECT_EQ(drain(keypad), expected);
}

TEST(RingKeypadErrors, KeyCountsWrapAtTwoToTheSixteenAndErrorCountsDoNot) {
  // docs/design.md, "Results and counters": a ring node keeps bad wire data in 32 bits, other counts in 16.
  ring::keypad<> keypad;  // local mode: every key press is lost and counted
  for (std::uint32_t i = 0; i < 65536U + 3U; ++i) (void)keypad.press(ring::key::digit_1);
  EXPECT_EQ(keypad.counters().keys_lost, 3U);
  for (std::uint32_t i = 0; i < 65536U + 3U; ++i) {
    feed(keypad, std::vector<std::uint8_t>{0x41});  // data outside a message
    feed(keypad, std::vector<std::uint8_t>{ring::make_end_of_message(1)});  // a stray end of message each time
  }
  EXPECT_EQ(keypad.counters().frame_errors, 2U * (65536U + 3U));
}

}  // namespace
