// Fuzz harness: the host-side candump text parser and formatter (src/host/trionet/host/candump.hpp) on arbitrary text.
//
// Input: the text is parsed as one line, and again split at every '\n' as the lines of a candump file. The
// last 14 bytes also make a frame (identifier word, DLC, data) that is formatted and parsed back.
// Invariants:
//   - no crash, no undefined behaviour, whatever the text (ASan/UBSan in scripts/fuzz);
//   - a parsed line's lengths are within its frame type's (classic 8, FD 64, XL 2048; an error frame, whose
//     identifier word may carry a CAN FD length, 64) and a classic frame
//     with a legal identifier is a legal frame: an 11-bit identifier (or 29-bit with the extended flag), no
//     other identifier bits, DLC 0..15;
//   - such a frame formats to a compact frame that parses back to the same frame, and a line with a numeric
//     timestamp formats to a log line that parses back to the same frame, interface, direction and time (to
//     the digits written);
//   - format -> parse: any frame the formatter can write (identifier within its width, DLC 0..15) parses back
//     to the same frame.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "trionet/host/candump.hpp"
#include "fuzz_check.hpp"

// The host adapter is compiled into the CLI, not into the header library: compile it here, as the tests do.
#include "../src/host/candump.cpp"

namespace {

using trionet::can::frame;
using namespace trionet::host;

void check_frame(const frame& f) {
  if (f.extended()) {
    FUZZ_CHECK((f.id & ~(frame::extended_flag | frame::remote_flag | frame::extended_mask)) == 0);
  } else {
    FUZZ_CHECK((f.id & ~(frame::remote_flag | frame::standard_mask)) == 0);
  }
  FUZZ_CHECK(f.dlc <= 15);
  if (f.remote()) FUZZ_CHECK(f.payload().empty());
}

void check_line(std::string_view line) {
  const candump_result parsed = parse_candump_line(line);
  if (parsed.status != candump_status::ok) {
    FUZZ_CHECK(to_string(parsed.status) != nullptr);
    return;
  }
  const candump_record& record = parsed.record;
  switch (record.type) {
    case candump_frame_type::classic:
      FUZZ_CHECK(record.length <= 8);
      break;
    case candump_frame_type::error:  // the error flag after `##` or with a CAN FD length: up to 64 bytes
    case candump_frame_type::fd:
      FUZZ_CHECK(record.length <= 64);
      break;
    case candump_frame_type::xl:
      FUZZ_CHECK(record.length <= 2048);
      break;
  }
  FUZZ_CHECK(record.nanoseconds <= 999999999);
  FUZZ_CHECK(record.form == candump_form::compact || !record.interface_name.empty());
  if (!record.classic_frame()) return;
  check_frame(record.frame);

  const candump_result bare = parse_candump_line(format_candump_frame(record.frame));
  FUZZ_CHECK(bare.status == candump_status::ok);
  FUZZ_CHECK(bare.record.form == candump_form::compact && bare.record.classic_frame());
  FUZZ_CHECK(bare.record.frame == record.frame);

  if (!record.has_timestamp) return;
  const std::string text = format_candump_line(record);
  const candump_result again = parse_candump_line(text);
  FUZZ_CHECK(again.status == candump_status::ok);
  FUZZ_CHECK(again.record.frame == record.frame);
  FUZZ_CHECK(again.record.direction == record.direction);
  FUZZ_CHECK(again.record.seconds == record.seconds);
  const std::uint32_t kept = record.fraction_digits == 9 ? record.nanoseconds : record.nanoseconds / 1000 * 1000;
  FUZZ_CHECK(again.record.nanoseconds == kept);
  FUZZ_CHECK(format_candump_line(again.record) == text);
}

void check_format(const std::uint8_t* bytes) {
  frame f;
  f.id = static_cast<std::uint32_t>(bytes[0]) << 24 | static_cast<std::uint32_t>(bytes[1]) << 16 |
         static_cast<std::uint32_t>(bytes[2]) << 8 | bytes[3];
  f.id &= f.extended() ? frame::extended_flag | frame::remote_flag | frame::extended_mask
                       : frame::remote_flag | frame::standard_mask;
  f.dlc = static_cast<std::uint8_t>(bytes[4] & 15u);
  for (std::size_t i = 0; i < 8; ++i) f.data[i] = bytes[5 + i];

  candump_record record;
  record.frame = f;
  record.has_timestamp = (bytes[13] & 1u) != 0;
  record.seconds = bytes[13];
  record.nanoseconds = bytes[12] * 3907000u;
  record.fraction_digits = 6;
  record.interface_name = (bytes[13] & 2u) != 0 ? "vcan0" : "";
  record.direction = (bytes[13] & 4u) != 0 ? 'T' : 0;
  const candump_result parsed = parse_candump_line(format_candump_line(record));
  FUZZ_CHECK(parsed.status == candump_status::ok);
  FUZZ_CHECK(parsed.record.frame == f);
  FUZZ_CHECK(parsed.record.has_timestamp == record.has_timestamp);
  if (record.has_timestamp) {
    FUZZ_CHECK(parsed.record.seconds == record.seconds);
    FUZZ_CHECK(parsed.record.nanoseconds == record.nanoseconds);
    FUZZ_CHECK(parsed.record.interface_name == (record.interface_name.empty() ? "can0" : "vcan0"));
    FUZZ_CHECK(parsed.record.direction == record.direction);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), data == nullptr ? 0 : size);
  check_line(text);
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    if (start != 0 || end != text.size()) check_line(text.substr(start, end - start));
    start = end + 1;
  }
  if (size >= 14) check_format(data + size - 14);
  return 0;
}
