// The lock-free state the two sides of a node share (detail/single_writer.hpp, detail/netstat_register.hpp):
// copies carry the value, and the link side cannot raise NETSTAT's bit 0, which is the program side's.
#include <gtest/gtest.h>

#include <cstdint>

#include "trionet/detail/netstat_register.hpp"
#include "trionet/detail/single_writer.hpp"

namespace {

using trionet::detail::netstat_register;
using trionet::detail::request_flag;
using trionet::detail::single_writer;

TEST(SharedState, ASingleWriterValueIsCopiedByConstructionAndByAssignment) {
  const single_writer<std::uint16_t> seven(7);
  const single_writer<std::uint16_t> built(seven);
  EXPECT_EQ(built.load(), 7);
  single_writer<std::uint16_t> assigned(3);
  assigned = seven;
  EXPECT_EQ(assigned.load(), 7);
}

TEST(SharedState, ARequestFlagIsCopiedByConstructionAndByAssignment) {
  request_flag asked;
  asked.raise();
  const request_flag built(asked);
  EXPECT_TRUE(built.raised());
  request_flag assigned;
  assigned = asked;
  EXPECT_TRUE(assigned.raised());
  const request_flag quiet;
  assigned = quiet;
  EXPECT_FALSE(assigned.raised());
}

TEST(SharedState, TheLinkSideRaisesNetstatBitsOneToFourOnly) {
  netstat_register netstat;
  netstat.raise(0x1F);  // bit 0 is the program side's own message refused: not the link side's to raise
  EXPECT_EQ(netstat.read(), 0x1E);
  netstat.raise_tx_timeout();
  EXPECT_EQ(netstat.read(), 0x1F);
  netstat.clear();
  EXPECT_EQ(netstat.read(), 0);
  netstat.raise(0x01);
  EXPECT_EQ(netstat.read(), 0);
  netstat.raise(0x04);
  netstat.raise(0x04);  // raised already: stays raised, not flipped back
  EXPECT_EQ(netstat.read(), 0x04);
}

}  // namespace
