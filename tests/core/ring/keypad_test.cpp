// The membrane keypad (docs/protocol.md 1.7-1.9): local mode until its keypad offset arrives, key presses to the
// offset with the keypad mode's key OFF characters, the codes and names of its keys, and the display that
// character messages drive.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "support/ring_frames.hpp"
#include "trionet/ring.hpp"
#include "trionet/ring/keypad_codes.hpp"
#include "trionet/vr.hpp"

namespace ring = trionet::ring;
using trionet::byte_view;
using trionet::test::chars;
using trionet::test::drain;
using trionet::test::feed;
using trionet::test::frame_of;

// "SEND(n,2,data1): ... data1 is in the range 10..24 to specify the number of nodes from the keypad that the
// key characters are sent": sent again, it moves the keys.
TEST(RingKeypad, ASecondKeypadOffsetMovesWhereKeysGo) {
  ring::keypad<> keypad;
  feed(keypad, {ring::make_header(1, 3), 2, ring::make_end_of_message(1)});  // SEND(n,2,11): 2 hops on
  ASSERT_TRUE(keypad.network_mode());
  ASSERT_EQ(keypad.press(ring::key::digit_7), ring::key_status::ok);
  EXPECT_EQ(drain(keypad), (std::vector<std::uint8_t>{ring::make_header(2, 1), '7', ring::make_end_of_message(2)}));
  feed(keypad, {ring::make_header(1, 3), 5, ring::make_end_of_message(1)});  // SEND(n,2,14): 5 hops on
  EXPECT_EQ(keypad.offset(), 5);
  ASSERT_EQ(keypad.press(ring::key::yes), ring::key_status::ok);
  EXPECT_EQ(drain(keypad), (std::vector<std::uint8_t>{ring::make_header(5, 1), 'Y', ring::make_end_of_message(5)}));
  EXPECT_EQ(keypad.counters().frame_errors, 0u);
}

// Every key_status has its enumerator's spelling (the CLI and the traces print it).
TEST(RingKeypad, KeyStatusNamesAreTheEnumeratorsSpelling) {
  EXPECT_STREQ(trionet::ring::to_string(trionet::ring::key_status::ok), "ok");
  EXPECT_STREQ(trionet::ring::to_string(trionet::ring::key_status::nothing_to_send), "nothing_to_send");
  EXPECT_STREQ(trionet::ring::to_string(trionet::ring::key_status::local_mode), "local_mode");
  EXPECT_STREQ(trionet::ring::to_string(trionet::ring::key_status::queue_full), "queue_full");
  EXPECT_STREQ(trionet::ring::to_string(static_cast<trionet::ring::key_status>(99)), "unknown");
}

TEST(RingKeypad, LocalModeUntilItsOffsetArrives) {
  ring::keypad<> keypad;
  EXPECT_FALSE(keypad.network_mode());
  EXPECT_EQ(keypad.press(ring::key::digit_5), ring::key_status::local_mode);
  feed(keypad, chars(1, "TO ME"));    // to it: dropped
  feed(keypad, chars(2, "THROUGH"));  // through it: dropped, not forwarded
  EXPECT_FALSE(keypad.transmit_pending());
  EXPECT_TRUE(drain(keypad).empty());  // it never transmits in local mode
  EXPECT_EQ(keypad.counters().dropped_in_local_mode, 1u);
  EXPECT_EQ(keypad.forwarding_counters().messages_dropped, 1u);
  EXPECT_EQ(keypad.counters().keys_lost, 1u);

  feed(keypad, frame_of(ring::message::keypad_offset(1, 2)));
  EXPECT_TRUE(keypad.network_mode());
  EXPECT_EQ(keypad.offset(), 2);
  feed(keypad, chars(2, "THROUGH"));
  EXPECT_EQ(drain(keypad), chars(1, "THROUGH"));  // now it forwards
}

TEST(RingKeypad, KeyPressesGoToTheOffsetAndModeAddsKeyOff) {
  ring::keypad<> keypad;
  feed(keypad, frame_of(ring::message::keypad_offset(1, 3)));
  EXPECT_EQ(keypad.press(ring::key::digit_7), ring::key_status::ok);
  EXPECT_EQ(keypad.release(ring::key::digit_7), ring::key_status::nothing_to_send);  // mode 0: key ON only
  EXPECT_EQ(drain(keypad), chars(3, "7"));
  feed(keypad, frame_of(ring::message::keypad_mode(1, 127)));
  EXPECT_EQ(keypad.mode(), 127);
  EXPECT_EQ(keypad.press(ring::key::up), ring::key_status::ok);
  EXPECT_EQ(keypad.release(ring::key::up), ring::key_status::ok);
  std::vector<std::uint8_t> expected = chars(3, "U");
  const auto off = chars(3, std::string(1, static_cast<char>('U' + 64 < 128 ? 'U' + 64 : 'U')));
  expected.insert(expected.end(), off.begin(), off.end());
  EXPECT_EQ(drain(keypad), expected);
  EXPECT_EQ(ring::default_key_off_code('0'), 'p');  // 48 + 64
  EXPECT_EQ(ring::default_key_off_code('U'), 'U');  // 85 + 64 > 127: the same character
}

TEST(RingKeypad, ConfigurableCodesAndKeyOff) {
  static constexpr ring::keypad_codes codes = {
      {'a', 'b', 'c', 'd', 'e', 'f', 'g', 'h', 'i', 'j', 'k', 'l', 'm', 'n', 'o', 'p', 'q', 'r'}};
  ring::keypad_config config;
  config.codes = &codes;
  config.key_off_code = [](std::uint8_t on) noexcept { return static_cast<std::uint8_t>(on - 32); };
  ring::keypad<> keypad(config);
  feed(keypad, frame_of(ring::message::keypad_offset(1, 1)));
  feed(keypad, frame_of(ring::message::keypad_mode(1, 127)));
  ASSERT_EQ(keypad.press(ring::key::start), ring::key_status::ok);
  ASSERT_EQ(keypad.release(ring::key::start), ring::key_status::ok);
  std::vector<std::uint8_t> expected = chars(1, "q");
  const auto off = chars(1, "Q");
  expected.insert(expected.end(), off.begin(), off.end());
  EXPECT_EQ(drain(keypad), expected);
}

TEST(RingKeypad, CharacterMessagesDriveTheDisplayAndVariablesAreIgnored) {
  ring::keypad<> keypad;
  feed(keypad, frame_of(ring::message::keypad_offset(1, 1)));
  feed(keypad, chars(1, "\x0c\x0eHELLO"));
  EXPECT_EQ(std::string(keypad.display().line(0)), "HELLO               ");
  EXPECT_FALSE(keypad.display().cursor_visible());
  feed(keypad, frame_of(ring::message::variable(1, 1, 1)));
  EXPECT_EQ(keypad.counters().variables_ignored, 1u);
  EXPECT_EQ(keypad.counters().display_messages, 1u);
}

TEST(RingKeypadDisplay, ControlCharacters) {
  ring::keypad_display d;
  d.write(byte_view(reinterpret_cast<const std::uint8_t*>("AB\rCD\rEF"), 8));
  EXPECT_EQ(std::string(d.line(0)), "EF                  ");  // 13 goes to the start of the other line
  EXPECT_EQ(std::string(d.line(1)), "CD                  ");
  d.write(13);  // after "EF": to the start of the second line
  EXPECT_EQ(d.cursor(), 20u);
  const std::uint8_t to_28[] = {27, 'H', 28, 'X', 14, 20, 7};
  d.write(byte_view(to_28, sizeof to_28));
  EXPECT_EQ(std::string(d.line(1)), "CD      X           ");
  EXPECT_EQ(d.cursor(), 29u);
  EXPECT_FALSE(d.cursor_visible());
  d.write(15);
  EXPECT_TRUE(d.cursor_visible());
  const std::uint8_t to_39[] = {27, 'H', 39, 'Y', 'Z'};  // writes at 39 and wraps to 0
  d.write(byte_view(to_39, sizeof to_39));
  EXPECT_EQ(d.line(1)[19], 'Y');
  EXPECT_EQ(d.line(0)[0], 'Z');
  const std::uint8_t bad_position[] = {27, 'H', 40, 27,
                                       'Q'};  // position 40 ignored; ESC abandoned, 'Q' written
  d.write(byte_view(bad_position, sizeof bad_position));
  EXPECT_EQ(d.line(0)[1], 'Q');
  d.write(12);
  EXPECT_EQ(std::string(d.line(0)), "                    ");
  EXPECT_EQ(d.cursor(), 0u);
}

// Protocol 1.9 as revised: 13 does nothing at the start of a line, so PRINT's CR LF ends a line without
// skipping the next one; 10 is ignored.
TEST(RingKeypadDisplay, CarriageReturnAtTheStartOfALineDoesNothing) {
  ring::keypad_display d;
  const auto write = [&](const char* text) {
    d.write(byte_view(reinterpret_cast<const std::uint8_t*>(text), std::strlen(text)));
  };
  write("\r\n");  // at 0, the start of the first line: nothing
  EXPECT_EQ(d.cursor(), 0u);
  write("SPEED:\r\n");  // mid first line: to 20; LF ignored
  EXPECT_EQ(d.cursor(), 20u);
  write("\r\n\r");  // at 20, the start of the second line: nothing, however many
  EXPECT_EQ(d.cursor(), 20u);
  write("LENGTH:\r\n");  // mid second line: to 0
  EXPECT_EQ(d.cursor(), 0u);
  EXPECT_EQ(std::string(d.line(0)), "SPEED:              ");
  EXPECT_EQ(std::string(d.line(1)), "LENGTH:             ");
  const std::uint8_t to_20[] = {27, 'H', 20, 13, 'X'};  // placed at the start of the second line: 13 stays
  d.write(byte_view(to_20, sizeof to_20));
  EXPECT_EQ(std::string(d.line(1)), "XENGTH:             ");
  const std::uint8_t line_feeds[] = {10, 10, 'Y'};
  d.write(byte_view(line_feeds, sizeof line_feeds));
  EXPECT_EQ(std::string(d.line(1)), "XYNGTH:             ");
}

// The display model is configurable (protocol 1.9): what 13 and 10 do, and how CURSOR's position is sent.
TEST(RingKeypadDisplay, TheModelChoosesWhatCarriageReturnAndLineFeedDo) {
  const auto shown = [](ring::display_model model, const char* text) {
    ring::keypad_display d(model);
    d.write(byte_view(reinterpret_cast<const std::uint8_t*>(text), std::strlen(text)));
    return std::string(d.line(0)) + "|" + std::string(d.line(1)) + "|" + std::to_string(d.cursor());
  };
  ring::display_model m;
  EXPECT_EQ(shown(m, "\rA\r\nB\r\n"), "A                   |B                   |0");
  m.carriage_return = ring::carriage_return_rule::other_line;  // 13 at the start of a line still moves
  EXPECT_EQ(shown(m, "\rA\r\nB\r\n"), "B                   |A                   |20");
  m.carriage_return = ring::carriage_return_rule::line_start;  // 13 returns on the same line
  EXPECT_EQ(shown(m, "AB\rC"), "CB                  |                    |1");
  m.line_feed = ring::line_feed_rule::next_line;  // CR LF: start of the line, then down (and back up)
  EXPECT_EQ(shown(m, "AB\r\nC\r\nD"), "DB                  |C                   |1");
  m.carriage_return = ring::carriage_return_rule::ignored;
  m.line_feed = ring::line_feed_rule::ignored;
  EXPECT_EQ(shown(m, "A\r\nB"), "AB                  |                    |2");
  EXPECT_EQ(ring::keypad_display(m).model().carriage_return, ring::carriage_return_rule::ignored);
  EXPECT_STREQ(ring::to_string(ring::carriage_return_rule::other_line_unless_at_line_start),
               "other_line_unless_at_line_start");
  EXPECT_STREQ(ring::to_string(ring::line_feed_rule::next_line), "next_line");
}

TEST(RingKeypadDisplay, ThePositionBaseIsTakenFromTheCursorCharacter) {
  ring::display_model m;
  m.position_base = 32;  // CURSOR(p) sent as the character p + 32
  ring::keypad_display d(m);
  const std::uint8_t to_28[] = {27, 'H', 28 + 32, 'X'};
  d.write(byte_view(to_28, sizeof to_28));
  EXPECT_EQ(std::string(d.line(1)), "        X           ");
  const std::uint8_t below_base[] = {27, 'H', 31, 'Y'};  // below the base: no position, ignored
  d.write(byte_view(below_base, sizeof below_base));
  EXPECT_EQ(d.cursor(), 30u);
  const std::uint8_t last[] = {27, 'H', 39 + 32, 'Z'};
  d.write(byte_view(last, sizeof last));
  EXPECT_EQ(d.line(1)[19], 'Z');
  static_assert(ring::max_position_base + 39 == 127, "the last position must stay a 7-bit character");
}

// A keypad's display follows the model of its configuration.
TEST(RingKeypadDisplay, TheKeypadTakesTheModelFromItsConfiguration) {
  ring::keypad_config config;
  config.display.carriage_return = ring::carriage_return_rule::line_start;
  ring::keypad<> keypad(config);
  feed(keypad, frame_of(ring::message::keypad_offset(1, 2)));
  feed(keypad, chars(1, "AB\rC"));
  EXPECT_EQ(std::string(keypad.display().line(0)), "CB                  ");
  EXPECT_EQ(keypad.display().model().carriage_return, ring::carriage_return_rule::line_start);
}

namespace {

bool named(const std::string& name, ring::key& out) {
  return ring::key_named(name.data(), name.size(), out);
}

TEST(RingKeypadNames, EveryKeyHasItsNamesInAnyCase) {
  ring::key k = ring::key::stop;
  for (unsigned d = 0; d < 10; ++d) {
    ASSERT_TRUE(named(std::to_string(d), k));
    EXPECT_EQ(k, ring::digit_key(d));
  }
  const std::pair<const char*, ring::key> cases[] = {
      {"up", ring::key::up},     {"+", ring::key::up},      {"DOWN", ring::key::down},  {"-", ring::key::down},
      {"Clr", ring::key::clear}, {"y", ring::key::yes},     {"Enter", ring::key::yes},  {"n", ring::key::no},
      {".", ring::key::point},   {"START", ring::key::start}, {"stop", ring::key::stop}};
  for (const auto& [name, key] : cases) {
    ASSERT_TRUE(named(name, k)) << name;
    EXPECT_EQ(k, key) << name;
  }
  static_assert([] {
    ring::key c = ring::key::digit_0;
    return ring::key_named("stop", 4, c) && c == ring::key::stop;
  }());
}

TEST(RingKeypadNames, OtherWordsAreNoKeys) {
  ring::key k = ring::key::digit_7;
  for (const char* word : {"", "10", "u", "upp", "sto", "start ", "wait=5", "quit", "yes"}) {
    EXPECT_FALSE(named(word, k)) << word;
  }
  EXPECT_EQ(k, ring::key::digit_7);  // untouched
  EXPECT_FALSE(ring::key_named("stopped", 4 + 3, k));
  EXPECT_TRUE(ring::key_named("stopped", 4, k));  // the length given is what counts
}

// Every key's to_string is its enumerator's spelling (the traces print it); a value outside the enum is
// "unknown".
TEST(RingKeypadNames, ToStringIsTheEnumeratorsSpelling) {
  const char* const digits[] = {"digit_0", "digit_1", "digit_2", "digit_3", "digit_4",
                                "digit_5", "digit_6", "digit_7", "digit_8", "digit_9"};
  for (unsigned d = 0; d < 10; ++d) EXPECT_STREQ(ring::to_string(ring::digit_key(d)), digits[d]);
  const std::pair<ring::key, const char*> others[] = {
      {ring::key::up, "up"},       {ring::key::down, "down"},   {ring::key::clear, "clear"},
      {ring::key::yes, "yes"},     {ring::key::no, "no"},       {ring::key::point, "point"},
      {ring::key::start, "start"}, {ring::key::stop, "stop"}};
  for (const auto& [key, name] : others) EXPECT_STREQ(ring::to_string(key), name);
  EXPECT_STREQ(ring::to_string(static_cast<ring::key>(99)), "unknown");
}

}  // namespace

