// Values a caller makes before anything fills them in start empty (genius/character.hpp, bus_access.hpp): a
// character is data 0, a turn, a margin, an analysis and a scan hold nothing and report nothing.
#include <gtest/gtest.h>

#include <cstdint>

#include <trionet/genius/bus_access.hpp>
#include <trionet/genius/character.hpp>

namespace {

using namespace trionet::genius;

TEST(GeniusStartingValues, ACharacterIsDataZero) {
  EXPECT_EQ(character{}, data_character(0));
  EXPECT_EQ(character{}.byte, 0);
  EXPECT_FALSE(character{}.control);
}

TEST(GeniusStartingValues, TurnsMarginsAnalysesAndScansHoldNothing) {
  const turn t{};
  EXPECT_EQ(t.sba, 0);
  EXPECT_EQ(t.position_ft, 0.0);
  EXPECT_EQ(t.start_us, 0.0);
  const turn_margin m{};
  EXPECT_EQ(m.first, 0);
  EXPECT_EQ(m.second, 0);
  EXPECT_EQ(m.margin_us, 0.0);
  EXPECT_FALSE(m.too_small);
  const turn_analysis a{};
  EXPECT_EQ(a.status, layout_status::ok);
  EXPECT_EQ(a.turn_count, 0U);
  EXPECT_EQ(a.margin_count, 0U);
  EXPECT_EQ(a.too_small_count, 0U);
  for (const turn& each : a.turns) EXPECT_EQ(each.start_us, 0.0);
  for (const turn_margin& each : a.margins) EXPECT_FALSE(each.too_small);
  EXPECT_FALSE(a.longer_than_rate_allows);
  EXPECT_FALSE(a.more_devices_than_rate_allows);
  const bus_scan s{};
  EXPECT_EQ(s.count, 0U);
  EXPECT_EQ(s.collisions, 0U);
  EXPECT_FALSE(s.complete);
  for (const scan_transmission& each : s.transmissions) EXPECT_FALSE(each.collided);
}

}  // namespace
