// The character maximum (docs/protocol.md 1.4): a character transfer longer than MaxCharacters is the wrong
// length whatever room its store has; a shorter one that its store cannot hold is `no_room`, valid but not
// kept.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "support/ring_events.hpp"
#include "support/ring_frames.hpp"
#include "trionet/ring.hpp"

namespace {

namespace ring = trionet::ring;
using trionet::test::chars;
using trionet::test::decode_bulk;
using trionet::test::decode_bytewise;
using trionet::test::event;

// `first` and then a short character transfer that must decode whatever happened to `first`.
std::vector<std::uint8_t> then_ok(std::vector<std::uint8_t> first) {
  const std::vector<std::uint8_t> ok = chars(1, "OK");
  first.insert(first.end(), ok.begin(), ok.end());
  return first;
}

template <class Decoder>
std::vector<event> both_ways(const std::vector<std::uint8_t>& bytes) {
  Decoder one, bulk;
  const std::vector<event> events = decode_bytewise(one, bytes);
  EXPECT_EQ(decode_bulk(bulk, bytes), events);
  return events;
}

// A store of 64 characters behind a decoder whose maximum is 16.
using roomy = ring::basic_decoder<trionet::detail::character_buffer<64>, 16>;
// A store of 8 characters behind a decoder whose maximum is 16.
using cramped = ring::basic_decoder<trionet::detail::character_buffer<8>, 16>;

TEST(RingCharacterMaximum, ATransferOfTheMaximumIsTaken) {
  const std::string sixteen(16, 'M');
  const std::vector<event> events = both_ways<roomy>(chars(3, sixteen));
  ASSERT_EQ(events.size(), 1U);
  EXPECT_EQ(events[0].status, ring::decode_status::ok);
  EXPECT_EQ(events[0].text, sixteen);
  EXPECT_EQ(events[0].hops, 3);
}

TEST(RingCharacterMaximum, OneCharacterMoreIsTheWrongLengthThoughTheStoreHasRoom) {
  for (std::size_t n : {17U, 18U, 64U, 65U, 300U}) {
    const std::vector<event> events = both_ways<roomy>(then_ok(chars(3, std::string(n, 'L'))));
    ASSERT_EQ(events.size(), 2U) << n;
    EXPECT_EQ(events[0].status, ring::decode_status::frame_error) << n;
    EXPECT_EQ(events[0].error, ring::frame_error::bad_length) << n;
    EXPECT_EQ(events[1].status, ring::decode_status::ok) << "the next message is decoded: " << n;
    EXPECT_EQ(events[1].text, "OK");
  }
}

TEST(RingCharacterMaximum, AValidTransferTheStoreCannotHoldIsNoRoom) {
  std::vector<event> events = both_ways<cramped>(chars(2, std::string(8, 'F')));
  ASSERT_EQ(events.size(), 1U);
  EXPECT_EQ(events[0].status, ring::decode_status::ok) << "eight characters fit";
  for (std::size_t n : {9U, 16U}) {
    events = both_ways<cramped>(then_ok(chars(2, std::string(n, 'N'))));
    ASSERT_EQ(events.size(), 2U) << n;
    EXPECT_EQ(events[0].status, ring::decode_status::no_room) << n;
    EXPECT_EQ(events[0].type, ring::message_type::character) << n;
    EXPECT_EQ(events[0].hops, 2) << n;
    EXPECT_EQ(events[1].text, "OK");
  }
  events = both_ways<cramped>(chars(2, std::string(17, 'L')));
  ASSERT_EQ(events.size(), 1U);
  EXPECT_EQ(events[0].error, ring::frame_error::bad_length) << "too long is too long, room or not";
}

}  // namespace
