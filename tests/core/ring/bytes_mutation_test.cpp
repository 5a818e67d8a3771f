// The ring's byte classes (ring/bytes.hpp) over every byte, and find_control, "the first control byte in
// [first, last), or last", over every run length up to 40 at every alignment, with its control byte anywhere
// or nowhere (the word-at-a-time search must agree with the byte-at-a-time definition everywhere).
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "trionet/ring/bytes.hpp"

namespace {

namespace ring = trionet::ring;

TEST(RingBytes, EveryByteIsDataAHeaderOrAnEndOfMessage) {
  for (unsigned b = 0; b < 256; ++b) {
    const auto byte = static_cast<std::uint8_t>(b);
    const ring::byte_class expected = b < 0x80         ? ring::byte_class::data
                                      : (b & 7U) != 0U ? ring::byte_class::header
                                                       : ring::byte_class::end_of_message;
    EXPECT_EQ(ring::classify(byte), expected) << b;
    EXPECT_EQ(ring::is_data(byte), b < 0x80) << b;
  }
}

const std::uint8_t* first_control_by_definition(const std::uint8_t* first, const std::uint8_t* last) {
  while (first != last && (*first & 0x80U) == 0) ++first;
  return first;
}

TEST(RingBytes, FindControlFindsTheFirstControlByteOfAnyRunAtAnyAlignment) {
  std::vector<std::uint8_t> buffer(64);
  for (std::size_t offset = 0; offset < 8; ++offset) {
    for (std::size_t length = 0; length <= 40; ++length) {
      // `at` == length: no control byte in the run (one just after it, which must not be found).
      for (std::size_t at = 0; at <= length; ++at) {
        for (std::size_t i = 0; i < buffer.size(); ++i) buffer[i] = static_cast<std::uint8_t>('a' + i % 26);
        const std::uint8_t* first = buffer.data() + offset;
        const std::uint8_t* last = first + length;
        buffer[offset + at] = ring::make_end_of_message(3);
        if (at + 1 < length) buffer[offset + at + 1] = ring::make_header(2, 1);  // a second one after it
        EXPECT_EQ(ring::find_control(first, last), first_control_by_definition(first, last))
            << "offset " << offset << ", length " << length << ", control at " << at;
      }
    }
  }
}

}  // namespace
