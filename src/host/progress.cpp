// Progress of long work on a terminal: see trionet/host/progress.hpp.
#include "trionet/host/progress.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace trionet::host {
namespace {

using steady = std::chrono::steady_clock;

constexpr auto first_after = std::chrono::milliseconds(500);
constexpr auto every = std::chrono::milliseconds(250);

// A count for people: three significant digits, with k, M or G from 10 000 on ("12.5", "1.23 M").
std::string amount(double value) {
  char text[32];
  const char* suffix = "";
  if (value >= 1e9) {
    value /= 1e9;
    suffix = " G";
  } else if (value >= 1e6) {
    value /= 1e6;
    suffix = " M";
  } else if (value >= 1e4) {
    value /= 1e3;
    suffix = " k";
  }
  const char* format = value >= 100 || value == std::floor(value) ? "%.0f%s" : value >= 10 ? "%.1f%s" : "%.2f%s";
  std::snprintf(text, sizeof text, format, value, suffix);
  return text;
}

// A duration for people: "3.20 s", "4 min 05 s", "2 h 03 min".
std::string duration(double seconds) {
  char text[32];
  if (seconds < 60) {
    std::snprintf(text, sizeof text, seconds < 10 ? "%.2f s" : "%.1f s", seconds);
  } else if (seconds < 3600) {
    const auto whole = static_cast<long>(seconds);
    std::snprintf(text, sizeof text, "%ld min %02ld s", whole / 60, whole % 60);
  } else {
    const auto minutes = static_cast<long>(seconds / 60);
    std::snprintf(text, sizeof text, "%ld h %02ld min", minutes / 60, minutes % 60);
  }
  return text;
}

void write_all(int fd, const std::string& text) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t wrote = ::write(fd, text.data() + done, text.size() - done);
    if (wrote <= 0) return;  // a progress line is not worth an error
    done += static_cast<std::size_t>(wrote);
  }
}

}  // namespace

progress::progress(std::string what, std::string unit, double total, int fd)
    : what_(std::move(what)), unit_(std::move(unit)), total_(total), fd_(fd), active_(::isatty(fd) == 1) {
  start_ = steady::now();
  next_ = start_ + first_after;
}

void progress::update(double done) {
  if (!active_) return;
  const steady::time_point now = steady::now();
  if (now < next_) return;
  next_ = now + every;
  std::string text = line(what_, unit_, done, total_, std::chrono::duration<double>(now - start_).count());
  winsize size{};
  if (::ioctl(fd_, TIOCGWINSZ, &size) == 0 && size.ws_col > 1 && text.size() >= size.ws_col) {
    text.resize(size.ws_col - 1U);  // a line that wraps cannot be redrawn in place
  }
  write_all(fd_, "\r" + text + "\x1b[K");
  drawn_ = true;
}

void progress::clear() {
  if (active_ && drawn_) write_all(fd_, "\r\x1b[K");
  drawn_ = false;
}

void progress::finish() {
  if (active_ && drawn_) write_all(fd_, "\r\x1b[K");
  active_ = false;
  drawn_ = false;
}

std::string progress::line(std::string_view what, std::string_view unit, double done, double total,
                           double elapsed_seconds) {
  std::string text(what);
  text += ": " + amount(done);
  if (total > 0) text += " of " + amount(total);
  text += ' ';
  text += unit;
  if (total > 0) {
    char percent[16];
    std::snprintf(percent, sizeof percent, " (%.0f%%)", std::fmin(100.0, 100.0 * done / total));
    text += percent;
  }
  if (elapsed_seconds > 0 && done > 0) {
    const double rate = done / elapsed_seconds;
    text += ", " + amount(rate) + " " + std::string(unit) + "/s";
    text += ", " + duration(elapsed_seconds) + " elapsed";
    if (total > done) text += ", about " + duration((total - done) / rate) + " left";
  }
  return text;
}

}  // namespace trionet::host
