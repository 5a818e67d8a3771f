// Progress of long work, for people watching a terminal: one line on standard error, redrawn in place, with
// what is done, the rate and an estimate of the time left. Silent when standard error is not a terminal (a
// file, a pipe, CI), so that no log ever holds it.
//
//   trionet::host::progress shown("ring simulate", "s of ring time", 60.0);
//   while (...) { ...; shown.update(ring_seconds); }
//   shown.finish();   // clears the line (also on destruction)
//
// A program that writes other lines to the same terminal meanwhile calls `clear()` before each.
//
// The line, at most 4 times a second from half a second after the start, cut to the terminal's width:
//
//   ring simulate: 12.5 of 60 s of ring time (21%), 3.91 s of ring time/s, 3.20 s elapsed, about 12.1 s left
//
// Host code only (system calls). `update` reads the monotonic clock: call it once per piece of work that
// takes microseconds, not once per byte.
#pragma once

#include <chrono>
#include <string>
#include <string_view>

namespace trionet::host {

class progress {
 public:
  /// `what` begins the line (the command, "ring learn crc"); `unit` names what is counted ("candidates");
  /// `total` is how many there will be (0 when not known: no percentage and no estimate). Shown on `fd`
  /// (standard error by default) only when it is a terminal.
  progress(std::string what, std::string unit, double total, int fd = 2);
  ~progress() { finish(); }
  progress(const progress&) = delete;
  progress& operator=(const progress&) = delete;

  /// `done` units so far: the line is redrawn when it is due.
  void update(double done);
  /// Clears the line for a moment, so that the caller can write to the same terminal (a table row, an
  /// event); the next `update` draws it again.
  void clear();
  /// The work is over: the line is cleared, and nothing more is drawn.
  void finish();
  /// True while the line may be drawn (the descriptor is a terminal and `finish` was not called).
  [[nodiscard]] bool active() const noexcept { return active_; }

  /// The text of the line (without the terminal's control sequences): for tests and for callers that show
  /// it elsewhere.
  [[nodiscard]] static std::string line(std::string_view what, std::string_view unit, double done, double total,
                                        double elapsed_seconds);

 private:
  std::string what_;
  std::string unit_;
  double total_;
  int fd_;
  bool active_ = false;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point next_;
};

}  // namespace trionet::host
