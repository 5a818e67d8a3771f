// Fuzz harness: the readers of the learning library (src/learn/) on arbitrary input: a profile (JSON), a
// sent list, and a stream of ring bytes searched for direct variable transfers.
//
// Input: the whole input is read as each of the three.
// Invariants:
//   - no crash, no undefined behaviour, whatever the input (ASan/UBSan in scripts/fuzz);
//   - a profile that reads is within the schema's ranges, and write -> read gives the same profile, written
//     the same way again (the writer is canonical); its header is generated; an error names a reason;
//   - a sent list that reads has every VR in 0..16383; an error has a line number inside the text;
//   - the frames found in a byte stream are 14 data bytes each, and with the bytes skipped account for every
//     byte of the stream (16 per frame).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz_check.hpp"
#include "learn/profile.hpp"
#include "learn/ring_capture.hpp"

// The learning library is host code, not part of the header library: compile its readers here.
#include "../src/learn/json.cpp"
#include "../src/learn/profile.cpp"
#include "../src/learn/ring_capture.cpp"

namespace {

using namespace trionet::learn;

void check_profile(std::string_view text) {
  const profile_result r = read_profile(text);
  if (!r) {
    FUZZ_CHECK(!r.message.empty() || r.status == profile_status::not_json);
    FUZZ_CHECK(to_string(r.status) != nullptr);
    return;
  }
  const profile& p = r.value;
  FUZZ_CHECK(p.ring.max_characters >= min_characters && p.ring.max_characters <= max_characters_limit);
  FUZZ_CHECK(p.ring.receive_buffer >= min_characters && p.ring.receive_buffer <= max_characters_limit);
  FUZZ_CHECK(p.can.node_count >= 2 && p.can.node_count <= 11);
  FUZZ_CHECK(p.genius.crc.polynomial < 64 && p.genius.crc.initial < 64 && p.genius.crc.xor_out < 64);
  for (std::uint8_t c : p.keypad.codes.raw) FUZZ_CHECK(c < 128);
  const std::string written = write_profile(p);
  const profile_result again = read_profile(written);
  FUZZ_CHECK(again.status == profile_status::ok);
  FUZZ_CHECK(again.value == p);
  FUZZ_CHECK(write_profile(again.value) == written);
  FUZZ_CHECK(profile_header(p).status == header_status::ok);
}

void check_sent_list(std::string_view text) {
  const sent_list_result r = parse_sent_list(text);
  if (!r) {
    FUZZ_CHECK(r.line >= 1);
    FUZZ_CHECK(r.sent.empty());
    return;
  }
  for (const sent_variable& s : r.sent) FUZZ_CHECK(s.vr <= 16383);
}

void check_stream(const std::uint8_t* data, std::size_t size) {
  const frame_extraction found = variable_transfers(trionet::byte_view(data, size));
  FUZZ_CHECK(found.frames.size() * 16 + found.skipped_bytes == size);
  for (const variable_frame& f : found.frames) {
    for (std::uint8_t b : f) FUZZ_CHECK(b < 0x80);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  check_profile(text);
  check_sent_list(text);
  check_stream(data, size);
  return 0;
}
