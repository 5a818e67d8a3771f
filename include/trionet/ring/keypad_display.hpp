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
// Cost: 42 bytes of text + 3 bytes of state; O(1) per character; ISR-safe.
#pragma once

#include <cstddef>
#include <cstdint>

#include "trionet/span.hpp"

namespace trionet::ring {

/// The display's text and cursor, changed by the characters written to it (the rules above).
class keypad_display {
 public:
  static constexpr std::size_t columns = 20;                ///< characters per line
  static constexpr std::size_t rows = 2;                    ///< lines
  static constexpr std::size_t positions = columns * rows;  ///< cursor positions, 0..39

  keypad_display() noexcept { clear(); }

  /// Handles one character received for the display.
  void write(std::uint8_t c) noexcept {
    if (escape_ == escape::position) {
      escape_ = escape::none;
      if (c < positions) cursor_ = c;
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
        if (cursor_ % columns != 0) cursor_ = static_cast<std::uint8_t>(cursor_ < columns ? columns : 0);
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

 private:
  enum class escape : std::uint8_t { none, start, position };
  static constexpr std::size_t row_of(std::size_t position) noexcept { return position / columns; }

  char text_[rows][columns + 1];
  std::uint8_t cursor_ = 0;
  bool cursor_visible_ = true;
  escape escape_ = escape::none;
};

}  // namespace trionet::ring
