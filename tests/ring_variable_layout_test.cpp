// Reflected and run-time CRCs, and the direct variable transfer's field layouts (docs/protocol.md 1.3).
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "trionet/ring.hpp"
#include "trionet/vr.hpp"

namespace ring = trionet::ring;
using trionet::byte_view;

namespace {

constexpr std::uint8_t check_bytes[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};

// The Rocksoft model, one message bit at a time, written independently of crc.hpp: the register holds the
// CRC in non-reflected order throughout; a reflected input feeds each byte's bits least significant first.
std::uint16_t reference_crc(const ring::crc16_parameters& p, const std::uint8_t* data, std::size_t size) {
  unsigned reg = p.initial;
  for (std::size_t i = 0; i < size; ++i) {
    for (int k = 0; k < 8; ++k) {
      const unsigned bit = p.reflect_in ? (data[i] >> k) & 1u : (data[i] >> (7 - k)) & 1u;
      const unsigned top = ((reg >> 15) & 1u) ^ bit;
      reg = (reg << 1) & 0xFFFFu;
      if (top != 0) reg ^= p.polynomial;
    }
  }
  if (p.reflect_out) reg = ring::reflect16(static_cast<std::uint16_t>(reg));
  return static_cast<std::uint16_t>(reg ^ p.xor_out);
}

template <class Crc>
std::uint16_t check_value() {
  return Crc::compute(check_bytes, sizeof check_bytes);
}

}  // namespace

// ---- reflected static policies: the catalogue's check values over "123456789" ----

TEST(RingCrcReflected, CatalogueCheckValuesInEveryTableKind) {
  using arc = ring::crc16<0x8005, 0x0000, 0x0000, ring::crc_table::lookup, true, true>;
  using arc_bitwise = ring::crc16<0x8005, 0x0000, 0x0000, ring::crc_table::none, true, true>;
  using arc_sliced = ring::crc16<0x8005, 0x0000, 0x0000, ring::crc_table::sliced, true, true>;
  EXPECT_EQ(check_value<arc>(), 0xBB3D);  // CRC-16/ARC
  EXPECT_EQ(check_value<arc_bitwise>(), 0xBB3D);
  EXPECT_EQ(check_value<arc_sliced>(), 0xBB3D);
  using x25 = ring::crc16<0x1021, 0xFFFF, 0xFFFF, ring::crc_table::sliced, true, true>;
  EXPECT_EQ(check_value<x25>(), 0x906E);  // CRC-16/IBM-SDLC
  using modbus = ring::crc16<0x8005, 0xFFFF, 0x0000, ring::crc_table::lookup, true, true>;
  EXPECT_EQ(check_value<modbus>(), 0x4B37);  // CRC-16/MODBUS
  using riello = ring::crc16<0x1021, 0xB2AA, 0x0000, ring::crc_table::none, true, true>;
  EXPECT_EQ(check_value<riello>(), 0x63D0);  // CRC-16/RIELLO: a non-symmetric init, reflected
  static_assert(arc_sliced::compute(check_bytes, 9) == 0xBB3D, "constexpr reflected CRC");
  // Unchanged defaults: CCITT-FALSE is still the default and not reflected.
  EXPECT_EQ(check_value<ring::crc16_ccitt_false>(), 0x29B1);
  static_assert(!ring::crc16_ccitt_false::reflect_in && !ring::crc16_ccitt_false::reflect_out, "");
}

TEST(RingCrcReflected, EveryTableKindAndReflectionMatchesTheBitModel) {
  std::mt19937_64 rng(16);
  std::vector<std::uint8_t> data(300);
  for (auto& b : data) b = static_cast<std::uint8_t>(rng());
  const auto check = [&](auto policy, ring::crc16_parameters p) {
    using crc = decltype(policy);
    for (std::size_t length : {0u, 1u, 3u, 4u, 5u, 12u, 13u, 64u, 299u}) {
      ASSERT_EQ(crc::compute(data.data(), length), reference_crc(p, data.data(), length)) << length;
      ASSERT_EQ((ring::crc_of<crc, 12>(data.data())), reference_crc(p, data.data(), 12));
    }
  };
  // Mixed reflections (no catalogue entry has them, the model allows them).
  check(ring::crc16<0x3D65, 0x1234, 0x0F0F, ring::crc_table::lookup, true, false>{},
        {0x3D65, 0x1234, true, false, 0x0F0F});
  check(ring::crc16<0x3D65, 0x1234, 0x0F0F, ring::crc_table::sliced, false, true>{},
        {0x3D65, 0x1234, false, true, 0x0F0F});
  check(ring::crc16<0x3D65, 0x1234, 0x0F0F, ring::crc_table::none, true, false>{},
        {0x3D65, 0x1234, true, false, 0x0F0F});
  check(ring::crc16<0x8BB7, 0xBEEF, 0x0000, ring::crc_table::sliced, true, true>{},
        {0x8BB7, 0xBEEF, true, true, 0x0000});
  check(ring::crc16<0x8BB7, 0xBEEF, 0x0000, ring::crc_table::lookup, false, false>{},
        {0x8BB7, 0xBEEF, false, false, 0x0000});
}

// ---- the run-time CRC ----

TEST(RingCrcRuntime, MatchesTheBitModelForRandomParameters) {
  std::mt19937_64 rng(17);
  std::vector<std::uint8_t> data(40);
  for (int round = 0; round < 400; ++round) {
    ring::crc16_parameters p;
    p.polynomial = static_cast<std::uint16_t>(rng());
    p.initial = static_cast<std::uint16_t>(rng());
    p.xor_out = static_cast<std::uint16_t>(rng());
    p.reflect_in = (round & 1) != 0;
    p.reflect_out = (round & 2) != 0;
    for (auto& b : data) b = static_cast<std::uint8_t>(rng());
    const ring::crc16_runtime crc(p);
    EXPECT_EQ(crc.parameters(), p);
    const std::size_t length = static_cast<std::size_t>(rng() % data.size());
    ASSERT_EQ(crc.compute(data.data(), length), reference_crc(p, data.data(), length)) << round;
    ASSERT_EQ(ring::crc_of<12>(crc, data.data()), reference_crc(p, data.data(), 12)) << round;
  }
}

TEST(RingCrcRuntime, DefaultIsTheRingCrcAndTheDecoderUsesIt) {
  const ring::crc16_runtime ccitt_false;
  EXPECT_EQ(ccitt_false.compute(check_bytes, 9), 0x29B1);
  // The protocol's example frame (docs/protocol.md 1.3) through a decoder holding a run-time CRC.
  const std::vector<std::uint8_t> golden = {0x8a, 0x48, 0x01, 0x00, 0x00, 0x00, 0x00, 0x30,
                                            0x0c, 0x00, 0x00, 0x00, 0x00, 0x7f, 0x3e, 0x88};
  ring::decoder<256, ring::crc16_runtime> d(ccitt_false);
  int messages = 0;
  d.push(byte_view(golden.data(), golden.size()), [&](const ring::decode_result& r) {
    EXPECT_EQ(r.status, ring::decode_status::ok);
    EXPECT_EQ(r.msg.vr, 200);
    EXPECT_EQ(r.msg.value, trionet::q32_from_integer(99));
    ++messages;
  });
  EXPECT_EQ(messages, 1);
  // Another run-time CRC (XMODEM) rejects it; the encoder with that CRC makes a frame it accepts.
  const ring::crc16_runtime xmodem(ring::crc16_parameters{0x1021, 0x0000, false, false, 0x0000});
  ring::decoder<256, ring::crc16_runtime> x(xmodem);
  ring::decode_result last;
  for (std::uint8_t b : golden) last = x.push(b);
  EXPECT_EQ(last.status, ring::decode_status::crc_error);
  std::uint8_t frame[16];
  ASSERT_TRUE(ring::encode_variable(frame, 1, 200, trionet::q32_from_integer(99), xmodem));
  for (std::uint8_t b : frame) last = x.push(b);
  EXPECT_EQ(last.status, ring::decode_status::ok);
  // Byte for byte what the static XMODEM policy sends.
  std::uint8_t expected[16];
  using xmodem_policy = ring::crc16<0x1021, 0x0000>;
  ASSERT_TRUE(ring::encode_variable<xmodem_policy>(expected, 1, 200, trionet::q32_from_integer(99)));
  EXPECT_EQ(0, std::memcmp(frame, expected, 16));
}

TEST(RingCrcRuntime, AStaticPolicyCostsTheDecoderNoRam) {
  EXPECT_EQ(sizeof(ring::decoder<256>), sizeof(ring::decoder<256, ring::crc16_ccitt_false_bitwise>));
  EXPECT_GT(sizeof(ring::decoder<256, ring::crc16_runtime>), sizeof(ring::decoder<256>));
}

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
  using node = ring::motion_coordinator<256, 32, 32, reflected, ring::default_max_characters, msf>;
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
  using mc = ring::motion_coordinator<256, 32, 32, ring::crc16_runtime, ring::default_max_characters, msf>;
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
