// Pieces the live-network commands share (ring monitor/send/join, can monitor/send/node): their events, the
// wall clock, signals, a capture file, and command lines read from standard input.
#pragma once

#include <poll.h>

#include <csignal>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <fstream>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "cli.hpp"
#include "trionet/host/pcapng.hpp"
#include "trionet/span.hpp"

namespace trionet::cli::live {

/// Nanoseconds since 1970 (CLOCK_REALTIME): event times and capture timestamps.
std::uint64_t now_ns();

// ---- events ----

/// The live commands' events: lines of the tool's one `event` (cli.hpp), with the field names and order of
/// the decoders (`ring decode`, `can decode`); the position of a live event is its `time` (`event::time`).
/// They gather in `text()` and go out at `flush()`, which a command calls before every wait, so each event is
/// seen as soon as it happened. As JSON, or as text for people: "HH:MM:SS.ffffff kind name=value ..." (local
/// time; values as in JSON).
class event_log {
 public:
  /// Events to standard output (`fd` 1, through write_stdout: a failure ends the command), or to standard
  /// error (`fd` 2).
  explicit event_log(bool json, int fd = 1) : json_(json), fd_(fd) {}
  ~event_log() { flush(); }
  event_log(const event_log&) = delete;
  event_log& operator=(const event_log&) = delete;

  /// Where an event is appended: `event(log.text(), "kind").time(t)...`.
  std::string& text() noexcept { return text_; }
  /// Writes the events gathered so far.
  void flush();
  /// From now on `flush` keeps the last `count` events as text for people instead of writing them (a
  /// screen shows them).
  void keep_last(std::size_t count) noexcept { keep_ = count; }
  /// The events kept, oldest first.
  [[nodiscard]] const std::deque<std::string>& kept() const noexcept { return kept_; }

 private:
  void write(const std::string& text);

  std::string text_;
  bool json_;
  int fd_;
  std::size_t keep_ = 0;
  std::deque<std::string> kept_;
};

/// One JSON event line (as `event` writes it) as text for people: its "time" first as the local time of day
/// with microseconds, then the kind, then `name=value` for every other field.
std::string text_for_people(std::string_view json_line);

// ---- signals ----

/// Ctrl-C, SIGTERM and SIGHUP ask the command to stop (it then puts back the port and the terminal, writes
/// its counters and ends); SIGUSR1 asks for the counters now. (SIGPIPE is ignored by the whole tool: a
/// closed socket or pipe is an error from write.) Installed without SA_RESTART, so a waiting poll() returns
/// at once. Restores the old handlers on destruction.
class signal_watch {
 public:
  signal_watch();
  ~signal_watch();
  signal_watch(const signal_watch&) = delete;
  signal_watch& operator=(const signal_watch&) = delete;

  static bool stop_requested() noexcept;
  /// True once per SIGUSR1.
  static bool take_report_request() noexcept;

 private:
  struct sigaction old_[4];
};

// ---- the wait of a live command ----

/// The one wait every live command runs in: poll() over its descriptors (the port, standard input, a
/// socket), woken at once by the signals `signal_watch` catches. Before each wait the event log is written,
/// so an event is out as soon as it happened. The loop ends when the command is asked to stop (Ctrl-C,
/// SIGTERM, SIGHUP), ends itself (`stop`: quit, its input ended), loses its link (`lost`), or its output
/// fails; `finish` turns that into the exit status (docs/cli.md).
class event_loop {
 public:
  /// `log` may be null (a command without events).
  explicit event_loop(event_log* log) : log_(log) {}

  /// Watches `fd` (not watched while negative) for `events`; the index for `set` and `ready`.
  std::size_t watch(int fd, short events);
  void set(std::size_t index, int fd, short events);

  /// Writes the log, then waits at most `timeout_ms` (0: only looks; -1: no limit) for a watched descriptor
  /// or a signal. False when the loop has ended (before or during the wait).
  bool wait(int timeout_ms);
  /// The events poll() found on a descriptor in the last wait (0 after a timeout).
  [[nodiscard]] short events(std::size_t index) const noexcept { return fds_[index].revents; }
  /// True when the last wait found the descriptor readable, closed or failed.
  [[nodiscard]] bool readable(std::size_t index) const noexcept {
    return (fds_[index].revents & (POLLIN | POLLHUP | POLLERR | POLLNVAL)) != 0;
  }
  /// True once per SIGUSR1 (the counters asked for).
  static bool report_requested() noexcept { return signal_watch::take_report_request(); }

  /// The command ends normally (quit, its input ended): exit status 0.
  void stop() noexcept { stopped_ = true; }
  /// The link is lost ("/dev/pts/3 closed", "can0: Network is down"): exit status 1 with that message.
  void lost(std::string cause);
  /// True until the loop has ended for any reason.
  [[nodiscard]] bool running() const;
  /// True when the link was lost.
  [[nodiscard]] bool link_lost() const noexcept { return !lost_.empty(); }

  /// Writes the log and gives the exit status: 1 with one message when the output failed or the link was
  /// lost ("trionet: <command>: <cause>"), else 0.
  int finish(const std::string& command);

 private:
  signal_watch signals_;
  event_log* log_;
  std::vector<pollfd> fds_;
  bool stopped_ = false;
  std::string lost_;
};

// ---- captures ----

/// A pcapng capture written while the command runs: every record is flushed at once, so a program
/// following the file (Wireshark) sees it live and a capture cut short by a crash holds every whole record.
class capture_file {
 public:
  bool open(const std::string& path, std::string& error);
  [[nodiscard]] bool is_open() const noexcept { return writer_ != nullptr; }
  /// Adds an interface (a ring link or a CAN bus); its id for `write`.
  std::uint32_t add(const std::string& name, host::capture_network network);
  void write(std::uint32_t interface, std::uint64_t time_ns, byte_view record);
  /// False once writing failed (disk full ...).
  [[nodiscard]] bool good() const noexcept { return !failed_; }
  /// Why writing failed: the system's cause of the first failed write ("No space left on device").
  [[nodiscard]] std::string cause() const;

 private:
  void check(bool ok) noexcept;  // records the first failure and its errno
  std::ofstream file_;
  std::unique_ptr<host::pcapng_writer> writer_;
  bool failed_ = false;
  int errno_ = 0;
};

// ---- command lines on standard input ----

/// Reads standard input without blocking the command: `read_some` after poll() said it is readable, then
/// take the whole lines it completed. At the end of input the last unterminated line counts as a line. A line
/// longer than `max_line` is cut there (the rest of it is dropped), so memory stays bounded whatever comes.
class line_reader {
 public:
  static constexpr std::size_t max_line = 65536;

  explicit line_reader(int fd = 0) : fd_(fd) {}
  /// One read(); false at the end of input or on an error.
  bool read_some();
  bool next(std::string& line);
  [[nodiscard]] bool ended() const noexcept { return ended_; }
  [[nodiscard]] int fd() const noexcept { return fd_; }

 private:
  int fd_;
  std::string pending_;
  bool ended_ = false;
  std::size_t open_length_ = 0;  // characters of the line not yet ended
  bool dropping_ = false;        // the rest of a line that was cut
};

/// Splits a line into blank-separated words.
std::vector<std::string> words_of(std::string_view line);

/// Text with C escapes (\r \n \t \\ \xNN) as bytes. False with `error` on a bad escape.
bool unescape(std::string_view text, std::string& out, std::string& error);

}  // namespace trionet::cli::live
