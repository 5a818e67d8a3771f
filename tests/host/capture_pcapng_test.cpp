// pcapng writer and reader: the bytes the writer puts out, round trips, and the reader on every kind of bad
// file (wrong first block, byte order, lengths, truncation, options, interfaces, timestamps, exported PDUs).
#include <gtest/gtest.h>

#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "trionet/host/pcapng.hpp"

namespace {

using namespace trionet::host;
using bytes = std::vector<std::uint8_t>;

trionet::byte_view view(const bytes& b) {
  return trionet::byte_view(b.data(), b.size());
}

// Hand-made pcapng blocks, in either byte order, to feed the reader what other writers write.
struct block_builder {
  bool big_endian = false;

  void u16(bytes& out, std::uint16_t v) const {
    if (big_endian) {
      out.push_back(static_cast<std::uint8_t>(v >> 8));
      out.push_back(static_cast<std::uint8_t>(v));
    } else {
      out.push_back(static_cast<std::uint8_t>(v));
      out.push_back(static_cast<std::uint8_t>(v >> 8));
    }
  }
  void u32(bytes& out, std::uint32_t v) const {
    if (big_endian) {
      u16(out, static_cast<std::uint16_t>(v >> 16));
      u16(out, static_cast<std::uint16_t>(v));
    } else {
      u16(out, static_cast<std::uint16_t>(v));
      u16(out, static_cast<std::uint16_t>(v >> 16));
    }
  }
  void option(bytes& out, std::uint16_t code, const bytes& value) const {
    u16(out, code);
    u16(out, static_cast<std::uint16_t>(value.size()));
    out.insert(out.end(), value.begin(), value.end());
    while (out.size() % 4 != 0) out.push_back(0);
  }
  bytes block(std::uint32_t type, bytes body) const {
    while (body.size() % 4 != 0) body.push_back(0);
    bytes out;
    u32(out, type);
    u32(out, static_cast<std::uint32_t>(body.size() + 12));
    out.insert(out.end(), body.begin(), body.end());
    u32(out, static_cast<std::uint32_t>(body.size() + 12));
    return out;
  }
  bytes section(std::uint16_t major = 1) const {
    bytes body;
    u32(body, 0x1A2B3C4D);
    u16(body, major);
    u16(body, 0);
    u32(body, 0xFFFFFFFF);
    u32(body, 0xFFFFFFFF);
    return block(0x0A0D0D0A, body);
  }
  bytes interface(std::uint16_t link_type, const std::string& name, int tsresol = -1,
                  const bytes& extra_options = {}) const {
    bytes body;
    u16(body, link_type);
    u16(body, 0);
    u32(body, 0);
    if (!name.empty()) option(body, 2, bytes(name.begin(), name.end()));
    if (tsresol >= 0) option(body, 9, bytes{static_cast<std::uint8_t>(tsresol)});
    body.insert(body.end(), extra_options.begin(), extra_options.end());
    option(body, 0, {});
    return block(1, body);
  }
  bytes packet(std::uint32_t interface, std::uint64_t ticks, const bytes& data) const {
    bytes body;
    u32(body, interface);
    u32(body, static_cast<std::uint32_t>(ticks >> 32));
    u32(body, static_cast<std::uint32_t>(ticks));
    u32(body, static_cast<std::uint32_t>(data.size()));
    u32(body, static_cast<std::uint32_t>(data.size()));
    body.insert(body.end(), data.begin(), data.end());
    return block(6, body);
  }
};

bytes join(std::initializer_list<bytes> parts) {
  bytes out;
  for (const bytes& part : parts) out.insert(out.end(), part.begin(), part.end());
  return out;
}

std::string as_string(const bytes& b) {
  return std::string(b.begin(), b.end());
}

struct read_back {
  std::vector<pcapng_read_status> statuses;  // every status up to the one that ends reading
  std::vector<pcapng_record> records;        // the ok ones (bytes copied below)
  std::vector<bytes> payloads;
  std::vector<std::string> dissectors;
};

read_back read_all(const std::string& file, pcapng_reader::limits limits = {}) {
  std::istringstream in(file);
  pcapng_reader reader(in, limits);
  read_back out;
  for (int guard = 0; guard < 100000; ++guard) {
    const pcapng_read_result r = reader.next();
    out.statuses.push_back(r.status);
    if (r) {
      out.records.push_back(r.record);
      out.payloads.emplace_back(r.record.bytes.begin(), r.record.bytes.end());
      out.dissectors.emplace_back(r.record.dissector);
    }
    if (r.status == pcapng_read_status::end_of_file || ends_reading(r.status)) break;
  }
  return out;
}

pcapng_read_status last_status(const std::string& file, pcapng_reader::limits limits = {}) {
  return read_all(file, limits).statuses.back();
}

// ---------------------------------------------------------------------------------------------------------
// writer

TEST(PcapngWriter, WritesTheBlocksWiresharkReads) {
  std::ostringstream out;
  pcapng_writer writer(out, "trionet");
  const pcapng_interface_result link = writer.add_interface("link 0: MC -> keypad", capture_network::ring);
  ASSERT_TRUE(link);
  EXPECT_EQ(link.id, 0u);
  ASSERT_EQ(writer.write(link.id, 0x0000000100000002ull, view(bytes{0x8a, 0x48})), pcapng_write_status::ok);

  const std::string file = out.str();
  const bytes expected = join({
      // section header: type, length 44, magic, version 1.0, section length -1, shb_userappl "trionet"
      {0x0A, 0x0D, 0x0D, 0x0A, 44, 0, 0, 0, 0x4D, 0x3C, 0x2B, 0x1A, 1, 0, 0, 0,
       0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF,
       4, 0, 7, 0, 't', 'r', 'i', 'o', 'n', 'e', 't', 0, 0, 0, 0, 0, 44, 0, 0, 0},
      // interface: type 1, length 56, link type 252, snap length 0, if_name, if_tsresol 9, end
      {1, 0, 0, 0, 56, 0, 0, 0, 252, 0, 0, 0, 0, 0, 0, 0,
       2, 0, 20, 0, 'l', 'i', 'n', 'k', ' ', '0', ':', ' ', 'M', 'C', ' ', '-', '>', ' ', 'k', 'e', 'y', 'p', 'a', 'd',
       9, 0, 1, 0, 9, 0, 0, 0, 0, 0, 0, 0, 56, 0, 0, 0},
  });
  ASSERT_GE(file.size(), expected.size());
  EXPECT_EQ(file.substr(0, expected.size()), as_string(expected));
  // enhanced packet: interface 0, timestamp high 1 low 2, exported-PDU tags naming trionet_ring, the bytes
  const bytes packet = {6, 0, 0, 0, 56, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 2, 0, 0, 0, 22, 0, 0, 0, 22, 0, 0, 0,
                        0, 12, 0, 12, 't', 'r', 'i', 'o', 'n', 'e', 't', '_', 'r', 'i', 'n', 'g',
                        0, 0, 0, 0, 0x8a, 0x48, 0, 0, 56, 0, 0, 0};
  EXPECT_EQ(file.substr(expected.size()), as_string(packet));
}

TEST(PcapngWriter, GeniusTagIsPaddedToFourBytes) {
  std::ostringstream out;
  pcapng_writer writer(out);
  const pcapng_interface_result line = writer.add_interface("genius", capture_network::genius);
  ASSERT_TRUE(line);
  ASSERT_EQ(writer.write(line.id, 0, view(bytes{0x04, 0x12})), pcapng_write_status::ok);
  const std::string file = out.str();
  const std::string tag = std::string("\x00\x0c\x00\x10trionet_genius\x00\x00\x00\x00\x00\x00\x04\x12", 26);
  EXPECT_NE(file.find(tag), std::string::npos);
}

TEST(PcapngWriter, MisuseIsReportedAndWritesNothing) {
  std::ostringstream out;
  pcapng_writer writer(out);
  const std::size_t header = out.str().size();
  EXPECT_EQ(writer.add_interface("x", capture_network::other).status, pcapng_write_status::bad_network);
  EXPECT_EQ(writer.add_interface(std::string(pcapng_writer::max_name_length + 1, 'n'), capture_network::ring)
                .status,
            pcapng_write_status::name_too_long);
  EXPECT_EQ(writer.write(0, 0, view(bytes{1})), pcapng_write_status::bad_interface);
  EXPECT_EQ(out.str().size(), header);
  const pcapng_interface_result bus = writer.add_interface("can0", capture_network::can);
  ASSERT_TRUE(bus);
  const std::size_t with_interface = out.str().size();
  const bytes huge(pcapng_writer::max_record_length + 1, 0);
  EXPECT_EQ(writer.write(bus.id, 0, view(huge)), pcapng_write_status::record_too_long);
  EXPECT_EQ(writer.write(bus.id + 1, 0, view(bytes{1})), pcapng_write_status::bad_interface);
  EXPECT_EQ(out.str().size(), with_interface);
  EXPECT_EQ(writer.interfaces(), 1u);
}

TEST(PcapngWriter, AFailingStreamFailsEveryCall) {
  std::ostringstream out;
  out.setstate(std::ios::badbit);
  pcapng_writer writer(out);
  EXPECT_EQ(writer.add_interface("can0", capture_network::can).status, pcapng_write_status::write_failed);
  EXPECT_EQ(writer.write(0, 0, view(bytes{1})), pcapng_write_status::write_failed);
  EXPECT_EQ(writer.flush(), pcapng_write_status::write_failed);
}

// ---------------------------------------------------------------------------------------------------------
// round trip

TEST(PcapngRoundTrip, ReaderGivesBackEverythingTheWriterWrote) {
  struct written {
    std::uint32_t interface;
    std::uint64_t time_ns;
    bytes data;
  };
  std::ostringstream out;
  pcapng_writer writer(out);
  const std::uint32_t ring0 = writer.add_interface("link 0: MC1 -> keypad", capture_network::ring).id;
  const std::uint32_t ring1 = writer.add_interface("link 1: keypad -> MC1", capture_network::ring).id;
  const std::uint32_t can0 = writer.add_interface("can0", capture_network::can).id;
  const std::uint32_t line = writer.add_interface("", capture_network::genius).id;
  std::vector<written> records = {
      {ring0, 0, {}},
      {ring0, 1, {0x8a}},
      {ring1, 999999999, {0x89, 0x48, 0x45}},
      {can0, 1700000000123456789ull, {0, 0, 0, 0x28, 8, 0, 0, 0, 1, 0, 0, 0, 0, 2, 0x0d, 0x7a}},
      {line, UINT64_MAX, {0x04, 0x12, 0x06, 0x94}},
      {ring0, 0xFFFFFFFFull, bytes(pcapng_writer::max_record_length - 20, 0x41)},
  };
  for (std::size_t size = 0; size < 9; ++size) records.push_back({line, size * 1000, bytes(size, 0x55)});
  for (const written& r : records) ASSERT_EQ(writer.write(r.interface, r.time_ns, view(r.data)), pcapng_write_status::ok);
  ASSERT_EQ(writer.flush(), pcapng_write_status::ok);

  std::istringstream in(out.str());
  pcapng_reader reader(in);
  for (const written& r : records) {
    const pcapng_read_result got = reader.next();
    ASSERT_EQ(got.status, pcapng_read_status::ok);
    EXPECT_EQ(got.record.interface, r.interface);
    EXPECT_EQ(got.record.time_ns, r.time_ns);
    EXPECT_EQ(bytes(got.record.bytes.begin(), got.record.bytes.end()), r.data);
    const capture_network network = r.interface == can0    ? capture_network::can
                                    : r.interface == line ? capture_network::genius
                                                          : capture_network::ring;
    EXPECT_EQ(got.record.network, network);
    EXPECT_EQ(got.record.dissector, dissector_name(network) == nullptr ? "" : dissector_name(network));
  }
  EXPECT_EQ(reader.next().status, pcapng_read_status::end_of_file);
  EXPECT_EQ(reader.next().status, pcapng_read_status::end_of_file);
  ASSERT_EQ(reader.interfaces().size(), 4u);
  EXPECT_EQ(reader.interfaces()[0].name, "link 0: MC1 -> keypad");
  EXPECT_EQ(reader.interfaces()[1].name, "link 1: keypad -> MC1");
  EXPECT_EQ(reader.interfaces()[2].name, "can0");
  EXPECT_EQ(reader.interfaces()[2].link_type, linktype_can_socketcan);
  EXPECT_EQ(reader.interfaces()[3].name, "");
  EXPECT_EQ(reader.interfaces()[3].link_type, linktype_wireshark_upper_pdu);
  EXPECT_EQ(reader.interfaces()[0].tsresol, 9);
  EXPECT_EQ(reader.sections(), 1u);
  EXPECT_EQ(reader.skipped_blocks(), 0u);
}

TEST(PcapngRoundTrip, EveryCutOfAFileIsTruncatedOrEndsAtABlock) {
  std::ostringstream out;
  pcapng_writer writer(out);
  std::vector<std::size_t> boundaries = {out.str().size()};  // file sizes after each block
  const std::uint32_t link = writer.add_interface("link", capture_network::ring).id;
  boundaries.push_back(out.str().size());
  for (std::uint8_t i = 0; i < 4; ++i) {
    ASSERT_EQ(writer.write(link, i, view(bytes(i, 0x41))), pcapng_write_status::ok);
    boundaries.push_back(out.str().size());
  }
  const std::string file = out.str();
  for (std::size_t cut = 0; cut <= file.size(); ++cut) {
    const read_back got = read_all(file.substr(0, cut));
    std::size_t whole = 0;  // packets wholly inside the cut
    bool boundary = false;
    for (std::size_t i = 0; i < boundaries.size(); ++i) {
      if (i >= 2 && boundaries[i] <= cut) ++whole;
      boundary = boundary || boundaries[i] == cut;
    }
    EXPECT_EQ(got.records.size(), whole) << "cut at " << cut;
    const pcapng_read_status expected = cut == 0  ? pcapng_read_status::not_pcapng
                                        : boundary ? pcapng_read_status::end_of_file
                                                   : pcapng_read_status::truncated;
    EXPECT_EQ(got.statuses.back(), expected) << "cut at " << cut;
  }
}

// ---------------------------------------------------------------------------------------------------------
// reader: files from other writers

TEST(PcapngReader, ReadsBigEndianFilesAndDefaultMicroseconds) {
  block_builder be{true};
  const std::string file = as_string(join({be.section(), be.interface(227, "can0"),
                                           be.packet(0, 1500000, bytes{0, 0, 0, 0x28, 0, 0, 0, 0})}));
  const read_back got = read_all(file);
  ASSERT_EQ(got.records.size(), 1u);
  EXPECT_EQ(got.records[0].time_ns, 1500000000u);  // 1.5 s at the default 10^-6 s
  EXPECT_EQ(got.records[0].network, capture_network::can);
  EXPECT_EQ(got.payloads[0], (bytes{0, 0, 0, 0x28, 0, 0, 0, 0}));
  EXPECT_EQ(got.statuses.back(), pcapng_read_status::end_of_file);
}

TEST(PcapngReader, ConvertsDecimalAndBinaryResolutions) {
  block_builder le;
  const std::string file = as_string(join({
      le.section(),
      le.interface(1, "s", 0),         // seconds
      le.interface(1, "ps", 12),       // picoseconds
      le.interface(1, "binary", 0x8A),  // 2^-10 s
      le.interface(1, "fine", 0x80 | 40),
      le.packet(0, 3, {}),
      le.packet(1, 1234567891234ull, {}),
      le.packet(2, 1024 * 5 + 512, {}),
      le.packet(3, std::uint64_t{1} << 40, {}),
  }));
  const read_back got = read_all(file);
  ASSERT_EQ(got.records.size(), 4u) << to_string(got.statuses.back());
  EXPECT_EQ(got.records[0].time_ns, 3000000000u);
  EXPECT_EQ(got.records[1].time_ns, 1234567891u);
  EXPECT_EQ(got.records[2].time_ns, 5500000000u);
  EXPECT_EQ(got.records[3].time_ns, 1000000000u);
}

// Every if_tsresol is read, as Wireshark reads it (s37 item 10: 10^-127 s and 2^-127 s were refused as an
// unsupported resolution and the records lost): a time finer than a nanosecond rounds down.
TEST(PcapngReader, ReadsTheFinestResolutions) {
  block_builder le;
  const std::string file = as_string(join({
      le.section(),
      le.interface(1, "10^-127", 0x7F),
      le.interface(1, "2^-127", 0xFF),
      le.interface(1, "10^-28", 28),
      le.interface(1, "10^-29", 29),
      le.interface(1, "2^-64", 0x80 | 64),
      le.interface(1, "2^-93", 0x80 | 93),
      le.interface(1, "2^-94", 0x80 | 94),
      le.packet(0, UINT64_MAX, {}),
      le.packet(1, UINT64_MAX, {}),
      le.packet(2, 10000000000000000000ull, {}),  // 10^19 ticks of 10^-28 s: 10^-9 s
      le.packet(3, UINT64_MAX, {}),
      le.packet(4, UINT64_MAX, {}),               // just under 1 s
      le.packet(5, UINT64_MAX, {}),               // 2^64 / 2^93 s: under 2 ns
      le.packet(6, UINT64_MAX, {}),
  }));
  const read_back got = read_all(file);
  ASSERT_EQ(got.records.size(), 7u) << to_string(got.statuses.back());
  const std::uint64_t expected[] = {0, 0, 1, 0, 999999999, 1, 0};
  for (std::size_t i = 0; i < 7; ++i) EXPECT_EQ(got.records[i].time_ns, expected[i]) << i;
}

TEST(PcapngReader, AppliesTheTimestampOffset) {
  block_builder le;
  bytes offset;
  le.option(offset, 14, bytes{10, 0, 0, 0, 0, 0, 0, 0});  // +10 s
  bytes back;
  le.option(back, 14, bytes{0xFE, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF});  // -2 s
  const std::string file = as_string(join({le.section(), le.interface(1, "a", 9, offset),
                                           le.interface(1, "b", 9, back), le.packet(0, 5, {}),
                                           le.packet(1, 3000000000u, {}), le.packet(1, 1, {})}));
  const read_back got = read_all(file);
  ASSERT_EQ(got.records.size(), 2u);
  EXPECT_EQ(got.records[0].time_ns, 10000000005u);
  EXPECT_EQ(got.records[1].time_ns, 1000000000u);
  EXPECT_EQ(got.statuses[2], pcapng_read_status::timestamp_out_of_range);  // 1 ns - 2 s: before 1970
}

TEST(PcapngReader, SkipsUnknownBlocksAndReadsEverySection) {
  block_builder le;
  block_builder be{true};
  const std::string file = as_string(join({
      le.section(), le.interface(1, "first"), le.block(0x0BAD, bytes{1, 2, 3}), le.block(5, bytes(20, 0)),
      le.packet(0, 1, {}),
      be.section(), be.interface(227, "second"), be.block(4, {}), be.packet(0, 2, bytes{0xAA}),
  }));
  std::istringstream in(file);
  pcapng_reader reader(in);
  pcapng_read_result r = reader.next();
  ASSERT_TRUE(r);
  EXPECT_EQ(reader.interfaces()[0].name, "first");
  r = reader.next();
  ASSERT_TRUE(r);
  EXPECT_EQ(r.record.time_ns, 2000u);
  ASSERT_EQ(reader.interfaces().size(), 1u);
  EXPECT_EQ(reader.interfaces()[0].name, "second");
  EXPECT_EQ(reader.interfaces()[0].link_type, 227);
  EXPECT_EQ(reader.next().status, pcapng_read_status::end_of_file);
  EXPECT_EQ(reader.sections(), 2u);
  EXPECT_EQ(reader.skipped_blocks(), 3u);
}

TEST(PcapngReader, ForeignExportedPduIsOther) {
  block_builder le;
  const bytes tags = {0, 12, 0, 4, 's', 'i', 'p', 0, 0, 0, 0, 0, 'I', 'N', 'V'};
  const read_back got = read_all(as_string(join({le.section(), le.interface(252, ""), le.packet(0, 0, tags)})));
  ASSERT_EQ(got.records.size(), 1u);
  EXPECT_EQ(got.records[0].network, capture_network::other);
  EXPECT_EQ(got.dissectors[0], "sip");
  EXPECT_EQ(got.payloads[0], (bytes{'I', 'N', 'V'}));
}

// Wireshark reads the dissector name up to its first NUL: bytes after it (a damaged padding) do not make a
// Genius record another network's (s37 item 10: the tool lost the record that tshark decoded).
TEST(PcapngReader, TheDissectorNameEndsAtItsFirstNul) {
  block_builder le;
  const bytes tags = {0, 12, 0, 16, 't', 'r', 'i', 'o', 'n', 'e', 't', '_', 'g', 'e', 'n', 'i', 'u', 's', 0, '`',
                      0, 0,  0, 0,  0x04, 0x92};
  const read_back got = read_all(as_string(join({le.section(), le.interface(252, ""), le.packet(0, 0, tags)})));
  ASSERT_EQ(got.records.size(), 1u);
  EXPECT_EQ(got.dissectors[0], "trionet_genius");
  EXPECT_EQ(got.records[0].network, capture_network::genius);
  EXPECT_EQ(got.payloads[0], (bytes{0x04, 0x92}));
}

// ---------------------------------------------------------------------------------------------------------
// reader: bad files

TEST(PcapngReader, NotAPcapngFile) {
  EXPECT_EQ(last_status(""), pcapng_read_status::not_pcapng);
  // a classic pcap file header
  EXPECT_EQ(last_status(as_string(bytes{0xD4, 0xC3, 0xB2, 0xA1, 2, 0, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 4, 0,
                                        0xE3, 0, 0, 0})),
            pcapng_read_status::not_pcapng);
  block_builder le;
  EXPECT_EQ(last_status(as_string(le.interface(252, "no section"))), pcapng_read_status::not_pcapng);
}

TEST(PcapngReader, SectionHeaderChecks) {
  block_builder le;
  bytes section = le.section();
  section[8] = 0x11;  // byte-order magic
  EXPECT_EQ(last_status(as_string(section)), pcapng_read_status::bad_byte_order);
  EXPECT_EQ(last_status(as_string(le.section(2))), pcapng_read_status::unsupported_version);
  section = le.section();
  section[4] = 24;  // shorter than a section header can be
  EXPECT_EQ(last_status(as_string(section)), pcapng_read_status::bad_block_length);
  section = le.section();
  section[section.size() - 4] = 0;  // trailing length differs
  EXPECT_EQ(last_status(as_string(section)), pcapng_read_status::bad_block_length);
  bytes with_option;
  le.u32(with_option, 0x1A2B3C4D);
  le.u16(with_option, 1);
  le.u16(with_option, 0);
  le.u32(with_option, 0xFFFFFFFF);
  le.u32(with_option, 0xFFFFFFFF);
  le.u16(with_option, 4);
  le.u16(with_option, 200);  // runs past the block
  EXPECT_EQ(last_status(as_string(le.block(0x0A0D0D0A, with_option))), pcapng_read_status::bad_option);
}

TEST(PcapngReader, BlockLengthChecks) {
  block_builder le;
  const bytes section = le.section();
  bytes odd = le.packet(0, 0, {});
  odd[4] = 30;  // not a multiple of 4
  EXPECT_EQ(last_status(as_string(join({section, odd}))), pcapng_read_status::bad_block_length);
  bytes small = le.packet(0, 0, {});
  small[4] = 8;
  EXPECT_EQ(last_status(as_string(join({section, small}))), pcapng_read_status::bad_block_length);
  bytes trailer = le.packet(0, 0, {});
  trailer[trailer.size() - 4] ^= 4;
  EXPECT_EQ(last_status(as_string(join({section, le.interface(252, ""), trailer}))),
            pcapng_read_status::bad_block_length);
  pcapng_reader::limits tight;
  tight.max_block_length = 64;
  EXPECT_EQ(last_status(as_string(join({section, le.interface(252, ""), le.packet(0, 0, bytes(40, 1))})), tight),
            pcapng_read_status::block_too_long);
  // a length that promises far more than the file holds
  bytes huge = le.packet(0, 0, {});
  huge[6] = 0xF0;
  EXPECT_EQ(last_status(as_string(join({section, huge}))), pcapng_read_status::truncated);
}

TEST(PcapngReader, BlockFieldChecks) {
  block_builder le;
  const bytes section = le.section();
  EXPECT_EQ(last_status(as_string(join({section, le.block(1, bytes{1, 0, 0, 0})}))),
            pcapng_read_status::bad_block);
  EXPECT_EQ(last_status(as_string(join({section, le.interface(252, ""), le.block(6, bytes(16, 0))}))),
            pcapng_read_status::bad_block);
  bytes beyond = le.packet(0, 0, bytes{1, 2, 3, 4});
  beyond[20] = 9;  // captured length beyond the block
  EXPECT_EQ(last_status(as_string(join({section, le.interface(252, ""), beyond}))), pcapng_read_status::bad_block);
  bytes resolution;
  le.option(resolution, 9, bytes{6, 6});
  EXPECT_EQ(last_status(as_string(join({section, le.interface(252, "", -1, resolution)}))),
            pcapng_read_status::bad_option);
  bytes offset;
  le.option(offset, 14, bytes{1, 2, 3, 4});
  EXPECT_EQ(last_status(as_string(join({section, le.interface(252, "", -1, offset)}))),
            pcapng_read_status::bad_option);
  bytes packet_option = le.packet(0, 0, bytes{});
  packet_option.insert(packet_option.end() - 4, {1, 0, 200, 0});  // comment option running past the block
  packet_option[4] = static_cast<std::uint8_t>(packet_option.size());
  packet_option[packet_option.size() - 4] = static_cast<std::uint8_t>(packet_option.size());
  EXPECT_EQ(last_status(as_string(join({section, le.interface(252, ""), packet_option}))),
            pcapng_read_status::bad_option);
  pcapng_reader::limits few;
  few.max_interfaces = 2;
  EXPECT_EQ(last_status(as_string(join({section, le.interface(1, "a"), le.interface(1, "b"), le.interface(1, "c")})),
                        few),
            pcapng_read_status::too_many_interfaces);
}

TEST(PcapngReader, ABadRecordIsReportedAndReadingGoesOn) {
  block_builder le;
  const std::string file = as_string(join({
      le.section(),
      le.interface(252, "ring", 9),
      le.interface(1, "seconds", 0),
      le.packet(5, 0, {}),                 // no interface 5
      le.packet(1, UINT64_MAX, {}),        // seconds that do not fit nanoseconds
      le.packet(0, 0, bytes{0, 12, 0, 40, 'x'}),  // tag runs past the record
      le.packet(0, 0, bytes{0, 12, 0, 1, 'x'}),   // no end tag
      le.packet(0, 7, bytes{0, 0, 0, 0, 0x8a}),
  }));
  const read_back got = read_all(file);
  const std::vector<pcapng_read_status> expected = {
      pcapng_read_status::unknown_interface,      pcapng_read_status::timestamp_out_of_range,
      pcapng_read_status::bad_exported_pdu,
      pcapng_read_status::bad_exported_pdu,       pcapng_read_status::ok,
      pcapng_read_status::end_of_file};
  EXPECT_EQ(got.statuses, expected);
  ASSERT_EQ(got.records.size(), 1u);
  EXPECT_EQ(got.records[0].time_ns, 7u);
  EXPECT_EQ(got.payloads[0], bytes{0x8a});
  for (std::size_t i = 0; i + 2 < expected.size(); ++i) EXPECT_FALSE(ends_reading(expected[i]));
}

TEST(PcapngReader, AfterAFatalErrorEveryCallSaysTheSame) {
  std::istringstream in(std::string("\x0a\x0d\x0d\x0a\x1c\x00", 6));
  pcapng_reader reader(in);
  EXPECT_EQ(reader.next().status, pcapng_read_status::truncated);
  EXPECT_EQ(reader.next().status, pcapng_read_status::truncated);
  EXPECT_TRUE(ends_reading(pcapng_read_status::truncated));
}

}  // namespace
