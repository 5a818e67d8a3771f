// PRINT# and SEND at the edges of their ranges (docs/protocol.md 1.6): BASIC addresses 10 and 24, VR(16383),
// keypad offsets 10 and 24, keypad modes 0 and 127. The checks go address, then VR, then value: at VR(16383)
// an unrepresentable value is the value's fault.
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

#include "support/ring_frames.hpp"
#include "trionet/ring.hpp"
#include "trionet/vr.hpp"

namespace {

namespace ring = trionet::ring;
using trionet::test::drain;
using trionet::test::frame_of;

TEST(RingSendBoundaries, Vr16383IsTheLastAndItsBadValueIsTheValuesFault) {
  trionet::vr_table<16> vr;
  ring::motion_coordinator<> mc(vr);
  EXPECT_EQ(mc.send_variable(10, 16383, 3e9), ring::send_status::value_out_of_range);
  EXPECT_EQ(mc.send_variable(10, 16383, std::numeric_limits<double>::quiet_NaN()),
            ring::send_status::value_out_of_range);
  EXPECT_EQ(mc.send_variable(10, 16384, std::numeric_limits<double>::quiet_NaN()),
            ring::send_status::vr_out_of_range);
  EXPECT_EQ(mc.send_variable_q32(10, 16384, 0), ring::send_status::vr_out_of_range);
  EXPECT_EQ(mc.send_variable_q32(25, 16383, 0), ring::send_status::bad_address);
  EXPECT_FALSE(mc.transmit_pending());

  ASSERT_EQ(mc.send_variable(10, 16383, -2.5), ring::send_status::ok);
  EXPECT_EQ(drain(mc), frame_of(ring::message::variable(1, 16383, -(std::int64_t{5} << 31))));
  ASSERT_EQ(mc.send_variable_q32(24, 16383, 1), ring::send_status::ok);
  EXPECT_EQ(drain(mc), frame_of(ring::message::variable(15, 16383, 1)));
}

TEST(RingSendBoundaries, BasicAddressesTenAndTwentyFourAreTheFirstAndLastNode) {
  trionet::vr_table<16> vr;
  ring::motion_coordinator<> mc(vr);
  ASSERT_EQ(mc.print(10, "A").status, ring::send_status::ok);
  EXPECT_EQ(drain(mc), trionet::test::chars(1, "A"));
  ASSERT_EQ(mc.print(24, "Z").status, ring::send_status::ok);
  EXPECT_EQ(drain(mc), trionet::test::chars(15, "Z"));
  ASSERT_EQ(mc.send_keypad_offset(24, 10), ring::send_status::ok);
  EXPECT_EQ(drain(mc), frame_of(ring::message::keypad_offset(15, 1)));
  ASSERT_EQ(mc.send_keypad_offset(10, 24), ring::send_status::ok);
  EXPECT_EQ(drain(mc), frame_of(ring::message::keypad_offset(1, 15)));
  ASSERT_EQ(mc.send_keypad_mode(10, 0), ring::send_status::ok);
  EXPECT_EQ(drain(mc), frame_of(ring::message::keypad_mode(1, 0)));
  EXPECT_EQ(mc.send_keypad_mode(25, 0), ring::send_status::bad_address);
  EXPECT_EQ(mc.send_keypad_mode(10, 128), ring::send_status::mode_out_of_range);
  EXPECT_EQ(mc.send_keypad_mode(10, -1), ring::send_status::mode_out_of_range);
}

}  // namespace
