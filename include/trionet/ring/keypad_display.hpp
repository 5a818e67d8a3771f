// The 2 x 20 character display of a membrane keypad (docs/protocol.md 1.9), as a model readable as text.
//
//   position  0 .. 19   first line        (row-major; CURSOR(p) = CHR(27);"H";CHR(p))
//   position 20 .. 39   second line
//
//   12        clear and home the cursor        13   start of the other line, unless already at the
//   14        hide the cursor                       start of a line (then nothing)
//   15        show the cursor                  10   ignored
//   20        accepted and ignored             27 'H' p   cursor to p (0..39; others are ignored)
//   other < 32 and 127: ignored                32..126: written at the cursor, which advances and wraps
//
// So PRINT's CR LF ends a line without skipping one: PRINT #n,"SPEED:" then PRINT #n,"LENGTH:" put SPEED: on
// the first line and LENGTH: on the second, as the manual's Example 1 intends (protocol 1.9).
// An escape followed by anything but 'H' is abandoned and that character is handled as usual.
//
// The rules above are the default `display_model` (protocol 1.9, configurable). A real display may differ in
// what 13 and 10 do and in how the position after `27 'H'` is sent; `display_model` chooses:
//
//   carriage_return   other_line_unless_at_line_start (default) | other_line | line_start | ignored
//   line_feed         ignored (default) | next_line (same column on the other line)
//   position_base     0 (default: p is sent as the character p) .. 88 (p is sent as p + base, e.g. 32)
//
// Cost: 42 bytes of text + 3 bytes of state + 3 bytes of model; O(1) per character; ISR-safe.
#pragma once

#include <cstddef>
#include <cstdint>

#include "trionet/span.hpp"

namespace trionet::ring {

/// What character 13 (carriage return) does on the display.
enum class carriage_return_rule : std::uint8_t {
  other_line_unless_at_line_start,  ///< start of the other line; nothing at the start of a line (the default)
  other_line,                       ///< always the start of the other line
  line_start,                       ///< the start of the same line
  ignored,                          ///< nothing
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(carriage_return_rule rule) noexcept {
  switch (rule) {
    case carriage_return_rule::other_line_unless_at_line_start:
      return "other_line_unless_at_line_start";
    case carriage_return_rule::other_line:
      return "other_line";
    case carriage_return_rule::line_start:
      return "line_start";
    case carriage_return_rule::ignored:
      return "ignored";
  }
  return "unknown";
}

/// What character 10 (line feed) does on the display.
enum class line_feed_rule : std::uint8_t {
  ignored,    ///< nothing (the default)
  next_line,  ///< the same column of the other line
};

/// The enumerator's name as spelled in the code ("unknown" for a value outside the enum).
constexpr const char* to_string(line_feed_rule rule) noexcept {
  switch (rule) {
    case line_feed_rule::ignored:
      return "ignored";
    case line_feed_rule::next_line:
      return "next_line";
  }
  return "unknown";
}

/// The display's configurable behaviour (docs/protocol.md 1.9; the defaults are its decisions).
struct display_model {
  carriage_return_rule carriage_return = carriage_return_rule::other_line_unless_at_line_start;  ///< 13
  line_feed_rule line_feed = line_feed_rule::ignored;                                            ///< 10
  /// Added to the position p after the escape (27, then the letter H) on the wire: 0 sends p itself, 32
  /// sends p + 32 (a printable character). At most `max_position_base`.
  std::uint8_t position_base = 0;

  /// Equal when every choice is.
  friend constexpr bool operator==(const display_model& a, const display_model& b) noexcept {
    return a.carriage_return == b.carriage_return && a.line_feed == b.line_feed &&
           a.position_base == b.position_base;
  }
  /// Not equal when any choice differs.
  friend constexpr bool operator!=(const display_model& a, const display_model& b) noexcept {
    return !(a == b);
  }
};

/// The largest `display_model::position_base`: the last position, 39, must still be a 7-bit character.
constexpr std::uint8_t max_position_base = 127 - 39;

/// The display's text and cursor, changed by the characters written to it (the rules above).
class keypad_display {
 public:
  static constexpr std::size_t columns = 20;                ///< characters per line
  static constexpr std::size_t rows = 2;                    ///< lines
  static constexpr std::size_t positions = columns * rows;  ///< cursor positions, 0..39

  /// A clear display that follows `model` (the default: docs/protocol.md 1.9).
  explicit keypad_display(const display_model& model = display_model{}) noexcept : model_(model) { clear(); }

  /// Handles one character received for the display.
  void write(std::uint8_t c) noexcept {
    if (escape_ == escape::position) {
      escape_ = escape::none;
      const auto p = static_cast<std::uint8_t>(c - model_.position_base);  // below the base wraps high
      if (p < positions) cursor_ = p;
      return;
    }
    if (escape_ == escape::start) {
      escape_ = escape::none;
      if (c == 'H') {
        escape_ = escape::position;
        return;
      }
    }
    switch (c) {
      case 12:
        clear();
        return;
      case 13:
        carriage_return();
        return;
      case 10:
        if (model_.line_feed == line_feed_rule::next_line)
          cursor_ = static_cast<std::uint8_t>(cursor_ < columns ? cursor_ + columns : cursor_ - columns);
        return;
      case 14:
        cursor_visible_ = false;
        return;
      case 15:
        cursor_visible_ = true;
        return;
      case 27:
        escape_ = escape::start;
        return;
      default:
        break;
    }
    if (c < 32 || c > 126) return;
    text_[row_of(cursor_)][cursor_ % columns] = static_cast<char>(c);
    cursor_ = static_cast<std::uint8_t>(cursor_ + 1u < positions ? cursor_ + 1u : 0u);
  }

  /// Handles each of `characters` in turn.
  void write(byte_view characters) noexcept {
    for (std::uint8_t c : characters) write(c);
  }

  /// Clears the display and homes the cursor (character 12).
  void clear() noexcept {
    for (auto& row : text_) {
      for (std::size_t i = 0; i < columns; ++i) row[i] = ' ';
      row[columns] = '\0';
    }
    cursor_ = 0;
  }

  /// A line of the display (0 or 1) as a 20-character string.
  const char* line(std::size_t row) const noexcept { return text_[row < rows ? row : rows - 1]; }
  std::size_t cursor() const noexcept { return cursor_; }           ///< the cursor position, 0..39
  bool cursor_visible() const noexcept { return cursor_visible_; }  ///< false after character 14
  const display_model& model() const noexcept { return model_; }    ///< the rules it follows

 private:
  enum class escape : std::uint8_t { none, start, position };
  static constexpr std::size_t row_of(std::size_t position) noexcept { return position / columns; }

  void carriage_return() noexcept {
    const std::size_t line_start = cursor_ - cursor_ % columns;
    const auto other_line = static_cast<std::uint8_t>(cursor_ < columns ? columns : 0);
    switch (model_.carriage_return) {
      case carriage_return_rule::other_line_unless_at_line_start:
        if (cursor_ != line_start) cursor_ = other_line;
        return;
      case carriage_return_rule::other_line:
        cursor_ = other_line;
        return;
      case carriage_return_rule::line_start:
        cursor_ = static_cast<std::uint8_t>(line_start);
        return;
      case carriage_return_rule::ignored:
        return;
    }
  }

  char text_[rows][columns + 1];
  std::uint8_t cursor_ = 0;
  bool cursor_visible_ = true;
  escape escape_ = escape::none;
  display_model model_;
};

}  // namespace trionet::ring
