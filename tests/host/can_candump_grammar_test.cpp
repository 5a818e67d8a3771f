// candump text as can-utils writes and reads it (docs/protocol.md 2.3): every example of can-utils' lib.h
// comments (parse_canframe, snprintf_canframe, snprintf_long_canframe), the forms candump, log2long, asc2log
// and python-can's log writer produce, and can-utils' own leniencies.
#include <gtest/gtest.h>

#include <string>

#include "trionet/host/candump.hpp"

namespace {

using namespace trionet::host;
using trionet::can::frame;

candump_record read(const std::string& line) {
  const candump_result r = parse_candump_line(line);
  EXPECT_EQ(r.status, candump_status::ok) << line << ": " << to_string(r.status);
  return r.record;
}

void expect_classic(const std::string& line, std::uint32_t id_word, std::uint16_t length, std::uint8_t len8_dlc = 0) {
  const candump_record r = read(line);
  EXPECT_EQ(r.type, candump_frame_type::classic) << line;
  EXPECT_EQ(r.can_id, id_word) << line;
  EXPECT_EQ(r.length, length) << line;
  EXPECT_EQ(r.len8_dlc, len8_dlc) << line;
}

// The examples of parse_canframe in can-utils' lib.h, in its order.
TEST(CanCandumpGrammar, EveryParseCanframeExampleOfLibH) {
  expect_classic("123#", 0x123, 0);
  expect_classic("12345678#", frame::extended_flag | 0x12345678, 0);
  expect_classic("123#R", frame::remote_flag | 0x123, 0);
  expect_classic("123#R0", frame::remote_flag | 0x123, 0);
  expect_classic("123#R7", frame::remote_flag | 0x123, 7);
  expect_classic("123#R8_9", frame::remote_flag | 0x123, 8, 9);
  expect_classic("7A1#r", frame::remote_flag | 0x7A1, 0);
  expect_classic("123#00", 0x123, 1);
  expect_classic("123#1122334455667788", 0x123, 8);
  expect_classic("123#1122334455667788_E", 0x123, 8, 14);
  expect_classic("123#11.22.33.44.55.66.77.88", 0x123, 8);
  expect_classic("123#11.2233.44556677.88", 0x123, 8);
  const candump_record dotted = read("123#11.2233.44556677.88");
  for (std::uint8_t i = 0; i < 8; ++i) EXPECT_EQ(dotted.frame.data[i], 0x11 * (i + 1));

  const candump_record error = read("32345678#112233");
  EXPECT_EQ(error.type, candump_frame_type::error);
  EXPECT_EQ(error.can_id, 0x32345678U);
  EXPECT_EQ(error.length, 3);

  for (const auto& [line, flags, length] : {std::tuple{"123##0112233", 0, 3}, std::tuple{"123##1112233", 1, 3},
                                            std::tuple{"123##2112233", 2, 3}, std::tuple{"123##3", 3, 0}}) {
    const candump_record fd = read(line);
    EXPECT_EQ(fd.type, candump_frame_type::fd) << line;
    EXPECT_EQ(fd.can_id, 0x123U) << line;
    EXPECT_EQ(fd.flags, flags) << line;
    EXPECT_EQ(fd.length, length) << line;
  }

  const candump_record xl = read("45123#81:00:12345678#11223344.556677");
  EXPECT_EQ(xl.type, candump_frame_type::xl);
  EXPECT_EQ(xl.can_id >> 16U, 0x45U) << "VCID";
  EXPECT_EQ(xl.can_id & 0x7FFU, 0x123U) << "priority";
  EXPECT_EQ(xl.flags, 0x81);
  EXPECT_EQ(xl.sdt, 0x00);
  EXPECT_EQ(xl.af, 0x12345678U);
  EXPECT_EQ(xl.length, 7);
}

// The compact examples of snprintf_canframe in lib.h, read back, and what the formatter writes.
TEST(CanCandumpGrammar, EverySnprintfCanframeExampleReadsBack) {
  expect_classic("12345678#112233", frame::extended_flag | 0x12345678, 3);
  expect_classic("12345678#R", frame::extended_flag | frame::remote_flag | 0x12345678, 0);
  expect_classic("12345678#R5", frame::extended_flag | frame::remote_flag | 0x12345678, 5);
  for (const char* line : {"12345678#112233", "123#1122334455667788_E", "12345678#R", "12345678#R5", "123#R8_9"}) {
    EXPECT_EQ(format_candump_frame(read(line).frame), line);
  }
  EXPECT_EQ(format_candump_frame(read("123#11.22.33.44.55.66.77.88").frame), "123#1122334455667788");
}

// What can-utils' parser takes although no tool writes it: the same here.
TEST(CanCandumpGrammar, CanUtilsLeniencies) {
  expect_classic("123#11.", 0x123, 1);                        // a '.' at the end
  expect_classic("123#.11", 0x123, 1);                        // a '.' at the start
  expect_classic("123#1122334455667788_3", 0x123, 8, 0);      // `_` with a DLC that is not 9..F
  expect_classic("800#11", 0x800, 1);                         // 3 digits above 7FF
  EXPECT_FALSE(read("800#11").classic_frame()) << "read, but not a legal standard frame";
  expect_classic("C0000123#11", 0xC0000123U, 1);              // flag bits in the digits
  EXPECT_EQ(read("A0000000#").type, candump_frame_type::error);
}

// Leniencies of can-utils that made a plausible wrong frame, refused here (s38: 00028#0100000000020D7A was a
// VR message that `can node` wrote, and junk after a NUL was ignored): 5 digits are a CAN XL VCID and
// priority and need the XL header; a remote length is 0..8; a NUL is no character of the grammar.
TEST(CanCandumpGrammar, LenienciesThatMakeAPlausibleWrongFrameAreRefused) {
  const auto status = [](const std::string& line) { return parse_candump_line(line).status; };
  EXPECT_EQ(status("12345#1122"), candump_status::xl_header);
  EXPECT_EQ(status("00028#0100000000020D7A"), candump_status::xl_header);
  EXPECT_EQ(status("(1.000000) can0 00014#0100000000020D7A"), candump_status::xl_header);
  EXPECT_EQ(status("00028#80:0:00000000#01"), candump_status::xl_header);
  EXPECT_EQ(status("00028#R"), candump_status::identifier);
  EXPECT_EQ(status("00028##1AA"), candump_status::identifier);
  EXPECT_EQ(read("12028#80:00:00000000#01").type, candump_frame_type::xl) << "with its header it is CAN XL";
  EXPECT_EQ(status("123#R9"), candump_status::trailing);
  EXPECT_EQ(status(std::string("123#11\0zz", 9)), candump_status::data);
  EXPECT_EQ(status(std::string("028#0100000000020D7A\0GARBAGE", 28)), candump_status::trailing);
  EXPECT_NE(status(std::string("\0\0\0", 3)), candump_status::empty) << "NULs are not a blank line";
  EXPECT_NE(status(std::string("\0\0\0", 3)), candump_status::ok);
  // A time that 64-bit nanoseconds cannot hold is refused, not wrapped round (it was 0.290448384).
  EXPECT_EQ(status("(18446744074.000000) can0 028#0100000000020D7A"), candump_status::timestamp);
  EXPECT_EQ(status("(18446744073.709551616) can0 028#0100000000020D7A"), candump_status::timestamp);
  const candump_record last = read("(18446744073.709551615) can0 028#0100000000020D7A");
  EXPECT_EQ(last.seconds, 18446744073u);
  EXPECT_EQ(last.nanoseconds, 709551615u);
}

// Where can-utils reads a frame and ignores the rest of the word, the line is refused: more bytes than a frame
// holds would otherwise read as a plausible frame of the first eight.
TEST(CanCandumpGrammar, MoreInTheFrameWordThanTheFrameIsRefused) {
  for (const char* line : {"123#1122334455667788ZZ", "028#0100000000020D7A0102030405", "123#1122334455667788_9Z",
                           "123#rzz", "123#R8_9x", "(1.5) can0 028#0100000000020D7A00 R"}) {
    EXPECT_EQ(parse_candump_line(line).status, candump_status::trailing) << line;
  }
  expect_classic("123#1122334455667788_9", 0x123, 8, 9);  // the DLC after the 8th byte is the frame's
  expect_classic("123#R8_9", frame::remote_flag | 0x123, 8, 9);
  EXPECT_EQ(read("123##F" + std::string(128, 'A')).data.size(), 64u);  // CAN FD's 64 bytes
  EXPECT_EQ(parse_candump_line("123##F" + std::string(130, 'A')).status, candump_status::trailing);
}

TEST(CanCandumpGrammar, LogLinesAsCandumpAsc2logAndPythonCanWriteThem) {
  const candump_record log = read("(1700000000.123456) can0 028#0100000000020D7A");
  EXPECT_EQ(log.form, candump_form::log);
  EXPECT_EQ(log.direction, 0);

  const candump_record nano = read("(1700000000.123456789) vcan1 028#0100000000020D7A");  // candump -N
  EXPECT_EQ(nano.nanoseconds, 123456789U);
  EXPECT_EQ(nano.fraction_digits, 9);
  EXPECT_EQ(nano.timestamp, "1700000000.123456789");
  EXPECT_EQ(format_candump_line(nano), "(1700000000.123456789) vcan1 028#0100000000020D7A");

  const candump_record received = read("(1700000000.123456) can0 028#0100000000020D7A R");  // candump -x, asc2log
  EXPECT_EQ(received.direction, 'R');
  EXPECT_EQ(format_candump_line(received), "(1700000000.123456) can0 028#0100000000020D7A R");
  EXPECT_EQ(read("(1700000000.123456) can0 028#0100000000020D7A T").direction, 'T');
  EXPECT_EQ(read("(1700000000.123456)  can0 028#01 T\r\n").direction, 'T') << "candump pads interface names";

  // python-can's CanutilsLogWriter: "%f" seconds, remote frames as "R", error frames without direction.
  expect_classic("(1.500000) vcan0 123#R R", frame::remote_flag | 0x123, 0);
  EXPECT_EQ(read("(0.000000) vcan0 20000080#0000000000000000").type, candump_frame_type::error);
  EXPECT_EQ(read("(1.000000) vcan0 123##1AABB R").type, candump_frame_type::fd);
  expect_classic("(1.000000) vcan0 1FFFFFFF#AA T", frame::extended_flag | 0x1FFFFFFF, 1);
}

// candump's default screen format and log2long's output (lib.h's snprintf_long_canframe examples behind an
// interface name, with and without the timestamp column).
TEST(CanCandumpGrammar, ScreenFormatAsCandumpAndLog2longWriteIt) {
  const candump_record plain = read("  can0  028   [8]  01 00 00 00 00 02 0D 7A");
  EXPECT_EQ(plain.form, candump_form::screen);
  EXPECT_EQ(plain.interface_name, "can0");
  EXPECT_EQ(format_candump_frame(plain.frame), "028#0100000000020D7A");
  EXPECT_TRUE(plain.timestamp.empty());

  expect_classic("  can0  12345678   [3]  11 22 33", frame::extended_flag | 0x12345678, 3);
  expect_classic("  can0  12345678   [0]  remote request", frame::extended_flag | frame::remote_flag | 0x12345678, 0);
  expect_classic("  can0  14B0DC51   [8]  4A 94 E8 2A EC 58 55 62   'J..*.XUb'", frame::extended_flag | 0x14B0DC51, 8);
  expect_classic("  can0  321   {B}  11 22 33 44 55 66 77 88", 0x321, 8, 11);
  expect_classic("  can0       123   [3]  11 22 33", 0x123, 3);
  expect_classic("  can0  123   [2]  00010001 00100010", 0x123, 2);  // candump -b
  const candump_record error = read("  can0  20001111   [7]  C6 23 7B 32 69 98 3C      ERRORFRAME");
  EXPECT_EQ(error.type, candump_frame_type::error);
  EXPECT_EQ(error.length, 7);
  const candump_record fd = read("  can0  12345678  [03]  11 22 33");
  EXPECT_EQ(fd.type, candump_frame_type::fd);
  EXPECT_EQ(fd.length, 3);
  const candump_record xl = read("  can0       123 [0003] (45|81:00:12345678) 11 22 33");
  EXPECT_EQ(xl.type, candump_frame_type::xl);
  EXPECT_EQ(xl.can_id, 0x450123U);
  EXPECT_EQ(xl.af, 0x12345678U);

  const candump_record stamped = read(" (1700000000.123456)  can0  028   [8]  01 00 00 00 00 02 0D 7A");  // -t a
  EXPECT_EQ(stamped.timestamp, "1700000000.123456");
  EXPECT_TRUE(stamped.has_timestamp);
  EXPECT_EQ(read(" (000.000123)  can0  028   [1]  01").timestamp, "000.000123");  // -t d, -t z
  const candump_record dated = read(" (2024-01-02 03:04:05.123456)  can0  028   [1]  01");  // -t A: local time
  EXPECT_EQ(dated.timestamp, "2024-01-02 03:04:05.123456");
  EXPECT_FALSE(dated.has_timestamp);
  const candump_record extra = read("  can0  TX B E  123  [01]  AA");  // -x
  EXPECT_EQ(extra.direction, 'T');
  EXPECT_EQ(extra.type, candump_frame_type::fd);
  EXPECT_EQ(extra.flags, 3);
  EXPECT_EQ(read("  can0  RX - -  028   [8]  01 00 00 00 00 02 0D 7A").direction, 'R');
  // log2long: the timestamp column, the interface padded, the ASCII column (empty for no data)
  expect_classic("(1700000000.723456)  can0       7FF   [0]                            ''", 0x7FF, 0);
  expect_classic("(1700000000.423456)  can0  12345678   [2]  11 22                     '.\"'",
                 frame::extended_flag | 0x12345678, 2);
}

// "identifiers with the error flag are error frames" (docs/protocol.md 2.3), after `##` too: python-can's
// CanutilsLogWriter writes an ASC error frame of a CAN FD channel as `20000080##0`, and log2long prints
// can-utils' reading of it as an error frame with a CAN FD length.
TEST(CanCandumpGrammar, ErrorFlagInCanFdFrameIsAnErrorFrame) {
  const candump_record log = read("(30.806898) can4 20000080##0");
  EXPECT_EQ(log.type, candump_frame_type::error);
  EXPECT_EQ(log.can_id, 0x20000080U);
  EXPECT_EQ(log.length, 0);
  EXPECT_EQ(log.frame.id, 0x80U);
  const candump_record screen = read("(30.806898)  can4  20000080  [00]                            ERRORFRAME");
  EXPECT_EQ(screen.type, candump_frame_type::error);
  EXPECT_EQ(screen.can_id, 0x20000080U);
  EXPECT_EQ(screen.length, 0);
  const candump_record data = read("  can0  20001111  [12]  11 22 33 44 55 66 77 88 99 AA BB CC");
  EXPECT_EQ(data.type, candump_frame_type::error);
  EXPECT_EQ(data.length, 12);
  EXPECT_EQ(data.frame.dlc, 8);
  EXPECT_EQ(read("20001111##1AABB").type, candump_frame_type::error);
  EXPECT_EQ(read("20001111##1AABB").flags, 1);
}

TEST(CanCandumpGrammar, ScreenFormatErrors) {
  EXPECT_EQ(parse_candump_line("  can0  028   [9]  01").status, candump_status::length);
  EXPECT_EQ(parse_candump_line("  can0  028   8  01").status, candump_status::length);
  EXPECT_EQ(parse_candump_line("  can0  028   [2]  01").status, candump_status::data);
  EXPECT_EQ(parse_candump_line("  can0  028   [1]  0G").status, candump_status::data);
  EXPECT_EQ(parse_candump_line("  can0  028   [1]  01 02").status, candump_status::trailing);
  EXPECT_EQ(parse_candump_line("  can0  28   [1]  01").status, candump_status::identifier);
  EXPECT_EQ(parse_candump_line("  can0  028   [0]  remote query").status, candump_status::trailing);
  EXPECT_EQ(parse_candump_line("  can0  20001111 [0003] (45|81:00:12345678) 11 22 33").status,
            candump_status::length)
      << "no CAN XL frame has an 8-digit identifier";
}

}  // namespace
