// The keypad's codes (ring/keypad_codes.hpp, docs/protocol.md 1.7-1.8): the default key OFF rule at the edge
// where it switches, the DEFKEY table of the file comment for every character, and key names read within
// the length given and never past it (names that are not NUL-terminated, checked at compile time, where a
// read past the array is an error).
#include <gtest/gtest.h>

#include <cstdint>

#include "trionet/ring/keypad_codes.hpp"

namespace {

namespace ring = trionet::ring;

TEST(RingKeypadCodes, KeyOffIsOnPlus64BelowOneHundredTwentyEightElseTheSame) {
  EXPECT_EQ(ring::default_key_off_code(0), 64);
  EXPECT_EQ(ring::default_key_off_code(63), 127) << "63 + 64 = 127 is still below 128";
  EXPECT_EQ(ring::default_key_off_code(64), 64) << "64 + 64 = 128 is not";
  EXPECT_EQ(ring::default_key_off_code(127), 127);
  EXPECT_EQ(ring::same_key_off_code(63), 63);
}

TEST(RingKeypadCodes, TheDefaultDefkeyTableIsTheManualsAndTheIdentityElsewhere) {
  const char raw[] = {'0', '1', '2', '3', '4', '5', '6', '7', '8',
                      '9', 'U', 'D', 'C', 'Y', 'N', '.', 'S', 'T'};
  const std::uint8_t value[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 20, 21};
  for (unsigned c = 0; c < 128; ++c) {
    std::uint8_t expected = static_cast<std::uint8_t>(c);
    for (std::size_t k = 0; k < sizeof raw; ++k) {
      if (static_cast<unsigned>(raw[k]) == c) expected = value[k];
    }
    EXPECT_EQ(ring::default_defkey[static_cast<std::uint8_t>(c)], expected) << c;
    EXPECT_EQ(ring::default_defkey[static_cast<std::uint8_t>(c | 0x80U)], expected) << "bit 7 ignored: " << c;
  }
  for (std::size_t k = 0; k < ring::key_count; ++k) {
    EXPECT_EQ(ring::default_keypad_codes.raw[k], static_cast<std::uint8_t>(raw[k])) << k;
    EXPECT_EQ(ring::defkey_values[k], value[k]) << k;
  }
}

template <std::size_t N>
constexpr bool names_a_key(const char (&name)[N]) {
  ring::key k = ring::key::digit_0;
  return ring::key_named(name, N, k);
}

constexpr char u[] = {'u'};
constexpr char sto[] = {'s', 't', 'o'};
constexpr char star[] = {'s', 't', 'a', 'r'};
constexpr char ente[] = {'E', 'N', 'T', 'E'};
constexpr char stop[] = {'s', 't', 'o', 'p'};
constexpr char up[] = {'U', 'P'};
constexpr char seven[] = {'7'};
static_assert(!names_a_key(u) && !names_a_key(sto) && !names_a_key(star) && !names_a_key(ente),
              "the start of a key name is no key, and nothing past the name is read");
static_assert(names_a_key(stop) && names_a_key(up) && names_a_key(seven), "whole names without a NUL");

TEST(RingKeypadCodes, NamesAreReadWithinTheirLength) {
  EXPECT_FALSE(names_a_key(u));
  EXPECT_FALSE(names_a_key(sto));
  EXPECT_TRUE(names_a_key(stop));
}

}  // namespace
