// A classic CAN frame as the VR exchange sees it (can/frame.hpp): the identifier word with SocketCAN's flags,
// the data length code and the bytes on the wire, and when two frames are the same frame.
#include <gtest/gtest.h>

#include <cstdint>

#include <trionet/can/frame.hpp>

namespace {

using trionet::can::frame;

frame standard_frame(std::uint32_t id, std::uint8_t dlc) {
  frame f;
  f.id = id;
  f.dlc = dlc;
  for (std::uint8_t i = 0; i < 8; ++i) f.data[i] = static_cast<std::uint8_t>(0xA0 + i);
  return f;
}

TEST(CanFrame, AStandardIdentifierHasNoFlags) {
  const frame f = standard_frame(0x7FF, 8);
  EXPECT_FALSE(f.extended());
  EXPECT_FALSE(f.remote());
  EXPECT_EQ(f.identifier(), 0x7FFU);
  static_assert(frame{}.identifier() == 0 && !frame{}.extended() && !frame{}.remote(), "constexpr");
}

TEST(CanFrame, TheFlagsAreSocketCansTopBits) {
  EXPECT_EQ(frame::extended_flag, 0x80000000U);
  EXPECT_EQ(frame::remote_flag, 0x40000000U);
  frame f = standard_frame(frame::extended_flag | 0x1FFFFFFF, 8);
  EXPECT_TRUE(f.extended());
  EXPECT_FALSE(f.remote());
  EXPECT_EQ(f.identifier(), 0x1FFFFFFFU) << "a 29-bit identifier keeps its 29 bits";
  f.id = 0x12345 | frame::remote_flag;
  EXPECT_TRUE(f.remote());
  EXPECT_FALSE(f.extended());
  EXPECT_EQ(f.identifier(), 0x345U) << "a standard identifier is 11 bits: the rest is not part of it";
}

// On classic CAN a DLC of 0..8 carries that many bytes and 9..15 carry 8; a remote frame carries none.
TEST(CanFrame, DataLengthIsTheDlcUpToEightAndNoneForARemoteFrame) {
  for (std::uint8_t dlc = 0; dlc <= 15; ++dlc) {
    const frame f = standard_frame(10, dlc);
    const std::uint8_t expected = dlc > 8 ? 8 : dlc;
    EXPECT_EQ(f.data_length(), expected) << int(dlc);
    EXPECT_EQ(f.payload().size(), expected) << int(dlc);
    EXPECT_EQ(f.payload().data(), f.data);
  }
  frame remote = standard_frame(10 | frame::remote_flag, 8);
  EXPECT_EQ(remote.data_length(), 0);
  EXPECT_TRUE(remote.payload().empty());
}

TEST(CanFrame, FramesAreEqualWhenIdentifierDlcAndTheBytesOnTheWireAre) {
  const frame a = standard_frame(40, 3);
  frame b = a;
  EXPECT_TRUE(a == b);
  EXPECT_FALSE(a != b);
  b.data[5] = 0;  // past the DLC: not on the wire
  EXPECT_TRUE(a == b) << "bytes past the data length do not count";
  b.data[2] = 0;  // the last byte on the wire
  EXPECT_FALSE(a == b);
  EXPECT_TRUE(a != b);
  b = a;
  b.data[0] = 0;  // the first
  EXPECT_FALSE(a == b);
  b = a;
  b.id = 41;
  EXPECT_FALSE(a == b) << "another identifier";
  b = a;
  b.id = 40 | frame::extended_flag;
  EXPECT_FALSE(a == b) << "the same number as an extended identifier";
  b = a;
  b.dlc = 4;
  EXPECT_FALSE(a == b) << "another DLC";
  EXPECT_TRUE(a != b);
  frame nine = standard_frame(40, 9), fifteen = standard_frame(40, 15);
  EXPECT_FALSE(nine == fifteen) << "DLC 9 and 15 both carry 8 bytes, but they are different codes";
}

}  // namespace
