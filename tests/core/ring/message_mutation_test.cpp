// A message's fields (ring/message.hpp): "which fields mean something depends on `type`; the others are 0",
// for a message made empty and for each of the four made by its constructors; and link counters (netstat.hpp)
// start at 0.
#include <gtest/gtest.h>

#include <cstdint>

#include "trionet/ring/message.hpp"
#include "trionet/ring/netstat.hpp"

namespace {

namespace ring = trionet::ring;

void expect_fields(const ring::message& m, std::int64_t value, std::size_t text_size, std::uint16_t vr,
                   std::uint8_t hops, std::uint8_t offset, std::uint8_t mode) {
  EXPECT_EQ(m.value, value);
  EXPECT_EQ(m.text.size(), text_size);
  EXPECT_EQ(m.vr, vr);
  EXPECT_EQ(m.hops, hops);
  EXPECT_EQ(m.offset, offset);
  EXPECT_EQ(m.mode, mode);
}

TEST(RingStartingValues, AMessageIsACharacterTransferWithEveryFieldZero) {
  const ring::message m{};
  EXPECT_EQ(m.type, ring::message_type::character);
  expect_fields(m, 0, 0, 0, 0, 0, 0);
  EXPECT_EQ(ring::frame_length(m), ring::framing_length);
}

TEST(RingMessage, EachConstructorSetsItsFieldsAndLeavesTheOthersZero) {
  const std::uint8_t text[] = {'H', 'I'};
  const ring::message characters = ring::message::characters(3, text);
  EXPECT_EQ(characters.type, ring::message_type::character);
  expect_fields(characters, 0, 2, 0, 3, 0, 0);
  const ring::message variable = ring::message::variable(4, 300, -7);
  EXPECT_EQ(variable.type, ring::message_type::variable);
  expect_fields(variable, -7, 0, 300, 4, 0, 0);
  const ring::message offset = ring::message::keypad_offset(5, 9);
  EXPECT_EQ(offset.type, ring::message_type::keypad_offset);
  expect_fields(offset, 0, 0, 0, 5, 9, 0);
  const ring::message mode = ring::message::keypad_mode(6, ring::keypad_mode_key_on_off);
  EXPECT_EQ(mode.type, ring::message_type::keypad_mode);
  expect_fields(mode, 0, 0, 0, 6, 0, 127);
}

TEST(RingStartingValues, LinkCountersStartAtZero) {
  const ring::link_counters c{};
  EXPECT_EQ(c.forwards_lost, 0U);
  EXPECT_EQ(c.forwards_cut, 0U);
  EXPECT_EQ(c.forwards_ended_idle, 0U);
  EXPECT_EQ(c.messages_forwarded, 0U);
  EXPECT_EQ(c.messages_dropped, 0U);
  EXPECT_EQ(c.messages_sent, 0U);
  EXPECT_EQ(c.forwards_failed(), 0U);
}

}  // namespace
