// Fuzz harness: the profile reader (src/learn/profile.cpp, json.cpp) as the tool meets it: any bytes as a
// profile file, and what the tool would print about it.
//
// Input: the whole input is the file's text.
// Invariants:
//   - no crash, no undefined behaviour, whatever the input (ASan/UBSan in scripts/fuzz);
//   - an error names its reason, and its message and key hold no control character (a JSON "\u001b" in a
//     value is shown escaped, never as ESC) and are bounded: every value they echo is cut to 40 characters, so
//     a 900 KB value gives a short line;
//   - a profile that reads is within the schema's ranges and writes back canonically (write -> read -> write
//     gives the same text), and its written name is valid JSON text (no raw control character).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz_check.hpp"
#include "learn/profile.hpp"

// The learning library is host code, not part of the header library: compile its reader here.
#include "../src/learn/json.cpp"
#include "../src/learn/profile.cpp"

using namespace trionet::learn;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const profile_result r = read_profile(text);
  if (!r) {
    FUZZ_CHECK(r.status != profile_status::ok);
    FUZZ_CHECK(!r.message.empty() || r.status == profile_status::not_json);
    FUZZ_CHECK(trionet_fuzz::printable_line(r.message));
    FUZZ_CHECK(trionet_fuzz::printable_line(r.key));
    // The schema's messages are short; an echoed value adds at most 40 characters, each at most 8 bytes
    // escaped (a C1 control, \xc2\x9b), and "...".
    FUZZ_CHECK(r.message.size() <= 400);
    FUZZ_CHECK(r.key.size() <= 400);
    return 0;
  }
  const profile& p = r.value;
  FUZZ_CHECK(p.ring.max_characters >= min_characters && p.ring.max_characters <= max_characters_limit);
  FUZZ_CHECK(p.can.node_count >= 2 && p.can.node_count <= 11);
  const std::string written = write_profile(p);
  const profile_result again = read_profile(written);
  FUZZ_CHECK(again.status == profile_status::ok);
  FUZZ_CHECK(again.value == p);
  FUZZ_CHECK(write_profile(again.value) == written);
  // Every line of the written profile is printable (the name escaped as JSON).
  std::size_t start = 0;
  for (std::size_t end = written.find('\n'); end != std::string::npos; end = written.find('\n', start)) {
    FUZZ_CHECK(trionet_fuzz::printable_line(std::string_view(written).substr(start, end - start)));
    start = end + 1;
  }
  return 0;
}
