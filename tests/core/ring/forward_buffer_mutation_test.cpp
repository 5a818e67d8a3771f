// A Motion Coordinator always forwards (detail/forward_buffer.hpp, forwarding_switch<false>): it drops no
// message, so its link counters say 0 dropped after traffic through it and to it.
#include <gtest/gtest.h>

#include "support/ring_frames.hpp"
#include "trionet/ring.hpp"
#include "trionet/vr.hpp"

namespace {

namespace ring = trionet::ring;
using trionet::test::chars;
using trionet::test::drain;
using trionet::test::feed;

TEST(RingForwardBuffer, AMotionCoordinatorDropsNothing) {
  trionet::vr_table<16> vr;
  ring::motion_coordinator<> mc(vr);
  EXPECT_EQ(mc.forwarding_counters().messages_dropped, 0U);
  feed(mc, chars(2, "THROUGH"));
  feed(mc, chars(1, "TO IT"));
  EXPECT_EQ(drain(mc), chars(1, "THROUGH"));
  EXPECT_EQ(mc.forwarding_counters().messages_forwarded, 1U);
  EXPECT_EQ(mc.forwarding_counters().messages_dropped, 0U);
}

}  // namespace
