// What one capture record is: the ring and Genius record splitters and the SocketCAN record layout.
#include <gtest/gtest.h>

#include <cstdint>
#include <utility>
#include <vector>

#include "trionet/genius.hpp"
#include "trionet/host/capture.hpp"

namespace {

using namespace trionet;
using namespace trionet::host;
using bytes = std::vector<std::uint8_t>;
using record = std::pair<bytes, std::uint64_t>;  // bytes, time of the first

struct collector {
  std::vector<record> records;
  void operator()(byte_view b, std::uint64_t time_ns) { records.emplace_back(bytes(b.begin(), b.end()), time_ns); }
};

std::vector<record> split_ring(const bytes& stream, std::size_t max = ring_record_splitter::default_max_record_length) {
  ring_record_splitter splitter(max);
  collector out;
  for (std::size_t i = 0; i < stream.size(); ++i) splitter.push(stream[i], 10 * i, out);
  splitter.flush(out);
  EXPECT_FALSE(splitter.open());
  return out.records;
}

bytes concatenated(const std::vector<record>& records) {
  bytes all;
  for (const record& r : records) all.insert(all.end(), r.first.begin(), r.first.end());
  return all;
}

TEST(RingRecordSplitter, OneRecordPerMessageAndPerStrayRun) {
  const bytes golden = {0x8a, 0x48, 0x01, 0x00, 0x00, 0x00, 0x00, 0x30, 0x0c, 0x00, 0x00, 0x00, 0x00, 0x7f, 0x3e, 0x88};
  bytes stream = golden;
  const bytes rest = {
      0x89, 0x48, 0x45,  // PRINT "HE" cut short by the next header
      0x93, 0x05, 0x90,  // keypad offset 5 to hop 2, whole
      0x41, 0x42,        // stray data
      0x88,              // stray end of message
      0x88,              // another
      0x81, 0x41, 0x88,  // header with A = 0, data, end of message
      0x89, 0x41,        // open at the end (idle line)
  };
  stream.insert(stream.end(), rest.begin(), rest.end());
  const std::vector<record> expected = {
      {golden, 0},         {{0x89, 0x48, 0x45}, 160}, {{0x93, 0x05, 0x90}, 190}, {{0x41, 0x42}, 220},
      {{0x88}, 240},       {{0x88}, 250},             {{0x81, 0x41, 0x88}, 260}, {{0x89, 0x41}, 290},
  };
  const std::vector<record> got = split_ring(stream);
  EXPECT_EQ(got, expected);
  EXPECT_EQ(concatenated(got), stream);  // every byte that crossed is in exactly one record
}

TEST(RingRecordSplitter, StrayDataRunEndsAtTheNextControlByte) {
  const std::vector<record> got = split_ring({0x01, 0x02, 0x89, 0x41, 0x88, 0x03, 0x89});
  const std::vector<record> expected = {{{0x01, 0x02}, 0}, {{0x89, 0x41, 0x88}, 20}, {{0x03}, 50}, {{0x89}, 60}};
  EXPECT_EQ(got, expected);
}

TEST(RingRecordSplitter, ARecordNeverExceedsItsLimit) {
  const bytes stream = {0x89, 1, 2, 3, 4, 5, 0x88, 6, 7, 8, 9, 10};
  const std::vector<record> got = split_ring(stream, 4);
  const std::vector<record> expected = {
      {{0x89, 1, 2, 3}, 0}, {{4, 5}, 40}, {{0x88}, 60}, {{6, 7, 8, 9}, 70}, {{10}, 110}};
  EXPECT_EQ(got, expected);
  EXPECT_EQ(concatenated(got), stream);
}

// ---------------------------------------------------------------------------------------------------------
// Genius

std::vector<std::uint16_t> words_of(const genius::transmission& t) {
  std::uint16_t out[64];
  const genius::encode_result r = genius::encode_transmission(span<std::uint16_t>(out, 64), t);
  EXPECT_TRUE(r);
  return std::vector<std::uint16_t>(out, out + r.length);
}

bytes record_bytes(const std::vector<std::uint16_t>& words) {
  bytes out;
  for (std::uint16_t w : words) {
    out.push_back(static_cast<std::uint8_t>(w >> 8));
    out.push_back(static_cast<std::uint8_t>(w));
  }
  return out;
}

TEST(GeniusRecordSplitter, OneRecordPerTransmissionAndPerFramingError) {
  const std::uint8_t data[] = {0x11, 0x22};
  const genius::segment plain[] = {{false, 0, byte_view(data, 2)}};
  const std::vector<std::uint16_t> broadcast = words_of({4, true, 0, span<const genius::segment>(plain, 1)});
  const std::vector<std::uint16_t> directed = words_of({5, false, 9, span<const genius::segment>(plain, 1)});
  const std::uint16_t stray = genius::encode_character(genius::data_character(0x33));
  const std::uint16_t bad_start = 0x0695;  // start bit 1
  const std::uint16_t start = genius::encode_character(genius::start_character(7, true));

  std::vector<std::uint16_t> line = broadcast;
  line.push_back(stray);
  line.push_back(stray);
  line.insert(line.end(), directed.begin(), directed.end() - 1);  // its Stop lost ...
  line.push_back(bad_start);                                       // ... to a framing error
  line.push_back(start);                                           // a Start cut short by the next Start
  line.insert(line.end(), broadcast.begin(), broadcast.end());
  line.push_back(start);  // open at the end

  genius_record_splitter splitter;
  collector out;
  for (std::size_t i = 0; i < line.size(); ++i) splitter.push(line[i], 100 * i, out);
  splitter.flush(out);

  const std::vector<record> expected = {
      {record_bytes(broadcast), 0},
      {record_bytes({stray, stray}), 400},
      {record_bytes(std::vector<std::uint16_t>(directed.begin(), directed.end() - 1)), 600},
      {record_bytes({bad_start}), 1000},
      {record_bytes({start}), 1100},
      {record_bytes(broadcast), 1200},
      {record_bytes({start}), 1600},
  };
  EXPECT_EQ(out.records, expected);
  EXPECT_EQ(genius_record_words(byte_view(concatenated(out.records).data(), concatenated(out.records).size())),
            line);
}

TEST(GeniusRecordSplitter, CharactersAndLimit) {
  genius_record_splitter splitter(3);
  collector out;
  splitter.push(genius::start_character(1, true), 0, out);
  for (std::uint64_t i = 1; i <= 4; ++i) splitter.push(genius::data_character(0x40), i, out);
  splitter.push(genius::stop_character(0), 5, out);
  splitter.flush(out);
  ASSERT_EQ(out.records.size(), 2u);
  EXPECT_EQ(out.records[0].first.size(), 6u);  // Start and two data characters
  EXPECT_EQ(out.records[1].first.size(), 6u);  // two data characters and the Stop (outside a transmission)
  EXPECT_EQ(out.records[1].second, 3u);
}

TEST(GeniusRecordWords, AnOddByteIsNotAWord) {
  const bytes b = {0x06, 0x94, 0x04};
  EXPECT_EQ(genius_record_words(byte_view(b.data(), b.size())), std::vector<std::uint16_t>{0x0694});
}

// ---------------------------------------------------------------------------------------------------------
// SocketCAN

bytes record_of(const can::frame& f) {
  const auto r = socketcan_record(f);
  return bytes(r.begin(), r.end());
}

TEST(SocketcanRecord, TheNotesExampleFrame) {
  can::frame f;
  f.id = 0x028;
  f.dlc = 8;
  const std::uint8_t data[] = {0x01, 0x00, 0x00, 0x00, 0x00, 0x02, 0x0d, 0x7a};
  for (int i = 0; i < 8; ++i) f.data[i] = data[i];
  const bytes expected = {0, 0, 0, 0x28, 8, 0, 0, 0, 0x01, 0x00, 0x00, 0x00, 0x00, 0x02, 0x0d, 0x7a};
  EXPECT_EQ(record_of(f), expected);
  const socketcan_record_result back = read_socketcan_record(byte_view(expected.data(), expected.size()));
  ASSERT_TRUE(back);
  EXPECT_EQ(back.frame, f);
}

TEST(SocketcanRecord, FlagsShortFramesAndDlcAbove8RoundTrip) {
  can::frame extended_remote;
  extended_remote.id = can::frame::extended_flag | can::frame::remote_flag | 0x1ABCDEF;
  extended_remote.dlc = 3;
  can::frame short_frame;
  short_frame.id = 0x7FF;
  short_frame.dlc = 2;
  short_frame.data[0] = 0xAA;
  short_frame.data[1] = 0x55;
  can::frame long_dlc;
  long_dlc.id = 0x028;
  long_dlc.dlc = 12;
  for (auto& d : long_dlc.data) d = 0x11;
  for (const can::frame& f : {extended_remote, short_frame, long_dlc}) {
    const bytes r = record_of(f);
    const socketcan_record_result back = read_socketcan_record(byte_view(r.data(), r.size()));
    ASSERT_TRUE(back) << to_string(back.status);
    EXPECT_EQ(back.frame, f);
  }
  EXPECT_EQ(record_of(extended_remote)[0], 0xC1);
  EXPECT_EQ(record_of(extended_remote)[4], 3);
  EXPECT_EQ(record_of(long_dlc)[4], 8);
  EXPECT_EQ(record_of(long_dlc)[6], 12);  // len8_dlc
  EXPECT_EQ(record_of(short_frame)[10], 0);  // padding
}

TEST(SocketcanRecord, ReadRejectsWhatIsNotAClassicFrame) {
  const auto status_of = [](bytes r) { return read_socketcan_record(byte_view(r.data(), r.size())).status; };
  EXPECT_EQ(status_of({0, 0, 0, 0x28, 8, 0, 0}), socketcan_record_status::too_short);
  EXPECT_EQ(status_of({0, 0, 0, 0x28, 8, 0, 0, 0, 1, 2, 3}), socketcan_record_status::too_short);
  EXPECT_EQ(status_of({0, 0, 0, 0x28, 8, 0x04, 0, 0, 1, 2, 3, 4, 5, 6, 7, 8}), socketcan_record_status::not_classic);
  EXPECT_EQ(status_of(bytes(72, 0)), socketcan_record_status::not_classic);
  EXPECT_EQ(status_of({0x20, 0, 0, 0x04, 8, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}), socketcan_record_status::error_frame);
  EXPECT_EQ(status_of({0, 0, 0, 0x28, 9, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}), socketcan_record_status::bad_length);
  EXPECT_EQ(status_of({0, 0, 0x08, 0x00, 0, 0, 0, 0}), socketcan_record_status::bad_identifier);
  EXPECT_EQ(status_of({0x40, 0, 0, 0x28, 8, 0, 0, 0}), socketcan_record_status::ok);  // remote: no data bytes
}

}  // namespace
