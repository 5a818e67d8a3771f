// Genius 11-bit characters (docs/protocol.md 3.1): the word codec and the bit-stream receiver.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include <trionet/genius/character.hpp>

#include "support/rng.hpp"

namespace {

using trionet::test::rng;

using namespace trionet::genius;

// GE's bit order, spelled out: start 0, control bit, 8 data bits least significant first, stop 1.
std::vector<bool> wire_bits(character c) {
  std::vector<bool> bits{false, c.control};
  for (int i = 0; i < 8; ++i) bits.push_back(((c.byte >> i) & 1) != 0);
  bits.push_back(true);
  return bits;
}

TEST(GeniusCharacter, WordBitIAreWireBitI) {
  for (unsigned byte = 0; byte < 256; ++byte) {
    for (bool control : {false, true}) {
      const character c{static_cast<std::uint8_t>(byte), control};
      const std::uint16_t word = encode_character(c);
      const std::vector<bool> bits = wire_bits(c);
      ASSERT_EQ(bits.size(), character_bits);
      for (unsigned i = 0; i < character_bits; ++i)
        EXPECT_EQ(((word >> i) & 1u) != 0, bits[i]) << byte << " " << i;
      EXPECT_EQ(word >> character_bits, 0u);
    }
  }
}

TEST(GeniusCharacter, DocumentedExamples) {
  static_assert(encode_character(data_character(0xa5)) == 0x694);
  static_assert(encode_character(control_character(0x04)) == 0x412);
  EXPECT_EQ(encode_character(data_character(0x00)), 0x400);
  EXPECT_EQ(encode_character(control_character(0xff)), 0x7fe);
}

TEST(GeniusCharacter, EveryCharacterRoundTrips) {
  for (unsigned byte = 0; byte < 256; ++byte) {
    for (bool control : {false, true}) {
      const character c{static_cast<std::uint8_t>(byte), control};
      const character_result back = decode_character(encode_character(c));
      ASSERT_TRUE(back);
      EXPECT_EQ(back.value, c);
    }
  }
}

TEST(GeniusCharacter, FramingErrorsInWords) {
  const std::uint16_t good = encode_character(data_character(0x5a));
  EXPECT_EQ(decode_character(good | start_bit_mask).status, character_status::start_bit_not_0);
  EXPECT_EQ(decode_character(good & ~stop_bit_mask & 0xffff).status, character_status::stop_bit_not_1);
  // Both wrong: the start bit comes first on the wire and is the one reported.
  EXPECT_EQ(decode_character(static_cast<std::uint16_t>((good | start_bit_mask) & ~stop_bit_mask)).status,
            character_status::start_bit_not_0);
  EXPECT_EQ(decode_character(static_cast<std::uint16_t>(good | 0x800)).status, character_status::not_11_bits);
  EXPECT_FALSE(decode_character(0xffff));
}

// Feeds bits and collects every non-empty event.
struct collected {
  std::vector<bit_status> events;
  std::vector<character> characters;
};

collected feed(bit_receiver& rx, const std::vector<bool>& bits) {
  collected out;
  for (bool bit : bits) {
    const bit_status s = rx.push(bit);
    if (s == bit_status::nothing_yet) continue;
    out.events.push_back(s);
    if (s == bit_status::ok) out.characters.push_back(rx.last());
  }
  return out;
}

TEST(GeniusBitReceiver, IdleOnesAreIgnoredAndAZeroIsAStartBit) {
  bit_receiver rx;
  // Right after reset the line counts as idle, so the very first 0 is a start bit.
  std::vector<bool> bits = wire_bits(data_character(0x81));
  std::vector<bool> more = wire_bits(control_character(0x3c));
  bits.insert(bits.end(), {true, true, true});  // idle line between characters
  bits.insert(bits.end(), more.begin(), more.end());
  const collected got = feed(rx, bits);
  ASSERT_EQ(got.characters.size(), 2u);
  EXPECT_EQ(got.characters[0], data_character(0x81));
  EXPECT_EQ(got.characters[1], control_character(0x3c));
  EXPECT_EQ(rx.characters(), 2u);
}

TEST(GeniusBitReceiver, RandomBackToBackAndGappedCharactersRoundTrip) {
  rng random(5);
  for (int round = 0; round < 200; ++round) {
    bit_receiver rx;
    std::vector<character> sent;
    std::vector<bool> bits;
    const int count = 1 + static_cast<int>(random() % 40);
    for (int i = 0; i < count; ++i) {
      const character c{static_cast<std::uint8_t>(random() & 0xff), (random() & 1) != 0};
      sent.push_back(c);
      const std::vector<bool> w = wire_bits(c);
      bits.insert(bits.end(), w.begin(), w.end());
      const unsigned gap = random() % 3 == 0 ? random() % 5 : 0;
      for (unsigned g = 0; g < gap; ++g) bits.push_back(true);
    }
    const collected got = feed(rx, bits);
    ASSERT_EQ(got.characters, sent);
    EXPECT_EQ(rx.stop_bit_errors() + rx.start_bit_errors(), 0u);
  }
}

TEST(GeniusBitReceiver, StopBitNot1ThenResynchronisesOnTheNext1To0Transition) {
  bit_receiver rx;
  std::vector<bool> bits = wire_bits(data_character(0x00));
  bits.back() = false;  // the stop bit is 0
  // The line stays at 0 for a while: no 1->0 transition yet, so these zeros are not start bits.
  bits.insert(bits.end(), {false, false, false});
  bits.push_back(true);  // the line returns to 1
  const std::vector<bool> next = wire_bits(data_character(0x42));
  bits.insert(bits.end(), next.begin(), next.end());
  const collected got = feed(rx, bits);
  ASSERT_EQ(got.events.size(), 2u);
  EXPECT_EQ(got.events[0], bit_status::stop_bit_not_1);
  EXPECT_EQ(got.events[1], bit_status::ok);
  EXPECT_EQ(got.characters[0], data_character(0x42));
  EXPECT_EQ(rx.stop_bit_errors(), 1u);
}

TEST(GeniusBitReceiver, WithoutResyncTheZerosAfterABadStopBitWouldHaveStartedACharacter) {
  // Counter-check of the test above: the same bits with the stop bit intact decode differently.
  bit_receiver rx;
  std::vector<bool> bits = wire_bits(data_character(0x00));
  bits.insert(bits.end(), {false, false, false});
  for (int i = 0; i < 8; ++i) bits.push_back(true);
  const collected got = feed(rx, bits);
  ASSERT_EQ(got.characters.size(), 2u);
  // start 0 (first zero), control 0, d0 0, d1..d7 1, stop 1: data 0xfe.
  EXPECT_EQ(got.characters[1], data_character(0xfe));
}

TEST(GeniusBitReceiver, StartBitNot0WhenACharacterIsDue) {
  bit_receiver rx;
  std::vector<bool> bits = wire_bits(data_character(0x11));
  collected got = feed(rx, bits);
  ASSERT_EQ(got.characters.size(), 1u);
  rx.expect_next_character();
  EXPECT_EQ(rx.push(true), bit_status::start_bit_not_0);
  EXPECT_EQ(rx.start_bit_errors(), 1u);
  // The line is at 1 now: the next 0 is a 1->0 transition and starts a character.
  got = feed(rx, wire_bits(data_character(0x22)));
  ASSERT_EQ(got.characters.size(), 1u);
  EXPECT_EQ(got.characters[0], data_character(0x22));
}

TEST(GeniusBitReceiver, ExpectNextCharacterWithAStartBitIsQuiet) {
  bit_receiver rx;
  ASSERT_EQ(feed(rx, wire_bits(data_character(0x11))).characters.size(), 1u);
  rx.expect_next_character();
  const collected got = feed(rx, wire_bits(data_character(0x33)));
  ASSERT_EQ(got.events.size(), 1u);
  EXPECT_EQ(got.characters[0], data_character(0x33));
}

TEST(GeniusBitReceiver, ExpectNextCharacterIsIgnoredInsideACharacter) {
  bit_receiver rx;
  const std::vector<bool> bits = wire_bits(data_character(0xf0));
  for (std::size_t i = 0; i + 1 < bits.size(); ++i) {
    ASSERT_EQ(rx.push(bits[i]), bit_status::nothing_yet);
    rx.expect_next_character();
  }
  EXPECT_EQ(rx.push(bits.back()), bit_status::ok);
  EXPECT_EQ(rx.last(), data_character(0xf0));
  EXPECT_EQ(rx.start_bit_errors(), 0u);
}

TEST(GeniusBitReceiver, ResetAndCounters) {
  bit_receiver rx;
  EXPECT_EQ(rx.push(false), bit_status::nothing_yet);
  EXPECT_TRUE(rx.receiving());
  rx.reset();
  EXPECT_FALSE(rx.receiving());
  ASSERT_EQ(feed(rx, wire_bits(data_character(7))).characters.size(), 1u);
  EXPECT_EQ(rx.characters(), 1u);
  rx.clear_counters();
  EXPECT_EQ(rx.characters(), 0u);
}

}  // namespace
