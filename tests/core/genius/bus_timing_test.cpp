// The timing parameters of a Genius bus (docs/protocol.md 3.3): what a `bus_timing` holds before it is filled
// in, and which values the analysis refuses (`bad_timing`) before it computes anything.
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <vector>

#include <trionet/genius/bus_access.hpp>

namespace {

using namespace trionet::genius;

constexpr double infinity = std::numeric_limits<double>::infinity();
constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

// Three devices side by side: only the skip time separates their turns.
const std::vector<device_position> side_by_side = {{4, 0}, {5, 0}, {6, 0}};

layout_status checked(const bus_timing& timing) {
  return analyse_turns({side_by_side.data(), side_by_side.size()}, timing, 4).status;
}

TEST(GeniusBusTiming, ADefaultConstructedTimingIsRefusedUntilFilledIn) {
  const bus_timing timing{};
  EXPECT_EQ(timing.bus_rate, rate::standard_153k6);
  EXPECT_EQ(timing.bit_time_us, 0.0);
  EXPECT_EQ(timing.skip_us, 0.0);
  EXPECT_EQ(timing.propagation_us_per_2000ft, 3.0) << "docs/protocol.md 3.3: 3 us per 2000 ft";
  EXPECT_EQ(timing.detection_us, 0.0);
  EXPECT_EQ(checked(timing), layout_status::bad_timing) << "no bit time and no skip time";
  EXPECT_EQ(simulate_scan({side_by_side.data(), side_by_side.size()}, timing, 4).status,
            layout_status::bad_timing);
}

TEST(GeniusBusTiming, EachParameterOutOfItsRangeIsBadTiming) {
  const bus_timing good = default_timing(rate::standard_153k6);
  ASSERT_EQ(checked(good), layout_status::ok);
  for (double bad : {0.0, -1.0, infinity, not_a_number}) {
    bus_timing t = good;
    t.skip_us = bad;
    EXPECT_EQ(checked(t), layout_status::bad_timing) << "skip " << bad;
    t = good;
    t.bit_time_us = bad;
    EXPECT_EQ(checked(t), layout_status::bad_timing) << "bit time " << bad;
  }
  for (double bad : {-0.001, infinity, not_a_number}) {
    bus_timing t = good;
    t.propagation_us_per_2000ft = bad;
    EXPECT_EQ(checked(t), layout_status::bad_timing) << "propagation " << bad;
    t = good;
    t.detection_us = bad;
    EXPECT_EQ(checked(t), layout_status::bad_timing) << "detection " << bad;
  }
  bus_timing instant = good;  // a bus with no delay and a receiver that needs no time are limits, not errors
  instant.propagation_us_per_2000ft = 0;
  instant.detection_us = 0;
  EXPECT_EQ(checked(instant), layout_status::ok);
}

// A timing filled in field by field has no detection time unless it is given one: a margin of half a
// microsecond is then no collision risk.
TEST(GeniusBusTiming, ATimingFilledInByHandDetectsInstantly) {
  bus_timing timing;
  timing.bit_time_us = 6.5;
  timing.skip_us = 0.5;
  const turn_analysis a = analyse_turns({side_by_side.data(), side_by_side.size()}, timing, 4);
  ASSERT_EQ(a.status, layout_status::ok);
  ASSERT_EQ(a.margin_count, 1U);
  EXPECT_DOUBLE_EQ(a.margins[0].margin_us, 0.5);
  EXPECT_FALSE(a.margins[0].too_small);
  EXPECT_EQ(a.too_small_count, 0U);
  timing.detection_us = 0.6;
  EXPECT_TRUE(analyse_turns({side_by_side.data(), side_by_side.size()}, timing, 4).margins[0].too_small);
}

}  // namespace
