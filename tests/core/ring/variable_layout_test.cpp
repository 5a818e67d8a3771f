// The direct variable transfer's field layouts (docs/protocol.md 1.3). The CRCs are in crc_test.cpp.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "trionet/ring.hpp"
#include "trionet/vr.hpp"

namespace ring = trionet::ring;
using trionet::byte_view;

// ---- field layouts ----

TEST(RingVariableLayout, DefaultIsLeastSignificantGroupFirstAsTheProtocolExample) {
  std::uint8_t fields[12];
  ring::default_variable_layout::write(fields, 200, trionet::q32_from_integer(99));
  const std::uint8_t expected[12] = {0x48, 0x01, 0x00, 0x00, 0x00, 0x00, 0x30, 0x0c, 0x00, 0x00, 0x00, 0x00};
  EXPECT_EQ(0, std::memcmp(fields, expected, 12));
}

TEST(RingVariableLayout, MostSignificantFirstReversesEachFieldsGroups) {
  using msf = ring::variable_layout<ring::group_order::most_significant_first,
                                    ring::group_order::most_significant_first>;
  std::uint8_t fields[12];
  msf::write(fields, 200, trionet::q32_from_integer(99));
  const std::uint8_t expected[12] = {0x01, 0x48, 0x00, 0x00, 0x00, 0x00, 0x0c, 0x30, 0x00, 0x00, 0x00, 0x00};
  EXPECT_EQ(0, std::memcmp(fields, expected, 12));
  // Only the vr reversed; only the value reversed.
  using vr_msf = ring::variable_layout<ring::group_order::most_significant_first>;
  vr_msf::write(fields, 200, trionet::q32_from_integer(99));
  EXPECT_EQ(fields[0], 0x01);
  EXPECT_EQ(fields[1], 0x48);
  EXPECT_EQ(fields[7], 0x0c);  // X5, as in the default layout
  // A negative value: bit 63 sits alone in the first value group (X0) when most significant first.
  msf::write(fields, 1, -1);
  EXPECT_EQ(fields[2], 0x01);
  for (int k = 3; k < 12; ++k) EXPECT_EQ(fields[k], 0x7F) << k;
  EXPECT_EQ(msf::top_group, 2u);
  EXPECT_EQ(ring::default_variable_layout::top_group, 11u);
}

TEST(RingVariableLayout, EveryLayoutReadsWhatItWrites) {
  std::mt19937_64 rng(18);
  for (int round = 0; round < 2000; ++round) {
    ring::variable_layout_parameters p;
    p.vr = (round & 1) != 0 ? ring::group_order::most_significant_first
                            : ring::group_order::least_significant_first;
    p.value = (round & 2) != 0 ? ring::group_order::most_significant_first
                               : ring::group_order::least_significant_first;
    p.crc = (round & 4) != 0 ? ring::crc_input::least_significant_first : ring::crc_input::as_sent;
    const auto vr = static_cast<std::uint16_t>(rng() % 16384);
    const auto value = static_cast<std::int64_t>(rng());
    ring::with_variable_layout(p, [&](auto layout) {
      using L = decltype(layout);
      EXPECT_EQ(L::parameters, p);
      std::uint8_t fields[12];
      L::write(fields, vr, value);
      for (std::uint8_t b : fields) ASSERT_LT(b, 0x80);
      std::uint16_t vr_read = 0;
      std::int64_t value_read = 0;
      L::read(fields, vr_read, value_read);
      ASSERT_EQ(vr_read, vr);
      ASSERT_EQ(value_read, value);
      ring::read_variable_fields(fields, vr_read, value_read, p.vr, p.value);  // the value form agrees
      ASSERT_EQ(vr_read, vr);
      ASSERT_EQ(value_read, value);
      EXPECT_EQ(fields[L::top_group] & 0x7E, 0);
    });
  }
}

TEST(RingVariableLayout, EncoderAndDecoderAgreeInEveryLayoutAndTheDefaultDecoderDoesNot) {
  using msf = ring::variable_layout<ring::group_order::most_significant_first,
                                    ring::group_order::most_significant_first>;
  std::uint8_t frame[16];
  ASSERT_TRUE(
      (ring::encode_variable<ring::crc16_ccitt_false, msf>(frame, 3, 200, trionet::q32_from_integer(99))));
  ring::decoder<256, ring::crc16_ccitt_false, msf> d;
  ring::decode_result last;
  for (std::uint8_t b : frame) last = d.push(b);
  ASSERT_EQ(last.status, ring::decode_status::ok);
  EXPECT_EQ(last.msg.vr, 200);
  EXPECT_EQ(last.msg.value, trionet::q32_from_integer(99));
  // The default decoder checks the same CRC over the same bytes (the CRC covers them as sent), so it accepts
  // the frame but reads other numbers.
  ring::decoder<> plain;
  for (std::uint8_t b : frame) last = plain.push(b);
  ASSERT_EQ(last.status, ring::decode_status::ok);
  EXPECT_NE(last.msg.vr, 200);
  // A value whose top group is not 0 or 1 is a field error in the MSF layout (its X0 has bits 6..1 set).
  std::uint8_t bad[16];
  std::memcpy(bad, frame, 16);
  bad[3] = 0x02;
  const std::uint16_t crc = ring::crc16_ccitt_false::compute(bad + 1, 12);
  bad[13] = static_cast<std::uint8_t>(crc & 0x7F);
  bad[14] = static_cast<std::uint8_t>((crc >> 8) & 0x7F);
  for (std::uint8_t b : bad) last = d.push(b);
  EXPECT_EQ(last.status, ring::decode_status::frame_error);
  EXPECT_EQ(last.error, ring::frame_error::bad_field);
}

TEST(RingVariableLayout, CrcOverTheDefaultOrderGivesTheDefaultFramesCrc) {
  using msf_canonical_crc = ring::variable_layout<ring::group_order::most_significant_first,
                                                  ring::group_order::most_significant_first,
                                                  ring::crc_input::least_significant_first>;
  std::uint8_t frame[16], plain[16];
  ASSERT_TRUE((ring::encode_variable<ring::crc16_ccitt_false, msf_canonical_crc>(
      frame, 1, 200, trionet::q32_from_integer(99))));
  ASSERT_TRUE(ring::encode_variable(plain, 1, 200, trionet::q32_from_integer(99)));
  EXPECT_EQ(frame[13], plain[13]);
  EXPECT_EQ(frame[14], plain[14]);
  EXPECT_EQ(frame[13], 0x7f);  // the protocol example's C0 C1
  EXPECT_EQ(frame[14], 0x3e);
  // Its decoder accepts it; a decoder that takes the CRC over the bytes as sent finds a CRC error.
  ring::decoder<256, ring::crc16_ccitt_false, msf_canonical_crc> d;
  ring::decode_result last;
  for (std::uint8_t b : frame) last = d.push(b);
  EXPECT_EQ(last.status, ring::decode_status::ok);
  EXPECT_EQ(last.msg.vr, 200);
  using msf = ring::variable_layout<ring::group_order::most_significant_first,
                                    ring::group_order::most_significant_first>;
  ring::decoder<256, ring::crc16_ccitt_false, msf> as_sent;
  for (std::uint8_t b : frame) last = as_sent.push(b);
  EXPECT_EQ(last.status, ring::decode_status::crc_error);
}

TEST(RingVariableLayout, MotionCoordinatorsSendAndReceiveInTheirLayout) {
  using msf = ring::variable_layout<ring::group_order::most_significant_first,
                                    ring::group_order::most_significant_first>;
  using reflected = ring::crc16<0x8005, 0xFFFF, 0x0000, ring::crc_table::lookup, true, true>;  // MODBUS
  using node = ring::motion_coordinator<256, 32, 32, ring::default_max_characters, reflected, msf>;
  trionet::vr_table<256> vr_a, vr_b;
  node a(vr_a), b(vr_b);
  ASSERT_EQ(a.send_variable(10, 200, 99.0), ring::send_status::ok);  // BASIC address 10: the next node
  std::uint8_t byte = 0;
  std::vector<std::uint8_t> wire;
  while (a.transmit(byte)) wire.push_back(byte);
  std::uint8_t expected[16];
  ASSERT_TRUE((ring::encode_variable<reflected, msf>(expected, 1, 200, trionet::q32_from_integer(99))));
  ASSERT_EQ(wire, std::vector<std::uint8_t>(expected, expected + 16));
  for (std::uint8_t w : wire) b.receive(w);
  EXPECT_EQ(vr_b[200], 99.0);
  EXPECT_EQ(b.netstat(), 0);
}

namespace {

// A CRC chosen at run time (a profile's): the nodes take the object, send with it and check with it.
TEST(RingVariableLayout, NodesTakeACrcChosenAtRunTime) {
  using msf = ring::variable_layout<ring::group_order::most_significant_first,
                                    ring::group_order::most_significant_first>;
  const ring::crc16_runtime modbus(ring::crc16_parameters{0x8005, 0xFFFF, true, true, 0});
  using mc = ring::motion_coordinator<256, 32, 32, ring::default_max_characters, ring::crc16_runtime, msf>;
  trionet::vr_table<256> vr_a, vr_b;
  mc a(vr_a, ring::default_defkey, modbus), b(vr_b, ring::default_defkey, modbus);
  ASSERT_EQ(a.send_variable(10, 200, 99.0), ring::send_status::ok);
  std::uint8_t byte = 0;
  std::vector<std::uint8_t> wire;
  while (a.transmit(byte)) wire.push_back(byte);
  std::uint8_t expected[16];
  ASSERT_TRUE((ring::encode_variable<ring::crc16_runtime, msf>(expected, 1, 200, trionet::q32_from_integer(99),
                                                               modbus)));
  ASSERT_EQ(wire, std::vector<std::uint8_t>(expected, expected + 16));
  for (std::uint8_t w : wire) b.receive(w);
  EXPECT_EQ(vr_b[200], 99.0);
  EXPECT_EQ(b.netstat(), 0);

  // A node left with the default CRC object (CRC-16/CCITT-FALSE) refuses the frame: a CRC error.
  trionet::vr_table<256> vr_c;
  mc c(vr_c);
  for (std::uint8_t w : wire) c.receive(w);
  EXPECT_EQ(vr_c[200], 0.0);
  EXPECT_EQ(c.counters().crc_errors, 1u);

  // A keypad checks with its object too: the MODBUS frame passes its CRC check (and is ignored, counted).
  ring::keypad<16, 16, ring::default_max_characters, ring::crc16_runtime, msf> k(ring::keypad_config{}, modbus);
  for (int w : {0x8b, 0x01, 0x88}) k.receive(static_cast<std::uint8_t>(w));  // keypad offset 1: network mode
  for (std::uint8_t w : wire) k.receive(w);
  EXPECT_EQ(k.counters().crc_errors, 0u);
  EXPECT_EQ(k.counters().variables_ignored, 1u);
}

}  // namespace
