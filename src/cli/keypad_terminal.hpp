// The membrane keypad in a terminal: the keyboard as the keypad's keys, and its 2 x 20 display drawn and
// redrawn in place. Used by `trionet ring join PORT --as keypad` and `trionet ring simulate --interactive`.
//
// Keyboard map (docs in the README's "Live networks"):
//   0..9 .          the digit keys and the point
//   + u  Up         up / +                    - d  Down        down / -
//   c Backspace Del CLR                       y Enter          Y / enter
//   n               N                         s                start
//   t               stop                      Tab              the next keypad (several on screen)
//   q Ctrl-D        quit                      Ctrl-C           quit (a signal)
#pragma once

#include <termios.h>

#include <cstddef>
#include <cstdint>
#include <deque>
#include <cstdio>
#include <string>
#include <vector>

#include "trionet/ring/keypad_codes.hpp"

namespace trionet::cli {

/// The keyboard map as help lines that fit `columns` (two lines from 80 columns up, shorter below);
/// `several_keypads` adds Tab.
std::vector<std::string> keyboard_help(std::size_t columns, bool several_keypads);

/// A terminal on `fd` put into raw keyboard mode: no echo, no line buffering, each key at once; Ctrl-C
/// still a signal. Restored by `restore` or on destruction.
class raw_terminal {
 public:
  raw_terminal() = default;
  ~raw_terminal() { restore(); }
  raw_terminal(const raw_terminal&) = delete;
  raw_terminal& operator=(const raw_terminal&) = delete;

  /// False if `fd` is not a terminal (nothing changed).
  bool enter(int fd);
  void restore() noexcept;

 private:
  int fd_ = -1;
  termios saved_{};
};

/// Turns keyboard bytes (escape sequences included) into words: the keypad's key names ("0".."9", ".",
/// "up", "down", "clr", "y", "n", "start", "stop"), "next" (Tab) and "quit". Other bytes are ignored.
class key_decoder {
 public:
  void push(char c, std::vector<std::string>& keys);
  /// Reads what the keyboard `fd` has (after poll() said it is readable) and returns its words.
  std::vector<std::string> read(int fd);

 private:
  std::string escape_;  // an escape sequence being read
};

/// Key words from a file or pipe, in order; a word "wait=MS" holds the ones after it back MS milliseconds.
class key_script {
 public:
  /// Appends the words of one input line.
  void add_line(const std::string& line);
  /// The next word due at `now_ns`; false if none is due. Good wait=MS words are taken here; a bad one is
  /// returned in its place with `bad_wait` true (each one, in order), for the caller to report.
  bool next(std::uint64_t now_ns, std::string& word, bool& bad_wait);
  /// Milliseconds until a word is due: 0 if one is due now, -1 if none is queued.
  [[nodiscard]] int due_in_ms(std::uint64_t now_ns) const;
  /// True when no word is queued and no wait is running.
  [[nodiscard]] bool done(std::uint64_t now_ns) const;

 private:
  std::deque<std::string> words_;
  std::uint64_t resume_at_ = 0;
};

/// The key a word names: the key script's names (docs/basic.md: 0..9, up, +, down, -, clr, y, enter, n, .,
/// start, stop; any case). False for any other word.
bool keypad_key(const std::string& word, ring::key& out);

/// One keypad as drawn: a title, a status line, and the display's two lines.
struct keypad_panel {
  std::string title;
  std::string status;
  std::string lines[2];
  bool selected = false;  ///< marked when several keypads share the keyboard
};

/// The text lines of a panel: title, the boxed display, status (6 lines); `compact`: the title and status on
/// one line, then the display's two lines (3 lines).
std::vector<std::string> panel_lines(const keypad_panel& panel, bool compact = false);

/// A terminal's size in character cells.
struct screen_size {
  std::size_t columns = 80;
  std::size_t rows = 24;
  bool operator==(const screen_size& other) const { return columns == other.columns && rows == other.rows; }
  bool operator!=(const screen_size& other) const { return !(*this == other); }
};

/// `text` as one terminal line of at most `columns` - 1 cells: control characters shown as `\xNN`, a longer
/// line cut and ended with "..." (a UTF-8 sequence counts as one cell and is never split).
std::string fit_line(const std::string& text, std::size_t columns);

/// Draws panels and footer lines on a terminal, in place: each draw goes back over the previous one. A
/// drawing never wraps or scrolls, so that going back over it is exact: every line is cut to the terminal's
/// width less one column, and the drawing to its height less one line (events first, oldest first, then
/// compact panels, then what is left at the bottom).
class terminal_screen {
 public:
  explicit terminal_screen(std::FILE* out = stdout) : out_(out) {}
  ~terminal_screen() { leave(); }
  terminal_screen(const terminal_screen&) = delete;
  terminal_screen& operator=(const terminal_screen&) = delete;

  /// The terminal's size now (80 x 24 when the output is not a terminal).
  [[nodiscard]] screen_size size() const;
  /// True when the terminal's size is not that of the last drawing (draw again).
  [[nodiscard]] bool resized() const { return drawn_ && size() != drawn_size_; }

  /// Panels, then `footer` (help and status lines), then as many of `events` (oldest first) as fit, the
  /// newest kept. After a change of size the screen is cleared and the drawing starts at its top.
  void draw(const std::vector<keypad_panel>& panels, const std::vector<std::string>& footer,
            const std::vector<std::string>& events = {});
  /// Shows the cursor again, below the drawing.
  void leave();

 private:
  std::FILE* out_;
  std::size_t drawn_lines_ = 0;
  screen_size drawn_size_;
  bool drawn_ = false;
};

}  // namespace trionet::cli
