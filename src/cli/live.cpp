// Pieces the live-network commands share: see live.hpp.
#include "live.hpp"

#include <poll.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>

namespace trionet::cli::live {

std::uint64_t now_ns() {
  timespec t{};
  ::clock_gettime(CLOCK_REALTIME, &t);
  return static_cast<std::uint64_t>(t.tv_sec) * 1000000000u + static_cast<std::uint64_t>(t.tv_nsec);
}

void event_log::write(const std::string& text) {
  if (fd_ == STDOUT_FILENO) {
    write_stdout(text);
    return;
  }
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t wrote = ::write(fd_, text.data() + done, text.size() - done);
    if (wrote < 0 && errno == EINTR) continue;
    if (wrote <= 0) return;  // standard error is gone: nothing left to tell
    done += static_cast<std::size_t>(wrote);
  }
}

void event_log::flush() {
  if (text_.empty()) return;
  if (json_ && keep_ == 0) {
    write(text_);
    text_.clear();
    return;
  }
  std::string people;
  std::size_t at = 0;
  while (at < text_.size()) {
    std::size_t end = text_.find('\n', at);
    if (end == std::string::npos) end = text_.size();
    std::string line = text_for_people(std::string_view(text_).substr(at, end - at));
    at = end + 1;
    if (keep_ != 0) {
      kept_.push_back(std::move(line));
      if (kept_.size() > keep_) kept_.pop_front();
    } else {
      people += line;
      people += '\n';
    }
  }
  text_.clear();
  if (!people.empty()) write(people);
}

namespace {

// The end of the JSON value at `at` in a line that `event` wrote: a string (escapes skipped) or a bare word.
std::size_t value_end(std::string_view line, std::size_t at) {
  if (at < line.size() && line[at] == '"') {
    for (++at; at < line.size() && line[at] != '"'; ++at) {
      if (line[at] == '\\') ++at;
    }
    return at < line.size() ? at + 1 : line.size();
  }
  while (at < line.size() && line[at] != ',' && line[at] != '}') ++at;
  return at;
}

// "1700000000.123456789" as the local time of day with microseconds, "19:39:11.925318".
std::string time_of_day(std::string_view epoch) {
  std::uint64_t seconds = 0;
  std::size_t i = 0;
  for (; i < epoch.size() && epoch[i] >= '0' && epoch[i] <= '9'; ++i) seconds = seconds * 10 + static_cast<std::uint64_t>(epoch[i] - '0');
  std::string micros = i < epoch.size() && epoch[i] == '.' ? std::string(epoch.substr(i + 1, 6)) : "";
  micros.resize(6, '0');
  const auto t = static_cast<std::time_t>(seconds);
  std::tm local{};
  ::localtime_r(&t, &local);
  char stamp[24];
  std::snprintf(stamp, sizeof stamp, "%02d:%02d:%02d.", local.tm_hour, local.tm_min, local.tm_sec);
  return stamp + micros;
}

}  // namespace

std::string text_for_people(std::string_view line) {
  std::string kind;
  std::string time;
  std::string fields;
  std::size_t at = line.empty() ? 0 : 1;  // after '{'
  while (at < line.size() && line[at] == '"') {
    const std::size_t name_end = line.find('"', at + 1);
    if (name_end == std::string_view::npos || name_end + 1 >= line.size()) break;
    const std::string_view name = line.substr(at + 1, name_end - at - 1);
    const std::size_t value_at = name_end + 2;  // after ':'
    const std::size_t end = value_end(line, value_at);
    const std::string_view value = line.substr(value_at, end - value_at);
    if (name == "event" && value.size() >= 2) {
      kind = std::string(value.substr(1, value.size() - 2));
    } else if (name == "time" && value.size() >= 2) {
      time = time_of_day(value.substr(1, value.size() - 2));
    } else {
      fields += ' ';
      fields.append(name.data(), name.size());
      fields += '=';
      fields.append(value.data(), value.size());
    }
    at = end + 1;  // after ','
  }
  return time.empty() ? kind + fields : time + " " + kind + fields;
}

// ---- signals ----

namespace {

volatile std::sig_atomic_t stop_flag = 0;
volatile std::sig_atomic_t report_flag = 0;

extern "C" void on_stop(int) {
  stop_flag = 1;
}
extern "C" void on_report(int) {
  report_flag = 1;
}

constexpr int watched[4] = {SIGINT, SIGTERM, SIGHUP, SIGUSR1};

}  // namespace

signal_watch::signal_watch() {
  for (std::size_t i = 0; i < 4; ++i) {
    struct sigaction action {};
    sigemptyset(&action.sa_mask);
    action.sa_flags = 0;  // no SA_RESTART: poll() returns EINTR at once
    action.sa_handler = watched[i] == SIGUSR1 ? on_report : on_stop;
    ::sigaction(watched[i], &action, &old_[i]);
  }
}

signal_watch::~signal_watch() {
  for (std::size_t i = 0; i < 4; ++i) ::sigaction(watched[i], &old_[i], nullptr);
}

bool signal_watch::stop_requested() noexcept {
  return stop_flag != 0;
}

bool signal_watch::take_report_request() noexcept {
  if (report_flag == 0) return false;
  report_flag = 0;
  return true;
}

// ---- the wait of a live command ----

std::size_t event_loop::watch(int fd, short events) {
  fds_.push_back(pollfd{fd, events, 0});
  return fds_.size() - 1;
}

void event_loop::set(std::size_t index, int fd, short events) {
  fds_[index].fd = fd;
  fds_[index].events = events;
}

bool event_loop::wait(int timeout_ms) {
  for (pollfd& p : fds_) p.revents = 0;
  if (log_ != nullptr) log_->flush();
  if (!running()) return false;
  const int ready = ::poll(fds_.data(), fds_.size(), timeout_ms);
  if (ready < 0 && errno != EINTR) lost(std::string("poll: ") + std::strerror(errno));
  if (ready < 0) {
    for (pollfd& p : fds_) p.revents = 0;
  }
  return running();
}

void event_loop::lost(std::string cause) {
  if (lost_.empty()) lost_ = std::move(cause);
}

bool event_loop::running() const {
  return !stopped_ && lost_.empty() && !signal_watch::stop_requested() && !output_failed();
}

int event_loop::finish(const std::string& command) {
  if (log_ != nullptr) log_->flush();
  if (output_failed()) return fail_output();
  if (!lost_.empty()) return fail_io(command + ": " + lost_);
  return exit_ok;
}

// ---- captures ----

bool capture_file::open(const std::string& path, std::string& error) {
  file_.open(path, std::ios::binary | std::ios::trunc);
  if (!file_) {
    error = "cannot write the capture " + host::printable(path) + ": " + std::strerror(errno);
    return false;
  }
  writer_ = std::make_unique<host::pcapng_writer>(file_);
  errno = 0;
  check(writer_->flush() == host::pcapng_write_status::ok);
  return true;
}

void capture_file::check(bool ok) noexcept {
  if (ok || failed_) return;
  failed_ = true;
  errno_ = errno != 0 ? errno : EIO;
}

std::string capture_file::cause() const { return std::strerror(errno_ != 0 ? errno_ : EIO); }

std::uint32_t capture_file::add(const std::string& name, host::capture_network network) {
  if (!writer_) return 0;
  errno = 0;
  const host::pcapng_interface_result added = writer_->add_interface(name, network);
  check(added && writer_->flush() == host::pcapng_write_status::ok);
  return added.id;
}

void capture_file::write(std::uint32_t interface, std::uint64_t time_ns, byte_view record) {
  if (!writer_ || failed_) return;
  errno = 0;
  check(writer_->write(interface, time_ns, record) == host::pcapng_write_status::ok &&
        writer_->flush() == host::pcapng_write_status::ok);
}

// ---- command lines ----

bool line_reader::read_some() {
  char chunk[4096];
  const ssize_t got = ::read(fd_, chunk, sizeof chunk);
  if (got > 0) {
    for (ssize_t i = 0; i < got; ++i) {
      const char c = chunk[i];
      if (dropping_) {
        dropping_ = c != '\n';
      } else if (c == '\n') {
        pending_ += c;
        open_length_ = 0;
      } else if (open_length_ == max_line) {  // cut: what came so far is the line, its rest is dropped
        pending_ += '\n';
        open_length_ = 0;
        dropping_ = true;
      } else {
        pending_ += c;
        ++open_length_;
      }
    }
    return true;
  }
  if (got < 0 && (errno == EAGAIN || errno == EINTR)) return true;
  ended_ = true;
  if (!pending_.empty() && pending_.back() != '\n') pending_ += '\n';
  return false;
}

bool line_reader::next(std::string& line) {
  const std::size_t end = pending_.find('\n');
  if (end == std::string::npos) return false;
  line.assign(pending_, 0, end);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  pending_.erase(0, end + 1);
  return true;
}

std::vector<std::string> words_of(std::string_view line) {
  std::vector<std::string> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) words.emplace_back(line.substr(start, i - start));
  }
  return words;
}

bool unescape(std::string_view text, std::string& out, std::string& error) {
  out.clear();
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '\\') {
      out += text[i];
      continue;
    }
    if (i + 1 >= text.size()) {
      error = "a lone \\ at the end of the text";
      return false;
    }
    const char c = text[++i];
    if (c == 'r') {
      out += '\r';
    } else if (c == 'n') {
      out += '\n';
    } else if (c == 't') {
      out += '\t';
    } else if (c == '\\') {
      out += '\\';
    } else if (c == 'x' && i + 2 < text.size() && std::isxdigit(static_cast<unsigned char>(text[i + 1])) &&
               std::isxdigit(static_cast<unsigned char>(text[i + 2]))) {
      out += static_cast<char>(std::stoi(std::string(text.substr(i + 1, 2)), nullptr, 16));
      i += 2;
    } else {
      error = std::string("unknown escape \\") + c + " (use \\r \\n \\t \\\\ \\xNN)";
      return false;
    }
  }
  return true;
}

}  // namespace trionet::cli::live
