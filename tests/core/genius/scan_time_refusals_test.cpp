// GE's scan-time formula refuses what it has no figure for (genius/scan_time.hpp): more devices than the rate
// allows gives nothing but the reason, and a rate outside the four has no published terms.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include <trionet/genius/scan_time.hpp>

namespace {

using namespace trionet::genius;

TEST(GeniusScanTimeRefusals, TooManyDevicesCarriesNoFigures) {
  const std::vector<std::uint32_t> seventeen(17, 8);
  const scan_time_result r =
      bus_scan_time(rate::baud_38k4, trionet::span<const std::uint32_t>(seventeen.data(), seventeen.size()));
  EXPECT_FALSE(r);
  EXPECT_EQ(r.status, scan_time_status::too_many_devices);
  EXPECT_EQ(r.sum_ns, 0U);
  EXPECT_EQ(r.scan_ns, 0U);
  EXPECT_EQ(r.io_bytes, 0U);
  EXPECT_EQ(r.devices, 0U);
  const scan_time_result sixteen =
      bus_scan_time(rate::baud_38k4, trionet::span<const std::uint32_t>(seventeen.data(), 16));
  EXPECT_TRUE(sixteen);
  EXPECT_EQ(sixteen.devices, 16U);
  EXPECT_EQ(sixteen.io_bytes, 128U);
}

TEST(GeniusScanTimeRefusals, ARateOutsideTheFourHasNoTerms) {
  const scan_time_terms none = published_scan_time_terms(static_cast<rate>(9));
  EXPECT_EQ(none.fixed_ns, 0U);
  EXPECT_EQ(none.per_byte_ns, 0U);
  EXPECT_EQ(device_scan_time_ns(static_cast<rate>(9), 100), 0U);
}

}  // namespace
