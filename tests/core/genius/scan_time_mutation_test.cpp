// GE's printed scan-time table (genius/scan_time.hpp, GFK-0825F): one row of figures per byte count it lists,
// five of them, and the formula rounded next to each printed cell.
#include <gtest/gtest.h>

#include <cstdint>
#include <iterator>

#include "trionet/genius/scan_time.hpp"

namespace {

using namespace trionet::genius;

static_assert(std::size(published_table_bytes) == 5, "GE prints 16, 32, 64, 128 and 256 bytes");
static_assert(std::size(published_table_bytes) == std::size(published_table_centi_ms),
              "one row of the table per byte count");

TEST(GeniusScanTimeTable, EveryRowHasItsByteCountAndTheFormulaIsWithinAFewHundredths) {
  const std::uint32_t expected[] = {16, 32, 64, 128, 256};
  for (std::size_t row = 0; row < std::size(published_table_bytes); ++row) {
    EXPECT_EQ(published_table_bytes[row], expected[row]);
    EXPECT_NEAR(static_cast<double>(formula_centi_ms(rate::standard_153k6, published_table_bytes[row])),
                static_cast<double>(published_table_centi_ms[row][0]), 2.0)
        << published_table_bytes[row];
  }
}

}  // namespace
