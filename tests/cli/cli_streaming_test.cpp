// The decoders stream: through a pipe, an event is printed while the writer is still writing (the pipe stays
// open), and memory does not grow with the input (peak resident memory of the tool, from wait4, for a small
// and a large input). Speed and latency figures are measured by scripts/decode-figures, not here.
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fcntl.h>

#include <cerrno>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

// The tool running with its standard input and output on pipes.
struct child {
  pid_t pid = -1;
  int in = -1;   // write end: the tool's standard input
  int out = -1;  // read end: the tool's standard output (or -1 when it goes to /dev/null)
};

child spawn(const std::vector<std::string>& args, bool read_output) {
  int to_child[2];
  int from_child[2] = {-1, -1};
  if (::pipe(to_child) != 0 || (read_output && ::pipe(from_child) != 0)) return {};
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::dup2(to_child[0], STDIN_FILENO);
    if (read_output) {
      ::dup2(from_child[1], STDOUT_FILENO);
    } else {
      const int null = ::open("/dev/null", O_WRONLY);
      ::dup2(null, STDOUT_FILENO);
    }
    ::close(to_child[1]);
    if (read_output) ::close(from_child[0]);
    // Under AddressSanitizer freed memory waits in a quarantine (256 MB by default), which would look like
    // growth: keep it small, so that the figure is the decoder's own memory.
    const char* asan = std::getenv("ASAN_OPTIONS");
    const std::string options = std::string(asan != nullptr ? asan : "") + ":quarantine_size_mb=1";
    ::setenv("ASAN_OPTIONS", options.c_str(), 1);
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(TRIONET_CLI_PATH));
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(TRIONET_CLI_PATH, argv.data());
    ::_exit(127);
  }
  ::close(to_child[0]);
  if (read_output) ::close(from_child[1]);
  return {pid, to_child[1], read_output ? from_child[0] : -1};
}

bool write_all(int fd, const std::string& data) {
  std::size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

// Reads until a newline arrives or `timeout_ms` passes; what arrived.
std::string read_line(int fd, int timeout_ms) {
  std::string got;
  while (got.find('\n') == std::string::npos) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, timeout_ms) <= 0) break;
    char buffer[4096];
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n <= 0) break;
    got.append(buffer, static_cast<std::size_t>(n));
  }
  return got;
}

// The first event comes out while the writer keeps the pipe open (a generous 20 s for a loaded machine:
// this checks that the tool does not wait for the end of its input, not how fast it is).
void expect_event_before_end(const std::vector<std::string>& args, const std::string& first, const std::string& want) {
  const child c = spawn(args, true);
  ASSERT_GT(c.pid, 0);
  ASSERT_TRUE(write_all(c.in, first));
  const std::string got = read_line(c.out, 20000);
  EXPECT_NE(got.find(want), std::string::npos) << "no event while the input is still open; got: " << got;
  ::close(c.in);
  while (!read_line(c.out, 20000).empty()) {
  }
  ::close(c.out);
  int status = 0;
  ::waitpid(c.pid, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
}

TEST(CliStreaming, EachDecoderPrintsAnEventBeforeItsInputEnds) {
  expect_event_before_end({"ring", "decode"}, "8b 03 88\n", "\"type\":\"offset\"");
  expect_event_before_end({"ring", "decode", "--raw"}, std::string("\x8b\x03\x88", 3), "\"type\":\"offset\"");
  expect_event_before_end({"can", "decode"}, "(1700000000.123456) can0 028#0100000000020D7A\n", "\"event\":\"vr\"");
  expect_event_before_end({"genius", "decode"}, "c:23 5a c:75\n", "transmission from SBA 3");
}

// Peak resident memory (KiB) of `trionet args` decoding `repeat` copies of `unit` written to a pipe.
long peak_kib(const std::vector<std::string>& args, const std::string& unit, std::size_t repeat) {
  const child c = spawn(args, false);
  if (c.pid <= 0) return -1;
  std::string block;
  while (block.size() < (1U << 20U)) block += unit;
  const std::size_t blocks = unit.size() * repeat / block.size() + 1;
  for (std::size_t i = 0; i < blocks; ++i) {
    if (!write_all(c.in, block)) break;
  }
  ::close(c.in);
  int status = 0;
  rusage usage{};
  if (::wait4(c.pid, &status, 0, &usage) != c.pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0) return -1;
  return usage.ru_maxrss;
}

#if defined(__SANITIZE_ADDRESS__)
constexpr bool sanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool sanitized = true;
#else
constexpr bool sanitized = false;
#endif
#else
constexpr bool sanitized = false;
#endif

// 1 MiB and 16 MiB of input: the peak must not grow with it (a decoder that kept its input would need 15 MiB
// more), and without sanitizers it stays below 16 MiB. scripts/decode-figures measures 100 MB.
void expect_bounded(const std::vector<std::string>& args, const std::string& unit) {
  const long small = peak_kib(args, unit, (1U << 20U) / unit.size());
  const long large = peak_kib(args, unit, (16U << 20U) / unit.size());
  ASSERT_GT(small, 0);
  ASSERT_GT(large, 0);
  EXPECT_LT(large, small + 4096) << "peak KiB for 1 MiB: " << small << ", for 16 MiB: " << large;
  if (!sanitized) {
    EXPECT_LT(large, 16 * 1024) << "peak KiB for 16 MiB of input";
  }
}

TEST(CliStreaming, MemoryDoesNotGrowWithTheInput) {
  expect_bounded({"ring", "decode"}, "8a 48 01 00 00 00 00 30 0c 00 00 00 00 7f 3e 88 91 48 49 90\n");
  expect_bounded({"ring", "decode", "--raw"},
                 std::string("\x8a\x48\x01\x00\x00\x00\x00\x30\x0c\x00\x00\x00\x00\x7f\x3e\x88\x91\x48\x49\x90", 20));
  expect_bounded({"can", "decode"}, "(1700000000.123456) can0 028#0100000000020D7A R\n");
  expect_bounded({"genius", "decode"}, "c:04 07 11 22 c:89 aa bb c:ce 33 c:50\n");
}

}  // namespace
