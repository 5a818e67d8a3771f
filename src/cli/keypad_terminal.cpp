// The membrane keypad in a terminal: see keypad_terminal.hpp.
#include "keypad_terminal.hpp"

#include <unistd.h>

#include "cli.hpp"
#include "live.hpp"

namespace trionet::cli {

const char* const keyboard_map =
    "keys: 0-9 . | + u Up: up | - d Down: down | c Backspace: CLR | y Enter: Y | n: N | s: start | t: stop | "
    "q: quit";

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

bool key_script::next(std::uint64_t now_ns, std::string& word, std::string& bad_wait) {
  while (!words_.empty() && resume_at_ <= now_ns) {
    word = words_.front();
    words_.pop_front();
    if (word.compare(0, 5, "wait=") != 0) return true;
    long long ms = 0;
    if (!parse_integer(word.substr(5), 0, 3600000, ms)) {
      bad_wait = word;
      continue;
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

std::vector<std::string> panel_lines(const keypad_panel& panel) {
  const std::string mark = panel.selected ? "> " : "  ";
  return {mark + panel.title, "  +--------------------+", "  |" + panel.lines[0] + "|",
          "  |" + panel.lines[1] + "|", "  +--------------------+", "  " + panel.status};
}

void terminal_screen::draw(const std::vector<keypad_panel>& panels, const std::vector<std::string>& footer) {
  std::string out;
  if (!drawn_) out += "\x1b[?25l";  // hide the cursor while drawing
  if (drawn_lines_ != 0) out += "\x1b[" + std::to_string(drawn_lines_) + "F";  // back to the first line
  std::size_t lines = 0;
  const auto line = [&](const std::string& text) {
    out += "\x1b[2K" + text + "\n";
    ++lines;
  };
  for (const keypad_panel& panel : panels) {
    for (const std::string& text : panel_lines(panel)) line(text);
  }
  for (const std::string& text : footer) line(text);
  for (std::size_t i = lines; i < drawn_lines_; ++i) out += "\x1b[2K\n";  // a shorter drawing: clear the rest
  if (drawn_lines_ > lines) out += "\x1b[" + std::to_string(drawn_lines_ - lines) + "F";
  drawn_lines_ = lines;
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
