// Genius scan time (docs/protocol.md 3.3): GE's published figures (GFK-0825F) reproduced exactly, per device
// and summed over a bus, at all four rates. Expected values are worked by hand in milliseconds.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include <trionet/genius/scan_time.hpp>

namespace {

using namespace trionet::genius;
using trionet::span;

span<const std::uint32_t> view(const std::vector<std::uint32_t>& bytes) {
  return {bytes.data(), bytes.size()};
}

// Compile-time use: no floating point, exact.
static_assert(device_scan_time_ns(rate::standard_153k6, 16) == 2087000);
static_assert(bus_scan_time(rate::baud_38k4, span<const std::uint32_t>{}).sum_ns == 0);
static_assert(bus_scan_time(rate::baud_38k4, span<const std::uint32_t>{}).scan_ns == 3000000);

TEST(GeniusScanTime, PublishedTermsAreGesFigures) {
  // 0.943 + 0.0715 n, 1.015 + 0.0715 n, 1.538 + 0.143 n, 2.583 + 0.286 n (ms).
  EXPECT_EQ(published_scan_time_terms(rate::standard_153k6).fixed_ns, 943000u);
  EXPECT_EQ(published_scan_time_terms(rate::standard_153k6).per_byte_ns, 71500u);
  EXPECT_EQ(published_scan_time_terms(rate::extended_153k6).fixed_ns, 1015000u);
  EXPECT_EQ(published_scan_time_terms(rate::extended_153k6).per_byte_ns, 71500u);
  EXPECT_EQ(published_scan_time_terms(rate::baud_76k8).fixed_ns, 1538000u);
  EXPECT_EQ(published_scan_time_terms(rate::baud_76k8).per_byte_ns, 143000u);
  EXPECT_EQ(published_scan_time_terms(rate::baud_38k4).fixed_ns, 2583000u);
  EXPECT_EQ(published_scan_time_terms(rate::baud_38k4).per_byte_ns, 286000u);
}

TEST(GeniusScanTime, OneDeviceAtEveryRate) {
  const struct {
    rate r;
    std::uint32_t bytes;
    std::uint64_t ns;
  } cases[] = {
      {rate::standard_153k6, 0, 943000},     // 0.943 ms
      {rate::standard_153k6, 1, 1014500},    // 0.943 + 0.0715 = 1.0145 ms
      {rate::standard_153k6, 16, 2087000},   // 0.943 + 1.144 = 2.087 ms
      {rate::standard_153k6, 128, 10095000}, // 0.943 + 9.152 = 10.095 ms
      {rate::extended_153k6, 0, 1015000},
      {rate::extended_153k6, 1, 1086500},    // 1.0865 ms
      {rate::extended_153k6, 16, 2159000},   // 1.015 + 1.144
      {rate::extended_153k6, 128, 10167000}, // 1.015 + 9.152
      {rate::baud_76k8, 0, 1538000},
      {rate::baud_76k8, 1, 1681000},         // 1.538 + 0.143
      {rate::baud_76k8, 16, 3826000},        // 1.538 + 2.288
      {rate::baud_76k8, 128, 19842000},      // 1.538 + 18.304
      {rate::baud_38k4, 0, 2583000},
      {rate::baud_38k4, 1, 2869000},         // 2.583 + 0.286
      {rate::baud_38k4, 16, 7159000},        // 2.583 + 4.576
      {rate::baud_38k4, 128, 39191000},      // 2.583 + 36.608
  };
  for (const auto& c : cases) {
    EXPECT_EQ(device_scan_time_ns(c.r, c.bytes), c.ns) << properties(c.r).name << " " << c.bytes << " bytes";
  }
}

// The per-byte term is GE's figure, not the computed character time: at 38.4 kbaud a device with 256 bytes
// contributes 2.583 + 73.216 = 75.799 ms (one character time per byte would give 75.92 ms).
TEST(GeniusScanTime, PerByteTermIsGesFigureNotTheCharacterTime) {
  EXPECT_EQ(device_scan_time_ns(rate::baud_38k4, 256), 75799000u);
  EXPECT_NEAR(character_time_us(rate::baud_38k4), 286.458, 0.001);
  EXPECT_NEAR(character_time_us(rate::standard_153k6), 71.615, 0.001);
  EXPECT_NEAR(character_time_us(rate::baud_76k8), 143.229, 0.001);
}

TEST(GeniusScanTime, BusTotalIsTheSumOverItsDevices) {
  const std::vector<std::uint32_t> bytes = {16, 8, 4};
  const struct {
    rate r;
    std::uint64_t ns;
  } cases[] = {
      {rate::standard_153k6, 4831000},  // 3 x 0.943 + 28 x 0.0715 = 2.829 + 2.002
      {rate::extended_153k6, 5047000},  // 3 x 1.015 + 28 x 0.0715 = 3.045 + 2.002
      {rate::baud_76k8, 8618000},       // 3 x 1.538 + 28 x 0.143 = 4.614 + 4.004
      {rate::baud_38k4, 15757000},      // 3 x 2.583 + 28 x 0.286 = 7.749 + 8.008
  };
  for (const auto& c : cases) {
    const scan_time_result bus = bus_scan_time(c.r, view(bytes));
    ASSERT_TRUE(bus) << properties(c.r).name;
    EXPECT_EQ(bus.sum_ns, c.ns) << properties(c.r).name;
    EXPECT_EQ(bus.scan_ns, c.ns) << properties(c.r).name;  // above the 3 ms minimum
    EXPECT_FALSE(bus.minimum_applies);
    EXPECT_EQ(bus.io_bytes, 28u);
    EXPECT_EQ(bus.devices, 3u);
    EXPECT_EQ(bus.sum_ns, device_scan_time_ns(c.r, 16) + device_scan_time_ns(c.r, 8) +
                              device_scan_time_ns(c.r, 4));
  }
}

TEST(GeniusScanTime, FullBusesAreExact) {
  // 32 devices of 128 bytes at 153.6s: 32 x 0.943 + 4096 x 0.0715 = 30.176 + 292.864 = 323.04 ms.
  const scan_time_result full = bus_scan_time(rate::standard_153k6, view(std::vector<std::uint32_t>(32, 128)));
  ASSERT_TRUE(full);
  EXPECT_EQ(full.sum_ns, 323040000u);
  EXPECT_EQ(full.scan_ns, 323040000u);
  // 16 devices of 128 bytes at 38.4: 16 x 2.583 + 2048 x 0.286 = 41.328 + 585.728 = 627.056 ms.
  const scan_time_result slow = bus_scan_time(rate::baud_38k4, view(std::vector<std::uint32_t>(16, 128)));
  ASSERT_TRUE(slow);
  EXPECT_EQ(slow.sum_ns, 627056000u);
  // The largest device count does not overflow: 4294967295 bytes x 0.286 ms + 2.583 ms, exactly.
  EXPECT_EQ(device_scan_time_ns(rate::baud_38k4, 4294967295u), 2583000u + 286000ull * 4294967295ull);
}

TEST(GeniusScanTime, MoreDevicesThanTheRateAllowsIsMisuse) {
  const scan_time_result too_many = bus_scan_time(rate::standard_153k6, view(std::vector<std::uint32_t>(33, 1)));
  EXPECT_FALSE(too_many);
  EXPECT_EQ(too_many.status, scan_time_status::too_many_devices);
  EXPECT_EQ(too_many.sum_ns, 0u);
  EXPECT_EQ(too_many.scan_ns, 0u);
  EXPECT_EQ(bus_scan_time(rate::baud_38k4, view(std::vector<std::uint32_t>(17, 1))).status,
            scan_time_status::too_many_devices);
  EXPECT_TRUE(bus_scan_time(rate::baud_38k4, view(std::vector<std::uint32_t>(16, 1))));
  const scan_time_result empty = bus_scan_time(rate::baud_76k8, view({}));
  EXPECT_TRUE(empty);
  EXPECT_EQ(empty.sum_ns, 0u);
  EXPECT_EQ(empty.devices, 0u);
  EXPECT_STREQ(to_string(scan_time_status::ok), "ok");
  EXPECT_STREQ(to_string(scan_time_status::too_many_devices), "too_many_devices");
}

TEST(GeniusScanTime, ABusControllerNeverLetsAScanBeShorterThan3Ms) {
  // One device of 16 bytes at 153.6s: GE's figure is 2.087 ms; the scan is 3 ms.
  const std::vector<std::uint32_t> one = {16};
  const scan_time_result bus = bus_scan_time(rate::standard_153k6, view(one));
  EXPECT_EQ(bus.sum_ns, 2087000u);
  EXPECT_EQ(bus.scan_ns, 3000000u);
  EXPECT_TRUE(bus.minimum_applies);
  // Exactly at the minimum it does not apply; the minimum is a parameter, 0 for none.
  const std::vector<std::uint32_t> exact = {29, 0};  // 0.943 + 2.0735 + 0.943 > 3; below: 0.943 + 0.943 + n x 0.0715
  EXPECT_FALSE(bus_scan_time(rate::standard_153k6, view(exact)).minimum_applies);
  const scan_time_result none = bus_scan_time(rate::standard_153k6, view(one), 0);
  EXPECT_EQ(none.scan_ns, 2087000u);
  EXPECT_FALSE(none.minimum_applies);
  const scan_time_result five = bus_scan_time(rate::standard_153k6, view(one), 5000000);
  EXPECT_EQ(five.scan_ns, 5000000u);
  const std::vector<std::uint32_t> two = {16, 0};  // 2.087 + 0.943 = 3.030 ms
  EXPECT_FALSE(bus_scan_time(rate::standard_153k6, view(two)).minimum_applies);
  EXPECT_EQ(bus_scan_time(rate::standard_153k6, view(two)).scan_ns, 3030000u);
}

// GE's printed table (GFK-0825F) against GE's own formula: six cells are not the formula rounded to
// 0.01 ms, and no linear formula could give them all (docs/genius.md lists them).
TEST(GeniusScanTime, GesPrintedTableDiffersFromItsFormulaInSixCells) {
  constexpr rate rates[] = {rate::standard_153k6, rate::extended_153k6, rate::baud_76k8, rate::baud_38k4};
  std::vector<std::string> differ;
  for (std::size_t row = 0; row < 5; ++row) {
    for (std::size_t col = 0; col < 4; ++col) {
      const std::uint32_t bytes = published_table_bytes[row];
      const std::uint64_t printed = published_table_centi_ms[row][col];
      if (formula_centi_ms(rates[col], bytes) == printed) continue;
      differ.push_back(std::to_string(bytes) + "@" + properties(rates[col]).name);
      // Never by more than 0.01 ms.
      const std::uint64_t formula_ns = device_scan_time_ns(rates[col], bytes);
      const std::uint64_t printed_ns = printed * 10000u;
      EXPECT_LT(printed_ns > formula_ns ? printed_ns - formula_ns : formula_ns - printed_ns, 10000u);
    }
  }
  EXPECT_EQ(differ, (std::vector<std::string>{"32@153.6s", "32@153.6e", "32@76.8", "64@153.6e", "128@76.8",
                                              "128@38.4"}));
  // The example docs/protocol.md gives: 32 bytes at 153.6s, table 3.24, formula 3.231.
  EXPECT_EQ(device_scan_time_ns(rate::standard_153k6, 32), 3231000u);
  EXPECT_EQ(published_table_centi_ms[1][0], 324u);
}

}  // namespace
