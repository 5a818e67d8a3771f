// A membrane keypad in network mode (docs/protocol.md 1.7): a second keypad offset moves where its keys go.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "trionet/ring.hpp"

namespace ring = trionet::ring;

namespace {

std::vector<std::uint8_t> drain(ring::keypad<>& keypad) {
  std::vector<std::uint8_t> out;
  std::uint8_t b = 0;
  while (keypad.transmit(b)) out.push_back(b);
  return out;
}

void feed(ring::keypad<>& keypad, const std::vector<std::uint8_t>& bytes) {
  for (std::uint8_t b : bytes) keypad.receive(b);
}

}  // namespace

// "SEND(n,2,data1): ... data1 is in the range 10..24 to specify the number of nodes from the keypad that the
// key characters are sent": sent again, it moves the keys.
TEST(RingKeypad, ASecondKeypadOffsetMovesWhereKeysGo) {
  ring::keypad<> keypad;
  feed(keypad, {ring::make_header(1, 3), 2, ring::make_end_of_message(1)});  // SEND(n,2,11): 2 hops on
  ASSERT_TRUE(keypad.network_mode());
  ASSERT_EQ(keypad.press(ring::key::digit_7), ring::key_status::ok);
  EXPECT_EQ(drain(keypad), (std::vector<std::uint8_t>{ring::make_header(2, 1), '7', ring::make_end_of_message(2)}));
  feed(keypad, {ring::make_header(1, 3), 5, ring::make_end_of_message(1)});  // SEND(n,2,14): 5 hops on
  EXPECT_EQ(keypad.offset(), 5);
  ASSERT_EQ(keypad.press(ring::key::yes), ring::key_status::ok);
  EXPECT_EQ(drain(keypad), (std::vector<std::uint8_t>{ring::make_header(5, 1), 'Y', ring::make_end_of_message(5)}));
  EXPECT_EQ(keypad.counters().frame_errors, 0u);
}

// Every key_status has its enumerator's spelling (the CLI and the traces print it).
TEST(RingKeypad, KeyStatusNamesAreTheEnumeratorsSpelling) {
  EXPECT_STREQ(trionet::ring::to_string(trionet::ring::key_status::ok), "ok");
  EXPECT_STREQ(trionet::ring::to_string(trionet::ring::key_status::nothing_to_send), "nothing_to_send");
  EXPECT_STREQ(trionet::ring::to_string(trionet::ring::key_status::local_mode), "local_mode");
  EXPECT_STREQ(trionet::ring::to_string(trionet::ring::key_status::queue_full), "queue_full");
  EXPECT_STREQ(trionet::ring::to_string(static_cast<trionet::ring::key_status>(99)), "unknown");
}
