// Host adapters: candump text both ways, SocketCAN frame conversion, and a real SocketCAN exchange on a vcan
// interface where one can be created.
#include <gtest/gtest.h>

#include <linux/can.h>
#include <net/if.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <trionet/can.hpp>

#include "trionet/host/candump.hpp"
#include "trionet/host/capture.hpp"
#include "support/vcan.hpp"
#include "trionet/host/socketcan.hpp"

namespace {

using namespace trionet::can;
using namespace trionet::host;

TEST(CanCandump, ReadsTheLogForm) {
  const candump_result r = parse_candump_line("(1700000000.123456) can0 028#0100000000020D7A");
  ASSERT_EQ(r.status, candump_status::ok);
  EXPECT_TRUE(r.record.has_timestamp);
  EXPECT_EQ(r.record.seconds, 1700000000U);
  EXPECT_EQ(r.record.nanoseconds, 123456000U);
  EXPECT_EQ(r.record.timestamp, "1700000000.123456");
  EXPECT_EQ(r.record.interface_name, "can0");
  EXPECT_EQ(r.record.frame.id, 0x028U);
  EXPECT_EQ(r.record.frame.dlc, 8);
  const std::uint8_t expected[8] = {0x01, 0x00, 0x00, 0x00, 0x00, 0x02, 0x0D, 0x7A};
  EXPECT_EQ(std::memcmp(r.record.frame.data, expected, 8), 0);
  EXPECT_EQ(format_candump_line(r.record), "(1700000000.123456) can0 028#0100000000020D7A");
}

TEST(CanCandump, ReadsTheCompactFormAndWritesUpperCase) {
  const candump_result r = parse_candump_line("  028#0100000000020d7a\r\n");
  ASSERT_EQ(r.status, candump_status::ok);
  EXPECT_FALSE(r.record.has_timestamp);
  EXPECT_TRUE(r.record.interface_name.empty());
  EXPECT_EQ(format_candump_line(r.record), "028#0100000000020D7A");
  EXPECT_EQ(format_candump_frame(r.record.frame), "028#0100000000020D7A");
}

TEST(CanCandump, OtherFrameShapes) {
  const candump_result empty_data = parse_candump_line("7FF#");
  ASSERT_EQ(empty_data.status, candump_status::ok);
  EXPECT_EQ(empty_data.record.frame.dlc, 0);
  EXPECT_EQ(format_candump_frame(empty_data.record.frame), "7FF#");

  const candump_result dotted = parse_candump_line("123#01.02.03");
  ASSERT_EQ(dotted.status, candump_status::ok);
  EXPECT_EQ(dotted.record.frame.dlc, 3);
  EXPECT_EQ(format_candump_frame(dotted.record.frame), "123#010203");

  const candump_result extended = parse_candump_line("(0.5) vcan0 1FFFFFFF#AA");
  ASSERT_EQ(extended.status, candump_status::ok);
  EXPECT_TRUE(extended.record.frame.extended());
  EXPECT_EQ(extended.record.frame.identifier(), 0x1FFFFFFFU);
  EXPECT_EQ(extended.record.nanoseconds, 500000000U);
  EXPECT_EQ(format_candump_line(extended.record), "(0000000000.500000) vcan0 1FFFFFFF#AA");

  const candump_result remote = parse_candump_line("028#R8");
  ASSERT_EQ(remote.status, candump_status::ok);
  EXPECT_TRUE(remote.record.frame.remote());
  EXPECT_EQ(remote.record.frame.dlc, 8);
  EXPECT_EQ(remote.record.frame.data_length(), 0);
  EXPECT_EQ(format_candump_frame(remote.record.frame), "028#R8");
  EXPECT_EQ(format_candump_frame(parse_candump_line("028#R").record.frame), "028#R");
}

// can-utils reads a log line with sscanf("(%llu.%llu) %s %s"): the blank after ')' may be missing.
TEST(CanCandump, ALogLineWithoutABlankAfterItsTimestamp) {
  const candump_result r = parse_candump_line("(1700000000.123456)can0 028#0100000000020D7A");
  ASSERT_EQ(r.status, candump_status::ok);
  EXPECT_EQ(r.record.form, candump_form::log);
  EXPECT_EQ(r.record.interface_name, "can0");
  EXPECT_EQ(r.record.seconds, 1700000000U);
  EXPECT_EQ(r.record.nanoseconds, 123456000U);
  EXPECT_EQ(format_candump_frame(r.record.frame), "028#0100000000020D7A");
  EXPECT_EQ(parse_candump_line("(1700000000.123456)\tcan0 028#01").status, candump_status::ok);
  EXPECT_EQ(parse_candump_line("(1700000000.123456)can0").status, candump_status::interface_name);
}

TEST(CanCandump, EveryDataByteIsKept) {
  const candump_result fd = parse_candump_line("123##1" + std::string(128, 'A'));
  ASSERT_EQ(fd.status, candump_status::ok);
  EXPECT_EQ(fd.record.data, std::vector<std::uint8_t>(64, 0xAA));
  const candump_result screen = parse_candump_line("can0  123  [12]  01 02 03 04 05 06 07 08 09 0A 0B 0C");
  ASSERT_EQ(screen.status, candump_status::ok);
  EXPECT_EQ(screen.record.data.size(), 12U);
  EXPECT_EQ(screen.record.data.back(), 0x0C);
}

TEST(CanCandump, SyntaxErrorsAreClassified) {
  EXPECT_EQ(parse_candump_line("   ").status, candump_status::empty);
  EXPECT_EQ(parse_candump_line("(1700000000) can0 028#01").status, candump_status::timestamp);
  EXPECT_EQ(parse_candump_line("(17000x0000.1) can0 028#01").status, candump_status::timestamp);
  EXPECT_EQ(parse_candump_line("(1.1234567890) can0 028#01").status, candump_status::timestamp);
  EXPECT_EQ(parse_candump_line("(99999999999999999999.1) can0 028#01").status, candump_status::timestamp);
  EXPECT_EQ(parse_candump_line("can0 028#01").status, candump_status::timestamp);
  EXPECT_EQ(parse_candump_line("(1700000000.123456)").status, candump_status::interface_name);
  EXPECT_EQ(parse_candump_line("(1700000000.123456) can0").status, candump_status::interface_name);
  EXPECT_EQ(parse_candump_line("28#01").status, candump_status::identifier);
  EXPECT_EQ(parse_candump_line("02G#01").status, candump_status::identifier);
  EXPECT_EQ(parse_candump_line("1234#01").status, candump_status::identifier);
  EXPECT_EQ(parse_candump_line("028##G0123").status, candump_status::fd_flags);
  EXPECT_EQ(parse_candump_line("45123#81-00:12345678#11").status, candump_status::xl_header);
  EXPECT_EQ(parse_candump_line("028#012").status, candump_status::data);
  EXPECT_EQ(parse_candump_line("028#01xx").status, candump_status::data);
  EXPECT_EQ(parse_candump_line("028#01..02").status, candump_status::data);
  EXPECT_EQ(parse_candump_line("028#01 junk").status, candump_status::trailing);
  EXPECT_EQ(parse_candump_line("(1.000000) can0 028#01 X").status, candump_status::trailing);
  EXPECT_EQ(parse_candump_line("(1.000000) can0 028#01 R R").status, candump_status::trailing);
  EXPECT_EQ(parse_candump_line(std::string(candump_max_line_length + 1, ' ')).status, candump_status::too_long);
  EXPECT_STRNE(to_string(candump_status::data), to_string(candump_status::trailing));
}

TEST(CanCandump, EveryFrameFormatsAndParsesBack) {
  for (std::uint32_t id : {0x000U, 0x028U, 0x7FFU, 0x80000000U | 0x1234567U}) {
    for (std::uint8_t dlc = 0; dlc <= 8; ++dlc) {
      frame f;
      f.id = id;
      f.dlc = dlc;
      for (std::uint8_t i = 0; i < dlc; ++i) f.data[i] = static_cast<std::uint8_t>(0xA5 ^ (i * 37 + dlc));
      candump_record record;
      record.has_timestamp = dlc % 2 == 0;
      record.seconds = 1700000000U + dlc;
      record.nanoseconds = (999999U - dlc) * 1000U;
      record.fraction_digits = 6;
      record.interface_name = "can1";
      record.frame = f;
      const std::string line = format_candump_line(record);
      const candump_result back = parse_candump_line(line);
      ASSERT_EQ(back.status, candump_status::ok) << line;
      EXPECT_EQ(back.record.frame, f) << line;
      EXPECT_EQ(back.record.has_timestamp, record.has_timestamp) << line;
      if (record.has_timestamp) {
        EXPECT_EQ(back.record.seconds, record.seconds);
        EXPECT_EQ(back.record.nanoseconds, record.nanoseconds);
        EXPECT_EQ(back.record.interface_name, "can1");
      }
    }
  }
}

// Hostile input: random lines made of candump's own characters either parse (and then format back to a line
// that parses to the same frame) or are classified; nothing else happens.
TEST(CanCandump, RandomLinesAreParsedOrClassified) {
  const char alphabet[] = "0123456789abcdefABCDEF#R.() \tcan";
  std::uint32_t state = 12345;
  int parsed = 0;
  for (int i = 0; i < 200000; ++i) {
    std::string line;
    state = state * 1103515245U + 12345U;
    const std::size_t length = state >> 16U & 31U;
    for (std::size_t j = 0; j < length; ++j) {
      state = state * 1103515245U + 12345U;
      line += alphabet[(state >> 16U) % (sizeof alphabet - 1)];
    }
    if (i % 2 == 0) line = "028#" + line.substr(0, length / 2);
    const candump_result r = parse_candump_line(line);
    if (r.status != candump_status::ok || !r.record.classic_frame()) continue;
    ++parsed;
    const candump_result again = parse_candump_line(format_candump_line(r.record));
    ASSERT_EQ(again.status, candump_status::ok) << line;
    EXPECT_EQ(again.record.frame, r.record.frame) << line;
  }
  EXPECT_GT(parsed, 1000) << "the generator reaches valid lines too";
}

TEST(CanSocketCan, FrameConversionBothWays) {
  frame f;
  f.id = 40;
  f.dlc = 8;
  const std::uint8_t bytes[8] = {0x01, 0x00, 0x00, 0x00, 0x00, 0x02, 0x0D, 0x7A};
  std::memcpy(f.data, bytes, 8);
  const ::can_frame raw = to_socketcan(f);
  EXPECT_EQ(raw.can_id, 40U);
  EXPECT_EQ(raw.len, 8);
  EXPECT_EQ(std::memcmp(raw.data, bytes, 8), 0);
  EXPECT_EQ(from_socketcan(raw), f);

  frame extended;
  extended.id = 0x1ABCDEF | frame::extended_flag | frame::remote_flag;
  extended.dlc = 12;
  const ::can_frame raw_extended = to_socketcan(extended);
  EXPECT_EQ(raw_extended.can_id, 0x1ABCDEFU | CAN_EFF_FLAG | CAN_RTR_FLAG);
  EXPECT_EQ(raw_extended.len, 8) << "DLC 9..15 means 8 bytes on classic CAN";

  ::can_frame error_frame;
  std::memset(&error_frame, 0, sizeof error_frame);
  error_frame.can_id = CAN_ERR_FLAG | 0x4U;
  error_frame.len = 8;
  EXPECT_EQ(from_socketcan(error_frame).id, 0x4U);
  static_assert(frame::extended_flag == CAN_EFF_FLAG && frame::remote_flag == CAN_RTR_FLAG,
                "the frame's flags are SocketCAN's");
}

TEST(CanSocketCan, ClosedPortFailsAndBadNamesAreRefused) {
  socketcan_port closed;
  EXPECT_FALSE(closed.is_open());
  EXPECT_EQ(closed.send(frame{}), transmit_status::failed);
  frame f;
  EXPECT_EQ(closed.receive(f, 0), socketcan_receive_status::failed);
  EXPECT_EQ(closed.open("").status, socketcan_status::name_too_long);
  EXPECT_EQ(closed.open("an-interface-name-too-long").status, socketcan_status::name_too_long);
}

// Node 1 and node 4 of a 5-node exchange on a real (virtual) CAN interface.
TEST(CanSocketCan, VrExchangeOverVcan) {
  const trionet::test::vcan_interface vcan("trionetvcan0");
  if (!vcan.usable()) {
    GTEST_SKIP() << "cannot create vcan interface " << vcan.name() << ": " << vcan.missing()
                 << "; frame conversion is tested without it";
  }
  const std::string& name = vcan.name();

  socketcan_port port1;
  socketcan_port port4;
  const socketcan_open_result opened1 = port1.open(name);
  if (opened1.status == socketcan_status::socket) {
    GTEST_SKIP() << "the kernel has no CAN socket support: " << std::strerror(opened1.system_error);
  }
  ASSERT_EQ(opened1.status, socketcan_status::ok)
      << to_string(opened1.status) << ": " << std::strerror(opened1.system_error);
  ASSERT_EQ(port4.open(name).status, socketcan_status::ok);

  trionet::vr_table<8> vrs1;
  trionet::vr_table<8> vrs4;
  vr_exchange_node node1(make_node_address(5, 1).address, port1, vrs1);
  vr_exchange_node node4(make_node_address(5, 4).address, port4, vrs4);
  ASSERT_EQ(node1.send_to_node(4, 1, 2.345), send_status::ok);
  frame received;
  ASSERT_EQ(port4.receive(received, 2000), socketcan_receive_status::ok);
  EXPECT_EQ(format_candump_frame(received), "028#0100000000020D7A");
  EXPECT_EQ(node4.receive(received).status, receive_status::ok);
  EXPECT_EQ(vrs4[1], 2.345);
}

}  // namespace

// What `can monitor --pcap` writes for frames that are not classic: the records Linux delivers to a raw
// socket (struct canfd_frame, an error frame with its flag), read back as such.
TEST(CanCapture, FdAndErrorFramesAsSocketCanRecords) {
  const candump_result fd = parse_candump_line("123##1" + std::string(48, 'A'));
  ASSERT_EQ(fd.status, candump_status::ok);
  const std::vector<std::uint8_t> fd_record = trionet::host::socketcan_record_of(fd.record);
  ASSERT_EQ(fd_record.size(), 72U);
  EXPECT_EQ(fd_record[3], 0x23);
  EXPECT_EQ(fd_record[4], 24);    // len
  EXPECT_EQ(fd_record[5], 0x05);  // CANFD_FDF | CANFD_BRS
  EXPECT_EQ(fd_record[8], 0xAA);
  EXPECT_EQ(fd_record[31], 0xAA);
  EXPECT_EQ(fd_record[32], 0x00);
  EXPECT_EQ(trionet::host::read_socketcan_record(trionet::byte_view(fd_record.data(), fd_record.size())).status,
            trionet::host::socketcan_record_status::not_classic);

  const candump_result error = parse_candump_line("20000004#0000080000000000");
  ASSERT_EQ(error.status, candump_status::ok);
  const std::vector<std::uint8_t> error_record = trionet::host::socketcan_record_of(error.record);
  ASSERT_EQ(error_record.size(), 16U);
  EXPECT_EQ(error_record[0], 0x20);
  EXPECT_EQ(error_record[3], 0x04);
  EXPECT_EQ(error_record[10], 0x08);
  EXPECT_EQ(trionet::host::read_socketcan_record(trionet::byte_view(error_record.data(), error_record.size())).status,
            trionet::host::socketcan_record_status::error_frame);

  const candump_result classic = parse_candump_line("028#0100000000020D7A");
  const std::vector<std::uint8_t> classic_record = trionet::host::socketcan_record_of(classic.record);
  const auto expected = trionet::host::socketcan_record(classic.record.frame);
  EXPECT_EQ(classic_record, std::vector<std::uint8_t>(expected.begin(), expected.end()));
  // A CAN XL frame has no record here.
  EXPECT_TRUE(trionet::host::socketcan_record_of(parse_candump_line("12345#80:00:00000000#11").record).empty());
}
