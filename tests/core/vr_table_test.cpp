// VR(): network values, the ready-made tables and their write policies.
#include <gtest/gtest.h>

#include <cstdint>

#include "trionet/vr.hpp"

using trionet::network_value;
using trionet::vr_table;
using trionet::vr_write_status;

namespace {
// The Q32.32 value of `v` in `raw`; false when it has none.
bool to_q32(const network_value& v, std::int64_t& raw) {
  const trionet::q32_result q = v.to_q32();
  raw = q.raw;
  return static_cast<bool>(q);
}
}  // namespace

TEST(VrNetworkValue, Q32ToDoubleAndBack) {
  const auto v = network_value::from_q32(std::int64_t{99} << 32);
  EXPECT_EQ(v.to_double(), 99.0);
  std::int64_t raw = 0;
  ASSERT_TRUE(to_q32(v, raw));
  EXPECT_EQ(raw, std::int64_t{99} << 32);
  EXPECT_EQ(network_value::from_q32(-(std::int64_t{1} << 31)).to_double(), -0.5);
}

TEST(VrNetworkValue, DecimalToDoubleIsTheNearestDouble) {
  EXPECT_EQ(network_value::from_decimal(false, 2, 3450).to_double(), 2.345);
  EXPECT_EQ(network_value::from_decimal(true, 256, 5).to_double(), -256.0005);
  EXPECT_EQ(network_value::from_decimal(false, 4294967295u, 9999).to_double(), 4294967295.9999);
  EXPECT_EQ(network_value::from_decimal(false, 0, 0).to_double(), 0.0);
}

TEST(VrNetworkValue, DecimalToQ32WithIntegersOnly) {
  std::int64_t raw = 0;
  ASSERT_TRUE(to_q32(network_value::from_decimal(false, 2, 5000), raw));
  EXPECT_EQ(raw, (std::int64_t{5} << 31));  // 2.5
  ASSERT_TRUE(to_q32(network_value::from_decimal(true, 1, 2500), raw));
  EXPECT_EQ(raw, -(std::int64_t{5} << 30));  // -1.25
  ASSERT_TRUE(to_q32(network_value::from_decimal(false, 0, 1), raw));
  EXPECT_EQ(raw, 429497);  // 2^32 / 10000 = 429496.7296 -> 429497
  // The Q32.32 range: [-2^31, 2^31 - 2^-32].
  ASSERT_TRUE(to_q32(network_value::from_decimal(true, 2147483648u, 0), raw));
  EXPECT_EQ(raw, INT64_MIN);
  EXPECT_FALSE(to_q32(network_value::from_decimal(false, 2147483648u, 0), raw));
  EXPECT_FALSE(to_q32(network_value::from_decimal(true, 2147483648u, 1), raw));
  ASSERT_TRUE(to_q32(network_value::from_decimal(false, 2147483647u, 9999), raw));
  EXPECT_GT(raw, 0);
}

TEST(VrTable, DoubleTableWithPolicy) {
  static int asked = 0;
  auto even_only = [](void* context, std::uint16_t vr, double value) noexcept {
    ++*static_cast<int*>(context);
    return vr % 2 == 0 && value < 100;
  };
  vr_table<8> table(even_only, &asked);
  EXPECT_EQ(table.write(2, network_value::from_decimal(false, 7, 0)), vr_write_status::ok);
  EXPECT_EQ(table[2], 7.0);
  EXPECT_EQ(table.write(3, network_value::from_decimal(false, 7, 0)), vr_write_status::refused);
  EXPECT_EQ(table.write(4, network_value::from_decimal(false, 700, 0)), vr_write_status::refused);
  EXPECT_EQ(table.write(8, network_value::from_decimal(false, 7, 0)), vr_write_status::out_of_range);
  EXPECT_EQ(table[3], 0.0);
  EXPECT_EQ(asked, 3);  // not asked for the vr past the table
}

TEST(VrTable, Q32TableNeedsNoFloatingPoint) {
  vr_table<4, std::int64_t> table;
  EXPECT_EQ(table.write(1, network_value::from_q32(-5)), vr_write_status::ok);
  EXPECT_EQ(table[1], -5);
  EXPECT_EQ(table.write(2, network_value::from_decimal(false, 3, 0)), vr_write_status::ok);
  EXPECT_EQ(table[2], std::int64_t{3} << 32);
  EXPECT_EQ(table.write(3, network_value::from_decimal(false, 3000000000u, 0)),
            vr_write_status::value_out_of_range);
  EXPECT_EQ(table[3], 0);
  auto positive_only = [](void*, std::uint16_t, std::int64_t value) noexcept { return value >= 0; };
  vr_table<4, std::int64_t> guarded(positive_only);
  EXPECT_EQ(guarded.write(0, network_value::from_q32(-1)), vr_write_status::refused);
  EXPECT_EQ(guarded.write(0, network_value::from_q32(1)), vr_write_status::ok);
}

TEST(VrNetworkValue, DecimalFractionToQ32IsExactlyRoundedForEveryTenThousandth) {
  for (std::uint32_t t = 0; t <= 9999; ++t) {
    std::int64_t raw = 0;
    ASSERT_TRUE(to_q32(network_value::from_decimal(false, 0, static_cast<std::uint16_t>(t)), raw));
    const std::uint64_t expected = ((static_cast<std::uint64_t>(t) << 32) + 5000u) / 10000u;  // round half up
    ASSERT_EQ(static_cast<std::uint64_t>(raw), expected) << t;
  }
  std::int64_t raw = 0;
  EXPECT_FALSE(to_q32(network_value::from_decimal(false, 0, 10000), raw));
  EXPECT_EQ(network_value::from_decimal(false, 0, 10000).to_q32().status,
            trionet::q32_status::fraction_out_of_range);
  EXPECT_EQ(network_value::from_decimal(false, 2147483648u, 0).to_q32().status,
            trionet::q32_status::out_of_range);
}

// Every vr_write_status has its enumerator's spelling; a value outside the enum is "unknown".
TEST(VrTable, WriteStatusNamesAreTheEnumeratorsSpelling) {
  EXPECT_STREQ(trionet::to_string(vr_write_status::ok), "ok");
  EXPECT_STREQ(trionet::to_string(vr_write_status::refused), "refused");
  EXPECT_STREQ(trionet::to_string(vr_write_status::out_of_range), "out_of_range");
  EXPECT_STREQ(trionet::to_string(vr_write_status::value_out_of_range), "value_out_of_range");
  EXPECT_STREQ(trionet::to_string(static_cast<vr_write_status>(99)), "unknown");
}
