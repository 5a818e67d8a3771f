// The library's precondition checks (TRIONET_ASSERT, detail/attributes.hpp) switched on, as a debug build of
// firmware would: defined before any trionet header to count the checks that fail. Ring nodes driven through
// the paths that check them (the transmit queue, the forward buffer, the receive buffer, a refused send, a
// direct variable transfer encoded) must fail none. This file is a test program of its own
// (tests/CMakeLists.txt), so that no other translation unit sees the library compiled without the checks.
#include <string>

namespace trionet_test {
inline int failed_checks = 0;
inline std::string first_failed;
inline void check_failed(const char* condition) {
  if (failed_checks++ == 0) first_failed = condition;
}
}  // namespace trionet_test

#define TRIONET_ASSERT(cond) ((cond) ? static_cast<void>(0) : trionet_test::check_failed(#cond))

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "support/ring_frames.hpp"
#include "trionet/ring.hpp"
#include "trionet/vr.hpp"

namespace {

namespace ring = trionet::ring;
using trionet::test::chars;
using trionet::test::drain;
using trionet::test::feed;
using trionet::test::frame_of;
using trionet::test::read_all;

class Preconditions : public ::testing::Test {
 protected:
  void SetUp() override {
    trionet_test::failed_checks = 0;
    trionet_test::first_failed.clear();
  }
  void TearDown() override {
    EXPECT_EQ(trionet_test::failed_checks, 0) << "first: " << trionet_test::first_failed;
  }
};

// A documented precondition broken on purpose is caught: the direct variable transfer's VR (encode.hpp,
// "Precondition: vr <= 16383"); the encoders check the VR before they get there.
TEST_F(Preconditions, AVrOutOfRangeIsCaughtByTheCheck) {
  std::uint8_t data[ring::variable_data_length] = {};
  trionet::detail::write_variable_data<ring::crc16_ccitt_false, ring::default_variable_layout>(
      data, ring::max_vr, 1, ring::crc16_ccitt_false{});
  EXPECT_EQ(trionet_test::failed_checks, 0);
  trionet::detail::write_variable_data<ring::crc16_ccitt_false, ring::default_variable_layout>(
      data, ring::max_vr + 1, 1, ring::crc16_ccitt_false{});
  EXPECT_EQ(trionet_test::failed_checks, 1);
  EXPECT_EQ(trionet_test::first_failed, "vr <= ring::max_vr");
  trionet_test::failed_checks = 0;  // the one expected
}

// The byte queue's precondition for a byte staged beyond its room (detail/fifo.hpp, "Precondition: k <
// free()").
TEST_F(Preconditions, ABytePastTheQueuesRoomIsCaughtByTheCheck) {
  trionet::detail::spsc_fifo<4> fifo;
  fifo.stage(3, 0x33);  // the last free byte
  EXPECT_EQ(trionet_test::failed_checks, 0);
  fifo.stage(4, 0x44);
  EXPECT_EQ(trionet_test::failed_checks, 1);
  EXPECT_EQ(trionet_test::first_failed, "k < free()");
  trionet_test::failed_checks = 0;  // the one expected
  const std::uint8_t bytes[] = {1, 2, 3};
  fifo.stage(1, bytes, 3);  // up to the last free byte
  EXPECT_EQ(trionet_test::failed_checks, 0);
  fifo.stage(2, bytes, 3);  // one past it
  EXPECT_EQ(trionet_test::failed_checks, 1);
  EXPECT_EQ(trionet_test::first_failed, "k + n <= free()");
  trionet_test::failed_checks = 0;
}

// A status map's precondition (detail/status_map.hpp: `from` one of First .. Last), broken on purpose.
TEST_F(Preconditions, AStatusOutsideItsMapIsCaughtByTheCheck) {
  using map = trionet::detail::decode_outcome;
  EXPECT_EQ(map::of(ring::decode_status::ok), ring::receive_status::ok);
  EXPECT_EQ(trionet_test::failed_checks, 0);
  (void)map::of(static_cast<ring::decode_status>(99));
  EXPECT_EQ(trionet_test::failed_checks, 1);
  trionet_test::failed_checks = 0;  // the one expected
}

// SEND refused for want of room: the queue is full (the only reason a checked message is not queued).
TEST_F(Preconditions, ASendRefusedForWantOfRoom) {
  trionet::vr_table<16> vr;
  ring::motion_coordinator<> mc(vr);
  const ring::print_result filled = mc.print(10, std::string(100, 'P').c_str());
  ASSERT_EQ(filled.status, ring::send_status::queue_full);
  EXPECT_EQ(mc.send_variable(11, 7, 1.5), ring::send_status::queue_full);
  EXPECT_EQ(mc.send_keypad_offset(11, 12), ring::send_status::queue_full);
  EXPECT_EQ(mc.counters().sends_refused, 3U);
  (void)drain(mc);
  EXPECT_EQ(mc.send_variable(11, 7, 1.5), ring::send_status::ok) << "room again once the queue is sent";
}

// Messages through a Motion Coordinator and to it, its own messages between them, and GET#.
TEST_F(Preconditions, ForwardingReceivingAndSending) {
  trionet::vr_table<16> vr;
  ring::motion_coordinator<> mc(vr);
  ASSERT_EQ(mc.print(10, "OWN").status, ring::send_status::ok);
  std::uint8_t b = 0;
  ASSERT_TRUE(mc.transmit(b));    // its own message has begun: forwarding waits
  feed(mc, chars(3, "THROUGH"));  // into the forward buffer meanwhile
  feed(mc, chars(1, "TO ME"));    // into the receive buffer
  feed(mc, frame_of(ring::message::variable(1, 5, std::int64_t{3} << 32)));
  const std::vector<std::uint8_t> sent = drain(mc);
  EXPECT_EQ(sent.size(), chars(1, "OWN").size() - 1 + chars(2, "THROUGH").size());
  EXPECT_EQ(read_all(mc), "TO ME");
  EXPECT_EQ(vr.get(5), 3.0);
  EXPECT_EQ(mc.send_variable(11, 16383, -2.25), ring::send_status::ok);
  EXPECT_EQ(drain(mc).size(), 16U);
}

// A keypad: its offset, keys, a message for its display and one through it.
TEST_F(Preconditions, AKeypad) {
  ring::keypad<> keypad;
  feed(keypad, frame_of(ring::message::keypad_offset(1, 2)));
  ASSERT_EQ(keypad.press(ring::key::digit_7), ring::key_status::ok);
  feed(keypad, chars(1, "HI"));
  feed(keypad, chars(3, "PAST"));
  EXPECT_FALSE(drain(keypad).empty());
  EXPECT_EQ(keypad.counters().display_messages, 1U);
}

}  // namespace
