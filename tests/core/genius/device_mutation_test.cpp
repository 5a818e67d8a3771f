// genius::device (docs/protocol.md 3.4) at the edges of what it takes: the longest timing that fits its
// 32-bit timer, turn data of exactly 255 bytes (a block's longest, and one plain segment's), turn data
// cleared, an empty directed transmission, and a framing error inside its own transmission.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "support/genius_words.hpp"
#include "trionet/genius/device.hpp"
#include "trionet/genius/transmission.hpp"

namespace {

using namespace trionet::genius;
using trionet::byte_view;
using trionet::span;
using trionet::test::take_turn;
using trionet::test::words_of;

// From power-up to its turn: the quiet bus restarts the turns as if SBA 31's Stop had ended; the next timer
// is its turn.
template <class Device>
void to_its_turn(Device& d) {
  (void)d.power_on();
  const link_request r = d.timer_expired();  // the idle restart
  ASSERT_EQ(r.timer, timer_action::arm);
}

TEST(GeniusDeviceEdges, TheLongestTimerMayBeExactlyTheLargest32BitTickCount) {
  device_timing timing{0x7FFFFFF, 31, 1};  // 32 x 0x7FFFFFF + 1 x 31 = 0xFFFFFFFF
  EXPECT_EQ(timing.longest_ticks(), 0xFFFFFFFFu);
  EXPECT_TRUE(timing.valid());
  timing.character_ticks = 32;  // one tick more
  EXPECT_EQ(timing.longest_ticks(), 0x100000000u);
  EXPECT_FALSE(timing.valid());
}

TEST(GeniusDeviceEdges, APlainBroadcastOf255BytesTakesTwoBytesMoreInTheTurnData) {
  device<257> d(0);
  std::vector<std::uint8_t> data(255);
  for (std::size_t i = 0; i < data.size(); ++i) data[i] = static_cast<std::uint8_t>(i);
  ASSERT_EQ(d.set_turn_data(byte_view(data.data(), data.size())), turn_data_status::ok)
      << "255 bytes + their header and length: 257";
  std::vector<std::uint8_t> longer(256, 0x5A);
  EXPECT_EQ(d.set_turn_data(byte_view(longer.data(), longer.size())), turn_data_status::too_long)
      << "256 bytes are two segments: 260";
  to_its_turn(d);
  const segment plain{false, 0, byte_view(data.data(), data.size())};
  EXPECT_EQ(take_turn(d), words_of(transmission{0, true, 0, span<const segment>(&plain, 1)}));
}

TEST(GeniusDeviceEdges, ABlockMayCarry255BytesNotMore) {
  device<300> d(0);
  std::vector<std::uint8_t> data(256, 0x33);
  const segment too_long{true, 4, byte_view(data.data(), 256)};
  EXPECT_EQ(d.set_turn_data(span<const segment>(&too_long, 1)), turn_data_status::too_long);
  const segment longest{true, 4, byte_view(data.data(), 255)};
  ASSERT_EQ(d.set_turn_data(span<const segment>(&longest, 1)), turn_data_status::ok);
  to_its_turn(d);
  EXPECT_EQ(take_turn(d), words_of(transmission{0, true, 0, span<const segment>(&longest, 1)}));
}

TEST(GeniusDeviceEdges, TurnDataClearedLetsItsTurnPassInSilence) {
  device<> d(0);
  const std::uint8_t data[] = {1, 2, 3};
  ASSERT_EQ(d.set_turn_data(data), turn_data_status::ok);
  d.clear_turn_data();
  to_its_turn(d);
  EXPECT_TRUE(take_turn(d, false).empty());
  EXPECT_EQ(d.counters().turns_passed, 1u);
  EXPECT_EQ(d.counters().turns_taken, 0u);
}

TEST(GeniusDeviceEdges, AnEmptyDirectedTransmissionIsStartDestinationStop) {
  device<> d(0);
  ASSERT_EQ(d.queue_directed(7, byte_view{}), queue_status::ok);
  to_its_turn(d);
  EXPECT_EQ(take_turn(d), words_of(transmission{0, false, 7, {}}));
  EXPECT_EQ(d.counters().transmissions_sent, 1u);
  EXPECT_EQ(d.directed_waiting(), 0u);
}

// A framing error while it sends is a collision; its own Start went out, so a transmission is open on the bus
// and the device waits for the silence that ends one (2 character times), not for the quiet bus.
TEST(GeniusDeviceEdges, AFramingErrorInsideItsOwnTransmissionWaitsForTheSilenceThatEndsIt) {
  const device_timing timing = bit_timing(rate::standard_153k6);  // 1 tick a skip, 11 a character, 2 idle
  device<> d(0, timing);
  const std::uint8_t data[] = {1, 2, 3};
  ASSERT_EQ(d.set_turn_data(data), turn_data_status::ok);
  to_its_turn(d);
  link_request r = d.timer_expired();
  ASSERT_TRUE(r.transmit);
  std::uint16_t w = 0;
  ASSERT_TRUE(d.transmit(w));  // its Start
  (void)d.start_bit();
  r = d.receive(w);  // read back unchanged
  ASSERT_TRUE(r.transmit);
  ASSERT_TRUE(d.transmit(w));  // the first data character
  (void)d.start_bit();
  r = d.framing_error();
  EXPECT_EQ(d.counters().collisions, 1u);
  EXPECT_FALSE(d.sending());
  EXPECT_EQ(r.timer, timer_action::arm);
  EXPECT_EQ(r.ticks, 2u * 11u) << "the silence inside a transmission, not 32 skips + 2 characters";
  r = d.timer_expired();  // that silence: as if its own Stop had ended, it waits for the quiet bus
  EXPECT_EQ(r.timer, timer_action::arm);
  EXPECT_EQ(r.ticks, 32u * 1u + 2u * 11u);
}

// "3 x (TurnCapacity + 1) for the turn data" (device.hpp, Cost): three buffers, so each byte more of
// turn-data capacity costs three bytes of RAM (32 more, in steps that keep every alignment).
TEST(GeniusDeviceEdges, TurnDataCapacityCostsThreeBuffers) {
  static_assert(sizeof(device<64>) - sizeof(device<32>) == 3 * 32, "three turn-data buffers");
  static_assert(sizeof(device<96>) - sizeof(device<64>) == 3 * 32, "three turn-data buffers");
}

}  // namespace
