// genius::device (docs/protocol.md 3.4) driven call by call, as its UART and timer interrupts would.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "support/genius_words.hpp"
#include "trionet/genius/bus_controller.hpp"
#include "trionet/genius/device.hpp"
#include "trionet/genius/transmission.hpp"

namespace {

using namespace trionet::genius;
using trionet::byte_buffer;
using trionet::byte_view;
using trionet::span;

using trionet::test::broadcast_from;
using trionet::test::hear;
using trionet::test::take_turn;
using trionet::test::words_of;

using default_device = device<>;

struct read_delivery {
  delivery_result result;
  std::vector<std::uint8_t> data;
};

template <class Device>
read_delivery next_delivery(Device& d) {
  read_delivery out;
  out.data.resize(255);
  out.result = d.read(byte_buffer(out.data.data(), out.data.size()));
  out.data.resize(out.result ? out.result.length : 0);
  return out;
}

TEST(GeniusDevice, UartWordsCarryTheControlBitInBitZeroAndTheByteAbove) {
  EXPECT_EQ(to_uart_word(control_character(0x24)), 0x049);
  EXPECT_EQ(to_uart_word(data_character(0xA5)), 0x14A);
  EXPECT_EQ(from_uart_word(0x049), control_character(0x24));
  EXPECT_EQ(from_uart_word(0x14A), data_character(0xA5));
  // The 11-bit wire word is the UART word between a start bit 0 and a stop bit 1.
  EXPECT_EQ(wire_word(to_uart_word(data_character(0xA5))), encode_character(data_character(0xA5)));
  EXPECT_EQ(wire_word(to_uart_word(control_character(0x04))), encode_character(control_character(0x04)));
}

TEST(GeniusDevice, PowerOnArmsTheIdleRestartOf32SkipTimesAndTwoCharacters) {
  default_device d(5);
  const link_request r = d.power_on();
  EXPECT_EQ(r.timer, timer_action::arm);
  EXPECT_EQ(r.ticks, 32u * 1u + 2u * 11u);
  EXPECT_FALSE(r.transmit);
  device<> extended(5, bit_timing(rate::extended_153k6));
  EXPECT_EQ(extended.power_on().ticks, 32u * 2u + 2u * 11u);
}

TEST(GeniusDevice, AfterAStopFromSbaSItArmsSkipTimesTheSbaDifferenceModulo32) {
  default_device d(6);
  const link_request r = hear(d, broadcast_from(4, {0x11}));
  EXPECT_EQ(r.timer, timer_action::arm);
  EXPECT_EQ(r.ticks, 2u);  // (6 - 4) mod 32 skip times of 1 bit
  EXPECT_TRUE(d.turn_armed());
  default_device wrap(1);
  EXPECT_EQ(hear(wrap, broadcast_from(30, {0x11})).ticks, 3u);  // (1 - 30) mod 32 = 3
  device<> extended(6, bit_timing(rate::extended_153k6));
  EXPECT_EQ(hear(extended, broadcast_from(4, {0x11})).ticks, 4u);  // 2 skip times of 2 bits
}

TEST(GeniusDevice, InsideATransmissionEachCharacterArmsTheTwoCharacterGap) {
  default_device d(6);
  const std::vector<std::uint16_t> words = broadcast_from(4, {0x11, 0x22});
  for (std::size_t k = 0; k + 1 < words.size(); ++k) {
    EXPECT_EQ(d.start_bit().timer, timer_action::cancel);
    const link_request r = d.receive(words[k]);
    EXPECT_EQ(r.timer, timer_action::arm);
    EXPECT_EQ(r.ticks, 22u);
    EXPECT_TRUE(d.in_transmission());
  }
}

TEST(GeniusDevice, AStartBitBeforeItsTurnCancelsTheTimer) {
  default_device d(6);
  (void)hear(d, broadcast_from(4, {0x11}));
  EXPECT_EQ(d.start_bit().timer, timer_action::cancel);
  EXPECT_FALSE(d.turn_armed());
  // The timer was cancelled: an expiry that raced it is ignored.
  EXPECT_EQ(d.timer_expired().timer, timer_action::keep);
  EXPECT_EQ(d.counters().turns_taken, 0u);
}

TEST(GeniusDevice, ItsTurnSendsItsTurnDataAsABroadcastWithItsSbaAndCrc6) {
  default_device d(6);
  const std::uint8_t inputs[] = {0x11, 0x22};
  ASSERT_EQ(d.set_turn_data(byte_view(inputs, 2)), turn_data_status::ok);
  (void)hear(d, broadcast_from(4, {0x33}));
  const std::vector<std::uint16_t> sent = take_turn(d);
  EXPECT_EQ(sent, broadcast_from(6, {0x11, 0x22}));
  const device_counters c = d.counters();
  EXPECT_EQ(c.turns_taken, 1u);
  EXPECT_EQ(c.transmissions_sent, 1u);
  EXPECT_EQ(c.collisions, 0u);
  EXPECT_FALSE(d.sending());
}

TEST(GeniusDevice, TurnDataIsRepeatedEveryTurnUntilChanged) {
  default_device d(6);
  const std::uint8_t first[] = {0x01};
  const std::uint8_t second[] = {0x02, 0x03};
  ASSERT_EQ(d.set_turn_data(byte_view(first, 1)), turn_data_status::ok);
  for (int turn = 0; turn < 3; ++turn) {
    (void)hear(d, broadcast_from(4, {0x33}));
    EXPECT_EQ(take_turn(d), broadcast_from(6, {0x01}));
  }
  ASSERT_EQ(d.set_turn_data(byte_view(second, 2)), turn_data_status::ok);
  (void)hear(d, broadcast_from(4, {0x33}));
  EXPECT_EQ(take_turn(d), broadcast_from(6, {0x02, 0x03}));
}

TEST(GeniusDevice, NewTurnDataDuringItsTransmissionWaitsForTheNextTurn) {
  default_device d(6);
  const std::uint8_t first[] = {0x01, 0x02, 0x03};
  const std::uint8_t second[] = {0x0A};
  ASSERT_EQ(d.set_turn_data(byte_view(first, 3)), turn_data_status::ok);
  (void)hear(d, broadcast_from(4, {0x33}));
  link_request r = d.timer_expired();
  std::vector<std::uint16_t> sent;
  std::uint16_t w = 0;
  int updates = 0;
  while (r.transmit && d.transmit(w)) {
    sent.push_back(w);
    // The program side changes the turn data twice while the link side sends.
    if (updates == 0) {
      ASSERT_EQ(d.set_turn_data(byte_view(second, 1)), turn_data_status::ok);
    } else if (updates == 1) {
      ASSERT_EQ(d.set_turn_data(byte_view(first, 3)), turn_data_status::ok);
    }
    ++updates;
    r = d.receive(w);
  }
  EXPECT_EQ(sent, broadcast_from(6, {0x01, 0x02, 0x03}));  // unchanged: the buffer it sends is not written
  ASSERT_EQ(d.set_turn_data(byte_view(second, 1)), turn_data_status::ok);
  (void)hear(d, broadcast_from(4, {0x33}));
  EXPECT_EQ(take_turn(d), broadcast_from(6, {0x0A}));
}

TEST(GeniusDevice, WithNothingToSendItsTurnPassesAndTheIdleRestartFollows) {
  default_device d(6);
  (void)hear(d, broadcast_from(4, {0x33}));
  const link_request r = d.timer_expired();
  EXPECT_FALSE(r.transmit);
  EXPECT_EQ(r.timer, timer_action::arm);
  EXPECT_EQ(r.ticks, (32u - 2u) * 1u + 22u);  // the rest of 32 skip times + 2 characters since the Stop
  EXPECT_EQ(d.counters().turns_passed, 1u);
}

TEST(GeniusDevice, AQueuedDirectedTransmissionGoesFirstAndOnlyOnce) {
  default_device d(6);
  const std::uint8_t inputs[] = {0x01};
  const std::uint8_t message[] = {0xAB, 0xCD};
  ASSERT_EQ(d.set_turn_data(byte_view(inputs, 1)), turn_data_status::ok);
  ASSERT_EQ(d.queue_directed(9, byte_view(message, 2)), queue_status::ok);
  EXPECT_EQ(d.directed_waiting(), 1u);
  (void)hear(d, broadcast_from(4, {0x33}));
  const segment plain{false, 0, byte_view(message, 2)};
  EXPECT_EQ(take_turn(d), words_of(transmission{6, false, 9, span<const segment>(&plain, 1)}));
  EXPECT_EQ(d.directed_waiting(), 0u);
  (void)hear(d, broadcast_from(4, {0x33}));
  EXPECT_EQ(take_turn(d), broadcast_from(6, {0x01}));
}

TEST(GeniusDevice, DirectedTransmissionsAreRefusedWhenMisusedOrFull) {
  device<32, 96, 4, 2> d(6);
  const std::uint8_t five[] = {1, 2, 3, 4, 5};
  EXPECT_EQ(d.queue_directed(32, byte_view(five, 1)), queue_status::destination_out_of_range);
  EXPECT_EQ(d.queue_directed(9, byte_view(five, 5)), queue_status::too_long);
  EXPECT_EQ(d.queue_directed(9, byte_view(five, 4)), queue_status::ok);
  EXPECT_EQ(d.queue_directed(9, byte_view()), queue_status::ok);  // the destination SBA is its data character
  EXPECT_EQ(d.queue_directed(9, byte_view(five, 1)), queue_status::full);
  EXPECT_EQ(d.directed_waiting(), 2u);
}

TEST(GeniusDevice, ACharacterReadBackDifferentIsACollisionAndItStopsSending) {
  default_device d(6);
  const std::uint8_t inputs[] = {0x01, 0x02};
  ASSERT_EQ(d.set_turn_data(byte_view(inputs, 2)), turn_data_status::ok);
  (void)hear(d, broadcast_from(4, {0x33}));
  ASSERT_TRUE(d.timer_expired().transmit);
  std::uint16_t w = 0;
  ASSERT_TRUE(d.transmit(w));
  const link_request r = d.receive(static_cast<std::uint16_t>(w ^ 0x10));  // another device's bits on top
  EXPECT_FALSE(r.transmit);
  EXPECT_FALSE(d.transmit(w));
  EXPECT_FALSE(d.sending());
  EXPECT_EQ(d.counters().collisions, 1u);
  EXPECT_EQ(d.counters().transmissions_sent, 0u);
  EXPECT_NE(d.netstat() & netstat_collision, 0);
  d.clear_netstat();
  EXPECT_EQ(d.netstat(), 0);
}

TEST(GeniusDevice, AStartBitFromElsewhereBeforeItsFirstWordIsACollision) {
  default_device d(6);
  const std::uint8_t inputs[] = {0x01};
  ASSERT_EQ(d.set_turn_data(byte_view(inputs, 1)), turn_data_status::ok);
  (void)hear(d, broadcast_from(4, {0x33}));
  ASSERT_TRUE(d.timer_expired().transmit);
  (void)d.start_bit();  // before `transmit` gave its Start
  std::uint16_t w = 0;
  EXPECT_FALSE(d.transmit(w));
  EXPECT_EQ(d.counters().collisions, 1u);
}

TEST(GeniusDevice, ADirectedTransmissionCutByACollisionIsSentAgainAtTheNextTurn) {
  default_device d(6);
  const std::uint8_t message[] = {0xAB};
  ASSERT_EQ(d.queue_directed(9, byte_view(message, 1)), queue_status::ok);
  (void)hear(d, broadcast_from(4, {0x33}));
  ASSERT_TRUE(d.timer_expired().transmit);
  std::uint16_t w = 0;
  ASSERT_TRUE(d.transmit(w));
  (void)d.receive(static_cast<std::uint16_t>(w ^ 0x02));
  EXPECT_EQ(d.directed_waiting(), 1u);
  (void)hear(d, broadcast_from(4, {0x33}));
  const segment plain{false, 0, byte_view(message, 1)};
  EXPECT_EQ(take_turn(d), words_of(transmission{6, false, 9, span<const segment>(&plain, 1)}));
  EXPECT_EQ(d.directed_waiting(), 0u);
}

TEST(GeniusDevice, BroadcastsAndTransmissionsDirectedToItAreDeliveredWithTheirSender) {
  default_device d(6);
  (void)hear(d, broadcast_from(4, {0x11, 0x22}));
  const std::uint8_t to_me[] = {0x33};
  const segment plain{false, 0, byte_view(to_me, 1)};
  (void)hear(d, words_of(transmission{7, false, 6, span<const segment>(&plain, 1)}));
  (void)hear(d, words_of(transmission{8, false, 9, span<const segment>(&plain, 1)}));  // not for it
  read_delivery first = next_delivery(d);
  ASSERT_TRUE(first.result);
  EXPECT_EQ(first.result.kind, delivery_kind::broadcast);
  EXPECT_EQ(first.result.sender, 4);
  EXPECT_EQ(first.data, (std::vector<std::uint8_t>{0x11, 0x22}));
  read_delivery second = next_delivery(d);
  ASSERT_TRUE(second.result);
  EXPECT_EQ(second.result.kind, delivery_kind::directed);
  EXPECT_EQ(second.result.sender, 7);
  EXPECT_EQ(second.data, (std::vector<std::uint8_t>{0x33}));
  EXPECT_EQ(next_delivery(d).result.status, delivery_status::none_waiting);
  const device_counters c = d.counters();
  EXPECT_EQ(c.transmissions_heard, 3u);
  EXPECT_EQ(c.deliveries, 2u);
}

TEST(GeniusDevice, ABlockAddressedToItInsideAnyTransmissionIsDelivered) {
  default_device d(6);
  const std::uint8_t a[] = {0x01, 0x02};
  const std::uint8_t b[] = {0x03};
  const std::uint8_t plain_bytes[] = {0x0F};
  const segment segments[] = {{true, 5, byte_view(a, 2)}, {true, 6, byte_view(b, 1)}, {false, 0, byte_view(plain_bytes, 1)}};
  (void)hear(d, words_of(transmission{31, true, 0, span<const segment>(segments, 3)}));
  read_delivery block = next_delivery(d);
  ASSERT_TRUE(block.result);
  EXPECT_EQ(block.result.kind, delivery_kind::block);
  EXPECT_EQ(block.result.sender, 31);
  EXPECT_EQ(block.data, (std::vector<std::uint8_t>{0x03}));
  read_delivery rest = next_delivery(d);
  ASSERT_TRUE(rest.result);
  EXPECT_EQ(rest.result.kind, delivery_kind::broadcast);
  EXPECT_EQ(rest.data, (std::vector<std::uint8_t>{0x0F}));
  // In a transmission directed elsewhere, its block is still its own.
  const segment directed_block[] = {{true, 6, byte_view(a, 2)}};
  (void)hear(d, words_of(transmission{31, false, 9, span<const segment>(directed_block, 1)}));
  block = next_delivery(d);
  ASSERT_TRUE(block.result);
  EXPECT_EQ(block.result.kind, delivery_kind::block);
  EXPECT_EQ(block.data, (std::vector<std::uint8_t>{0x01, 0x02}));
}

TEST(GeniusDevice, PlainDataAroundABlockForAnotherDeviceIsOneRecordAndAroundItsOwnThree) {
  default_device d(6);
  const std::uint8_t first[] = {0x01};
  const std::uint8_t block[] = {0x02};
  const std::uint8_t last[] = {0x03};
  const segment others[] = {
      {false, 0, byte_view(first, 1)}, {true, 5, byte_view(block, 1)}, {false, 0, byte_view(last, 1)}};
  (void)hear(d, words_of(transmission{31, true, 0, span<const segment>(others, 3)}));
  read_delivery plain = next_delivery(d);
  ASSERT_TRUE(plain.result);
  EXPECT_EQ(plain.result.kind, delivery_kind::broadcast);
  EXPECT_EQ(plain.data, (std::vector<std::uint8_t>{0x01, 0x03}));  // SBA 5's block is not its to see
  EXPECT_EQ(next_delivery(d).result.status, delivery_status::none_waiting);
  const segment its_own[] = {
      {false, 0, byte_view(first, 1)}, {true, 6, byte_view(block, 1)}, {false, 0, byte_view(last, 1)}};
  (void)hear(d, words_of(transmission{31, true, 0, span<const segment>(its_own, 3)}));
  const delivery_kind kinds[] = {delivery_kind::broadcast, delivery_kind::block, delivery_kind::broadcast};
  const std::uint8_t bytes[] = {0x01, 0x02, 0x03};
  for (int k = 0; k < 3; ++k) {
    const read_delivery got = next_delivery(d);
    ASSERT_TRUE(got.result);
    EXPECT_EQ(got.result.kind, kinds[k]);
    EXPECT_EQ(got.data, (std::vector<std::uint8_t>{bytes[k]}));
  }
  EXPECT_EQ(d.counters().deliveries, 4u);
}

TEST(GeniusDevice, AFramingErrorInItsOwnTransmissionWaitsForTheGapThenTheIdleRestart) {
  default_device d(6);
  const std::uint8_t inputs[] = {0x01, 0x02};
  ASSERT_EQ(d.set_turn_data(byte_view(inputs, 2)), turn_data_status::ok);
  (void)hear(d, broadcast_from(4, {0x33}));
  ASSERT_TRUE(d.timer_expired().transmit);
  std::uint16_t w = 0;
  for (int k = 0; k < 2; ++k) {  // its Start and first data character go out and come back
    ASSERT_TRUE(d.transmit(w));
    (void)d.start_bit();
    ASSERT_TRUE(d.receive(w).transmit);
  }
  (void)d.start_bit();
  const link_request r = d.framing_error();  // the next character comes back with a framing error
  EXPECT_EQ(r.ticks, 22u);                   // its own transmission is open on the bus: the two-character gap
  EXPECT_FALSE(r.transmit);
  EXPECT_FALSE(d.sending());
  EXPECT_EQ(d.counters().collisions, 1u);
  const link_request after = d.timer_expired();  // silence: as if its own Stop had ended
  EXPECT_EQ(after.ticks, 32u + 22u);             // no turn after its own Stop, only the idle restart
  EXPECT_FALSE(d.turn_armed());
  EXPECT_EQ(d.counters().lost_transmissions, 0u);  // the collision ended it, not the silence
}

TEST(GeniusDevice, AStrayStopIsAWireErrorOnceThenSkippedUntilTheNextStart) {
  default_device d(6);
  (void)hear(d, broadcast_from(4, {0x11}));  // in step
  const std::uint16_t stray = to_uart_word(stop_character(0));
  const link_request r = hear(d, {stray});
  EXPECT_EQ(r.ticks, 32u + 22u);  // no sender: no turn to hand on
  EXPECT_EQ(d.counters().wire_errors, 1u);
  EXPECT_NE(d.netstat() & netstat_wire_error, 0);
  const std::uint32_t skipped = d.counters().skipped;
  (void)hear(d, {stray});
  EXPECT_EQ(d.counters().wire_errors, 1u);
  EXPECT_EQ(d.counters().skipped, skipped + 1);
  (void)hear(d, broadcast_from(4, {0x22}));  // a Start brings it back in step
  EXPECT_EQ(d.counters().transmissions_heard, 2u);
}

TEST(GeniusDevice, InAnotherControlLayoutItSendsAndReceivesInThatLayout) {
  control_layout tags_low_reversed;
  tags_low_reversed.start = 3;
  tags_low_reversed.stop = 2;
  tags_low_reversed.start_of_block = 1;
  tags_low_reversed.end_of_block = 0;
  tags_low_reversed.position = tag_position::low;
  control_layout tags_high_swapped;
  tags_high_swapped.start = 1;
  tags_high_swapped.stop = 0;
  tags_high_swapped.start_of_block = 3;
  tags_high_swapped.end_of_block = 2;
  for (const control_layout& layout : {tags_low_reversed, tags_high_swapped, control_layout{}}) {
    default_device d(6, bit_timing(rate::standard_153k6), crc6_g704{}, layout);
    const std::uint8_t outputs[] = {0x5A, 0xA5};
    const std::uint8_t other[] = {0x01};
    const std::uint8_t plain_bytes[] = {0x0F, 0xF0};
    const segment from_controller[] = {
        {true, 5, byte_view(other, 1)}, {true, 6, byte_view(outputs, 2)}, {false, 0, byte_view(plain_bytes, 2)}};
    (void)hear(d, words_of(transmission{31, true, 0, span<const segment>(from_controller, 3)}, layout));
    read_delivery block = next_delivery(d);
    ASSERT_TRUE(block.result);
    EXPECT_EQ(block.result.kind, delivery_kind::block);
    EXPECT_EQ(block.result.sender, 31);
    EXPECT_EQ(block.data, (std::vector<std::uint8_t>{0x5A, 0xA5}));
    read_delivery plain = next_delivery(d);
    ASSERT_TRUE(plain.result);
    EXPECT_EQ(plain.result.kind, delivery_kind::broadcast);
    EXPECT_EQ(plain.data, (std::vector<std::uint8_t>{0x0F, 0xF0}));
    // A directed transmission to it from SBA 2 (its turn 4 skip times after that Stop), then its own turn.
    const std::uint8_t command[] = {0x42};
    const segment directed[] = {{false, 0, byte_view(command, 1)}};
    const link_request r = hear(d, words_of(transmission{2, false, 6, span<const segment>(directed, 1)}, layout));
    EXPECT_EQ(r.timer, timer_action::arm);
    EXPECT_EQ(r.ticks, 4u);
    read_delivery to_it = next_delivery(d);
    ASSERT_TRUE(to_it.result);
    EXPECT_EQ(to_it.result.kind, delivery_kind::directed);
    EXPECT_EQ(to_it.result.sender, 2);
    EXPECT_EQ(to_it.data, (std::vector<std::uint8_t>{0x42}));
    const std::uint8_t inputs[] = {0x11, 0x22, 0x33};
    ASSERT_EQ(d.set_turn_data(byte_view(inputs, 3)), turn_data_status::ok);
    const segment own[] = {{false, 0, byte_view(inputs, 3)}};
    EXPECT_EQ(take_turn(d), words_of(transmission{6, true, 0, span<const segment>(own, 1)}, layout));
    // A Start of block with its top field bit set is no control character of this layout: a wire error.
    std::vector<std::uint16_t> unknown = words_of(transmission{3, true, 0, span<const segment>(own, 1)}, layout);
    unknown.insert(unknown.begin() + 2, to_uart_word(unknown_control_character(layout)));
    (void)hear(d, unknown);
    EXPECT_FALSE(next_delivery(d).result);
    const device_counters c = d.counters();
    EXPECT_EQ(c.wire_errors, 1u);
    EXPECT_EQ(c.crc_errors, 0u);
    EXPECT_EQ(c.transmissions_heard, 2u);
    EXPECT_EQ(c.deliveries, 3u);
    EXPECT_EQ(c.transmissions_sent, 1u);
  }
}

TEST(GeniusDevice, NothingThatFailsItsCrc6IsDeliveredAndTheErrorIsCounted) {
  default_device d(6);
  std::vector<std::uint16_t> words = broadcast_from(4, {0x11, 0x22});
  words[1] ^= 0x02;  // a data bit of the first data character
  const link_request r = hear(d, words);
  EXPECT_EQ(r.ticks, 2u);  // the turns go on after the Stop all the same
  EXPECT_EQ(next_delivery(d).result.status, delivery_status::none_waiting);
  EXPECT_EQ(d.counters().crc_errors, 1u);
  EXPECT_NE(d.netstat() & netstat_crc_error, 0);
  // A block whose End of block does not match drops the whole transmission.
  const std::uint8_t a[] = {0x01};
  const segment block{true, 6, byte_view(a, 1)};
  words = words_of(transmission{31, true, 0, span<const segment>(&block, 1)});
  words[3] ^= 0x04;  // End of block's CRC
  (void)hear(d, words);
  EXPECT_EQ(next_delivery(d).result.status, delivery_status::none_waiting);
  EXPECT_EQ(d.counters().crc_errors, 2u);
}

TEST(GeniusDevice, AFramingErrorDiscardsTheTransmissionAndIsCounted) {
  default_device d(6);
  const std::vector<std::uint16_t> words = broadcast_from(4, {0x11, 0x22});
  (void)d.start_bit();
  (void)d.receive(words[0]);
  (void)d.start_bit();
  EXPECT_EQ(d.framing_error().ticks, 22u);  // still inside SBA 4's transmission
  for (std::size_t k = 2; k < words.size(); ++k) {
    (void)d.start_bit();
    (void)d.receive(words[k]);
  }
  EXPECT_EQ(next_delivery(d).result.status, delivery_status::none_waiting);
  const device_counters c = d.counters();
  EXPECT_EQ(c.framing_errors, 1u);
  EXPECT_EQ(c.wire_errors, 0u);  // the rest is skipped to the next Start, not counted again
  EXPECT_TRUE(d.turn_armed());   // its Stop still hands the turn on
}

TEST(GeniusDevice, SilenceInsideATransmissionLosesItAndActsAsItsSendersStop) {
  default_device d(6);
  const std::vector<std::uint16_t> words = broadcast_from(4, {0x11, 0x22});
  for (std::size_t k = 0; k < 2; ++k) {
    (void)d.start_bit();
    (void)d.receive(words[k]);
  }
  const link_request r = d.timer_expired();  // the two-character gap
  EXPECT_EQ(r.timer, timer_action::arm);
  EXPECT_EQ(r.ticks, 2u);  // as if SBA 4's Stop ended now
  EXPECT_TRUE(d.turn_armed());
  EXPECT_EQ(d.counters().lost_transmissions, 1u);
  EXPECT_EQ(next_delivery(d).result.status, delivery_status::none_waiting);
}

TEST(GeniusDevice, TheQuietBusRestartsTheTurnsFromSba0) {
  default_device d(6);
  (void)d.power_on();
  const link_request r = d.timer_expired();
  EXPECT_EQ(r.ticks, 7u);  // as if SBA 31's Stop had ended: (6 - 31) mod 32
  EXPECT_EQ(d.counters().idle_restarts, 1u);
  default_device first(0);
  (void)first.power_on();
  EXPECT_EQ(first.timer_expired().ticks, 1u);
  // SBA 31 itself waits a whole round, so that it takes its turns on a bus of its own too.
  default_device last(31);
  (void)last.power_on();
  EXPECT_EQ(last.timer_expired().ticks, 32u);
}

TEST(GeniusDevice, ALoneDeviceSendsEveryRoundAfterTheIdleTime) {
  default_device d(3);
  const std::uint8_t inputs[] = {0x42};
  ASSERT_EQ(d.set_turn_data(byte_view(inputs, 1)), turn_data_status::ok);
  (void)d.power_on();
  for (int round = 0; round < 3; ++round) {
    EXPECT_EQ(d.timer_expired().ticks, 4u);  // the idle restart: SBA 3's turn 4 skip times later
    EXPECT_EQ(take_turn(d), broadcast_from(3, {0x42}));
  }
  EXPECT_EQ(d.counters().transmissions_sent, 3u);
}

TEST(GeniusDevice, AStopWhoseStartItMissedHandsNoTurnOn) {
  default_device d(6);
  std::vector<std::uint16_t> words = broadcast_from(4, {0x11});
  words.erase(words.begin());  // joined after the Start
  const link_request r = hear(d, words);
  EXPECT_EQ(r.ticks, 32u + 22u);  // only the idle restart
  EXPECT_FALSE(d.turn_armed());
  EXPECT_EQ(d.counters().wire_errors, 0u);  // after power-up it skips to the first Start
}

TEST(GeniusDevice, StructureErrorsAreCountedAndNothingIsDelivered) {
  default_device d(6);
  (void)hear(d, {to_uart_word(start_character(4, true)), to_uart_word(stop_character(0))});  // no data
  (void)hear(d, {to_uart_word(start_character(4, false)), to_uart_word(data_character(40)),
                 to_uart_word(stop_character(0))});  // destination out of range
  EXPECT_EQ(d.counters().wire_errors, 2u);
  EXPECT_EQ(next_delivery(d).result.status, delivery_status::none_waiting);
}

TEST(GeniusDevice, ATransmissionThatDoesNotFitTheDeliveryQueueIsDroppedWholeAndCounted) {
  device<32, 8> d(6);  // room for one delivery of 5 bytes
  (void)hear(d, broadcast_from(4, {1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(next_delivery(d).result.status, delivery_status::none_waiting);
  EXPECT_EQ(d.counters().delivery_overflows, 1u);
  (void)hear(d, broadcast_from(4, {1, 2, 3, 4, 5}));
  EXPECT_TRUE(next_delivery(d).result);
}

TEST(GeniusDevice, AReadIntoATooSmallBufferLeavesTheDeliveryWaiting) {
  default_device d(6);
  (void)hear(d, broadcast_from(4, {1, 2, 3}));
  std::uint8_t small[2];
  const delivery_result r = d.read(byte_buffer(small, 2));
  EXPECT_EQ(r.status, delivery_status::buffer_too_small);
  EXPECT_EQ(r.length, 3u);
  EXPECT_TRUE(d.deliveries_waiting());
  EXPECT_EQ(next_delivery(d).data, (std::vector<std::uint8_t>{1, 2, 3}));
}

TEST(GeniusDevice, BroadcastsAreDeliveredOnlyFromTheSendersChosen) {
  default_device d(6);
  d.deliver_broadcasts_from(1u << 31);
  (void)hear(d, broadcast_from(4, {1}));
  (void)hear(d, broadcast_from(31, {2}));
  const std::uint8_t to_me[] = {3};
  const segment plain{false, 0, byte_view(to_me, 1)};
  (void)hear(d, words_of(transmission{4, false, 6, span<const segment>(&plain, 1)}));
  EXPECT_EQ(next_delivery(d).data, (std::vector<std::uint8_t>{2}));
  EXPECT_EQ(next_delivery(d).data, (std::vector<std::uint8_t>{3}));  // directed: whatever the mask
  EXPECT_EQ(next_delivery(d).result.status, delivery_status::none_waiting);
}

TEST(GeniusDevice, TurnDataIsRefusedWhenMisused) {
  device<8> d(6);
  const std::uint8_t bytes[] = {1, 2, 3, 4, 5, 6, 7};
  EXPECT_EQ(d.set_turn_data(byte_view(bytes, 7)), turn_data_status::too_long);  // 7 + 2 > 8
  EXPECT_EQ(d.set_turn_data(byte_view(bytes, 6)), turn_data_status::ok);
  const segment empty_block{true, 3, byte_view()};
  EXPECT_EQ(d.set_turn_data(span<const segment>(&empty_block, 1)), turn_data_status::empty_block);
  const segment far_block{true, 32, byte_view(bytes, 1)};
  EXPECT_EQ(d.set_turn_data(span<const segment>(&far_block, 1)), turn_data_status::destination_out_of_range);
}

TEST(GeniusBusController, SendsEveryDeviceItsOutputsAsBlocksInOneTransmission) {
  bus_controller<4, 4> controller(31);
  const std::uint8_t out3[] = {0x30, 0x31};
  const std::uint8_t out6[] = {0x60};
  ASSERT_EQ(controller.set_outputs(3, byte_view(out3, 2)), outputs_status::ok);
  ASSERT_EQ(controller.set_outputs(6, byte_view(out6, 1)), outputs_status::ok);
  EXPECT_EQ(controller.set_outputs(31, byte_view(out6, 1)), outputs_status::own_sba);
  const std::uint8_t five[] = {1, 2, 3, 4, 5};
  EXPECT_EQ(controller.set_outputs(7, byte_view(five, 5)), outputs_status::too_long);
  EXPECT_EQ(controller.set_outputs(32, byte_view(five, 1)), outputs_status::sba_out_of_range);
  ASSERT_EQ(controller.publish_outputs(), turn_data_status::ok);
  (void)hear(controller, broadcast_from(30, {0x01}));
  const std::vector<std::uint16_t> sent = take_turn(controller);
  const segment blocks[] = {{true, 3, byte_view(out3, 2)}, {true, 6, byte_view(out6, 1)}};
  EXPECT_EQ(sent, words_of(transmission{31, true, 0, span<const segment>(blocks, 2)}));
  // Device 6 takes its own block from it.
  default_device six(6);
  (void)hear(six, sent);
  const read_delivery got = next_delivery(six);
  EXPECT_EQ(got.result.kind, delivery_kind::block);
  EXPECT_EQ(got.data, (std::vector<std::uint8_t>{0x60}));
}

TEST(GeniusBusController, CollectsEveryDevicesInputs) {
  bus_controller<4, 2> controller(31);
  (void)hear(controller, broadcast_from(3, {0x11, 0x12}));
  (void)hear(controller, broadcast_from(6, {0x21, 0x22, 0x23}));  // longer than it keeps
  std::size_t visited = 0;
  EXPECT_EQ(controller.collect([&](const delivery_result&, byte_view) { ++visited; }), 2u);
  EXPECT_EQ(visited, 2u);
  EXPECT_EQ(std::vector<std::uint8_t>(controller.inputs(3).begin(), controller.inputs(3).end()),
            (std::vector<std::uint8_t>{0x11, 0x12}));
  EXPECT_EQ(std::vector<std::uint8_t>(controller.inputs(6).begin(), controller.inputs(6).end()),
            (std::vector<std::uint8_t>{0x21, 0x22}));
  EXPECT_EQ(controller.input_updates(3), 1u);
  EXPECT_EQ(controller.input_overflows(), 1u);
  EXPECT_TRUE(controller.inputs(9).empty());
}

TEST(GeniusDevice, EveryEnumHasItsName) {
  EXPECT_STREQ(to_string(timer_action::cancel), "cancel");
  EXPECT_STREQ(to_string(delivery_kind::block), "block");
  EXPECT_STREQ(to_string(delivery_status::buffer_too_small), "buffer_too_small");
  EXPECT_STREQ(to_string(turn_data_status::empty_block), "empty_block");
  EXPECT_STREQ(to_string(queue_status::full), "full");
  EXPECT_STREQ(to_string(outputs_status::own_sba), "own_sba");
  EXPECT_STREQ(to_string(netstat_idle_restart), "netstat_idle_restart");
}

}  // namespace
