// The ring decoder fed in bulk (docs/protocol.md 1.4): exactly the results of the same bytes one at a time,
// also for the 16-byte windows that look like a whole direct variable transfer and are not one, which the
// bulk path must not take for one.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "support/ring_events.hpp"
#include "support/ring_frames.hpp"
#include "trionet/ring.hpp"

namespace {

namespace ring = trionet::ring;
using trionet::byte_view;
using trionet::test::decode_bulk;
using trionet::test::decode_bytewise;
using trionet::test::event;
using trionet::test::frame_of;
using Bytes = std::vector<std::uint8_t>;

constexpr std::int64_t ninety_nine = std::int64_t{99} << 32;

// docs/protocol.md 1.3's example: hop 1, VR(200) = 99: header, V0 V1 X0..X9 C0 C1, end of message.
Bytes example_variable() {
  return frame_of(ring::message::variable(1, 200, ninety_nine));
}

Bytes operator+(Bytes a, const Bytes& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// The events of `bytes` fed one at a time, in one bulk push and in bulk pieces of every size 1..17; all must
// agree. Returns the first.
std::vector<event> decoded(const Bytes& bytes) {
  ring::decoder<64> one_at_a_time, whole;
  const std::vector<event> expected = decode_bytewise(one_at_a_time, bytes);
  EXPECT_EQ(decode_bulk(whole, bytes), expected);
  for (std::size_t piece = 1; piece <= 17; ++piece) {
    ring::decoder<64> pieces;
    std::vector<event> got;
    for (std::size_t at = 0; at < bytes.size(); at += piece) {
      const std::size_t n = std::min(piece, bytes.size() - at);
      pieces.push(byte_view(bytes.data() + at, n),
                  [&](const ring::decode_result& r) { got.push_back(trionet::test::to_event(r)); });
    }
    EXPECT_EQ(got, expected) << "in pieces of " << piece;
  }
  return expected;
}

void expect_frame_errors(const std::vector<event>& events, std::vector<ring::frame_error> errors) {
  ASSERT_EQ(events.size(), errors.size());
  for (std::size_t i = 0; i < errors.size(); ++i) {
    EXPECT_EQ(events[i].status, ring::decode_status::frame_error) << i;
    EXPECT_EQ(events[i].error, errors[i]) << i;
  }
}

void expect_example_variable(const event& e) {
  EXPECT_EQ(e.status, ring::decode_status::ok);
  EXPECT_EQ(e.type, ring::message_type::variable);
  EXPECT_EQ(e.hops, 1);
  EXPECT_EQ(e.vr, 200);
  EXPECT_EQ(e.value, ninety_nine);
}

TEST(RingDecoderBulk, AWholeDirectVariableTransferIsDecodedAsByteByByte) {
  const std::vector<event> events = decoded(example_variable());
  ASSERT_EQ(events.size(), 1U);
  expect_example_variable(events[0]);
  const std::vector<event> twice = decoded(example_variable() + example_variable());
  ASSERT_EQ(twice.size(), 2U);
  expect_example_variable(twice[1]);
}

TEST(RingDecoderBulk, AHeaderWithHopsZeroIsNotATransfer) {
  Bytes f = example_variable();
  f.front() = ring::with_hops(f.front(), 0);
  f.back() = ring::with_hops(f.back(), 0);
  expect_frame_errors(decoded(f), {ring::frame_error::zero_hops});
  const std::vector<event> then = decoded(f + example_variable());
  ASSERT_EQ(then.size(), 2U) << "the skipped message ends at its end of message";
  expect_example_variable(then[1]);
}

TEST(RingDecoderBulk, AnEndOfMessageWithOtherHopsIsAMismatch) {
  Bytes f = example_variable();
  f.back() = ring::make_end_of_message(2);
  expect_frame_errors(decoded(f), {ring::frame_error::eom_mismatch});
}

TEST(RingDecoderBulk, FourteenCharactersAreACharacterTransfer) {
  const std::vector<event> events = decoded(trionet::test::chars(1, "ABCDEFGHIJKLMN"));
  ASSERT_EQ(events.size(), 1U);
  EXPECT_EQ(events[0].status, ring::decode_status::ok);
  EXPECT_EQ(events[0].type, ring::message_type::character);
  EXPECT_EQ(events[0].text, "ABCDEFGHIJKLMN");
}

TEST(RingDecoderBulk, FourteenBytesOfAnotherTypeAreTheWrongLength) {
  Bytes f = example_variable();
  f.front() = ring::make_header(1, 3);  // a keypad offset carries one byte
  expect_frame_errors(decoded(f), {ring::frame_error::bad_length});
  f.front() = ring::make_header(1, 5);
  expect_frame_errors(decoded(f), {ring::frame_error::unknown_type});
}

TEST(RingDecoderBulk, AControlByteInsideTheFourteenBytesEndsTheTransfer) {
  Bytes f = example_variable();
  f[7] = ring::make_header(1, 1);  // a character transfer starts in the middle
  const std::vector<event> events = decoded(f);
  ASSERT_EQ(events.size(), 2U);
  EXPECT_EQ(events[0].error, ring::frame_error::interrupted);
  EXPECT_EQ(events[1].status, ring::decode_status::ok);
  EXPECT_EQ(events[1].type, ring::message_type::character);
  EXPECT_EQ(events[1].text.size(), 7U);

  f = example_variable();
  f[7] = ring::make_end_of_message(1);  // the transfer ends after 6 bytes; the rest is stray
  expect_frame_errors(decoded(f), {ring::frame_error::bad_length, ring::frame_error::stray_data,
                                   ring::frame_error::stray_eom});
}

TEST(RingDecoderBulk, ADataByteWhoseBitsLookLikeAHeaderIsStrayData) {
  Bytes f = example_variable();
  f.front() = static_cast<std::uint8_t>(f.front() & 0x7F);  // bit 7 clear: hops 1, type 2 in its other bits
  expect_frame_errors(decoded(f), {ring::frame_error::stray_data, ring::frame_error::stray_eom});
}

TEST(RingDecoderBulk, AFieldOutOfRangeAndACrcErrorAreReportedAsByteByByte) {
  Bytes f = example_variable();
  f[12] =
      static_cast<std::uint8_t>(f[12] | 0x02);  // X9 bit 1: the value's top group allows only bits 0 and 7
  expect_frame_errors(decoded(f), {ring::frame_error::bad_field});
  f = example_variable();
  f[13] = static_cast<std::uint8_t>(f[13] ^ 0x01);  // C0
  const std::vector<event> events = decoded(f);
  ASSERT_EQ(events.size(), 1U);
  EXPECT_EQ(events[0].status, ring::decode_status::crc_error);
  EXPECT_EQ(events[0].hops, 1) << "a CRC error keeps the header's hops";
  EXPECT_EQ(events[0].vr, 200) << "and the VR as received";
}

TEST(RingDecoderBulk, AWholeTransferAfterAnOpenMessageInterruptsIt) {
  const std::vector<event> events = decoded(Bytes{ring::make_header(2, 1), 'A', 'B'} + example_variable());
  ASSERT_EQ(events.size(), 2U);
  EXPECT_EQ(events[0].error, ring::frame_error::interrupted);
  expect_example_variable(events[1]);
}

TEST(RingDecoderBulk, AWholeTransferAfterStrayDataOrASkippedMessageIsDecoded) {
  std::vector<event> events = decoded(Bytes{'x', 'y'} + example_variable());
  ASSERT_EQ(events.size(), 2U);
  EXPECT_EQ(events[0].error, ring::frame_error::stray_data);
  expect_example_variable(events[1]);
  events = decoded(Bytes{ring::make_header(0, 1), 'x'} + example_variable());
  ASSERT_EQ(events.size(), 2U);
  EXPECT_EQ(events[0].error, ring::frame_error::zero_hops);
  expect_example_variable(events[1]);
}

// A decoder given a CRC at run time checks the bulk transfers with it: the example under XMODEM's CRC is
// accepted by such a decoder and is a CRC error for the default one.
TEST(RingDecoderBulk, ARunTimeCrcChecksBulkTransfersToo) {
  const ring::crc16_runtime xmodem(ring::crc16_parameters{0x1021, 0x0000, false, false, 0x0000});
  Bytes f(16);
  ASSERT_TRUE((ring::encode_variable<ring::crc16_runtime>(trionet::byte_buffer(f.data(), f.size()), 1, 200,
                                                          ninety_nine, xmodem)));
  ring::decoder<64, ring::crc16_runtime> with_xmodem(xmodem);
  const std::vector<event> events = decode_bulk(with_xmodem, f);
  ASSERT_EQ(events.size(), 1U);
  expect_example_variable(events[0]);
  ring::decoder<64> with_default;
  const std::vector<event> refused = decode_bulk(with_default, f);
  ASSERT_EQ(refused.size(), 1U);
  EXPECT_EQ(refused[0].status, ring::decode_status::crc_error);
}

}  // namespace
