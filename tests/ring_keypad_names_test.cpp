// The keys' names (the key script's words, docs/basic.md), one table for the simulator and the keypad
// emulator.
#include <gtest/gtest.h>

#include <string>
#include <utility>

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

// Every key's to_string is its enumerator's spelling (the traces print it); a value outside the enum is
// "unknown".
TEST(RingKeypadNames, ToStringIsTheEnumeratorsSpelling) {
  const char* const digits[] = {"digit_0", "digit_1", "digit_2", "digit_3", "digit_4",
                                "digit_5", "digit_6", "digit_7", "digit_8", "digit_9"};
  for (unsigned d = 0; d < 10; ++d) EXPECT_STREQ(ring::to_string(ring::digit_key(d)), digits[d]);
  const std::pair<ring::key, const char*> others[] = {
      {ring::key::up, "up"},       {ring::key::down, "down"},   {ring::key::clear, "clear"},
      {ring::key::yes, "yes"},     {ring::key::no, "no"},       {ring::key::point, "point"},
      {ring::key::start, "start"}, {ring::key::stop, "stop"}};
  for (const auto& [key, name] : others) EXPECT_STREQ(ring::to_string(key), name);
  EXPECT_STREQ(ring::to_string(static_cast<ring::key>(99)), "unknown");
}

}  // namespace
