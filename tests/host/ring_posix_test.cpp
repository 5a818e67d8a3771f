// The POSIX host adapter: ring nodes talking through real file descriptors (a socket pair, a pty).
#include <gtest/gtest.h>

#include <fcntl.h>
#include <stdlib.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include <cstring>
#include <string>

#include "trionet/host/posix_link.hpp"
#include "trionet/ring.hpp"

namespace ring = trionet::ring;

namespace {

std::string read_all(ring::motion_coordinator<>& mc) {
  std::string out;
  while (auto r = mc.get(4)) out += static_cast<char>(r.value);
  return out;
}

}  // namespace

TEST(RingPosixLink, TwoNodeRingOverASocketPair) {
  int sv[2];
  ASSERT_EQ(::socketpair(AF_UNIX, SOCK_STREAM, 0, sv), 0);
  for (int fd : sv) ASSERT_EQ(::fcntl(fd, F_SETFL, O_NONBLOCK), 0);
  trionet::vr_table<256> vr_a, vr_b;
  ring::motion_coordinator<> a(vr_a), b(vr_b);
  trionet::host::fd_link link_a(sv[0], a), link_b(sv[1], b);  // a -> b over one direction, b -> a the other

  ASSERT_EQ(a.print(10, "HELLO").status, ring::send_status::ok);
  ASSERT_EQ(a.send_variable(10, 200, 99), ring::send_status::ok);
  ASSERT_EQ(a.print(11, "ROUND").status, ring::send_status::ok);  // 2 hops: b forwards it back to a
  std::size_t ended_at_b = 0;  // messages b's pumps saw end: HELLO and the variable (for b), ROUND (forwarded)
  for (int i = 0; i < 200 && !(read_all(b) == "HELLO" || b.characters_waiting() != 0); ++i) {
    (void)link_a.pump(5);
    ended_at_b += link_b.pump(5).ended;
  }
  for (int i = 0; i < 50; ++i) {
    (void)link_a.pump(1);
    ended_at_b += link_b.pump(1).ended;
  }
  EXPECT_EQ(ended_at_b, 3u);
  EXPECT_EQ(vr_b[200], 99.0);
  EXPECT_EQ(read_all(a), "ROUND");
  EXPECT_EQ(b.forwarding_counters().messages_forwarded, 1u);
  EXPECT_EQ(link_a.unsent(), 0u);
  ::close(sv[0]);
  const auto closed = link_b.pump(100);
  EXPECT_TRUE(closed.closed);
  ::close(sv[1]);
}

TEST(RingPosixLink, SerialPortOnAPty) {
  const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
  ASSERT_GE(master, 0);
  ASSERT_EQ(::grantpt(master), 0);
  ASSERT_EQ(::unlockpt(master), 0);
  const std::string slave = ::ptsname(master);
  std::string error;
  const int fd = trionet::host::open_serial(slave, 115200, error);
  ASSERT_GE(fd, 0) << error;
  trionet::vr_table<16> vr;
  ring::motion_coordinator<> mc(vr);
  trionet::host::fd_link link(fd, mc);
  const std::uint8_t frame[] = {0x89, 'O', 'K', 0x88};
  ASSERT_EQ(::write(master, frame, sizeof frame), static_cast<ssize_t>(sizeof frame));
  std::size_t ended = 0;
  for (int i = 0; i < 50 && mc.characters_waiting() < 2; ++i) ended += link.pump(10).ended;
  EXPECT_EQ(read_all(mc), "OK");
  EXPECT_EQ(ended, 1u);
  ::close(fd);
  ::close(master);

  EXPECT_EQ(trionet::host::open_serial("/nonexistent/tty", 9600, error), -1);
  EXPECT_NE(error.find("cannot open"), std::string::npos);
  EXPECT_EQ(trionet::host::open_serial(slave, 49, error), -1);
  EXPECT_NE(error.find("unsupported baud rate 49 for " + slave), std::string::npos);
  EXPECT_EQ(trionet::host::open_serial(slave, 4000001, error), -1);
  EXPECT_EQ(trionet::host::open_serial("/dev/null", 9600, error), -1);
  EXPECT_NE(error.find("not a serial port"), std::string::npos);
}

// A message whose rest never comes: the pump's read timeout is the idle line (docs/protocol.md 1.10), so
// the node ends it (counted) and sends its own message.
TEST(RingPosixLink, ReadTimeoutIsTheIdleLine) {
  int sv[2];
  ASSERT_EQ(::socketpair(AF_UNIX, SOCK_STREAM, 0, sv), 0);
  for (int fd : sv) ASSERT_EQ(::fcntl(fd, F_SETFL, O_NONBLOCK), 0);
  trionet::vr_table<16> vr;
  ring::motion_coordinator<> mc(vr);
  trionet::host::fd_link link(sv[0], mc);
  const std::uint8_t partial[] = {ring::make_header(3, 1), 'A', 'B'};  // forwarded; no end of message
  ASSERT_EQ(::write(sv[1], partial, sizeof partial), static_cast<ssize_t>(sizeof partial));
  ASSERT_EQ(mc.print(10, "OWN").status, ring::send_status::ok);
  bool idle = false;
  std::size_t ended = 0;
  for (int i = 0; i < 20 && !idle; ++i) {
    const auto r = link.pump(5);
    idle = r.line_idle;
    ended += r.ended;
  }
  EXPECT_TRUE(idle);
  EXPECT_EQ(ended, 1u);  // the idle line ended the forwarded message (lost: counted)
  EXPECT_EQ(mc.forwarding_counters().forwards_ended_idle, 1u);
  for (int i = 0; i < 5; ++i) (void)link.pump(5);
  std::uint8_t got[16] = {};
  const ssize_t n = ::read(sv[1], got, sizeof got);
  const std::uint8_t expected[] = {ring::make_header(2, 1), 'A', 'B', ring::make_header(1, 1), 'O', 'W', 'N',
                                   ring::make_end_of_message(1)};
  ASSERT_EQ(n, static_cast<ssize_t>(sizeof expected));
  EXPECT_EQ(std::memcmp(got, expected, sizeof expected), 0);
  ::close(sv[0]);
  ::close(sv[1]);
}

// Any rate, not only the Bnnn constants (termios2), and the settings before are put back.
TEST(RingPosixLink, SerialPortAtAnyRateIsRestored) {
  const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
  ASSERT_GE(master, 0);
  ASSERT_EQ(::grantpt(master), 0);
  ASSERT_EQ(::unlockpt(master), 0);
  const std::string slave = ::ptsname(master);
  const int keep = ::open(slave.c_str(), O_RDWR | O_NOCTTY);
  ASSERT_GE(keep, 0);
  termios before{};
  ASSERT_EQ(::tcgetattr(keep, &before), 0);
  before.c_lflag |= ECHO | ICANON;
  ::cfsetspeed(&before, B4800);
  ASSERT_EQ(::tcsetattr(keep, TCSANOW, &before), 0);
  ASSERT_EQ(::tcgetattr(keep, &before), 0);

  std::string error;
  trionet::host::serial_settings saved;
  const int fd = trionet::host::open_serial(slave, 125000, error, trionet::host::flow_control::none, &saved);
  ASSERT_GE(fd, 0) << error;
  EXPECT_TRUE(saved.saved);
  termios during{};
  ASSERT_EQ(::tcgetattr(fd, &during), 0);
  EXPECT_EQ(during.c_lflag & (ECHO | ICANON | ISIG), 0u);
  EXPECT_EQ(during.c_cflag & CSIZE, static_cast<tcflag_t>(CS8));
  EXPECT_EQ(during.c_cflag & CRTSCTS, 0u);
  EXPECT_EQ(during.c_iflag & (IXON | IXOFF), 0u);
  EXPECT_TRUE(trionet::host::restore_serial(fd, saved));
  termios after{};
  ASSERT_EQ(::tcgetattr(keep, &after), 0);
  EXPECT_EQ(after.c_lflag, before.c_lflag);
  EXPECT_EQ(after.c_cflag, before.c_cflag);
  EXPECT_EQ(::cfgetispeed(&after), B4800);
  ::close(fd);

  const int flow = trionet::host::open_serial(slave, 9600, error, trionet::host::flow_control::software);
  ASSERT_GE(flow, 0) << error;
  ASSERT_EQ(::tcgetattr(flow, &during), 0);
  EXPECT_EQ(during.c_iflag & (IXON | IXOFF), static_cast<tcflag_t>(IXON | IXOFF));
  ::close(flow);
  ::close(keep);
  ::close(master);
}
