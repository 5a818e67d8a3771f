// Live-link test helpers: a pseudo-terminal pair (the test holds the master end, the tool opens the slave)
// and the `trionet` tool run as a second process with pipes on its standard input and output.
#pragma once

#include <fcntl.h>
#include <poll.h>
#include <sys/file.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "support/text_match.hpp"

namespace trionet::test {

/// A pty pair: the test reads and writes `master`; `slave_path` is what the tool opens as its port.
struct pty_pair {
  int master = -1;
  std::string slave_path;
  int slave_keep = -1;  // held open so that the master does not see a hang-up between the tool's runs

  pty_pair() {
    // A pty number is used again as soon as its pair is closed, even while a tool started by another test
    // still has the old device open and locked (as it has until it has exited): then the new device reads as
    // locked. Such a pair is kept aside, unused, while this one lives, and another is taken.
    for (int tries = 0; tries < 8 && open_pair(); ++tries) {
      if (::flock(slave_keep, LOCK_EX | LOCK_NB) == 0) {
        ::flock(slave_keep, LOCK_UN);
        break;
      }
      set_aside.push_back(master);
      set_aside.push_back(slave_keep);
      master = slave_keep = -1;
    }
    if (master < 0 || slave_keep < 0) return;
    termios raw{};
    ::tcgetattr(slave_keep, &raw);
    ::cfmakeraw(&raw);
    ::tcsetattr(slave_keep, TCSANOW, &raw);
    ::fcntl(master, F_SETFL, O_NONBLOCK);
  }
  ~pty_pair() {
    if (slave_keep >= 0) ::close(slave_keep);
    if (master >= 0) ::close(master);
    for (const int fd : set_aside) ::close(fd);
  }
  pty_pair(const pty_pair&) = delete;
  pty_pair& operator=(const pty_pair&) = delete;

  [[nodiscard]] bool ok() const { return master >= 0 && slave_keep >= 0; }

 private:
  std::vector<int> set_aside;

  // Close-on-exec: a tool started by the test must not hold the test's ends of the pair, or closing them
  // would not close the link.
  bool open_pair() {
    master = ::posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (master < 0 || ::grantpt(master) != 0 || ::unlockpt(master) != 0) return false;
    slave_path = ::ptsname(master);
    slave_keep = ::open(slave_path.c_str(), O_RDWR | O_NOCTTY | O_CLOEXEC);
    return slave_keep >= 0;
  }

 public:

  void write_all(const std::vector<std::uint8_t>& bytes) const {
    std::size_t done = 0;
    while (done < bytes.size()) {
      const ssize_t n = ::write(master, bytes.data() + done, bytes.size() - done);
      if (n > 0) {
        done += static_cast<std::size_t>(n);
      } else {
        pollfd p{master, POLLOUT, 0};
        ::poll(&p, 1, 100);
      }
    }
  }

  /// Reads from the master until `enough(bytes)` or `timeout_ms`.
  std::vector<std::uint8_t> read_until(const std::function<bool(const std::vector<std::uint8_t>&)>& enough,
                                       int timeout_ms) const {
    std::vector<std::uint8_t> got;
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    while (!enough(got) && std::chrono::steady_clock::now() < until) {
      pollfd p{master, POLLIN, 0};
      if (::poll(&p, 1, 20) <= 0) continue;
      std::uint8_t chunk[4096];
      const ssize_t n = ::read(master, chunk, sizeof chunk);
      if (n > 0) got.insert(got.end(), chunk, chunk + n);
    }
    return got;
  }
  std::vector<std::uint8_t> read_bytes(std::size_t count, int timeout_ms) const {
    return read_until([count](const std::vector<std::uint8_t>& b) { return b.size() >= count; }, timeout_ms);
  }
};

/// The tool running as a child, its standard input and output on pipes (standard error to `err_path`).
class tool_process {
 public:
  tool_process(const std::vector<std::string>& args, const std::string& err_path = "/dev/null") {
    int in[2];
    int out[2];
    if (::pipe(in) != 0 || ::pipe(out) != 0) return;
    pid_ = ::fork();
    if (pid_ == 0) {
      ::dup2(in[0], 0);
      ::dup2(out[1], 1);
      const int err = ::open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (err >= 0) ::dup2(err, 2);
      ::close(in[0]);
      ::close(in[1]);
      ::close(out[0]);
      ::close(out[1]);
      std::vector<char*> argv;
      std::string path = TRIONET_CLI_PATH;
      argv.push_back(path.data());
      std::vector<std::string> copy = args;
      for (std::string& a : copy) argv.push_back(a.data());
      argv.push_back(nullptr);
      ::execv(path.c_str(), argv.data());
      ::_exit(127);
    }
    ::close(in[0]);
    ::close(out[1]);
    stdin_ = in[1];
    stdout_ = out[0];
    ::fcntl(stdout_, F_SETFL, O_NONBLOCK);
  }
  ~tool_process() {
    close_input();
    if (pid_ > 0 && status_ < 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    if (stdout_ >= 0) ::close(stdout_);
  }
  tool_process(const tool_process&) = delete;
  tool_process& operator=(const tool_process&) = delete;

  void write(const std::string& text) const {
    if (stdin_ >= 0) (void)!::write(stdin_, text.data(), text.size());
  }
  void close_input() {
    if (stdin_ >= 0) ::close(stdin_);
    stdin_ = -1;
  }
  void signal(int number) const {
    if (pid_ > 0) ::kill(pid_, number);
  }

  /// Reads standard output until `enough(all output so far)` or `timeout_ms`; returns all output so far.
  const std::string& read_until(const std::function<bool(const std::string&)>& enough, int timeout_ms) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    while (!enough(out_) && std::chrono::steady_clock::now() < until) {
      pollfd p{stdout_, POLLIN, 0};
      if (::poll(&p, 1, 20) <= 0) continue;
      char chunk[4096];
      const ssize_t n = ::read(stdout_, chunk, sizeof chunk);
      if (n > 0) out_.append(chunk, static_cast<std::size_t>(n));
      if (n == 0) break;
    }
    return out_;
  }
  /// Output until it holds `count` lines containing `text`.
  const std::string& read_lines_with(const std::string& text, std::size_t count, int timeout_ms) {
    return read_until([&](const std::string& all) { return occurrences(all, text) >= count; }, timeout_ms);
  }
  /// Whether the process holds `path` open within `timeout_ms` (its /proc/PID/fd links): a test that acts on a
  /// port once the tool has opened it, however slow a loaded machine makes the start.
  bool holds_open(const std::string& path, int timeout_ms) const {
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    do {
      for (int fd = 0; fd < 64; ++fd) {
        const std::string link = "/proc/" + std::to_string(pid_) + "/fd/" + std::to_string(fd);
        char target[256];
        const ssize_t n = ::readlink(link.c_str(), target, sizeof target - 1);
        if (n > 0 && path == std::string(target, static_cast<std::size_t>(n))) return true;
      }
      ::usleep(10000);
    } while (std::chrono::steady_clock::now() < until);
    return false;
  }
  /// Waits for the process to end (at most `timeout_ms`); its exit code, or -1.
  int wait(int timeout_ms) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    while (status_ < 0 && std::chrono::steady_clock::now() < until) {
      read_until([](const std::string&) { return true; }, 0);
      int status = 0;
      if (::waitpid(pid_, &status, WNOHANG) == pid_) {
        status_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        break;
      }
      pollfd p{stdout_, POLLIN, 0};
      if (::poll(&p, 1, 20) > 0) {
        char chunk[4096];
        const ssize_t n = ::read(stdout_, chunk, sizeof chunk);
        if (n > 0) out_.append(chunk, static_cast<std::size_t>(n));
      }
    }
    if (status_ >= 0) {  // the rest of the output
      char chunk[4096];
      ssize_t n = 0;
      while ((n = ::read(stdout_, chunk, sizeof chunk)) > 0) out_.append(chunk, static_cast<std::size_t>(n));
    }
    return status_;
  }
  [[nodiscard]] const std::string& output() const { return out_; }

  static std::size_t occurrences(const std::string& all, const std::string& text) {
    std::size_t count = 0;
    for (std::size_t at = all.find(text); at != std::string::npos; at = all.find(text, at + 1)) ++count;
    return count;
  }

 private:
  pid_t pid_ = -1;
  int stdin_ = -1;
  int stdout_ = -1;
  int status_ = -1;
  std::string out_;
};

/// JSON event lines of the live commands with their "time" field (right after the kind, seconds since 1970
/// with 9 decimals) taken out, so that a test can look for the fields after it. The number of lines that
/// had no such field is added to `without`.
inline std::string without_times(const std::string& events, std::size_t* without = nullptr) {
  const std::string time_field = ",\"time\":\"[0-9]+\\.[0-9]{9}\"";
  std::string out;
  std::size_t at = 0;
  while (at < events.size()) {
    std::size_t end = events.find('\n', at);
    end = end == std::string::npos ? events.size() : end + 1;
    const std::string line = events.substr(at, end - at);
    const std::string cut = replace_pattern(line, time_field, "", true);
    if (without != nullptr && cut == line && line.rfind("{\"event\":", 0) == 0) ++*without;
    out += cut;
    at = end;
  }
  return out;
}

/// The events of the given kinds, one string each, with their positions taken out (time, line, record,
/// interface_id, interface): what a live command printed, to compare with what `decode --pcap` prints for
/// the capture it wrote.
inline std::vector<std::string> events_without_positions(const std::string& events,
                                                         const std::vector<std::string>& kinds) {
  const std::string position = ",\"(time|line|record|interface_id|interface)\":(\"([^\"\\\\]|\\\\.)*\"|[0-9]+)";
  std::vector<std::string> out;
  std::size_t at = 0;
  while (at < events.size()) {
    std::size_t end = events.find('\n', at);
    if (end == std::string::npos) end = events.size();
    const std::string line = events.substr(at, end - at);
    at = end + 1;
    for (const std::string& kind : kinds) {
      if (line.rfind("{\"event\":\"" + kind + "\"", 0) == 0) out.push_back(replace_pattern(line, position, ""));
    }
  }
  return out;
}

}  // namespace trionet::test
