// A CRC-6 whose parameters come at run time (a profile read by a host tool, docs/protocol.md 3.2): the same
// results as the compile-time `crc6` with those parameters, the reveng catalogue's check values for every
// CRC-6 model, parameters masked to 6 bits.
#include <gtest/gtest.h>

#include <cstdint>

#include <trionet/genius/crc6.hpp>

#include "support/rng.hpp"

namespace {

using namespace trionet::genius;

constexpr std::uint8_t check_input[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};

struct model {
  const char* name;
  crc6_parameters parameters;
  std::uint8_t check;
};

constexpr model catalogue[] = {
    {"CRC-6/G-704", {0x03, 0x00, true, true, 0x00}, 0x06},
    {"CRC-6/DARC", {0x19, 0x00, true, true, 0x00}, 0x26},
    {"CRC-6/CDMA2000-A", {0x27, 0x3f, false, false, 0x00}, 0x0d},
    {"CRC-6/CDMA2000-B", {0x07, 0x3f, false, false, 0x00}, 0x3b},
    {"CRC-6/GSM", {0x2f, 0x00, false, false, 0x3f}, 0x13},
};

TEST(GeniusCrc6Runtime, EveryCatalogueModelGivesItsCheckValue) {
  for (const model& m : catalogue) {
    const crc6_runtime crc(m.parameters);
    EXPECT_EQ(crc.compute(check_input), m.check) << m.name;
    EXPECT_EQ(crc.parameters(), m.parameters) << m.name;
  }
  EXPECT_EQ(crc6_runtime{}.compute(check_input), 0x06) << "the default is the Genius CRC, CRC-6/G-704";
  EXPECT_EQ(crc6_runtime{}.parameters(), crc6_parameters{});
}

TEST(GeniusCrc6Runtime, ParametersAreMaskedToSixBits) {
  const crc6_runtime gsm(crc6_parameters{0xef, 0xc0, false, false, 0xff});  // GSM's 0x2f, 0x00, 0x3f
  EXPECT_EQ(gsm.parameters(), (crc6_parameters{0x2f, 0x00, false, false, 0x3f}));
  EXPECT_EQ(gsm.compute(check_input), 0x13);
}

template <std::uint8_t Poly, std::uint8_t Init, bool RefIn, bool RefOut, std::uint8_t XorOut>
void expect_same_as_compile_time(trionet::test::rng& random) {
  const crc6_runtime at_run_time(crc6_parameters{Poly, Init, RefIn, RefOut, XorOut});
  using at_compile_time = crc6<Poly, Init, RefIn, RefOut, XorOut>;
  for (int round = 0; round < 200; ++round) {
    std::uint8_t bytes[40];
    const std::size_t size = random() % sizeof bytes;
    for (std::size_t i = 0; i < size; ++i) bytes[i] = static_cast<std::uint8_t>(random());
    const trionet::byte_view view(bytes, size);
    ASSERT_EQ(at_run_time.compute(view), at_compile_time::compute(view)) << int(Poly) << " " << size;
    auto reg = at_run_time.begin();  // incremental, as the transmission parser feeds it
    for (std::uint8_t byte : view) reg = at_run_time.update(reg, byte);
    ASSERT_EQ(at_run_time.finish(reg), at_compile_time::compute(view));
  }
}

TEST(GeniusCrc6Runtime, AgreesWithTheCompileTimeCrcOnRandomInput) {
  trionet::test::rng random(66);
  expect_same_as_compile_time<0x03, 0x00, true, true, 0x00>(random);
  expect_same_as_compile_time<0x27, 0x3f, false, false, 0x00>(random);
  expect_same_as_compile_time<0x2f, 0x15, false, true, 0x2a>(random);
  expect_same_as_compile_time<0x19, 0x21, true, false, 0x3f>(random);
}

}  // namespace
