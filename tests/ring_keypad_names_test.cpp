// The keys' names (the key script's words, docs/basic.md), one table for the simulator and the keypad
// emulator.
#include <gtest/gtest.h>

#include <string>

#include "trionet/ring/keypad_codes.hpp"

namespace ring = trionet::ring;

namespace {

bool named(const std::string& name, ring::key& out) {
  return ring::key_named(name.data(), name.size(), out);
}

TEST(RingKeypadNames, EveryKeyHasItsNamesInAnyCase) {
  ring::key k = ring::key::stop;
  for (unsigned d = 0; d < 10; ++d) {
    ASSERT_TRUE(named(std::to_string(d), k));
    EXPECT_EQ(k, ring::digit_key(d));
  }
  const std::pair<const char*, ring::key> cases[] = {
      {"up", ring::key::up},     {"+", ring::key::up},      {"DOWN", ring::key::down},  {"-", ring::key::down},
      {"Clr", ring::key::clear}, {"y", ring::key::yes},     {"Enter", ring::key::yes},  {"n", ring::key::no},
      {".", ring::key::point},   {"START", ring::key::start}, {"stop", ring::key::stop}};
  for (const auto& [name, key] : cases) {
    ASSERT_TRUE(named(name, k)) << name;
    EXPECT_EQ(k, key) << name;
  }
  static_assert([] {
    ring::key c = ring::key::digit_0;
    return ring::key_named("stop", 4, c) && c == ring::key::stop;
  }());
}

TEST(RingKeypadNames, OtherWordsAreNoKeys) {
  ring::key k = ring::key::digit_7;
  for (const char* word : {"", "10", "u", "upp", "sto", "start ", "wait=5", "quit", "yes"}) {
    EXPECT_FALSE(named(word, k)) << word;
  }
  EXPECT_EQ(k, ring::key::digit_7);  // untouched
  EXPECT_FALSE(ring::key_named("stopped", 4 + 3, k));
  EXPECT_TRUE(ring::key_named("stopped", 4, k));  // the length given is what counts
}

}  // namespace
