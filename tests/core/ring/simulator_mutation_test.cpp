// The simulator's bit flips (ring/simulator.hpp): a fault hook acts "in addition to the faults above", so a
// bit that flip_next and the hook both flip is flipped twice and arrives as sent; bits only one of them flips
// arrive flipped.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "support/ring_frames.hpp"
#include "trionet/ring.hpp"
#include "trionet/vr.hpp"

namespace {

namespace ring = trionet::ring;
using trionet::test::read_all;

// Flips bits 0 and 1 of the first byte on link 0.
ring::byte_fault flip_first_byte(void* context, std::size_t link, std::uint64_t, std::uint8_t) {
  bool& done = *static_cast<bool*>(context);
  if (link != 0 || done) return {};
  done = true;
  return ring::byte_fault{false, 0x03};
}

TEST(RingSimulatorFaults, ABitFlippedByBothFlipNextAndTheHookArrivesAsSent) {
  trionet::vr_table<16> vr0, vr1;
  ring::motion_coordinator<> a(vr0), b(vr1);
  ring::simulator<> sim;
  ASSERT_TRUE(sim.add(a));
  ASSERT_TRUE(sim.add(b));
  bool done = false;
  sim.set_fault_hook(flip_first_byte, &done);
  sim.flip_next(0, 0x01);  // bit 0 twice, bit 1 by the hook alone
  ASSERT_EQ(a.print(10, "A").status, ring::send_status::ok);
  std::vector<ring::link_byte> bytes;
  sim.run(1, [&](const ring::link_byte& x) { bytes.push_back(x); });
  ASSERT_EQ(bytes.size(), 1U);
  EXPECT_EQ(bytes[0].link, 0U);
  EXPECT_TRUE(bytes[0].delivered);
  EXPECT_EQ(bytes[0].received, static_cast<std::uint8_t>(bytes[0].sent ^ 0x02U));
}

TEST(RingSimulatorFaults, AFaultOnALinkTheRingDoesNotHaveYetDoesNothing) {
  trionet::vr_table<16> vr0, vr1, vr2;
  ring::motion_coordinator<> a(vr0), b(vr1), c(vr2);
  ring::simulator<3> sim;
  ASSERT_TRUE(sim.add(a));
  ASSERT_TRUE(sim.add(b));
  sim.cut(2);  // link 2 (c to a) does not exist yet
  sim.drop_next(2);
  sim.flip_next(2, 0x01);
  ASSERT_TRUE(sim.add(c));
  ASSERT_EQ(c.print(10, "TO A").status, ring::send_status::ok);
  int lost = 0;
  sim.run(20, [&](const ring::link_byte& x) {
    if (!x.delivered || x.received != x.sent) ++lost;
  });
  EXPECT_EQ(lost, 0);
  EXPECT_EQ(read_all(a, 4), "TO A");
}

TEST(RingSimulator, QuietAsksEveryNodeAndBytesDeliveredCountsWhatArrived) {
  trionet::vr_table<16> vr0, vr1;
  ring::motion_coordinator<> a(vr0), b(vr1);
  ring::simulator<> sim;
  ASSERT_TRUE(sim.add(a));
  ASSERT_TRUE(sim.add(b));
  EXPECT_TRUE(sim.quiet());
  ASSERT_EQ(a.print(10, "HI").status, ring::send_status::ok);  // node 0 has something to send
  EXPECT_FALSE(sim.quiet());
  std::uint64_t arrived = 0;
  sim.run(10, [&](const ring::link_byte& x) { arrived += x.delivered ? 1 : 0; });
  EXPECT_TRUE(sim.quiet());
  EXPECT_EQ(arrived, 4U);  // header, H, I, end of message
  EXPECT_EQ(sim.bytes_delivered(), arrived);
  sim.drop_next(0);
  ASSERT_EQ(a.print(10, "X").status, ring::send_status::ok);
  sim.run(10);
  EXPECT_EQ(sim.bytes_delivered(), arrived + 2U) << "the dropped header is not counted";
}

}  // namespace
