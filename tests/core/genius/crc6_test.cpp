// CRC-6 policy (docs/protocol.md 3.2): default CRC-6/G-704, configurable parameters.
#include <gtest/gtest.h>

#include <random>

#include <trionet/genius/crc6.hpp>

#include "support/rng.hpp"

namespace {

using trionet::test::rng;

using namespace trionet::genius;

constexpr std::uint8_t check_input[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};

TEST(GeniusCrc6, G704CheckValueIs0x06) {
  static_assert(crc6_g704::compute(trionet::byte_view(check_input)) == 0x06, "computed at compile time");
  EXPECT_EQ(crc6_g704::compute(check_input), 0x06);
  EXPECT_EQ(crc6_g704_bitwise::compute(check_input), 0x06);
}

// Check values of the other CRC-6 models in the reveng catalogue exercise the non-default parameter paths
// (non-reflected, non-zero init, xorout).
TEST(GeniusCrc6, OtherCatalogueModelsMatchTheirCheckValues) {
  EXPECT_EQ((crc6<0x19, 0x00, true, true, 0x00>::compute(check_input)), 0x26);    // CRC-6/DARC
  EXPECT_EQ((crc6<0x27, 0x3f, false, false, 0x00>::compute(check_input)), 0x0d);  // CRC-6/CDMA2000-A
  EXPECT_EQ((crc6<0x07, 0x3f, false, false, 0x00>::compute(check_input)), 0x3b);  // CRC-6/CDMA2000-B
  EXPECT_EQ((crc6<0x2f, 0x00, false, false, 0x3f>::compute(check_input)), 0x13);  // CRC-6/GSM
  EXPECT_EQ((crc6<0x2f, 0x00, false, false, 0x3f, false>::compute(check_input)), 0x13);
}

TEST(GeniusCrc6, TableAndBitwiseAgreeOnRandomInput) {
  rng random(6);
  for (int round = 0; round < 500; ++round) {
    std::uint8_t bytes[64];
    const std::size_t size = random() % sizeof bytes;
    for (std::size_t i = 0; i < size; ++i) bytes[i] = static_cast<std::uint8_t>(random());
    const trionet::byte_view view(bytes, size);
    const std::uint8_t crc = crc6_g704::compute(view);
    EXPECT_LT(crc, 64);
    EXPECT_EQ(crc, crc6_g704_bitwise::compute(view));
    EXPECT_EQ((crc6<0x27, 0x3f, false, false, 0>::compute(view)),
              (crc6<0x27, 0x3f, false, false, 0, false>::compute(view)));
  }
}

TEST(GeniusCrc6, IncrementalEqualsOneShotAndDetectsEverySingleBitError) {
  const std::uint8_t message[] = {0x07, 0x11, 0x22, 0xaa, 0xbb, 0x33};
  auto reg = crc6_g704::begin();
  for (std::uint8_t byte : message) reg = crc6_g704::update(reg, byte);
  const std::uint8_t crc = crc6_g704::finish(reg);
  EXPECT_EQ(crc, crc6_g704::compute(message));
  for (std::size_t i = 0; i < sizeof message; ++i) {
    for (int bit = 0; bit < 8; ++bit) {
      std::uint8_t corrupted[sizeof message];
      for (std::size_t k = 0; k < sizeof message; ++k) corrupted[k] = message[k];
      corrupted[i] = static_cast<std::uint8_t>(corrupted[i] ^ (1u << bit));
      EXPECT_NE(crc6_g704::compute(corrupted), crc) << i << " " << bit;
    }
  }
}

TEST(GeniusCrc6, EmptyInputIsInitThroughTheOutputStage) {
  EXPECT_EQ(crc6_g704::compute(trionet::byte_view()), 0x00);
  EXPECT_EQ((crc6<0x2f, 0x00, false, false, 0x3f>::compute(trionet::byte_view())), 0x3f);
}

}  // namespace
