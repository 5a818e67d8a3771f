// The membrane keypad in a terminal: see keypad_terminal.hpp.
#include "keypad_terminal.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <utility>

#include "cli.hpp"
#include "live.hpp"

namespace trionet::cli {

std::vector<std::string> keyboard_help(std::size_t columns, bool several_keypads) {
  if (columns >= 77) {
    return {"keys: 0-9 .  + u Up: up  - d Down: down  c Backspace Delete: CLR  y Enter: Y",
            std::string("      n: N  s: start  t: stop  q: quit") + (several_keypads ? "  Tab: next keypad" : "")};
  }
  if (columns >= 51) {
    return {"keys: 0-9 .  u: up  d: down  c: CLR  y: Y  n: N",
            std::string("      s: start  t: stop  q: quit") + (several_keypads ? "  Tab: next keypad" : "")};
  }
  return {std::string("keys 0-9 . u d c y n s t q") + (several_keypads ? " Tab" : "")};
}

bool raw_terminal::enter(int fd) {
  termios now{};
  if (::isatty(fd) == 0 || ::tcgetattr(fd, &now) != 0) return false;
  saved_ = now;
  now.c_lflag &= ~static_cast<tcflag_t>(ICANON | ECHO | ECHONL | IEXTEN);
  now.c_iflag &= ~static_cast<tcflag_t>(IXON | ICRNL | INLCR);
  now.c_cc[VMIN] = 1;
  now.c_cc[VTIME] = 0;
  if (::tcsetattr(fd, TCSANOW, &now) != 0) return false;
  fd_ = fd;
  return true;
}

void raw_terminal::restore() noexcept {
  if (fd_ < 0) return;
  (void)::tcsetattr(fd_, TCSANOW, &saved_);
  fd_ = -1;
}

void key_decoder::push(char c, std::vector<std::string>& keys) {
  if (!escape_.empty()) {  // ESC [ ... final byte
    escape_ += c;
    if (escape_.size() == 2 && c != '[' && c != 'O') {
      escape_.clear();
      return;
    }
    if (escape_.size() >= 3 && c >= 0x40 && c <= 0x7E) {
      if (escape_ == "\x1b[A" || escape_ == "\x1bOA") keys.emplace_back("up");
      if (escape_ == "\x1b[B" || escape_ == "\x1bOB") keys.emplace_back("down");
      if (escape_ == "\x1b[3~") keys.emplace_back("clr");
      escape_.clear();
    } else if (escape_.size() > 8) {
      escape_.clear();
    }
    return;
  }
  if (c >= '0' && c <= '9') {
    keys.emplace_back(1, c);
    return;
  }
  switch (c) {
    case 0x1b:
      escape_ = "\x1b";
      return;
    case '.':
      keys.emplace_back(".");
      return;
    case '+':
    case 'u':
    case 'U':
      keys.emplace_back("up");
      return;
    case '-':
    case 'd':
    case 'D':
      keys.emplace_back("down");
      return;
    case 'c':
    case 'C':
    case 0x7f:
    case 0x08:
      keys.emplace_back("clr");
      return;
    case 'y':
    case 'Y':
    case '\r':
    case '\n':
      keys.emplace_back("y");
      return;
    case 'n':
    case 'N':
      keys.emplace_back("n");
      return;
    case 's':
    case 'S':
      keys.emplace_back("start");
      return;
    case 't':
    case 'T':
      keys.emplace_back("stop");
      return;
    case '\t':
      keys.emplace_back("next");
      return;
    case 'q':
    case 'Q':
    case 0x04:
      keys.emplace_back("quit");
      return;
    default:
      return;
  }
}

std::vector<std::string> key_decoder::read(int fd) {
  std::vector<std::string> keys;
  char bytes[64];
  const ssize_t got = ::read(fd, bytes, sizeof bytes);
  for (ssize_t i = 0; i < got; ++i) push(bytes[i], keys);
  return keys;
}

void key_script::add_line(const std::string& line) {
  for (const std::string& word : live::words_of(line)) words_.push_back(word);
}

bool key_script::next(std::uint64_t now_ns, std::string& word, bool& bad_wait) {
  bad_wait = false;
  while (!words_.empty() && resume_at_ <= now_ns) {
    word = words_.front();
    words_.pop_front();
    if (word.compare(0, 5, "wait=") != 0) return true;
    long long ms = 0;
    if (!parse_integer(word.substr(5), 0, 3600000, ms)) {
      bad_wait = true;
      return true;
    }
    resume_at_ = now_ns + static_cast<std::uint64_t>(ms) * 1000000u;
  }
  return false;
}

int key_script::due_in_ms(std::uint64_t now_ns) const {
  if (words_.empty()) return -1;
  return resume_at_ <= now_ns ? 0 : static_cast<int>((resume_at_ - now_ns + 999999u) / 1000000u);
}

bool key_script::done(std::uint64_t now_ns) const {
  return words_.empty() && resume_at_ <= now_ns;
}

bool keypad_key(const std::string& word, ring::key& out) {
  return ring::key_named(word.data(), word.size(), out);
}

std::vector<std::string> panel_lines(const keypad_panel& panel, bool compact) {
  const std::string mark = panel.selected ? "> " : "  ";
  if (compact) return {mark + panel.title + ": " + panel.status, "  |" + panel.lines[0] + "|", "  |" + panel.lines[1] + "|"};
  return {mark + panel.title, "  +--------------------+", "  |" + panel.lines[0] + "|",
          "  |" + panel.lines[1] + "|", "  +--------------------+", "  " + panel.status};
}

namespace {

// The length of the UTF-8 sequence at `text[at]` that encodes a printable character (not a C1 control), or 0.
std::size_t printable_utf8(const std::string& text, std::size_t at) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  const unsigned lead = byte(at);
  std::size_t length = 0;
  unsigned value = 0;
  if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2;
    value = lead & 0x1FU;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3;
    value = lead & 0x0FU;
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4;
    value = lead & 0x07U;
  } else {
    return 0;
  }
  if (at + length > text.size()) return 0;
  for (std::size_t i = 1; i < length; ++i) {
    if ((byte(at + i) & 0xC0U) != 0x80U) return 0;
    value = (value << 6U) | (byte(at + i) & 0x3FU);
  }
  const unsigned smallest[] = {0, 0, 0x80, 0x800, 0x10000};
  if (value < smallest[length] || value > 0x10FFFF || (value >= 0xD800 && value <= 0xDFFF)) return 0;
  if (value <= 0x9F) return 0;  // C1 control characters
  return length;
}

}  // namespace

std::string fit_line(const std::string& text, std::size_t columns) {
  const std::size_t room = columns > 1 ? columns - 1 : 1;
  // Pieces printable as they are, with their width in cells: an ASCII character, a UTF-8 sequence (1), or a
  // byte shown as \xNN (4).
  std::vector<std::pair<std::string, std::size_t>> pieces;
  std::size_t width = 0;
  for (std::size_t at = 0; at < text.size();) {
    const auto byte = static_cast<unsigned char>(text[at]);
    if (byte >= 0x20 && byte < 0x7F) {
      pieces.emplace_back(std::string(1, text[at++]), 1);
    } else if (const std::size_t length = printable_utf8(text, at); length != 0) {
      pieces.emplace_back(text.substr(at, length), 1);
      at += length;
    } else {
      const char hex[] = "0123456789abcdef";
      pieces.emplace_back(std::string{'\\', 'x', hex[byte >> 4U], hex[byte & 0xFU]}, 4);
      ++at;
    }
    width += pieces.back().second;
  }
  const bool cut = width > room;
  const std::size_t limit = cut && room > 3 ? room - 3 : room;
  std::string out;
  std::size_t used = 0;
  for (const auto& [piece, cells] : pieces) {
    if (used + cells > limit) break;
    out += piece;
    used += cells;
  }
  if (cut && room > 3) out += "...";
  return out;
}

screen_size terminal_screen::size() const {
  screen_size s;
  winsize w{};
  if (::ioctl(::fileno(out_), TIOCGWINSZ, &w) == 0 && w.ws_col > 0 && w.ws_row > 0) {
    s.columns = w.ws_col;
    s.rows = w.ws_row;
  }
  return s;
}

void terminal_screen::draw(const std::vector<keypad_panel>& panels, const std::vector<std::string>& footer,
                           const std::vector<std::string>& events) {
  const screen_size now = size();
  const std::size_t room = now.rows > 1 ? now.rows - 1 : 1;  // the cursor's line stays on the screen
  bool compact = false;
  std::vector<std::string> lines;
  for (int attempt = 0; attempt < 2; ++attempt) {
    compact = attempt == 1;
    lines.clear();
    for (const keypad_panel& panel : panels) {
      for (const std::string& text : panel_lines(panel, compact)) lines.push_back(text);
    }
    lines.insert(lines.end(), footer.begin(), footer.end());
    if (lines.size() <= room) break;
  }
  if (lines.size() < room) {
    const std::size_t shown = std::min(events.size(), room - lines.size());
    lines.insert(lines.end(), events.end() - static_cast<std::ptrdiff_t>(shown), events.end());
  }
  if (lines.size() > room) lines.resize(room);

  std::string out;
  if (!drawn_) out += "\x1b[?25l";  // hide the cursor while drawing
  if (drawn_ && now != drawn_size_) {
    out += "\x1b[H\x1b[J";  // the old drawing was re-flowed or cut by the terminal: start again at the top
    drawn_lines_ = 0;
  }
  if (drawn_lines_ != 0) out += "\x1b[" + std::to_string(drawn_lines_) + "F";  // back to the first line
  for (const std::string& text : lines) out += "\x1b[2K" + fit_line(text, now.columns) + "\n";
  for (std::size_t i = lines.size(); i < drawn_lines_; ++i) out += "\x1b[2K\n";  // a shorter drawing: clear the rest
  if (drawn_lines_ > lines.size()) out += "\x1b[" + std::to_string(drawn_lines_ - lines.size()) + "F";
  drawn_lines_ = lines.size();
  drawn_size_ = now;
  drawn_ = true;
  std::fwrite(out.data(), 1, out.size(), out_);
  std::fflush(out_);
}

void terminal_screen::leave() {
  if (!drawn_) return;
  std::fputs("\x1b[?25h", out_);
  std::fflush(out_);
  drawn_ = false;
}

}  // namespace trionet::cli
