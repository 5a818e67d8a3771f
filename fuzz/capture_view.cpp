// Fuzz harness: what the host library does with a capture record (src/host/trionet/host/capture.hpp and
// capture_view.hpp): the ring and Genius record splitters, the SocketCAN record, and the record views that
// tools print as JSON and that the Wireshark dissectors must match.
//
// Input: the bytes, as they stand, are a ring record, a Genius record (16-bit big-endian words) and a
// SocketCAN record; the input size picks the splitters' limit (1..7) and the CAN node count.
// Invariants:
//   - no crash, no undefined behaviour, whatever the record (ASan/UBSan in scripts/fuzz);
//   - the splitters put every byte (word) in exactly one record, in order, none empty or over the limit;
//   - the views give exactly one decoder status per message (transmission) the splitter finds in the record,
//     and one word field per Genius character;
//   - a SocketCAN record that reads as a frame has Wireshark's can.* fields, and the frame written again reads
//     back the same.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fuzz_check.hpp"
#include "trionet/host/capture.hpp"
#include "trionet/host/capture_view.hpp"

// The host library is compiled into the tool, not into the header library: compile it here.
#include "../src/host/capture.cpp"
#include "../src/host/capture_view.cpp"
#include "../src/host/pcapng.cpp"

namespace {

using namespace trionet;
using namespace trionet::host;

std::size_t count(const capture_fields& fields, const char* name) {
  std::size_t n = 0;
  for (const capture_field& field : fields) n += field.name == name ? 1u : 0u;
  return n;
}

// The input as a record of each network.
void check_records(const std::uint8_t* data, std::size_t size) {
  const byte_view record(data, size);
  const std::size_t limit = 1 + size % 7;

  std::vector<std::uint8_t> joined;
  std::size_t units = 0;
  ring_record_splitter ring_split(limit);
  const auto ring_sink = [&](byte_view part, std::uint64_t) {
    FUZZ_CHECK(!part.empty() && part.size() <= limit);
    joined.insert(joined.end(), part.begin(), part.end());
  };
  for (std::uint8_t byte : record) ring_split.push(byte, 0, ring_sink);
  ring_split.flush(ring_sink);
  FUZZ_CHECK(joined == std::vector<std::uint8_t>(record.begin(), record.end()));
  ring_record_splitter whole(size + 1);
  const auto count_unit = [&](byte_view, std::uint64_t) { ++units; };
  for (std::uint8_t byte : record) whole.push(byte, 0, count_unit);
  whole.flush(count_unit);
  const capture_fields ring_fields = ring_record_fields(record);
  FUZZ_CHECK(count(ring_fields, "trionet_ring.status") == units);

  const std::vector<std::uint16_t> words = genius_record_words(record);
  FUZZ_CHECK(words.size() == size / 2);
  std::vector<std::uint16_t> joined_words;
  genius_record_splitter genius_split(limit);
  const auto genius_sink = [&](byte_view part, std::uint64_t) {
    FUZZ_CHECK(!part.empty() && part.size() % 2 == 0 && part.size() <= 2 * limit);
    const std::vector<std::uint16_t> part_words = genius_record_words(part);
    joined_words.insert(joined_words.end(), part_words.begin(), part_words.end());
  };
  for (std::uint16_t word : words) genius_split.push(word, 0, genius_sink);
  genius_split.flush(genius_sink);
  FUZZ_CHECK(joined_words == words);
  units = 0;
  genius_record_splitter whole_line(words.size() + 1);
  for (std::uint16_t word : words) whole_line.push(word, 0, count_unit);
  whole_line.flush(count_unit);
  const capture_fields genius_fields = genius_record_fields(record);
  FUZZ_CHECK(count(genius_fields, "trionet_genius.status") == units);
  FUZZ_CHECK(count(genius_fields, "trionet_genius.word") == words.size());

  const capture_fields can_fields = can_record_fields(record, static_cast<std::uint8_t>(size % 13));
  const socketcan_record_result frame = read_socketcan_record(record);
  // An identifier for a classic frame that reads, and for a CAN FD frame (not CAN XL, no error flag).
  const bool fd = frame.status == socketcan_record_status::not_classic && (record[5] & 0x80U) == 0 &&
                  (record[0] & 0x20U) == 0;
  FUZZ_CHECK(count(can_fields, "can.id") == (frame || fd ? 1u : 0u));
  FUZZ_CHECK(count(can_fields, "can.flags.err") ==
             (frame || frame.status == socketcan_record_status::error_frame ? 1u : 0u));
  if (frame) {
    const auto again = socketcan_record(frame.frame);
    const socketcan_record_result back = read_socketcan_record(byte_view(again.data(), again.size()));
    FUZZ_CHECK(back && back.frame == frame.frame);
  }
  FUZZ_CHECK(fields_json(ring_fields).front() == '{' && fields_json(genius_fields).back() == '}');
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  check_records(data, data == nullptr ? 0 : size);
  return 0;
}
