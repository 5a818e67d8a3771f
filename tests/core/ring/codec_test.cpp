// The ring codec against docs/protocol.md 1.2-1.4 and the manual's message format.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "support/ring_events.hpp"
#include "trionet/ring.hpp"

namespace ring = trionet::ring;
using trionet::byte_view;
using trionet::test::decode_bulk;
using trionet::test::decode_bytewise;
using trionet::test::event;
using trionet::test::to_event;

namespace {

// docs/protocol.md 1.3's example frame.
const std::vector<std::uint8_t>& golden = trionet::test::golden_variable_transfer;

std::vector<std::uint8_t> bytes_of(std::initializer_list<int> list) {
  std::vector<std::uint8_t> out;
  for (int b : list) out.push_back(static_cast<std::uint8_t>(b));
  return out;
}

std::vector<event> decode_all(const std::vector<std::uint8_t>& bytes) {
  ring::decoder<> d;
  return decode_bytewise(d, bytes);
}

ring::frame_error only_error(const std::vector<std::uint8_t>& bytes) {
  const auto events = decode_all(bytes);
  EXPECT_EQ(events.size(), 1u);
  if (events.size() != 1) return ring::frame_error::none;
  EXPECT_EQ(events[0].status, ring::decode_status::frame_error);
  return events[0].error;
}

}  // namespace

// ---- docs/protocol.md 1.3 example: hop 1, vr 200, value 99 ----

TEST(RingGoldenExample, EncodesByteForByte) {
  std::uint8_t frame[16];
  const auto result = ring::encode_variable(frame, 1, 200, trionet::q32_from_integer(99));
  ASSERT_TRUE(result);
  ASSERT_EQ(result.length, 16u);
  EXPECT_EQ(std::vector<std::uint8_t>(frame, frame + 16), golden);
  EXPECT_EQ(ring::crc16_ccitt_false::compute(frame + 1, 12), 0x3EFF);
}

TEST(RingGoldenExample, Decodes) {
  const auto events = decode_all(golden);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].status, ring::decode_status::ok);
  EXPECT_EQ(events[0].type, ring::message_type::variable);
  EXPECT_EQ(events[0].hops, 1);
  EXPECT_EQ(events[0].vr, 200);
  EXPECT_EQ(events[0].value, trionet::q32_from_integer(99));
  EXPECT_EQ(trionet::q32_to_double(events[0].value), 99.0);
}

// ---- bytes, hops and BASIC addresses ----

TEST(RingBytes, ClassifiedByBitSevenAndType) {
  EXPECT_EQ(ring::classify(0x00), ring::byte_class::data);
  EXPECT_EQ(ring::classify(0x7F), ring::byte_class::data);
  EXPECT_EQ(ring::classify(0x8A), ring::byte_class::header);
  EXPECT_EQ(ring::classify(0x88), ring::byte_class::end_of_message);
  EXPECT_EQ(ring::classify(0x80), ring::byte_class::end_of_message);
  EXPECT_EQ(ring::classify(0xFF), ring::byte_class::header);
}

TEST(RingBytes, HeaderAndEndOfMessageCarryHops) {
  for (std::uint8_t hops = 1; hops <= 15; ++hops) {
    for (std::uint8_t type = 1; type <= 7; ++type) {
      const std::uint8_t header = ring::make_header(hops, type);
      EXPECT_EQ(ring::classify(header), ring::byte_class::header);
      EXPECT_EQ(ring::hops_of(header), hops);
      EXPECT_EQ(ring::type_of(header), type);
      EXPECT_EQ(ring::hops_of(ring::with_hops(header, 3)), 3);
      EXPECT_EQ(ring::type_of(ring::with_hops(header, 3)), type);
    }
    const std::uint8_t end = ring::make_end_of_message(hops);
    EXPECT_EQ(ring::classify(end), ring::byte_class::end_of_message);
    EXPECT_EQ(ring::hops_of(end), hops);
  }
}

// What a forwarder sends for every control byte: A - 1 with type (and bit 7) unchanged, A = 0 left at 0.
TEST(RingBytes, DecrementHopsForEveryControlByte) {
  for (unsigned b = 0x80; b <= 0xFF; ++b) {
    const auto byte = static_cast<std::uint8_t>(b);
    const std::uint8_t hops = ring::hops_of(byte);
    const std::uint8_t forwarded = ring::decrement_hops(byte);
    EXPECT_EQ(ring::hops_of(forwarded), hops == 0 ? 0 : hops - 1) << b;
    EXPECT_EQ(ring::type_of(forwarded), ring::type_of(byte)) << b;
    EXPECT_EQ(ring::classify(forwarded), ring::classify(byte)) << b;
  }
}

TEST(RingAddressing, BasicAddressIsHopsPlusNine) {
  EXPECT_FALSE(ring::hops_from_basic_address(9).has_value());
  EXPECT_FALSE(ring::hops_from_basic_address(25).has_value());
  EXPECT_FALSE(ring::hops_from_basic_address(-1).has_value());
  for (int n = 10; n <= 24; ++n) {
    ASSERT_TRUE(ring::hops_from_basic_address(n).has_value());
    EXPECT_EQ(*ring::hops_from_basic_address(n), n - 9);
    EXPECT_EQ(*ring::basic_address_from_hops(static_cast<unsigned>(n - 9)), n);
  }
  EXPECT_FALSE(ring::basic_address_from_hops(0).has_value());
  EXPECT_FALSE(ring::basic_address_from_hops(16).has_value());
}

// ---- Q32.32 ----

TEST(RingQ32, RoundsToNearestTiesAwayFromZero) {
  const double step = 1.0 / trionet::q32_one;
  EXPECT_EQ(trionet::q32_from_double(0.5 * step).raw, 1);
  EXPECT_EQ(trionet::q32_from_double(-0.5 * step).raw, -1);
  EXPECT_EQ(trionet::q32_from_double(0.49 * step).raw, 0);
  EXPECT_EQ(trionet::q32_from_double(1.5 * step).raw, 2);
  EXPECT_EQ(trionet::q32_from_double(-1.5 * step).raw, -2);
  EXPECT_EQ(trionet::q32_from_double(2.5 * step).raw, 3);
  EXPECT_EQ(trionet::q32_from_double(99.0).raw, trionet::q32_from_integer(99));
  EXPECT_EQ(trionet::q32_from_double(-2.5).raw, -(std::int64_t{5} << 31));
}

TEST(RingQ32, OutOfRangeIsAnErrorNeverWrapped) {
  EXPECT_TRUE(trionet::q32_from_double(-2147483648.0));
  EXPECT_EQ(trionet::q32_from_double(-2147483648.0).raw, INT64_MIN);
  EXPECT_EQ(trionet::q32_from_double(2147483648.0).status, trionet::q32_status::out_of_range);
  EXPECT_EQ(trionet::q32_from_double(-2147483649.0).status, trionet::q32_status::out_of_range);
  EXPECT_EQ(trionet::q32_from_double(1e300).status, trionet::q32_status::out_of_range);
  EXPECT_EQ(trionet::q32_from_double(-1e300).status, trionet::q32_status::out_of_range);
  EXPECT_EQ(trionet::q32_from_double(std::numeric_limits<double>::infinity()).status,
            trionet::q32_status::out_of_range);
  EXPECT_EQ(trionet::q32_from_double(std::nan("")).status, trionet::q32_status::not_a_number);
  // The largest double below 2^31 is in range.
  const double below = std::nextafter(2147483648.0, 0.0);
  ASSERT_TRUE(trionet::q32_from_double(below));
  EXPECT_GT(trionet::q32_from_double(below).raw, 0);
}

TEST(RingQ32, RawBitsAreTwosComplement) {
  EXPECT_EQ(trionet::q32_from_raw(0xFFFFFFFFFFFFFFFFull), -1);
  EXPECT_EQ(trionet::q32_from_raw(0x8000000000000000ull), INT64_MIN);
  EXPECT_EQ(trionet::q32_from_raw(0x0000006300000000ull), trionet::q32_from_integer(99));
  EXPECT_EQ(trionet::q32_to_raw(-1), 0xFFFFFFFFFFFFFFFFull);
  EXPECT_EQ(trionet::q32_to_double(trionet::q32_from_raw(0xFFFFFFFF80000000ull)), -0.5);
}

// ---- encoders ----

TEST(RingEncode, CharacterTransfer) {
  std::uint8_t frame[8];
  const auto result = ring::encode_characters(frame, 2, "HI", 2);
  ASSERT_TRUE(result);
  EXPECT_EQ(std::vector<std::uint8_t>(frame, frame + result.length), bytes_of({0x91, 'H', 'I', 0x90}));
}

TEST(RingEncode, KeypadOffsetAndMode) {
  std::uint8_t frame[3];
  ASSERT_TRUE(ring::encode_keypad_offset(frame, 1, 3));
  EXPECT_EQ(std::vector<std::uint8_t>(frame, frame + 3), bytes_of({0x8b, 0x03, 0x88}));
  ASSERT_TRUE(ring::encode_keypad_mode(frame, 3, 127));
  EXPECT_EQ(std::vector<std::uint8_t>(frame, frame + 3), bytes_of({0x9c, 0x7f, 0x98}));
}

TEST(RingEncode, NegativeValueCarriesBit63InX9) {
  std::uint8_t frame[16];
  ASSERT_TRUE(ring::encode_variable(frame, 1, 0, -1));
  for (int k = 0; k < 9; ++k) EXPECT_EQ(frame[3 + k], 0x7F) << k;
  EXPECT_EQ(frame[12], 0x01);
}

TEST(RingEncode, ErrorsWriteNothing) {
  struct bad_case {
    ring::message m;
    ring::encode_status expected;
  };
  const std::uint8_t high[] = {'A', 200};
  const std::uint8_t ok[] = {'A'};
  const bad_case cases[] = {
      {ring::message::characters(0, byte_view(ok, 1)), ring::encode_status::hops_out_of_range},
      {ring::message::characters(16, byte_view(ok, 1)), ring::encode_status::hops_out_of_range},
      {ring::message::characters(1, byte_view()), ring::encode_status::empty_text},
      {ring::message::characters(1, byte_view(high, 2)), ring::encode_status::character_out_of_range},
      {ring::message::variable(1, 16384, 0), ring::encode_status::vr_out_of_range},
      {ring::message::keypad_offset(1, 0), ring::encode_status::offset_out_of_range},
      {ring::message::keypad_offset(1, 16), ring::encode_status::offset_out_of_range},
      {ring::message::keypad_mode(1, 1), ring::encode_status::mode_out_of_range},
      {ring::message::keypad_mode(1, 128), ring::encode_status::mode_out_of_range},
  };
  for (const auto& c : cases) {
    std::uint8_t frame[32];
    std::memset(frame, 0xA5, sizeof frame);
    const auto result = ring::encode(frame, c.m);
    EXPECT_EQ(result.status, c.expected) << ring::to_string(c.expected);
    EXPECT_EQ(result.length, 0u);
    for (std::uint8_t b : frame) ASSERT_EQ(b, 0xA5) << "partial write for " << ring::to_string(c.expected);
  }
  ring::message unknown = ring::message::keypad_mode(1, 0);
  unknown.type = static_cast<ring::message_type>(5);
  std::uint8_t frame[8];
  EXPECT_EQ(ring::encode(frame, unknown).status, ring::encode_status::unknown_type);
}

TEST(RingEncode, BufferTooSmallWritesNothing) {
  std::uint8_t frame[16];
  std::memset(frame, 0xA5, sizeof frame);
  const auto result = ring::encode_variable(trionet::byte_buffer(frame, 15), 1, 200, 0);
  EXPECT_EQ(result.status, ring::encode_status::buffer_too_small);
  for (std::uint8_t b : frame) EXPECT_EQ(b, 0xA5);
  EXPECT_EQ(ring::encode_characters(trionet::byte_buffer(frame, 4), 1, "ABC", 3).status,
            ring::encode_status::buffer_too_small);
  EXPECT_TRUE(ring::encode_characters(trionet::byte_buffer(frame, 5), 1, "ABC", 3));
}

// ---- decoder: every frame-error reason ----

TEST(RingDecodeErrors, StrayDataOncePerRun) {
  const auto events = decode_all(bytes_of({0x01, 0x02, 0x03, 0x91, 'A', 0x90, 0x04, 0x05}));
  ASSERT_EQ(events.size(), 3u);
  EXPECT_EQ(events[0].error, ring::frame_error::stray_data);
  EXPECT_EQ(events[1].status, ring::decode_status::ok);
  EXPECT_EQ(events[1].text, "A");
  EXPECT_EQ(events[2].error, ring::frame_error::stray_data);
}

TEST(RingDecodeErrors, StrayEndOfMessage) {
  EXPECT_EQ(only_error(bytes_of({0x88})), ring::frame_error::stray_eom);
  EXPECT_EQ(only_error(bytes_of({0x80})), ring::frame_error::stray_eom);
}

TEST(RingDecodeErrors, InterruptedByHeaderThenTheNewMessageDecodes) {
  const auto events = decode_all(bytes_of({0x89, 'A', 'B', 0x91, 'C', 0x90}));
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].error, ring::frame_error::interrupted);
  EXPECT_EQ(events[1].status, ring::decode_status::ok);
  EXPECT_EQ(events[1].hops, 2);
  EXPECT_EQ(events[1].text, "C");
}

TEST(RingDecodeErrors, EndOfMessageMismatch) {
  EXPECT_EQ(only_error(bytes_of({0x89, 'A', 0x90})), ring::frame_error::eom_mismatch);
}

TEST(RingDecodeErrors, BadLength) {
  EXPECT_EQ(only_error(bytes_of({0x89, 0x88})), ring::frame_error::bad_length);        // empty characters
  EXPECT_EQ(only_error(bytes_of({0x8b, 0x88})), ring::frame_error::bad_length);        // offset, no data
  EXPECT_EQ(only_error(bytes_of({0x8b, 3, 3, 0x88})), ring::frame_error::bad_length);  // offset, two
  EXPECT_EQ(only_error(bytes_of({0x8c, 0, 0, 0x88})), ring::frame_error::bad_length);  // mode, two
  std::vector<std::uint8_t> short_var(golden);
  short_var.erase(short_var.begin() + 5);
  EXPECT_EQ(only_error(short_var), ring::frame_error::bad_length);
  std::vector<std::uint8_t> long_var(golden);
  long_var.insert(long_var.begin() + 5, 0x00);
  EXPECT_EQ(only_error(long_var), ring::frame_error::bad_length);
}

TEST(RingDecodeErrors, BadField) {
  EXPECT_EQ(only_error(bytes_of({0x8b, 0, 0x88})), ring::frame_error::bad_field);   // offset 0
  EXPECT_EQ(only_error(bytes_of({0x8b, 16, 0x88})), ring::frame_error::bad_field);  // offset 16
  EXPECT_EQ(only_error(bytes_of({0x8c, 1, 0x88})), ring::frame_error::bad_field);   // mode 1
  // X9 bits 6..1 set, with a CRC that matches (so the field check is reached).
  std::vector<std::uint8_t> frame(golden);
  frame[12] = 0x02;
  const std::uint16_t crc = ring::crc16_ccitt_false::compute(frame.data() + 1, 12);
  frame[13] = static_cast<std::uint8_t>(crc & 0x7F);
  frame[14] = static_cast<std::uint8_t>((crc >> 8) & 0x7F);
  EXPECT_EQ(only_error(frame), ring::frame_error::bad_field);
}

TEST(RingDecodeErrors, UnknownType) {
  for (int type = 5; type <= 7; ++type) {
    EXPECT_EQ(only_error(bytes_of({0x88 | type, 1, 2, 3, 0x88})), ring::frame_error::unknown_type) << type;
  }
}

TEST(RingDecodeErrors, ZeroHopsSkipsToThatMessagesEnd) {
  // A = 0 header, its data and its end of message: one report, then the next message decodes.
  const auto events = decode_all(bytes_of({0x81, 'X', 'Y', 0x80, 0x89, 'A', 0x88}));
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].error, ring::frame_error::zero_hops);
  EXPECT_EQ(events[1].status, ring::decode_status::ok);
  EXPECT_EQ(events[1].text, "A");
  // ... or to the next header.
  const auto again = decode_all(bytes_of({0x81, 'X', 0x89, 'A', 0x88}));
  ASSERT_EQ(again.size(), 2u);
  EXPECT_EQ(again[0].error, ring::frame_error::zero_hops);
  EXPECT_EQ(again[1].text, "A");
}

TEST(RingDecodeErrors, ZeroHopsInsideAMessageIsOneReportForBoth) {
  // An A = 0 header while a message is open: one report (the open message was interrupted), the A = 0
  // message is skipped to its end, then the next message decodes. One error for two messages: the ring soak
  // counts the A = 0 message as merged.
  const auto events = decode_all(bytes_of({0x89, 'A', 0x81, 'X', 'Y', 0x80, 0x89, 'B', 0x88}));
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].error, ring::frame_error::interrupted);
  EXPECT_EQ(events[1].status, ring::decode_status::ok);
  EXPECT_EQ(events[1].text, "B");
}

TEST(RingDecodeErrors, CrcErrorReportsHopsAndVrAndChecksLengthFirst) {
  std::vector<std::uint8_t> frame(golden);
  frame[7] ^= 0x01;  // corrupt X4
  auto events = decode_all(frame);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].status, ring::decode_status::crc_error);
  EXPECT_EQ(events[0].hops, 1);
  EXPECT_EQ(events[0].vr, 200);
  // A corrupted CRC byte is a CRC error too.
  frame = golden;
  frame[14] ^= 0x40;
  events = decode_all(frame);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].status, ring::decode_status::crc_error);
  // Regression: a CRC error is a message that is otherwise well formed (docs/protocol.md 1.4). X9 bits 6..1
  // set and a wrong CRC is a frame error (bad field), not a CRC error.
  frame = golden;
  frame[12] = 0x7E;
  events = decode_all(frame);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].status, ring::decode_status::frame_error);
  EXPECT_EQ(events[0].error, ring::frame_error::bad_field);
}

TEST(RingDecodeErrors, LongCharacterMessageIsConsumedNotOverflowed) {
  ring::decoder<8> d;
  std::vector<std::uint8_t> stream = {0x89};
  for (int i = 0; i < 100000; ++i) stream.push_back(static_cast<std::uint8_t>('a' + i % 26));
  stream.push_back(0x88);
  stream.insert(stream.end(), {0x89, 'o', 'k', 0x88});
  auto events = decode_bytewise(d, stream);
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].error, ring::frame_error::bad_length);
  EXPECT_EQ(events[1].text, "ok");
  ring::decoder<8> bulk;
  EXPECT_EQ(decode_bulk(bulk, stream), events);
}

TEST(RingDecode, MaximumLengthIsATemplateParameter) {
  std::vector<std::uint8_t> eight = {0x89, '1', '2', '3', '4', '5', '6', '7', '8', 0x88};
  std::vector<std::uint8_t> nine = {0x89, '1', '2', '3', '4', '5', '6', '7', '8', '9', 0x88};
  ring::decoder<8> d;
  auto events = decode_bytewise(d, eight);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].text, "12345678");
  events = decode_bytewise(d, nine);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].error, ring::frame_error::bad_length);

  // The default is 256 characters.
  std::vector<std::uint8_t> max = {0x89};
  max.insert(max.end(), 256, 'x');
  max.push_back(0x88);
  EXPECT_EQ(decode_all(max).at(0).text.size(), 256u);
  max.insert(max.begin() + 1, 'x');
  EXPECT_EQ(decode_all(max).at(0).error, ring::frame_error::bad_length);
}

TEST(RingDecode, RecoversAtNextHeaderAfterEveryError) {
  const std::vector<std::vector<std::uint8_t>> garbage = {
      bytes_of({0x01}),          bytes_of({0x88}),
      bytes_of({0x89, 'A'}),     bytes_of({0x89, 'A', 0x90}),
      bytes_of({0x89, 0x88}),    bytes_of({0x8c, 5, 0x88}),
      bytes_of({0x8d, 1, 0x88}), bytes_of({0x81, 1})};
  for (const auto& g : garbage) {
    std::vector<std::uint8_t> stream(g);
    stream.insert(stream.end(), golden.begin(), golden.end());
    const auto events = decode_all(stream);
    ASSERT_FALSE(events.empty());
    EXPECT_EQ(events.back().status, ring::decode_status::ok);
    EXPECT_EQ(events.back().vr, 200);
  }
}

// ---- properties ----

namespace {

ring::message random_message(std::mt19937_64& rng, std::vector<std::uint8_t>& text_storage) {
  const auto hops = static_cast<std::uint8_t>(1 + rng() % 15);
  switch (rng() % 4) {
    case 0: {
      const std::size_t length = 1 + rng() % 256;
      text_storage.resize(length);
      for (auto& c : text_storage) c = static_cast<std::uint8_t>(rng() % 128);
      return ring::message::characters(hops, byte_view(text_storage.data(), length));
    }
    case 1:
      return ring::message::variable(hops, static_cast<std::uint16_t>(rng() % 16384),
                                     static_cast<std::int64_t>(rng()));
    case 2:
      return ring::message::keypad_offset(hops, static_cast<std::uint8_t>(1 + rng() % 15));
    default:
      return ring::message::keypad_mode(hops, rng() % 2 == 0 ? 0 : 127);
  }
}

}  // namespace

TEST(RingProperty, HundredThousandRandomMessagesRoundTrip) {
  std::mt19937_64 rng(20261122);
  ring::decoder<> d;
  std::vector<std::uint8_t> text;
  std::uint8_t frame[300];
  int count = 0;
  for (; count < 100000; ++count) {
    const ring::message m = random_message(rng, text);
    const auto encoded = ring::encode(frame, m);
    ASSERT_TRUE(encoded);
    ASSERT_EQ(encoded.length, ring::frame_length(m));
    ring::decode_result last;
    int results = 0;
    for (std::size_t i = 0; i < encoded.length; ++i) {
      const auto r = d.push(frame[i]);
      if (r.status != ring::decode_status::incomplete) {
        last = r;
        ++results;
      }
    }
    ASSERT_EQ(results, 1);
    ASSERT_EQ(last.status, ring::decode_status::ok);
    ASSERT_EQ(last.msg.type, m.type);
    ASSERT_EQ(last.msg.hops, m.hops);
    switch (m.type) {
      case ring::message_type::character:
        ASSERT_EQ(last.msg.text.size(), m.text.size());
        ASSERT_EQ(std::memcmp(last.msg.text.data(), m.text.data(), m.text.size()), 0);
        break;
      case ring::message_type::variable:
        ASSERT_EQ(last.msg.vr, m.vr);
        ASSERT_EQ(last.msg.value, m.value);
        break;
      case ring::message_type::keypad_offset:
        ASSERT_EQ(last.msg.offset, m.offset);
        break;
      case ring::message_type::keypad_mode:
        ASSERT_EQ(last.msg.mode, m.mode);
        break;
    }
    // Re-encoding the decoded message gives the same frame.
    std::uint8_t again[300];
    const auto re = ring::encode(again, last.msg);
    ASSERT_TRUE(re);
    ASSERT_EQ(std::memcmp(again, frame, re.length), 0);
  }
  EXPECT_EQ(count, 100000);
}

TEST(RingProperty, BytewiseAndBulkGiveTheSameResultsOnCorruptedStreams) {
  std::mt19937_64 rng(7);
  std::vector<std::uint8_t> text;
  std::uint8_t frame[300];
  std::size_t total_events = 0;
  for (int round = 0; round < 200; ++round) {
    std::vector<std::uint8_t> stream;
    for (int i = 0; i < 50; ++i) {
      const auto encoded = ring::encode(frame, random_message(rng, text));
      ASSERT_TRUE(encoded);
      stream.insert(stream.end(), frame, frame + encoded.length);
    }
    // Corruption: flipped bits, dropped bytes, inserted random bytes.
    for (int i = 0; i < 40; ++i) {
      const std::size_t at = rng() % stream.size();
      switch (rng() % 3) {
        case 0:
          stream[at] = static_cast<std::uint8_t>(stream[at] ^ (1u << (rng() % 8)));
          break;
        case 1:
          stream.erase(stream.begin() + static_cast<std::ptrdiff_t>(at));
          break;
        default:
          stream.insert(stream.begin() + static_cast<std::ptrdiff_t>(at), static_cast<std::uint8_t>(rng()));
          break;
      }
    }
    ring::decoder<64> one, bulk, chunked;
    const auto expected = decode_bytewise(one, stream);
    EXPECT_EQ(decode_bulk(bulk, stream), expected);
    // In random chunks too: the decoder's state carries across calls.
    std::vector<event> pieces;
    for (std::size_t at = 0; at < stream.size();) {
      const std::size_t n = std::min<std::size_t>(stream.size() - at, 1 + rng() % 40);
      chunked.push(byte_view(stream.data() + at, n),
                   [&](const ring::decode_result& r) { pieces.push_back(to_event(r)); });
      at += n;
    }
    EXPECT_EQ(pieces, expected);
    total_events += expected.size();
  }
  EXPECT_GT(total_events, 10000u);  // the streams really exercised the decoder
}

// Every encode_status, decode_status and frame_error has its enumerator's spelling (the CLI, the traces and
// the decoder's JSON print them), and a value outside the enum is "unknown".
TEST(RingCodec, StatusNamesAreTheEnumeratorsSpelling) {
  using ring::decode_status;
  using ring::encode_status;
  using ring::frame_error;
  const std::pair<encode_status, const char*> encodes[] = {
      {encode_status::ok, "ok"},
      {encode_status::buffer_too_small, "buffer_too_small"},
      {encode_status::hops_out_of_range, "hops_out_of_range"},
      {encode_status::empty_text, "empty_text"},
      {encode_status::character_out_of_range, "character_out_of_range"},
      {encode_status::vr_out_of_range, "vr_out_of_range"},
      {encode_status::offset_out_of_range, "offset_out_of_range"},
      {encode_status::mode_out_of_range, "mode_out_of_range"},
      {encode_status::unknown_type, "unknown_type"}};
  for (const auto& [status, name] : encodes) EXPECT_STREQ(ring::to_string(status), name);
  EXPECT_STREQ(ring::to_string(static_cast<encode_status>(99)), "unknown");
  const std::pair<decode_status, const char*> decodes[] = {{decode_status::incomplete, "incomplete"},
                                                           {decode_status::ok, "ok"},
                                                           {decode_status::frame_error, "frame_error"},
                                                           {decode_status::crc_error, "crc_error"},
                                                           {decode_status::no_room, "no_room"}};
  for (const auto& [status, name] : decodes) EXPECT_STREQ(ring::to_string(status), name);
  EXPECT_STREQ(ring::to_string(static_cast<decode_status>(99)), "unknown");
  const std::pair<frame_error, const char*> errors[] = {
      {frame_error::none, "none"},           {frame_error::stray_data, "stray_data"},
      {frame_error::stray_eom, "stray_eom"}, {frame_error::interrupted, "interrupted"},
      {frame_error::eom_mismatch, "eom_mismatch"}, {frame_error::bad_length, "bad_length"},
      {frame_error::bad_field, "bad_field"}, {frame_error::unknown_type, "unknown_type"},
      {frame_error::zero_hops, "zero_hops"}, {frame_error::idle_line, "idle_line"}};
  for (const auto& [error, name] : errors) EXPECT_STREQ(ring::to_string(error), name);
  EXPECT_STREQ(ring::to_string(static_cast<frame_error>(99)), "unknown");
}
