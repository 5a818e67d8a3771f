// A keypad's display as it starts (ring/keypad_display.hpp): clear, the cursor home and shown until a
// character 14 hides it; a keypad's own display starts so too. And 127, the one printable-range code it
// ignores.
#include <gtest/gtest.h>

#include <string>

#include "trionet/ring.hpp"

namespace {

namespace ring = trionet::ring;

TEST(RingStartingValues, ADisplayStartsClearWithTheCursorHomeAndShown) {
  const ring::keypad_display display;
  EXPECT_EQ(std::string(display.line(0)), std::string(20, ' '));
  EXPECT_EQ(std::string(display.line(1)), std::string(20, ' '));
  EXPECT_EQ(display.cursor(), 0U);
  EXPECT_TRUE(display.cursor_visible());
  const ring::keypad<> keypad;
  EXPECT_TRUE(keypad.display().cursor_visible());
  EXPECT_EQ(keypad.display().cursor(), 0U);
}

TEST(RingKeypadDisplay, FourteenHidesTheCursorFifteenShowsItAndAClearLeavesItAsItWas) {
  ring::keypad_display display;
  display.write(14);
  EXPECT_FALSE(display.cursor_visible());
  display.write(12);
  EXPECT_FALSE(display.cursor_visible()) << "12 clears the text and homes the cursor, nothing more";
  display.write(15);
  EXPECT_TRUE(display.cursor_visible());
}

TEST(RingKeypadDisplay, OneHundredTwentySevenIsIgnoredOneHundredTwentySixIsWritten) {
  ring::keypad_display display;
  display.write(127);  // DEL: "other < 32 and 127: ignored"
  EXPECT_EQ(display.cursor(), 0U);
  EXPECT_EQ(std::string(display.line(0)), std::string(20, ' '));
  display.write(126);  // '~', the last character written
  EXPECT_EQ(display.cursor(), 1U);
  EXPECT_EQ(std::string(display.line(0)), "~" + std::string(19, ' '));
}

}  // namespace
