// The decoder and its character store (detail/character_store.hpp): a character transfer's characters are
// committed when the message is valid and aborted when it is discarded, once each, and a store is never told
// to abort a message it has already committed or one that was not a character transfer. A store that keeps
// characters for someone else (a Motion Coordinator's receive buffer stages them for GET#) relies on that.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "support/ring_frames.hpp"
#include "trionet/ring.hpp"

namespace {

namespace ring = trionet::ring;
using trionet::test::chars;
using trionet::test::frame_of;

// What the decoder told its store, since the last `clear`.
struct store_calls {
  int begun = 0;
  int committed = 0;
  int aborted = 0;
  int misuse = 0;  // a commit or abort with no character transfer open (none begun since the last one)
  bool open = false;
};
store_calls calls;

// A character_buffer that records what the decoder tells it in `calls`.
class recording_store {
 public:
  static constexpr std::size_t payload_at = 0;
  std::uint8_t* slots() noexcept { return buffer_.slots(); }
  const std::uint8_t* slots() const noexcept { return buffer_.slots(); }
  trionet::detail::store_window begin() noexcept {
    ++calls.begun;
    calls.open = true;
    return buffer_.begin();
  }
  static trionet::detail::store_window next(std::size_t stored) noexcept {
    return trionet::detail::character_buffer<32>::next(stored);
  }
  trionet::byte_view commit(std::size_t length) noexcept {
    ++calls.committed;
    if (!calls.open) ++calls.misuse;
    calls.open = false;
    return buffer_.commit(length);
  }
  trionet::byte_view text(std::size_t length) const noexcept { return buffer_.text(length); }
  static void abort() noexcept {
    ++calls.aborted;
    if (!calls.open) ++calls.misuse;
    calls.open = false;
  }

 private:
  trionet::detail::character_buffer<32> buffer_;
};

using recording_decoder = ring::basic_decoder<recording_store, 32>;

template <class Decoder>
std::vector<ring::decode_result> push_all(Decoder& decoder, const std::vector<std::uint8_t>& bytes) {
  std::vector<ring::decode_result> results;
  for (std::uint8_t b : bytes) {
    const ring::decode_result r = decoder.push(b);
    if (r.status != ring::decode_status::incomplete) results.push_back(r);
  }
  return results;
}

std::vector<std::uint8_t> operator+(std::vector<std::uint8_t> a, const std::vector<std::uint8_t>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

TEST(RingDecoderStore, AValidCharacterTransferIsCommittedOnceAndNeverAbortedAfterwards) {
  calls = {};
  recording_decoder decoder;
  const auto results = push_all(decoder, chars(1, "AB") + chars(2, "CD"));
  ASSERT_EQ(results.size(), 2U);
  EXPECT_EQ(results[0].status, ring::decode_status::ok);
  EXPECT_EQ(std::string(results[1].msg.text.begin(), results[1].msg.text.end()), "CD");
  EXPECT_EQ(calls.begun, 2);
  EXPECT_EQ(calls.committed, 2);
  EXPECT_EQ(calls.aborted, 0) << "the next header does not discard a message already taken";
  EXPECT_EQ(calls.misuse, 0);
}

TEST(RingDecoderStore, ACharacterTransferCutByAHeaderIsAbortedOnce) {
  calls = {};
  recording_decoder decoder;
  std::vector<std::uint8_t> cut = chars(1, "CUT");
  cut.pop_back();  // no end of message: the next header interrupts it
  const auto results = push_all(decoder, cut + chars(1, "OK"));
  ASSERT_EQ(results.size(), 2U);
  EXPECT_EQ(results[0].error, ring::frame_error::interrupted);
  EXPECT_EQ(results[1].status, ring::decode_status::ok);
  EXPECT_EQ(calls.begun, 2);
  EXPECT_EQ(calls.aborted, 1);
  EXPECT_EQ(calls.committed, 1);
  EXPECT_EQ(calls.misuse, 0);
}

TEST(RingDecoderStore, AVariableTransferCutByAHeaderAbortsNothing) {
  calls = {};
  recording_decoder decoder;
  std::vector<std::uint8_t> cut = frame_of(ring::message::variable(1, 7, std::int64_t{3} << 31));
  cut.resize(6);  // its header and a few data bytes
  const auto results = push_all(decoder, cut + chars(1, "OK"));
  ASSERT_EQ(results.size(), 2U);
  EXPECT_EQ(results[0].error, ring::frame_error::interrupted);
  EXPECT_EQ(results[1].status, ring::decode_status::ok);
  EXPECT_EQ(calls.begun, 1) << "only the character transfer uses the character store";
  EXPECT_EQ(calls.aborted, 0) << "no character transfer was open";
  EXPECT_EQ(calls.committed, 1);
  EXPECT_EQ(calls.misuse, 0);
}

}  // namespace
