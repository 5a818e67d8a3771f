// Pieces the live-network commands share (ring monitor/send/join, can monitor/send/node): the one event
// formatter, the wall clock, signals, a capture file, and command lines read from standard input.
#pragma once

#include <csignal>
#include <cstdint>
#include <fstream>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "trionet/can/frame.hpp"
#include "trionet/host/pcapng.hpp"
#include "trionet/ring/decoder.hpp"
#include "trionet/span.hpp"

namespace trionet::cli::live {

/// Nanoseconds since 1970 (CLOCK_REALTIME): event times and capture timestamps.
std::uint64_t now_ns();

// ---- events: one formatter for both networks ----

/// One thing that happened, with its time and its fields in print order (values already JSON: numbers,
/// strings with quotes, true/false).
struct event {
  std::uint64_t time_ns = 0;
  std::string name;  ///< "message", "frame_error", "vr", "counters", ...
  std::vector<std::pair<std::string, std::string>> fields;

  event(std::uint64_t time, std::string event_name) : time_ns(time), name(std::move(event_name)) {}
  event& text(const std::string& field, std::string_view value);
  event& number(const std::string& field, long long value);
  event& number(const std::string& field, unsigned long long value);
  event& real(const std::string& field, double value);
  event& flag(const std::string& field, bool value);
};

/// A ring decoder result as an event: the fields and names of `trionet ring decode` (event, type, hops,
/// text, vr, raw, value, offset, mode, reason), and its time.
event ring_event(std::uint64_t time_ns, const ring::decode_result& result);

/// A CAN frame as an event: for a VR frame of an exchange of `nodes` controllers the fields of
/// `trionet can decode` (event "vr", id, from, to, vr, negative, int, frac, value); otherwise
/// {"event":"error","reason":...} with the frame itself (id, frame as compact candump text).
event can_event(std::uint64_t time_ns, const can::frame& frame, std::uint8_t nodes);

/// The event as one line without its newline: JSON {"time":S.ffffff,"event":NAME,...}, or text
/// "HH:MM:SS.ffffff NAME field=value ..." (local time) for people.
std::string format(const event& e, bool json);

/// Prints the event on standard output (or `to`) and flushes it, so it is seen as soon as it happened.
void emit(const event& e, bool json, std::FILE* to = stdout);

// ---- signals ----

/// Ctrl-C, SIGTERM and SIGHUP ask the command to stop (it then puts back the port and the terminal, writes
/// its counters and ends); SIGUSR1 asks for the counters now. SIGPIPE is ignored (a closed socket is an
/// error from write). Installed without SA_RESTART, so a waiting poll() returns at once. Restores the old
/// handlers on destruction.
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
  struct sigaction old_[5];
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

 private:
  std::ofstream file_;
  std::unique_ptr<host::pcapng_writer> writer_;
  bool failed_ = false;
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

namespace trionet::cli {
/// `trionet can monitor|send|node ...` (`command` is the word after `can`).
int can_live_main(const std::string& command, const std::vector<std::string>& words);
/// The same, one command each, for the can part's command table; their help text.
int can_monitor_main(const std::vector<std::string>& args);
int can_send_main(const std::vector<std::string>& args);
int can_node_main(const std::vector<std::string>& args);
extern const char* const can_live_usage;
}  // namespace trionet::cli
