// The library's view of capture records: the fields the dissectors must show, per network.
#include <gtest/gtest.h>

#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "trionet/genius.hpp"
#include "trionet/host/capture.hpp"
#include "trionet/host/capture_view.hpp"
#include "trionet/host/pcapng.hpp"
#include "trionet/ring.hpp"

namespace {

using namespace trionet;
using namespace trionet::host;
using bytes = std::vector<std::uint8_t>;

// The values of field `name`, in order, as the JSON writes them.
std::vector<std::string> values(const capture_fields& fields, const std::string& name) {
  std::vector<std::string> out;
  for (const capture_field& f : fields) {
    if (f.name != name) continue;
    capture_fields one = {f};
    const std::string json = fields_json(one);  // {"name":value}
    out.push_back(json.substr(name.size() + 4, json.size() - name.size() - 5));
  }
  return out;
}
std::string value(const capture_fields& fields, const std::string& name) {
  const std::vector<std::string> all = values(fields, name);
  return all.size() == 1 ? all[0] : "(" + std::to_string(all.size()) + " values)";
}
bool has(const capture_fields& fields, const std::string& name) {
  return !values(fields, name).empty();
}

capture_fields ring(const bytes& b) {
  return ring_record_fields(byte_view(b.data(), b.size()));
}

const bytes golden = {0x8a, 0x48, 0x01, 0x00, 0x00, 0x00, 0x00, 0x30, 0x0c, 0x00, 0x00, 0x00, 0x00, 0x7f, 0x3e, 0x88};

TEST(RingRecordFields, TheGoldenVariableTransfer) {
  const capture_fields f = ring(golden);
  EXPECT_EQ(value(f, "trionet_ring.header"), "138");
  EXPECT_EQ(value(f, "trionet_ring.hops"), "1");
  EXPECT_EQ(value(f, "trionet_ring.type"), "2");
  EXPECT_EQ(value(f, "trionet_ring.length"), "14");
  EXPECT_EQ(value(f, "trionet_ring.data"), "\"48:01:00:00:00:00:30:0c:00:00:00:00:7f:3e\"");
  EXPECT_EQ(value(f, "trionet_ring.eom"), "136");
  EXPECT_EQ(value(f, "trionet_ring.eom_hops"), "1");
  EXPECT_EQ(value(f, "trionet_ring.vr"), "200");
  EXPECT_EQ(value(f, "trionet_ring.value_raw"), std::to_string(std::int64_t{99} << 32));
  EXPECT_EQ(value(f, "trionet_ring.value"), "99.0");
  EXPECT_EQ(value(f, "trionet_ring.crc"), std::to_string(0x3e7f));
  EXPECT_EQ(value(f, "trionet_ring.crc_computed"), std::to_string(0x3e7f));
  EXPECT_EQ(value(f, "trionet_ring.crc_good"), "true");
  EXPECT_EQ(value(f, "trionet_ring.status"), "\"message\"");
  EXPECT_FALSE(has(f, "trionet_ring.frame_error"));
}

TEST(RingRecordFields, CrcErrorKeepsVrAndValue) {
  bytes b = golden;
  b[13] ^= 0x01;
  const capture_fields f = ring(b);
  EXPECT_EQ(value(f, "trionet_ring.status"), "\"crc_error\"");
  EXPECT_EQ(value(f, "trionet_ring.crc_good"), "false");
  EXPECT_EQ(value(f, "trionet_ring.crc"), std::to_string(0x3e7e));
  EXPECT_EQ(value(f, "trionet_ring.vr"), "200");
  EXPECT_TRUE(has(f, "trionet_ring.expert.crc_error"));
}

TEST(RingRecordFields, EveryFrameErrorReason) {
  struct sample {
    bytes record;
    const char* reason;
  };
  const std::vector<sample> samples = {
      {{0x41, 0x42}, "stray_data"},
      {{0x88}, "stray_eom"},
      {{0x89, 0x41}, "interrupted"},
      {{0x89, 0x41, 0x90}, "eom_mismatch"},
      {{0x89, 0x88}, "bad_length"},
      {{0x8b, 0x00, 0x88}, "bad_field"},
      {{0x8d, 0x41, 0x88}, "unknown_type"},
      {{0x81, 0x41, 0x80}, "zero_hops"},
  };
  for (const sample& s : samples) {
    const capture_fields f = ring(s.record);
    EXPECT_EQ(value(f, "trionet_ring.status"), "\"frame_error\"") << s.reason;
    EXPECT_EQ(value(f, "trionet_ring.frame_error"), std::string("\"") + s.reason + "\"");
    EXPECT_TRUE(has(f, std::string("trionet_ring.expert.") + s.reason)) << s.reason;
  }
}

TEST(RingRecordFields, TextIsEscapedSoEveryCharacterShows) {
  const bytes b = {0x91, 'S', 'P', 0x00, '\\', '\r', '\n', 0x1b, 0x7f, 0x90};
  const capture_fields f = ring(b);
  EXPECT_EQ(value(f, "trionet_ring.hops"), "2");
  EXPECT_EQ(value(f, "trionet_ring.type"), "1");
  EXPECT_EQ(value(f, "trionet_ring.text"), "\"SP\\\\x00\\\\\\\\\\\\r\\\\n\\\\x1b\\\\x7f\"");
  EXPECT_EQ(value(f, "trionet_ring.status"), "\"message\"");
  EXPECT_EQ(escaped_text(byte_view(b.data() + 1, 8)), "SP\\x00\\\\\\r\\n\\x1b\\x7f");
}

TEST(RingRecordFields, OffsetModeAndARecordOfSeveralMessages) {
  const bytes b = {0x9b, 0x05, 0x98, 0x9c, 0x7f, 0x98, 0x41};
  const capture_fields f = ring(b);
  EXPECT_EQ(values(f, "trionet_ring.hops"), (std::vector<std::string>{"3", "3"}));
  EXPECT_EQ(value(f, "trionet_ring.offset"), "5");
  EXPECT_EQ(value(f, "trionet_ring.mode"), "127");
  EXPECT_EQ(values(f, "trionet_ring.status"),
            (std::vector<std::string>{"\"message\"", "\"message\"", "\"frame_error\""}));
  EXPECT_EQ(value(f, "trionet_ring.frame_error"), "\"stray_data\"");
}

// ---------------------------------------------------------------------------------------------------------
// Genius

bytes genius_record(const std::vector<genius::character>& characters) {
  bytes out;
  for (const genius::character c : characters) {
    const std::uint16_t w = genius::encode_character(c);
    out.push_back(static_cast<std::uint8_t>(w >> 8));
    out.push_back(static_cast<std::uint8_t>(w));
  }
  return out;
}
capture_fields genius_fields(const bytes& b) {
  return genius_record_fields(byte_view(b.data(), b.size()));
}
std::vector<genius::character> encoded(const genius::transmission& t) {
  genius::character out[64];
  const genius::encode_result r = genius::encode_transmission(span<genius::character>(out, 64), t);
  EXPECT_TRUE(r);
  return std::vector<genius::character>(out, out + r.length);
}

TEST(GeniusRecordFields, DirectedTransmissionWithABlock) {
  const std::uint8_t plain[] = {0x11};
  const std::uint8_t block[] = {0x22, 0x33};
  const genius::segment segments[] = {{false, 0, byte_view(plain, 1)}, {true, 7, byte_view(block, 2)}};
  const std::vector<genius::character> t = encoded({4, false, 9, span<const genius::segment>(segments, 2)});
  const capture_fields f = genius_fields(genius_record(t));
  EXPECT_EQ(values(f, "trionet_genius.kind"),
            (std::vector<std::string>{"\"start\"", "\"data\"", "\"data\"", "\"start_of_block\"", "\"data\"",
                                      "\"data\"", "\"end_of_block\"", "\"stop\""}));
  EXPECT_EQ(value(f, "trionet_genius.sender"), "4");
  EXPECT_EQ(value(f, "trionet_genius.broadcast"), "false");
  EXPECT_EQ(value(f, "trionet_genius.destination"), "9");
  EXPECT_EQ(value(f, "trionet_genius.block_destination"), "7");
  const std::uint8_t block_crc = genius::crc6_g704::compute(byte_view(block, 2));
  const std::uint8_t all[] = {9, 0x11, 0x22, 0x33};
  const std::uint8_t stop_crc = genius::crc6_g704::compute(byte_view(all, 4));
  EXPECT_EQ(value(f, "trionet_genius.block_crc"), std::to_string(block_crc));
  EXPECT_EQ(value(f, "trionet_genius.block_crc_computed"), std::to_string(block_crc));
  EXPECT_EQ(value(f, "trionet_genius.block_crc_good"), "true");
  EXPECT_EQ(value(f, "trionet_genius.crc"), std::to_string(stop_crc));
  EXPECT_EQ(value(f, "trionet_genius.crc_computed"), std::to_string(stop_crc));
  EXPECT_EQ(value(f, "trionet_genius.crc_good"), "true");
  EXPECT_EQ(value(f, "trionet_genius.parse_status"), "\"ok\"");
  EXPECT_EQ(value(f, "trionet_genius.status"), "\"ok\"");
  EXPECT_EQ(values(f, "trionet_genius.control").size(), 8u);
  EXPECT_EQ(values(f, "trionet_genius.start_bit"), std::vector<std::string>(8, "0"));
  EXPECT_EQ(values(f, "trionet_genius.stop_bit"), std::vector<std::string>(8, "1"));
}

TEST(GeniusRecordFields, StopCrcMismatch) {
  const std::uint8_t data[] = {0x55};
  const genius::segment plain[] = {{false, 0, byte_view(data, 1)}};
  std::vector<genius::character> t = encoded({3, true, 0, span<const genius::segment>(plain, 1)});
  t.back().byte ^= 0x01;
  const capture_fields f = genius_fields(genius_record(t));
  EXPECT_EQ(value(f, "trionet_genius.status"), "\"stop_crc_mismatch\"");
  EXPECT_EQ(value(f, "trionet_genius.crc_good"), "false");
  EXPECT_TRUE(has(f, "trionet_genius.expert.stop_crc_mismatch"));
}

TEST(GeniusRecordFields, FramingErrorIncompleteAndOutside) {
  const capture_fields framing = genius_fields({0x06, 0x95});
  EXPECT_EQ(value(framing, "trionet_genius.character_status"), "\"start_bit_not_0\"");
  EXPECT_EQ(value(framing, "trionet_genius.status"), "\"framing_error\"");
  EXPECT_FALSE(has(framing, "trionet_genius.kind"));

  const capture_fields open = genius_fields(genius_record({genius::start_character(2, true)}));
  EXPECT_EQ(value(open, "trionet_genius.status"), "\"incomplete\"");
  EXPECT_TRUE(has(open, "trionet_genius.expert.incomplete"));

  const capture_fields outside =
      genius_fields(genius_record({genius::data_character(1), genius::stop_character(0)}));
  EXPECT_EQ(values(outside, "trionet_genius.parse_status"),
            (std::vector<std::string>{"\"data_outside_transmission\"", "\"skipped\""}));
  EXPECT_EQ(value(outside, "trionet_genius.status"), "\"data_outside_transmission\"");

  const capture_fields odd = genius_fields({0x04, 0x12, 0x07});
  EXPECT_EQ(value(odd, "trionet_genius.odd_byte"), "7");
  EXPECT_TRUE(has(odd, "trionet_genius.expert.odd_length"));
}

// ---------------------------------------------------------------------------------------------------------
// CAN

capture_fields can_fields(std::uint32_t id, std::uint8_t dlc, bytes data, std::uint8_t nodes = 5) {
  can::frame f;
  f.id = id;
  f.dlc = dlc;
  for (std::size_t i = 0; i < data.size() && i < 8; ++i) f.data[i] = data[i];
  const auto r = socketcan_record(f);
  return can_record_fields(byte_view(r.data(), r.size()), nodes);
}

TEST(CanRecordFields, TheNotesExample) {
  const capture_fields f = can_fields(0x028, 8, {0x01, 0x00, 0x00, 0x00, 0x00, 0x02, 0x0d, 0x7a});
  EXPECT_EQ(value(f, "can.id"), "40");
  EXPECT_EQ(value(f, "can.len"), "8");
  EXPECT_EQ(value(f, "trionet_can.sender"), "1");
  EXPECT_EQ(value(f, "trionet_can.receiver"), "4");
  EXPECT_EQ(value(f, "trionet_can.receive_channel"), "1");
  EXPECT_EQ(value(f, "trionet_can.vr"), "1");
  EXPECT_EQ(value(f, "trionet_can.sign"), "0");
  EXPECT_EQ(value(f, "trionet_can.integer"), "2");
  EXPECT_EQ(value(f, "trionet_can.fraction"), "3450");
  EXPECT_EQ(value(f, "trionet_can.value"), "2.345");
  EXPECT_FALSE(has(f, "trionet_can.error"));
}

TEST(CanRecordFields, NonVrFramesHaveOnlyWiresharksFields) {
  EXPECT_FALSE(has(can_fields(0x123, 8, bytes(8, 0)), "trionet_can.sender"));      // foreign identifier
  EXPECT_FALSE(has(can_fields(0x028, 3, bytes(3, 0)), "trionet_can.sender"));      // DLC 3
  EXPECT_FALSE(has(can_fields(0x028, 12, bytes(8, 0)), "trionet_can.sender"));     // DLC 12
  EXPECT_FALSE(has(can_fields(0x40000028, 8, {}), "trionet_can.sender"));          // remote
  EXPECT_FALSE(has(can_fields(0x80000028, 8, bytes(8, 0)), "trionet_can.sender"));  // extended
  EXPECT_FALSE(has(can_fields(0x02A, 8, bytes(8, 0), 3), "trionet_can.sender"));   // node 4 of 3
  EXPECT_EQ(value(can_fields(0x02A, 8, bytes(8, 0), 5), "trionet_can.sender"), "3");
  EXPECT_EQ(value(can_fields(0x40000028, 8, {}), "can.flags.rtr"), "true");
}

TEST(CanRecordFields, BadSignAndFraction) {
  const capture_fields sign = can_fields(0x028, 8, {1, 2, 0, 0, 0, 0, 0, 0});
  EXPECT_EQ(value(sign, "trionet_can.error"), "\"bad_sign\"");
  EXPECT_TRUE(has(sign, "trionet_can.expert.bad_sign"));
  EXPECT_FALSE(has(sign, "trionet_can.value"));
  const capture_fields fraction = can_fields(0x028, 8, {1, 1, 0, 0, 0, 0, 0x27, 0x10});
  EXPECT_EQ(value(fraction, "trionet_can.error"), "\"bad_fraction\"");
  EXPECT_TRUE(has(fraction, "trionet_can.expert.bad_fraction"));
  const capture_fields negative_zero = can_fields(0x028, 8, {1, 1, 0, 0, 0, 0, 0, 0});
  EXPECT_EQ(value(negative_zero, "trionet_can.value"), "-0.0");
}

// ---------------------------------------------------------------------------------------------------------
// whole records and JSON

TEST(RecordFields, FrameFieldsAndJson) {
  std::ostringstream out;
  pcapng_writer writer(out);
  const std::uint32_t link = writer.add_interface("link 0: MC -> keypad", capture_network::ring).id;
  ASSERT_EQ(writer.write(link, 1500000001u, byte_view(golden.data(), 4)), pcapng_write_status::ok);
  std::istringstream in(out.str());
  pcapng_reader reader(in);
  const pcapng_read_result r = reader.next();
  ASSERT_TRUE(r);
  EXPECT_EQ(fields_json(record_fields(reader, r.record)),
            "{\"frame.interface_id\":0,\"frame.interface_name\":\"link 0: MC -> keypad\","
            "\"frame.time_epoch\":\"1.500000001\",\"exported_pdu.prot_name\":\"trionet_ring\","
            "\"trionet_ring.header\":138,\"trionet_ring.hops\":1,\"trionet_ring.type\":2,"
            "\"trionet_ring.length\":3,\"trionet_ring.data\":\"48:01:00\",\"trionet_ring.status\":\"frame_error\","
            "\"trionet_ring.frame_error\":\"interrupted\",\"trionet_ring.expert.interrupted\":\"\"}");
}

TEST(RecordFields, JsonEscapesAndGroupsRepeatedNames) {
  capture_fields fields(3);
  fields[0].name = "a";
  fields[0].kind = capture_field::type::text;
  fields[0].text = "q\"\\\x01";
  fields[1].name = "b";
  fields[1].kind = capture_field::type::real;
  fields[1].real = 0.1;
  fields[2] = fields[0];
  fields[2].text = "";
  // The shortest decimal that reads back as the same double, never an exponent.
  EXPECT_EQ(fields_json(fields), "{\"a\":[\"q\\\"\\\\\\u0001\",\"\"],\"b\":0.1}");
  fields[1].real = 1e-7;
  EXPECT_EQ(fields_json(fields), "{\"a\":[\"q\\\"\\\\\\u0001\",\"\"],\"b\":0.0000001}");
  fields[1].real = -0.0;
  EXPECT_EQ(fields_json(fields), "{\"a\":[\"q\\\"\\\\\\u0001\",\"\"],\"b\":-0.0}");
}

}  // namespace
