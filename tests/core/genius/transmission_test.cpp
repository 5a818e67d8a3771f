// Genius transmissions (docs/protocol.md 3.2): encoder, streaming parser and the bits-to-transmissions
// receiver.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <type_traits>
#include <vector>

#include <trionet/genius/transmission.hpp>

#include "support/rng.hpp"

namespace {

using trionet::test::rng;

using namespace trionet::genius;
using trionet::byte_view;
using trionet::span;

template <class Crc = crc6_g704>
std::vector<character> encode(const transmission& t) {
  std::vector<character> out(600);
  const encode_result r = encode_transmission<Crc>(span<character>(out.data(), out.size()), t);
  EXPECT_TRUE(r) << static_cast<int>(r.status);
  out.resize(r.length);
  return out;
}

template <class Parser>
std::vector<parse_status> push_all(Parser& parser, const std::vector<character>& characters) {
  std::vector<parse_status> statuses;
  for (character c : characters) statuses.push_back(parser.push(c));
  return statuses;
}

// The running example: SBA 4 to SBA 7, data 11 22, a block for SBA 9 (aa bb), data 33.
const std::uint8_t plain1[] = {0x11, 0x22};
const std::uint8_t block1[] = {0xaa, 0xbb};
const std::uint8_t plain2[] = {0x33};
const segment example_segments[] = {{false, 0, plain1}, {true, 9, block1}, {false, 0, plain2}};
const transmission example{4, false, 7, example_segments};

TEST(GeniusTransmission, ControlCharacterLayouts) {
  EXPECT_EQ(start_character(4, false), control_character(0x04));
  EXPECT_EQ(start_character(31, true), control_character(0x3f));
  EXPECT_EQ(stop_character(0x2a), control_character(0x6a));
  EXPECT_EQ(start_of_block_character(9), control_character(0x89));
  EXPECT_EQ(end_of_block_character(0x3f), control_character(0xff));
  EXPECT_EQ(read_control(0x24).kind, control_kind::start);
  EXPECT_TRUE(read_control(0x24).broadcast);
  EXPECT_EQ(read_control(0x24).sba, 4);
  EXPECT_EQ(read_control(0x6a).kind, control_kind::stop);
  EXPECT_EQ(read_control(0x6a).crc, 0x2a);
  EXPECT_EQ(read_control(0x89).kind, control_kind::start_of_block);
  EXPECT_EQ(read_control(0x89).sba, 9);
  EXPECT_EQ(read_control(0xa9).kind, control_kind::unknown);  // Start of block with bit 5 set
  EXPECT_EQ(read_control(0xd5).kind, control_kind::end_of_block);
  EXPECT_EQ(read_control(0xd5).crc, 0x15);
}

TEST(GeniusTransmission, EncodeDirectedWithBlock) {
  const std::uint8_t stop_covered[] = {0x07, 0x11, 0x22, 0xaa, 0xbb, 0x33};  // Decision: blocks count
  const std::vector<character> expected = {
      control_character(0x04), data_character(0x07),
      data_character(0x11),    data_character(0x22),
      control_character(0x89), data_character(0xaa),
      data_character(0xbb),    end_of_block_character(crc6_g704::compute(block1)),
      data_character(0x33),    stop_character(crc6_g704::compute(stop_covered))};
  EXPECT_EQ(encode(example), expected);
  EXPECT_EQ(encoded_length(example).length, expected.size());
}

TEST(GeniusTransmission, EncodeMinimalBroadcast) {
  const std::uint8_t data[] = {0x5a};
  const segment segments[] = {{false, 0, data}};
  const std::vector<character> expected = {control_character(0x23), data_character(0x5a),
                                           stop_character(crc6_g704::compute(data))};
  EXPECT_EQ(encode(transmission{3, true, 0, segments}), expected);
}

TEST(GeniusTransmission, EncodeWordsAreTheCharactersWords) {
  const std::vector<character> characters = encode(example);
  std::uint16_t words[16] = {};
  const encode_result r = encode_transmission(span<std::uint16_t>(words), example);
  ASSERT_TRUE(r);
  ASSERT_EQ(r.length, characters.size());
  for (std::size_t i = 0; i < r.length; ++i) EXPECT_EQ(words[i], encode_character(characters[i]));
}

TEST(GeniusTransmission, EncodeErrorsWriteNothing) {
  const character sentinel = control_character(0xee);
  auto try_encode = [&](const transmission& t, std::size_t room) {
    std::vector<character> out(room, sentinel);
    const encode_result r = encode_transmission(span<character>(out.data(), out.size()), t);
    for (character c : out) EXPECT_EQ(c, sentinel);
    return r.status;
  };
  EXPECT_EQ(try_encode(example, 9), encode_status::buffer_too_small);
  EXPECT_EQ(try_encode(example, 0), encode_status::buffer_too_small);
  transmission t = example;
  t.sender = 32;
  EXPECT_EQ(try_encode(t, 20), encode_status::sender_out_of_range);
  t = example;
  t.destination = 32;
  EXPECT_EQ(try_encode(t, 20), encode_status::destination_out_of_range);
  const segment bad_block[] = {{true, 40, block1}};
  EXPECT_EQ(try_encode(transmission{1, true, 0, bad_block}, 20), encode_status::destination_out_of_range);
  const segment empty_block[] = {{false, 0, plain1}, {true, 5, byte_view()}};
  EXPECT_EQ(try_encode(transmission{1, true, 0, empty_block}, 20), encode_status::empty_block);
  EXPECT_EQ(try_encode(transmission{1, true, 0, {}}, 20), encode_status::empty_transmission);
  // A directed transmission with nothing but its destination is the minimum: Start, one data, Stop.
  std::vector<character> out(3);
  EXPECT_TRUE(encode_transmission(span<character>(out.data(), 3), transmission{1, false, 2, {}}));
  std::vector<character> exact(10);
  EXPECT_TRUE(encode_transmission(span<character>(exact.data(), exact.size()), example));
}

TEST(GeniusTransmission, ParseTheExample) {
  transmission_parser<> parser;
  const std::vector<parse_status> statuses = push_all(parser, encode(example));
  for (std::size_t i = 0; i + 1 < statuses.size(); ++i) EXPECT_EQ(statuses[i], parse_status::in_progress);
  ASSERT_EQ(statuses.back(), parse_status::ok);
  const transmission& got = parser.received();
  EXPECT_EQ(got.sender, 4);
  EXPECT_FALSE(got.broadcast);
  EXPECT_EQ(got.destination, 7);
  ASSERT_EQ(got.segments.size(), 3u);
  EXPECT_FALSE(got.segments[0].block);
  EXPECT_EQ(std::vector<std::uint8_t>(got.segments[0].data.begin(), got.segments[0].data.end()),
            (std::vector<std::uint8_t>{0x11, 0x22}));
  EXPECT_TRUE(got.segments[1].block);
  EXPECT_EQ(got.segments[1].destination, 9);
  EXPECT_EQ(std::vector<std::uint8_t>(got.segments[1].data.begin(), got.segments[1].data.end()),
            (std::vector<std::uint8_t>{0xaa, 0xbb}));
  EXPECT_EQ(got.segments[2].data.size(), 1u);
  EXPECT_EQ(parser.count(parse_status::ok), 1u);
  EXPECT_EQ(parser.errors(), 0u);
  EXPECT_FALSE(parser.in_transmission());
}

// Random transmissions: no two plain segments adjacent (the parser merges those), blocks never empty.
struct random_transmission {
  transmission t;
  std::vector<segment> segments;
  std::vector<std::vector<std::uint8_t>> storage;
};

void make_random(rng& random, random_transmission& out) {
  const std::size_t count = random() % 6;
  out.storage.assign(count, {});
  out.segments.assign(count, {});
  bool previous_plain = false;
  for (std::size_t i = 0; i < count; ++i) {
    const bool block = previous_plain || (random() & 1) != 0;
    const std::size_t size = 1 + random() % 20;
    for (std::size_t k = 0; k < size; ++k) out.storage[i].push_back(static_cast<std::uint8_t>(random()));
    out.segments[i] = segment{block, static_cast<std::uint8_t>(block ? random() % 32 : 0),
                              byte_view(out.storage[i].data(), size)};
    previous_plain = !block;
  }
  out.t.sender = static_cast<std::uint8_t>(random() % 32);
  out.t.broadcast = count != 0 && (random() & 1) != 0;  // a broadcast needs data
  out.t.destination = static_cast<std::uint8_t>(out.t.broadcast ? 0 : random() % 32);
  out.t.segments = span<const segment>(out.segments.data(), out.segments.size());
}

void expect_same(const transmission& got, const transmission& sent) {
  EXPECT_EQ(got.sender, sent.sender);
  EXPECT_EQ(got.broadcast, sent.broadcast);
  if (!sent.broadcast) {
    EXPECT_EQ(got.destination, sent.destination);
  }
  ASSERT_EQ(got.segments.size(), sent.segments.size());
  for (std::size_t i = 0; i < sent.segments.size(); ++i) {
    EXPECT_EQ(got.segments[i].block, sent.segments[i].block);
    if (sent.segments[i].block) {
      EXPECT_EQ(got.segments[i].destination, sent.segments[i].destination);
    }
    EXPECT_EQ(std::vector<std::uint8_t>(got.segments[i].data.begin(), got.segments[i].data.end()),
              std::vector<std::uint8_t>(sent.segments[i].data.begin(), sent.segments[i].data.end()));
  }
}

TEST(GeniusTransmission, RandomTransmissionsRoundTripBackToBack) {
  rng random(55);
  transmission_parser<128, 8> parser;
  for (int round = 0; round < 500; ++round) {
    random_transmission r;
    make_random(random, r);
    const std::vector<parse_status> statuses = push_all(parser, encode(r.t));
    ASSERT_EQ(statuses.back(), parse_status::ok) << round;
    expect_same(parser.received(), r.t);
  }
  EXPECT_EQ(parser.count(parse_status::ok), 500u);
  EXPECT_EQ(parser.errors(), 0u);
}

TEST(GeniusTransmission, RandomSingleCharacterCorruptionIsNeverAccepted) {
  // Flip one bit of one character's byte or its control flag: the parser must not accept the result
  // (CRC-6 catches every single-bit error in a data byte; other changes break the structure or a CRC),
  // except where the flipped bit is an SBA in a control character, which no CRC covers.
  rng random(56);
  for (int round = 0; round < 500; ++round) {
    random_transmission r;
    make_random(random, r);
    std::vector<character> characters = encode(r.t);
    const std::size_t at = random() % characters.size();
    const unsigned flip = random() % 9;
    if (flip == 8) {
      characters[at].control = !characters[at].control;
    } else {
      characters[at].byte = static_cast<std::uint8_t>(characters[at].byte ^ (1u << flip));
    }
    transmission_parser<128, 8> parser;
    const std::vector<parse_status> statuses = push_all(parser, characters);
    // Not covered by any CRC (docs/protocol.md 3.2 covers data bytes only): the Start's sender and broadcast
    // bit, and the destination SBA in a Start of block.
    const character original = encode(r.t)[at];
    const bool uncovered =
        at == 0 ||
        (original.control && read_control(original.byte).kind == control_kind::start_of_block && flip < 5);
    if (statuses.back() == parse_status::ok && !uncovered) {
      ADD_FAILURE() << "corruption at " << at << " bit " << flip << " accepted";
    }
  }
}

// One wire error each, then the next good transmission is received (recovery at the next Start).
template <std::size_t Data = 256, std::size_t Segments = 16>
void expect_error_then_recovery(const std::vector<character>& bad, parse_status error) {
  transmission_parser<Data, Segments> parser;
  const std::vector<parse_status> statuses = push_all(parser, bad);
  std::size_t errors = 0;
  for (parse_status s : statuses) {
    if (is_error(s)) {
      ++errors;
      EXPECT_EQ(s, error);
    }
    EXPECT_NE(s, parse_status::ok);
  }
  EXPECT_EQ(errors, 1u);
  EXPECT_EQ(parser.count(error), 1u);
  EXPECT_EQ(parser.errors(), 1u);
  const std::uint8_t data[] = {0x01};
  const segment segments[] = {{false, 0, data}};
  const std::vector<parse_status> after = push_all(parser, encode(transmission{2, true, 0, segments}));
  EXPECT_EQ(after.back(), parse_status::ok);
  EXPECT_EQ(parser.received().sender, 2);
}

TEST(GeniusTransmissionErrors, DataBeforeStart) {
  expect_error_then_recovery({data_character(0x11), data_character(0x22)},
                             parse_status::data_outside_transmission);
}

TEST(GeniusTransmissionErrors, ControlBeforeStart) {
  expect_error_then_recovery({stop_character(0), end_of_block_character(0)},
                             parse_status::control_outside_transmission);
}

TEST(GeniusTransmissionErrors, CharactersAfterAnErrorAreSkippedNotCountedAgain) {
  transmission_parser<> parser;
  const std::vector<parse_status> statuses =
      push_all(parser, {data_character(1), data_character(2), stop_character(0), data_character(3)});
  EXPECT_EQ(statuses,
            (std::vector<parse_status>{parse_status::data_outside_transmission, parse_status::skipped,
                                       parse_status::skipped, parse_status::skipped}));
  EXPECT_EQ(parser.count(parse_status::skipped), 3u);
  // After a good Stop the parser is idle, not skipping: a stray data character is an error again.
  push_all(parser, encode(example));
  EXPECT_EQ(parser.push(data_character(9)), parse_status::data_outside_transmission);
}

TEST(GeniusTransmissionErrors, StartInsideTransmissionBeginsTheNewOne) {
  transmission_parser<> parser;
  std::vector<character> characters = {start_character(1, true), data_character(0x10)};
  const std::vector<character> second = encode(example);
  characters.insert(characters.end(), second.begin(), second.end());
  const std::vector<parse_status> statuses = push_all(parser, characters);
  EXPECT_EQ(statuses[2], parse_status::start_inside_transmission);
  EXPECT_EQ(statuses.back(), parse_status::ok);
  expect_same(parser.received(), example);
  EXPECT_EQ(parser.errors(), 1u);
}

TEST(GeniusTransmissionErrors, UnknownControl) {
  expect_error_then_recovery({start_character(1, true), data_character(0x10), control_character(0xa3)},
                             parse_status::unknown_control);
}

TEST(GeniusTransmissionErrors, DestinationOutOfRange) {
  expect_error_then_recovery({start_character(1, false), data_character(32), data_character(1)},
                             parse_status::destination_out_of_range);
}

TEST(GeniusTransmissionErrors, MissingDestination) {
  expect_error_then_recovery({start_character(1, false), start_of_block_character(3), data_character(1)},
                             parse_status::missing_destination);
}

TEST(GeniusTransmissionErrors, BlockNotClosedBeforeStop) {
  const std::uint8_t covered[] = {0x10};
  expect_error_then_recovery({start_character(1, true), start_of_block_character(3), data_character(0x10),
                              stop_character(crc6_g704::compute(covered))},
                             parse_status::block_not_closed);
}

TEST(GeniusTransmissionErrors, BlockNotClosedBeforeNextBlock) {
  expect_error_then_recovery({start_character(1, true), start_of_block_character(3), data_character(0x10),
                              start_of_block_character(4)},
                             parse_status::block_not_closed);
}

TEST(GeniusTransmissionErrors, EndOfBlockOutsideBlock) {
  expect_error_then_recovery({start_character(1, true), data_character(0x10), end_of_block_character(0)},
                             parse_status::end_of_block_outside_block);
}

TEST(GeniusTransmissionErrors, EmptyBlock) {
  expect_error_then_recovery({start_character(1, true), data_character(0x10), start_of_block_character(3),
                              end_of_block_character(crc6_g704::compute(byte_view()))},
                             parse_status::empty_block);
}

TEST(GeniusTransmissionErrors, EmptyTransmission) {
  expect_error_then_recovery({start_character(1, true), stop_character(crc6_g704::compute(byte_view()))},
                             parse_status::empty_transmission);
}

TEST(GeniusTransmissionErrors, BlockCrcMismatchFromCorruptBlockData) {
  std::vector<character> characters = encode(example);
  characters[5].byte ^= 0x01;  // aa -> ab inside the block
  expect_error_then_recovery(characters, parse_status::block_crc_mismatch);
}

TEST(GeniusTransmissionErrors, BlockCrcMismatchFromCorruptEndOfBlock) {
  std::vector<character> characters = encode(example);
  characters[7] =
      end_of_block_character(static_cast<std::uint8_t>(read_control(characters[7].byte).crc ^ 0x20));
  expect_error_then_recovery(characters, parse_status::block_crc_mismatch);
}

TEST(GeniusTransmissionErrors, StopCrcMismatchFromCorruptData) {
  std::vector<character> characters = encode(example);
  characters[2].byte ^= 0x80;
  expect_error_then_recovery(characters, parse_status::stop_crc_mismatch);
}

TEST(GeniusTransmissionErrors, StopCrcMismatchFromCorruptDestination) {
  std::vector<character> characters = encode(example);
  characters[1].byte = 8;  // still a valid SBA, but covered by the Stop CRC
  expect_error_then_recovery(characters, parse_status::stop_crc_mismatch);
}

TEST(GeniusTransmissionErrors, StopCrcCoversBlockData) {
  // Decision: the Stop CRC covers the data inside blocks. Change a block byte and repair the block's own
  // CRC: only the Stop CRC can catch it.
  std::vector<character> characters = encode(example);
  characters[5].byte = 0x00;
  const std::uint8_t changed_block[] = {0x00, 0xbb};
  characters[7] = end_of_block_character(crc6_g704::compute(changed_block));
  expect_error_then_recovery(characters, parse_status::stop_crc_mismatch);
}

TEST(GeniusTransmissionErrors, DataOverflowDoesNotLoseSync) {
  const std::uint8_t data[] = {1, 2, 3, 4, 5};
  const segment segments[] = {{false, 0, data}};
  expect_error_then_recovery<4, 4>(encode(transmission{1, true, 0, segments}), parse_status::overflow);
}

TEST(GeniusTransmissionErrors, SegmentOverflowDoesNotLoseSync) {
  expect_error_then_recovery<64, 2>(encode(example), parse_status::overflow);
}

TEST(GeniusTransmissionErrors, FramingErrorDiscardsTheOpenTransmission) {
  transmission_parser<> parser;
  const std::vector<character> characters = encode(example);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(parser.push(characters[i]), parse_status::in_progress);
  EXPECT_EQ(parser.push_framing_error(), parse_status::framing_error);
  for (std::size_t i = 4; i < characters.size(); ++i)
    EXPECT_EQ(parser.push(characters[i]), parse_status::skipped);
  EXPECT_EQ(parser.count(parse_status::framing_error), 1u);
  EXPECT_EQ(parser.count(parse_status::ok), 0u);
}

TEST(GeniusTransmission, ExactCapacityFits) {
  const std::uint8_t data[] = {1, 2, 3, 4};
  const segment segments[] = {{false, 0, data}};
  transmission_parser<4, 1> parser;
  EXPECT_EQ(push_all(parser, encode(transmission{1, true, 0, segments})).back(), parse_status::ok);
}

TEST(GeniusTransmission, CrcPolicyIsConfigurable) {
  using darc = crc6<0x19, 0x00, true, true, 0x00>;
  const std::uint8_t covered[] = {0x07, 0x11, 0x22, 0xaa, 0xbb, 0x33};
  ASSERT_NE(darc::compute(covered), crc6_g704::compute(covered));
  const std::vector<character> characters = encode<darc>(example);
  transmission_parser<256, 16, darc> with_darc;
  EXPECT_EQ(push_all(with_darc, characters).back(), parse_status::ok);
  transmission_parser<> with_default;
  const std::vector<parse_status> statuses = push_all(with_default, characters);
  EXPECT_NE(statuses.back(), parse_status::ok);
  EXPECT_EQ(with_default.errors(), 1u);
}

// A CRC chosen at run time (a profile's) encodes and checks exactly as the same static policy, for many
// parameter sets; a static policy costs the parser no byte.
TEST(GeniusTransmission, RunTimeCrcObjectIsTheStaticPolicy) {
  using darc = crc6<0x19, 0x00, true, true, 0x00>;
  const crc6_runtime runtime_darc(crc6_parameters{0x19, 0x00, true, true, 0x00});
  std::vector<character> by_object(600);
  const encode_result r =
      encode_transmission(span<character>(by_object.data(), by_object.size()), example, runtime_darc);
  ASSERT_TRUE(r);
  by_object.resize(r.length);
  EXPECT_EQ(by_object, encode<darc>(example));
  std::vector<std::uint16_t> words(600);
  const encode_result w = encode_transmission(span<std::uint16_t>(words.data(), words.size()), example, runtime_darc);
  ASSERT_TRUE(w);
  for (std::size_t i = 0; i < w.length; ++i) EXPECT_EQ(words[i], encode_character(by_object[i]));

  transmission_parser<256, 16, crc6_runtime> with_object(runtime_darc);
  EXPECT_EQ(push_all(with_object, by_object).back(), parse_status::ok);
  transmission_parser<256, 16, crc6_runtime> with_default_object;  // CRC-6/G-704
  EXPECT_NE(push_all(with_default_object, by_object).back(), parse_status::ok);
  EXPECT_EQ(with_default_object.count(parse_status::block_crc_mismatch), 1u);
  EXPECT_EQ(push_all(with_default_object, encode(example)).back(), parse_status::ok);

  // Every parameter set: begin/update/finish of the object give the static policy's CRC.
  rng random(7);
  for (int i = 0; i < 200; ++i) {
    const crc6_parameters p{static_cast<std::uint8_t>(random() & 0x3f), static_cast<std::uint8_t>(random() & 0x3f),
                            (random() & 1u) != 0, (random() & 1u) != 0, static_cast<std::uint8_t>(random() & 0x3f)};
    const crc6_runtime crc(p);
    std::vector<character> characters(600);
    const encode_result e = encode_transmission(span<character>(characters.data(), characters.size()), example, crc);
    ASSERT_TRUE(e);
    characters.resize(e.length);
    transmission_parser<256, 16, crc6_runtime> parser(crc);
    EXPECT_EQ(push_all(parser, characters).back(), parse_status::ok);
  }
  const std::uint8_t check[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  EXPECT_EQ(crc6_runtime().compute(check), crc6_g704::compute(check));
  EXPECT_EQ(runtime_darc.compute(check), darc::compute(check));

  static_assert(std::is_empty<crc6_g704>::value, "a static policy is held as nothing");
  EXPECT_EQ(sizeof(transmission_parser<256, 16, crc6_runtime>) - sizeof(transmission_parser<>),
            alignof(transmission_parser<>));  // the 5 bytes of the object, padded
}

// ---- bits to transmissions

std::vector<bool> bits_of(const std::vector<character>& characters) {
  std::vector<bool> bits;
  for (character c : characters) {
    const std::uint16_t word = encode_character(c);
    for (unsigned i = 0; i < character_bits; ++i) bits.push_back(((word >> i) & 1u) != 0);
  }
  return bits;
}

template <class Receiver>
std::vector<bit_result> push_bits(Receiver& rx, const std::vector<bool>& bits) {
  std::vector<bit_result> events;
  for (bool bit : bits) {
    const bit_result r = rx.push(bit);
    if (r.status != bit_status::nothing_yet) events.push_back(r);
  }
  return events;
}

TEST(GeniusTransmissionReceiver, TakesARunTimeCrcObject) {
  const crc6_runtime darc(crc6_parameters{0x19, 0x00, true, true, 0x00});
  std::vector<character> characters(600);
  const encode_result e = encode_transmission(span<character>(characters.data(), characters.size()), example, darc);
  ASSERT_TRUE(e);
  characters.resize(e.length);
  transmission_receiver<256, 16, crc6_runtime> with_darc(darc);
  const std::vector<bit_result> events = push_bits(with_darc, bits_of(characters));
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.back().parse, parse_status::ok);
  transmission_receiver<> with_default;
  EXPECT_NE(push_bits(with_default, bits_of(characters)).back().parse, parse_status::ok);
  EXPECT_EQ(with_default.parser().count(parse_status::ok), 0u);
}

TEST(GeniusTransmissionReceiver, RandomTransmissionsWithIdleGapsRoundTrip) {
  rng random(57);
  transmission_receiver<128, 8> rx;
  for (int round = 0; round < 200; ++round) {
    random_transmission r;
    make_random(random, r);
    std::vector<bool> bits(random() % 30, true);  // idle line before the transmission
    const std::vector<bool> body = bits_of(encode(r.t));
    bits.insert(bits.end(), body.begin(), body.end());
    const std::vector<bit_result> events = push_bits(rx, bits);
    ASSERT_FALSE(events.empty());
    EXPECT_EQ(events.back().parse, parse_status::ok);
    expect_same(rx.parser().received(), r.t);
  }
  EXPECT_EQ(rx.bits().start_bit_errors() + rx.bits().stop_bit_errors(), 0u);
}

TEST(GeniusTransmissionReceiver, GapInsideATransmissionIsAStartBitError) {
  transmission_receiver<> rx;
  std::vector<bool> bits = bits_of(encode(example));
  bits.insert(bits.begin() + 3 * character_bits, true);  // an idle bit where the 4th start bit is due
  const std::vector<bit_result> events = push_bits(rx, bits);
  bool saw = false;
  for (const bit_result& e : events) {
    if (e.status == bit_status::start_bit_not_0) {
      saw = true;
      EXPECT_EQ(e.parse, parse_status::framing_error);
    }
    EXPECT_NE(e.parse, parse_status::ok);
  }
  EXPECT_TRUE(saw);
  EXPECT_EQ(rx.bits().start_bit_errors(), 1u);
  // The next transmission is received normally.
  const std::vector<bit_result> next = push_bits(rx, bits_of(encode(example)));
  EXPECT_EQ(next.back().parse, parse_status::ok);
}

TEST(GeniusTransmissionReceiver, IdleAfterStopIsNotAnError) {
  transmission_receiver<> rx;
  std::vector<bool> bits = bits_of(encode(example));
  bits.insert(bits.end(), 50, true);
  const std::vector<bit_result> events = push_bits(rx, bits);
  EXPECT_EQ(events.back().parse, parse_status::ok);
  EXPECT_EQ(rx.bits().start_bit_errors(), 0u);
}

TEST(GeniusTransmissionReceiver, StopBitErrorInsideATransmission) {
  transmission_receiver<> rx;
  std::vector<bool> bits = bits_of(encode(example));
  bits[2 * character_bits + 10] = false;  // stop bit of the 3rd character
  const std::vector<bit_result> events = push_bits(rx, bits);
  // Characters 1 and 2 arrive, then the framing error; what follows is out of step (the receiver waits for
  // a 1->0 transition inside character 4) and may produce more framing errors, but never a transmission.
  ASSERT_GE(events.size(), 3u);
  EXPECT_EQ(events[0].status, bit_status::ok);
  EXPECT_EQ(events[1].status, bit_status::ok);
  EXPECT_EQ(events[2].status, bit_status::stop_bit_not_1);
  EXPECT_EQ(events[2].parse, parse_status::framing_error);
  for (const bit_result& e : events) EXPECT_NE(e.parse, parse_status::ok);
  EXPECT_GE(rx.bits().stop_bit_errors(), 1u);
  bits = std::vector<bool>(5, true);
  const std::vector<bool> next = bits_of(encode(example));
  bits.insert(bits.end(), next.begin(), next.end());
  EXPECT_EQ(push_bits(rx, bits).back().parse, parse_status::ok);
}

}  // namespace

// ---- control layouts (docs/protocol.md 3.2: configurable) ----

// Every layout: the four tags as a permutation of 0..3, in bits 7..6 or 1..0.
std::vector<control_layout> every_layout() {
  std::vector<control_layout> layouts;
  std::uint8_t tags[4] = {0, 1, 2, 3};
  do {
    for (tag_position position : {tag_position::high, tag_position::low}) {
      layouts.push_back(control_layout{tags[0], tags[1], tags[2], tags[3], position});
    }
  } while (std::next_permutation(tags, tags + 4));
  return layouts;
}

TEST(GeniusControlLayout, TheDefaultIsTheDrawnLayout) {
  constexpr control_layout drawn{};
  static_assert(drawn.valid(), "the default layout is valid");
  EXPECT_EQ(start_character(4, false, drawn), start_character(4, false));
  EXPECT_EQ(stop_character(0x2a, drawn), control_character(0x6a));
  EXPECT_EQ(unknown_control_character(), control_character(0xa0));
  EXPECT_EQ(read_control(0xa0).kind, control_kind::unknown);
}

TEST(GeniusControlLayout, TagInTheLowBitsMovesTheFieldsUp) {
  // Stop = 0, Start = 1, End of block = 2, Start of block = 3, tag in bits 1..0.
  const control_layout low{1, 0, 3, 2, tag_position::low};
  ASSERT_TRUE(low.valid());
  EXPECT_EQ(start_character(31, true, low), control_character(0xfd));        // 1 11111 01
  EXPECT_EQ(stop_character(0x2a, low), control_character(0xa8));             // 101010 00
  EXPECT_EQ(start_of_block_character(9, low), control_character(0x27));      // 0 01001 11
  EXPECT_EQ(end_of_block_character(0x3f, low), control_character(0xfe));     // 111111 10
  EXPECT_EQ(unknown_control_character(low), control_character(0x83));        // 1 00000 11
  const control_fields start = read_control(0xfd, low);
  EXPECT_EQ(start.kind, control_kind::start);
  EXPECT_TRUE(start.broadcast);
  EXPECT_EQ(start.sba, 31u);
  EXPECT_EQ(read_control(0xa8, low).crc, 0x2au);
  EXPECT_EQ(read_control(0x83, low).kind, control_kind::unknown);
}

TEST(GeniusControlLayout, ValidOnlyForFourDifferentTagsBelowFour) {
  EXPECT_FALSE((control_layout{0, 0, 2, 3, tag_position::high}.valid()));
  EXPECT_FALSE((control_layout{0, 1, 2, 4, tag_position::high}.valid()));
  EXPECT_EQ(every_layout().size(), 48u);
  for (const control_layout& l : every_layout()) EXPECT_TRUE(l.valid());
}

bool same(const transmission& got, const transmission& sent) {
  if (got.sender != sent.sender || got.broadcast != sent.broadcast) return false;
  if (!sent.broadcast && got.destination != sent.destination) return false;
  if (got.segments.size() != sent.segments.size()) return false;
  for (std::size_t i = 0; i < sent.segments.size(); ++i) {
    const segment& a = got.segments[i];
    const segment& b = sent.segments[i];
    if (a.block != b.block || (b.block && a.destination != b.destination)) return false;
    if (!std::equal(a.data.begin(), a.data.end(), b.data.begin(), b.data.end())) return false;
  }
  return true;
}

TEST(GeniusControlLayout, EveryLayoutRoundTripsAndEveryByteReadsAsItWasWritten) {
  rng random(77);
  unsigned differing = 0;
  for (const control_layout& layout : every_layout()) {
    // Each control byte reads back as the character that wrote it.
    for (unsigned fields = 0; fields < 64; ++fields) {
      const auto f = static_cast<std::uint8_t>(fields);
      const control_fields start = read_control(start_character(f & 0x1f, (f & 0x20) != 0, layout).byte, layout);
      EXPECT_EQ(start.kind, control_kind::start);
      EXPECT_EQ(start.sba, f & 0x1f);
      EXPECT_EQ(start.broadcast, (f & 0x20) != 0);
      EXPECT_EQ(read_control(stop_character(f, layout).byte, layout).crc, f);
      EXPECT_EQ(read_control(stop_character(f, layout).byte, layout).kind, control_kind::stop);
      EXPECT_EQ(read_control(end_of_block_character(f, layout).byte, layout).kind, control_kind::end_of_block);
      EXPECT_EQ(read_control(start_of_block_character(f & 0x1f, layout).byte, layout).sba, f & 0x1f);
    }
    // Transmissions encoded in the layout parse back in it. Read in the default layout, a transmission whose
    // characters differ from its default encoding is never the transmission that was sent.
    transmission_parser<128, 8> parser(crc6_g704{}, layout);
    transmission_parser<128, 8> default_parser;
    for (int round = 0; round < 20; ++round) {
      random_transmission r;
      make_random(random, r);
      std::vector<character> out(600);
      const encode_result e = encode_transmission(span<character>(out.data(), out.size()), r.t, crc6_g704{}, layout);
      ASSERT_TRUE(e);
      out.resize(e.length);
      ASSERT_EQ(push_all(parser, out).back(), parse_status::ok);
      expect_same(parser.received(), r.t);
      const std::vector<character> in_default = encode(r.t);
      if (in_default != out) {
        ++differing;
        const bool read_as_sent = push_all(default_parser, out).back() == parse_status::ok &&
                                  same(default_parser.received(), r.t);
        EXPECT_FALSE(read_as_sent);
      }
    }
  }
  EXPECT_GT(differing, 47u * 10u);  // most transmissions of the 47 other layouts differ
}

TEST(GeniusControlLayout, TheReceiverTakesALayout) {
  const control_layout swapped{1, 0, 2, 3, tag_position::high};
  std::vector<character> characters(600);
  const encode_result e =
      encode_transmission(span<character>(characters.data(), characters.size()), example, crc6_g704{}, swapped);
  ASSERT_TRUE(e);
  characters.resize(e.length);
  transmission_receiver<256, 16> with_layout(crc6_g704{}, swapped);
  EXPECT_EQ(push_bits(with_layout, bits_of(characters)).back().parse, parse_status::ok);
  transmission_receiver<> with_default;
  push_bits(with_default, bits_of(characters));
  EXPECT_EQ(with_default.parser().count(parse_status::ok), 0u);
}
