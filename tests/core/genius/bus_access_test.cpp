// Genius bus access (docs/protocol.md 3.3): rates, turn timing, margins and the bus scan.
#include <gtest/gtest.h>

#include <vector>

#include <trionet/genius/bus_access.hpp>

namespace {

using namespace trionet::genius;
using trionet::span;

span<const device_position> view(const std::vector<device_position>& devices) {
  return {devices.data(), devices.size()};
}

// GE's worked example (GFK-1535A): SBA 4 and 6 at one end of a 2000 ft bus, SBA 5 at the other, 153.6 kbaud standard.
const std::vector<device_position> seed_layout = {{4, 0}, {5, 2000}, {6, 0}};

TEST(GeniusSeedWorkedExample, Skip26usGivesSba5At29Sba6At52Margin20) {
  bus_timing timing = default_timing(rate::standard_153k6);
  timing.skip_us = 26;
  const turn_analysis a = analyse_turns(view(seed_layout), timing, 4);
  ASSERT_EQ(a.status, layout_status::ok);
  ASSERT_EQ(a.turn_count, 2u);
  EXPECT_EQ(a.turns[0].sba, 5);
  EXPECT_DOUBLE_EQ(a.turns[0].start_us, 29.0);  // "SBA 5 will start transmitting 29 uSec after SBA 4 quit"
  EXPECT_EQ(a.turns[1].sba, 6);
  EXPECT_DOUBLE_EQ(a.turns[1].start_us, 52.0);  // "2 skip times (52 uSec)"
  ASSERT_EQ(a.margin_count, 1u);
  EXPECT_EQ(a.margins[0].first, 5);
  EXPECT_EQ(a.margins[0].second, 6);
  EXPECT_DOUBLE_EQ(a.margins[0].margin_us, 20.0);  // "leaves only 20 uSec"
  EXPECT_FALSE(a.margins[0].too_small);
  EXPECT_EQ(a.too_small_count, 0u);
  EXPECT_DOUBLE_EQ(a.bus_length_ft, 2000.0);
  EXPECT_FALSE(a.longer_than_rate_allows);
}

TEST(GeniusSeedWorkedExample, RuleSkipTimeLeavesAboutHalfAMicrosecondAndIsFlagged) {
  const bus_timing timing = default_timing(rate::standard_153k6);
  EXPECT_NEAR(timing.skip_us, 6.51, 0.005);
  const turn_analysis a = analyse_turns(view(seed_layout), timing, 4);
  ASSERT_EQ(a.status, layout_status::ok);
  ASSERT_EQ(a.turn_count, 2u);
  EXPECT_NEAR(a.turns[0].start_us, 3.0 + 6.51, 0.01);
  EXPECT_NEAR(a.turns[1].start_us, 2 * 6.51, 0.01);
  ASSERT_EQ(a.margin_count, 1u);
  EXPECT_NEAR(a.margins[0].margin_us, 0.51, 0.01);
  EXPECT_TRUE(a.margins[0].too_small);
  EXPECT_EQ(a.too_small_count, 1u);
}

TEST(GeniusSeedWorkedExample, DetectionTimeIsConfigurable) {
  bus_timing timing = default_timing(rate::standard_153k6);
  timing.skip_us = 26;
  timing.detection_us = 20.5;
  EXPECT_TRUE(analyse_turns(view(seed_layout), timing, 4).margins[0].too_small);
  timing.detection_us = 20.0;  // a margin equal to the detection time is enough
  EXPECT_FALSE(analyse_turns(view(seed_layout), timing, 4).margins[0].too_small);
}

TEST(GeniusSeedWorkedExample, PropagationDelayIsConfigurable) {
  bus_timing timing = default_timing(rate::standard_153k6);
  timing.skip_us = 26;
  timing.propagation_us_per_2000ft = 4;
  const turn_analysis a = analyse_turns(view(seed_layout), timing, 4);
  EXPECT_DOUBLE_EQ(a.turns[0].start_us, 30.0);
  EXPECT_DOUBLE_EQ(a.margins[0].margin_us, 52.0 - 30.0 - 4.0);
}

TEST(GeniusRates, TableOfProtocolSection33) {
  struct row {
    rate r;
    const char* name;
    double bit_time_us;
    double skip_bits;
    unsigned max_ft;
    unsigned max_devices;
  };
  const row rows[] = {{rate::standard_153k6, "153.6s", 6.51, 1, 2000, 32},
                      {rate::extended_153k6, "153.6e", 6.51, 2, 3500, 32},
                      {rate::baud_76k8, "76.8", 13.02, 1, 4500, 32},
                      {rate::baud_38k4, "38.4", 26.04, 1, 7500, 16}};
  for (const row& x : rows) {
    EXPECT_STREQ(properties(x.r).name, x.name);
    EXPECT_NEAR(bit_time_us(x.r), x.bit_time_us, 0.005) << x.name;
    EXPECT_NEAR(rule_skip_us(x.r), x.skip_bits * x.bit_time_us, 0.01) << x.name;
    EXPECT_EQ(properties(x.r).max_length_ft, x.max_ft);
    EXPECT_EQ(properties(x.r).max_devices, x.max_devices);
    rate parsed{};
    ASSERT_TRUE(rate_from_name(x.name, parsed));
    EXPECT_EQ(parsed, x.r);
  }
  rate parsed{};
  EXPECT_FALSE(rate_from_name("153.6", parsed));
  EXPECT_FALSE(rate_from_name("", parsed));
}

TEST(GeniusTurns, OrderWrapsRoundSba31) {
  const std::vector<device_position> devices = {{2, 0}, {30, 0}, {0, 0}, {31, 0}};
  const turn_analysis a = analyse_turns(view(devices), default_timing(rate::baud_76k8), 30);
  ASSERT_EQ(a.turn_count, 3u);
  const double skip = rule_skip_us(rate::baud_76k8);
  EXPECT_EQ(a.turns[0].sba, 31);
  EXPECT_DOUBLE_EQ(a.turns[0].start_us, 1 * skip);
  EXPECT_EQ(a.turns[1].sba, 0);
  EXPECT_DOUBLE_EQ(a.turns[1].start_us, 2 * skip);
  EXPECT_EQ(a.turns[2].sba, 2);
  EXPECT_DOUBLE_EQ(a.turns[2].start_us, 4 * skip);  // unused SBA 1 lengthens the gap
  EXPECT_DOUBLE_EQ(a.margins[1].margin_us, 2 * skip);
}

TEST(GeniusTurns, LayoutErrors) {
  const bus_timing timing = default_timing(rate::standard_153k6);
  EXPECT_EQ(analyse_turns(view({{4, 0}, {4, 10}}), timing, 4).status, layout_status::duplicate_sba);
  EXPECT_EQ(analyse_turns(view({{4, 0}, {32, 10}}), timing, 4).status, layout_status::sba_out_of_range);
  EXPECT_EQ(analyse_turns(view({{4, 0}, {5, 10}}), timing, 6).status, layout_status::sender_not_on_bus);
  EXPECT_EQ(analyse_turns(view({{4, 0}, {5, -1}}), timing, 4).status, layout_status::bad_position);
  bus_timing bad = timing;
  bad.skip_us = 0;
  EXPECT_EQ(analyse_turns(view(seed_layout), bad, 4).status, layout_status::bad_timing);
  bad = timing;
  bad.propagation_us_per_2000ft = -1;
  EXPECT_EQ(analyse_turns(view(seed_layout), bad, 4).status, layout_status::bad_timing);
  EXPECT_EQ(simulate_scan(view({{4, 0}, {4, 10}}), timing, 4).status, layout_status::duplicate_sba);
}

TEST(GeniusTurns, RateLimitsAreReported) {
  EXPECT_TRUE(analyse_turns(view({{1, 0}, {2, 2500}}), default_timing(rate::standard_153k6), 1)
                  .longer_than_rate_allows);
  EXPECT_FALSE(analyse_turns(view({{1, 0}, {2, 2500}}), default_timing(rate::extended_153k6), 1)
                   .longer_than_rate_allows);
  std::vector<device_position> many;
  for (std::uint8_t sba = 0; sba < 17; ++sba) many.push_back({sba, 0});
  EXPECT_TRUE(analyse_turns(view(many), default_timing(rate::baud_38k4), 0).more_devices_than_rate_allows);
  EXPECT_FALSE(analyse_turns(view(many), default_timing(rate::baud_76k8), 0).more_devices_than_rate_allows);
}

bool has_collision(const bus_scan& scan) {
  for (std::size_t i = 0; i < scan.count; ++i) {
    if (scan.transmissions[i].collided) return true;
  }
  return false;
}

std::vector<std::uint8_t> order_of(const bus_scan& scan) {
  std::vector<std::uint8_t> order;
  for (std::size_t i = 0; i < scan.count; ++i) order.push_back(scan.transmissions[i].sba);
  return order;
}

TEST(GeniusBusScan, SeedLayoutCollidesAtTheRuleSkipTime) {
  const bus_scan scan = simulate_scan(view(seed_layout), default_timing(rate::standard_153k6), 4);
  ASSERT_EQ(scan.status, layout_status::ok);
  EXPECT_EQ(scan.collisions, 1u);
  ASSERT_GE(scan.count, 2u);
  EXPECT_EQ(scan.transmissions[0].sba, 5);
  EXPECT_TRUE(scan.transmissions[0].collided);
  EXPECT_EQ(scan.transmissions[1].sba, 6);
  EXPECT_TRUE(scan.transmissions[1].collided);
  EXPECT_TRUE(scan.complete);
}

TEST(GeniusBusScan, ResequencingSbasAlongTheBusRemovesTheCollision) {
  // Same devices and cable, SBAs now in order along the bus: 4 and 5 at one end, 6 at the other.
  const std::vector<device_position> resequenced = {{4, 0}, {5, 0}, {6, 2000}};
  const bus_scan scan = simulate_scan(view(resequenced), default_timing(rate::standard_153k6), 4);
  ASSERT_EQ(scan.status, layout_status::ok);
  EXPECT_EQ(scan.collisions, 0u);
  EXPECT_FALSE(has_collision(scan));
  EXPECT_EQ(order_of(scan), (std::vector<std::uint8_t>{5, 6, 4}));
  EXPECT_TRUE(scan.complete);
  const turn_analysis a = analyse_turns(view(resequenced), default_timing(rate::standard_153k6), 4);
  EXPECT_EQ(a.too_small_count, 0u);
}

TEST(GeniusBusScan, TheSeedsOtherFixesAlsoWork) {
  // Skipping an SBA: 6 becomes 7.
  EXPECT_EQ(
      simulate_scan(view({{4, 0}, {5, 2000}, {7, 0}}), default_timing(rate::standard_153k6), 4).collisions,
      0u);
  // 153.6 extended (two-bit skip) or a lower rate.
  EXPECT_EQ(simulate_scan(view(seed_layout), default_timing(rate::extended_153k6), 4).collisions, 0u);
  EXPECT_EQ(simulate_scan(view(seed_layout), default_timing(rate::baud_76k8), 4).collisions, 0u);
  // And GE's own 26 us skip time.
  bus_timing timing = default_timing(rate::standard_153k6);
  timing.skip_us = 26;
  EXPECT_EQ(simulate_scan(view(seed_layout), timing, 4).collisions, 0u);
}

TEST(GeniusBusScan, ColocatedDevicesTakeTurnsInSbaOrder) {
  std::vector<device_position> devices = {{9, 100}, {1, 100}, {3, 100}, {20, 100}};
  devices[2].data_bytes = 4;
  const bus_timing timing = default_timing(rate::baud_38k4);
  const bus_scan scan = simulate_scan(view(devices), timing, 3);
  ASSERT_EQ(scan.status, layout_status::ok);
  EXPECT_EQ(order_of(scan), (std::vector<std::uint8_t>{9, 20, 1, 3}));
  EXPECT_FALSE(has_collision(scan));
  EXPECT_TRUE(scan.complete);
  const double character = character_time_us(rate::baud_38k4);
  // SBA 9 waits 6 skips after the Stop of SBA 3; its transmission is Start, 1 data byte, Stop.
  EXPECT_DOUBLE_EQ(scan.transmissions[0].start_us, 6 * timing.skip_us);
  EXPECT_DOUBLE_EQ(scan.transmissions[0].end_us, scan.transmissions[0].start_us + 3 * character);
  EXPECT_DOUBLE_EQ(scan.transmissions[1].start_us, scan.transmissions[0].end_us + 11 * timing.skip_us);
  // SBA 3 has 4 data bytes.
  EXPECT_DOUBLE_EQ(scan.transmissions[3].end_us - scan.transmissions[3].start_us, 6 * character);
}

TEST(GeniusBusScan, LoneDeviceHasNoTurns) {
  const bus_scan scan = simulate_scan(view({{4, 0}}), default_timing(rate::standard_153k6), 4);
  EXPECT_EQ(scan.status, layout_status::ok);
  EXPECT_EQ(scan.count, 0u);
}

}  // namespace
