// `trionet ring wire ENDPOINT ENDPOINT ...`: the fibre between byte endpoints. What endpoint i sends goes to
// endpoint i + 1, and what the last sends to the first, so programs that each own one endpoint (emulated
// boards on Unix sockets, `ring join` on a pty, real nodes on serial adapters) form one ring. Each link can
// lose and corrupt bytes (seeded), be cut for a while, and is decoded as its next node receives it (events,
// a capture with one interface per link, counters).
#include <fcntl.h>
#include <arpa/inet.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "cli.hpp"
#include "live.hpp"
#include "profile_cli.hpp"
#include "ring_cli.hpp"
#include "ring_live.hpp"
#include "ring_wire_cli.hpp"
#include "trionet/host/link_device.hpp"
#include "trionet/ring/bytes.hpp"

namespace trionet::cli {

const char* const ring_wire_usage =
    "usage: trionet ring wire ENDPOINT ENDPOINT [ENDPOINT...] [options]\n"
    "Connects the endpoints into a ring in the order given: what endpoint i sends goes to endpoint i+1, what\n"
    "the last sends goes to the first. Link i runs from endpoint i to endpoint i+1 (both counted from 0).\n"
    "ENDPOINT:\n"
    "  PATH            a serial port or pty (raw, 8N1, --baud), a FIFO or a Unix socket\n"
    "  unix:PATH       a Unix stream socket to connect to (QEMU's -chardev socket,server=on)\n"
    "  tcp:HOST:PORT   a TCP connection\n"
    "  pty[:LINK]      a new pseudo-terminal for another program to open (`ring join`); its path is printed\n"
    "                  as a \"pty\" event, and LINK, if given, is made a symbolic link to it\n"
    "options:\n"
    "  --drop [L:]P    lose each byte with probability P (0..1): on link L, else on every link (repeatable)\n"
    "  --flip [L:]P    flip one bit of each byte with probability P (repeatable)\n"
    "  --cut L@T+D     link L carries nothing from T ms after the start for D ms (repeatable)\n"
    "  --seed S        seed of the faults (default 1): each link draws from its own generator\n"
    "  --pcap FILE     every link's bytes as its next endpoint receives them, one interface per link\n"
    "  --json          events as JSON lines (else text for people)\n"
    "  --trace         also an event for every message on every link\n"
    "  --idle-ms T     a link with a message open that carries nothing for T ms is idle: the message is\n"
    "                  reported cut short (docs/protocol.md 1.10; default 50)\n"
    "  --connect-ms T  keep trying to connect unix: and tcp: endpoints for T ms (default 5000)\n"
    "  --baud B        serial ports: bits per second (default 125000)\n"
    "Commands on standard input, one per line: drop [L:]P | flip [L:]P | cut L D (link L for D ms, now) |\n"
    "  faults off | counters | quit\n"
    "Events: pty, faults, cut, cut_end, damaged (a message the faults changed, at its end: its bytes as sent\n"
    "and as received, and `began`, when its first byte came), frame_error and crc_error as the next endpoint\n"
    "receives them (each with its link), and one counters event per link at the end, on SIGUSR1 and on\n"
    "`counters`.\n"
    "Exit status: 0 stopped by quit, Ctrl-C or SIGTERM; 1 an endpoint could not be opened, or it closed or\n"
    "failed while the wire ran (the ring is broken); 2 bad arguments, a malformed endpoint among them (tcp:\n"
    "without a host, a port outside 1..65535).\n";

const option_list& ring_wire_options() {
  static const option_list options = {
      {"ENDPOINT", nullptr, "@port unix:@file tcp: pty pty:@file",
       "PATH (a serial port or pty, a FIFO, a Unix socket), unix:PATH, tcp:HOST:PORT, or pty[:LINK]"},
      {"--drop", "[L:]P", "", "lose each byte with probability P: on link L, else on every link", true},
      {"--flip", "[L:]P", "", "flip one bit of each byte with probability P", true},
      {"--cut", "L@T+D", "", "link L carries nothing from T ms after the start for D ms", true},
      {"--seed", "S", "", "seed of the faults (default 1)"},
      {"--pcap", "FILE", "@file", "every link's bytes as its next endpoint receives them"},
      {"--json", nullptr, "", "events as JSON lines"},
      {"--trace", nullptr, "", "also an event for every message on every link"},
      {"--idle-ms", "T", "", "a link with a message open that carries nothing for T ms is idle (default 50)"},
      {"--connect-ms", "T", "", "keep trying to connect unix: and tcp: endpoints for T ms (default 5000)"},
      {"--baud", "B", "9600 19200 38400 57600 115200 125000 250000 500000 1000000",
       "serial ports: bits per second (default 125000)"},
  };
  return options;
}

namespace {

constexpr std::size_t link_buffer = 1U << 16U;  // bytes waiting for the next endpoint, per link
constexpr std::size_t read_chunk = 4096;
constexpr std::size_t damaged_bytes_shown = 64;  // a damaged message's bytes in its event

std::uint64_t monotonic_ns() {
  timespec t{};
  ::clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<std::uint64_t>(t.tv_sec) * 1000000000U + static_cast<std::uint64_t>(t.tv_nsec);
}

// ---- endpoints ----

class endpoint {
 public:
  endpoint() = default;
  ~endpoint() { close(); }
  endpoint(const endpoint&) = delete;
  endpoint& operator=(const endpoint&) = delete;

  // Opens what `spec` names; false with `error` naming it and the cause.
  bool open(const std::string& spec, const host::link_options& options, int connect_ms, std::string& error) {
    spec_ = spec;
    if (spec.compare(0, 5, "unix:") == 0) return connect_unix(spec.substr(5), connect_ms, error);
    if (spec.compare(0, 4, "tcp:") == 0) return connect_tcp(spec.substr(4), connect_ms, error);
    if (spec == "pty" || spec.compare(0, 4, "pty:") == 0) return open_pty(spec.size() > 4 ? spec.substr(4) : "", error);
    if (!device_.open(spec, options, error)) return false;
    fd_ = device_.fd();
    return true;
  }

  void close() noexcept {
    if (device_.fd() >= 0) {
      device_.close();
    } else if (fd_ >= 0) {
      ::close(fd_);
    }
    fd_ = -1;
    if (pty_keeper_ >= 0) ::close(pty_keeper_);
    pty_keeper_ = -1;
    if (!symlink_.empty()) ::unlink(symlink_.c_str());
    symlink_.clear();
  }

  [[nodiscard]] int fd() const noexcept { return fd_; }
  [[nodiscard]] const std::string& spec() const noexcept { return spec_; }
  [[nodiscard]] const std::string& pty_path() const noexcept { return pty_path_; }
  [[nodiscard]] const std::string& symlink() const noexcept { return symlink_; }

 private:
  bool connect_unix(const std::string& path, int connect_ms, std::string& error) {
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    if (path.empty() || path.size() >= sizeof address.sun_path) {
      error = "unix:" + host::printable(path) + ": the socket path must be 1.." +
              std::to_string(sizeof address.sun_path - 1) + " characters";
      return false;
    }
    std::memcpy(address.sun_path, path.c_str(), path.size() + 1);
    const std::uint64_t until = monotonic_ns() + static_cast<std::uint64_t>(connect_ms) * 1000000U;
    for (;;) {
      fd_ = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
      if (fd_ < 0) {
        error = "cannot make a socket for " + host::printable(spec_) + ": " + std::strerror(errno);
        return false;
      }
      // sockaddr_un is the address type connect() expects for AF_UNIX; the cast is the socket API's contract.
      if (::connect(fd_, reinterpret_cast<const sockaddr*>(&address), sizeof address) == 0) break;
      const int cause = errno;
      ::close(fd_);
      fd_ = -1;
      if ((cause != ENOENT && cause != ECONNREFUSED) || monotonic_ns() >= until) {
        error = "cannot connect to " + host::printable(spec_) + ": " + std::strerror(cause);
        return false;
      }
      ::usleep(20000);
    }
    (void)::fcntl(fd_, F_SETFL, O_NONBLOCK);
    return true;
  }

  bool connect_tcp(const std::string& where, int connect_ms, std::string& error) {
    const std::size_t colon = where.rfind(':');
    if (colon == std::string::npos || colon == 0 || colon + 1 == where.size()) {
      error = "tcp:" + host::printable(where) + ": expected tcp:HOST:PORT";
      return false;
    }
    std::string host_name = where.substr(0, colon);
    if (host_name.size() > 2 && host_name.front() == '[' && host_name.back() == ']') {
      host_name = host_name.substr(1, host_name.size() - 2);
    }
    long long port = 0;
    if (!parse_integer(where.substr(colon + 1), 1, 65535, port)) {
      error = host::printable(spec_) + ": the port must be 1..65535";
      return false;
    }
    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    addrinfo* found = nullptr;
    const int status = ::getaddrinfo(host_name.c_str(), std::to_string(port).c_str(), &hints, &found);
    if (status != 0) {
      error = "cannot resolve " + host::printable(host_name) + ": " + ::gai_strerror(status);
      return false;
    }
    std::unique_ptr<addrinfo, void (*)(addrinfo*)> addresses(found, ::freeaddrinfo);
    const std::uint64_t until = monotonic_ns() + static_cast<std::uint64_t>(connect_ms) * 1000000U;
    int cause = 0;
    for (;;) {
      for (const addrinfo* a = addresses.get(); a != nullptr; a = a->ai_next) {
        fd_ = ::socket(a->ai_family, a->ai_socktype | SOCK_CLOEXEC, a->ai_protocol);
        if (fd_ < 0) {
          cause = errno;
          continue;
        }
        if (::connect(fd_, a->ai_addr, a->ai_addrlen) == 0) {
          const int on = 1;
          (void)::setsockopt(fd_, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
          (void)::fcntl(fd_, F_SETFL, O_NONBLOCK);
          return true;
        }
        cause = errno;
        ::close(fd_);
        fd_ = -1;
      }
      if (cause != ECONNREFUSED || monotonic_ns() >= until) break;
      ::usleep(20000);
    }
    error = "cannot connect to " + host::printable(spec_) + ": " + std::strerror(cause);
    return false;
  }

  bool open_pty(const std::string& link, std::string& error) {
    fd_ = ::posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (fd_ < 0 || ::grantpt(fd_) != 0 || ::unlockpt(fd_) != 0) {
      error = std::string("cannot make a pty: ") + std::strerror(errno);
      return false;
    }
    char name[128];
    if (::ptsname_r(fd_, name, sizeof name) != 0) {
      error = std::string("cannot name the new pty: ") + std::strerror(errno);
      return false;
    }
    pty_path_ = name;
    // The wire keeps the other side open itself, raw: a program that opens it later finds no echo and no
    // line discipline, and its closing does not end the wire (another may open it again).
    pty_keeper_ = ::open(name, O_RDWR | O_NOCTTY | O_CLOEXEC);
    termios tio{};
    if (pty_keeper_ < 0 || ::tcgetattr(pty_keeper_, &tio) != 0) {
      error = "cannot open the new pty " + pty_path_ + ": " + std::strerror(errno);
      return false;
    }
    ::cfmakeraw(&tio);
    (void)::tcsetattr(pty_keeper_, TCSANOW, &tio);
    (void)::fcntl(fd_, F_SETFL, O_NONBLOCK);
    if (!link.empty()) {
      (void)::unlink(link.c_str());  // a link left by an earlier run
      if (::symlink(name, link.c_str()) != 0) {
        error = "cannot link " + host::printable(link) + " to " + pty_path_ + ": " + std::strerror(errno);
        return false;
      }
      symlink_ = link;
    }
    return true;
  }

  std::string spec_;
  int fd_ = -1;
  host::link_device device_;
  int pty_keeper_ = -1;
  std::string pty_path_;
  std::string symlink_;
};

// The endpoint's syntax, before anything is opened: empty when `spec` is well formed, else what is wrong
// with it (a bad argument, exit 2; failing to open or connect a well-formed one is a runtime failure, 1).
std::string endpoint_syntax_error(const std::string& spec) {
  const std::string named = host::printable(spec);
  if (spec.empty()) return "an endpoint is empty: expected PATH, unix:PATH, tcp:HOST:PORT or pty[:LINK]";
  if (spec.compare(0, 5, "unix:") == 0) {
    const std::size_t length = spec.size() - 5;
    const std::size_t most = sizeof(sockaddr_un{}.sun_path) - 1;
    if (length == 0 || length > most) {
      return named + ": the socket path must be 1.." + std::to_string(most) + " characters";
    }
    return "";
  }
  if (spec.compare(0, 4, "tcp:") != 0) return "";
  const std::string where = spec.substr(4);
  const std::size_t colon = where.rfind(':');
  if (colon == std::string::npos) return named + ": expected tcp:HOST:PORT (no port)";
  std::string host_name = where.substr(0, colon);
  const std::string port_text = where.substr(colon + 1);
  if (host_name.empty()) return named + ": expected tcp:HOST:PORT (the host is empty)";
  if (port_text.empty()) return named + ": expected tcp:HOST:PORT (the port is empty)";
  long long port = 0;
  if (!parse_integer(port_text, 1, 65535, port)) {
    return named + ": the port must be a number 1..65535, got '" + host::printable(port_text) + "'";
  }
  if (host_name.front() == '[' || host_name.back() == ']') {
    in6_addr address{};
    if (host_name.size() < 3 || host_name.front() != '[' || host_name.back() != ']' ||
        ::inet_pton(AF_INET6, host_name.substr(1, host_name.size() - 2).c_str(), &address) != 1) {
      return named + ": the host '" + host::printable(host_name) + "' is not an IPv6 address in [ ]";
    }
    return "";
  }
  in6_addr address{};
  if (host_name.find(':') != std::string::npos) {
    if (::inet_pton(AF_INET6, host_name.c_str(), &address) == 1) return "";
    return named + ": the host '" + host::printable(host_name) + "' is not a host name or address";
  }
  for (const char c : host_name) {
    const bool fits = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
                      c == '.' || c == '_';
    if (!fits) {
      return named + ": the host '" + host::printable(host_name) +
             "' is not a host name or address (letters, digits, '-', '.' and '_' only)";
    }
  }
  return "";
}

// ---- faults ----

struct fault_settings {
  double drop = 0;
  double flip = 0;
};

// "P" or "L:P" for `links` links: which links (all when `link` is -1) and the probability.
bool parse_probability(const std::string& text, std::size_t links, int& link, double& p, std::string& error) {
  link = -1;
  std::string value = text;
  const std::size_t colon = text.find(':');
  if (colon != std::string::npos) {
    long long l = 0;
    if (!parse_integer(text.substr(0, colon), 0, static_cast<long long>(links) - 1, l)) {
      error = "no link " + host::printable(text.substr(0, colon)) + " (links 0.." + std::to_string(links - 1) + ")";
      return false;
    }
    link = static_cast<int>(l);
    value = text.substr(colon + 1);
  }
  if (!host::parse_real(value, 0.0, 1.0, p)) {
    error = "a probability is a number 0..1, got '" + host::printable(value) + "'";
    return false;
  }
  return true;
}

struct scheduled_cut {
  std::size_t link = 0;
  std::uint64_t at_ms = 0;
  std::uint64_t for_ms = 0;
};

// "L@T+D".
bool parse_cut(const std::string& text, std::size_t links, scheduled_cut& cut, std::string& error) {
  const std::size_t at = text.find('@');
  const std::size_t plus = text.find('+', at == std::string::npos ? 0 : at);
  long long l = 0;
  long long t = 0;
  long long d = 0;
  if (at == std::string::npos || plus == std::string::npos ||
      !parse_integer(text.substr(0, at), 0, static_cast<long long>(links) - 1, l) ||
      !parse_integer(text.substr(at + 1, plus - at - 1), 0, 86400000, t) ||
      !parse_integer(text.substr(plus + 1), 1, 86400000, d)) {
    error = "--cut takes L@T+D (link 0.." + std::to_string(links - 1) +
            ", T and D in milliseconds), got '" + host::printable(text) + "'";
    return false;
  }
  cut = {static_cast<std::size_t>(l), static_cast<std::uint64_t>(t), static_cast<std::uint64_t>(d)};
  return true;
}

// ---- links ----

// Each link's own generator: the seed and the link's number mixed (SplitMix64's finaliser), so that links
// draw different faults and a link's faults do not depend on how many links there are.
std::uint64_t link_seed(std::uint64_t seed, std::size_t index) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15U * (static_cast<std::uint64_t>(index) + 1);
  z = (z ^ (z >> 30U)) * 0xBF58476D1CE4E5B9U;
  z = (z ^ (z >> 27U)) * 0x94D049BB133111EBU;
  return z ^ (z >> 31U);
}

// One link: the bytes endpoint `from` sent, with the faults applied, on their way to endpoint `to`.
class link {
 public:
  link(std::size_t index, std::size_t from, std::size_t to, std::uint64_t seed, live::capture_file* capture,
       const std::string& name)
      : index_(index), from_(from), to_(to), random_(link_seed(seed, index)),
        tap_(capture, name) {}

  fault_settings faults;

  [[nodiscard]] std::size_t from() const noexcept { return from_; }
  [[nodiscard]] std::size_t to() const noexcept { return to_; }
  [[nodiscard]] std::size_t waiting() const noexcept { return pending_.size() - sent_; }
  [[nodiscard]] bool room() const noexcept { return pending_.size() - sent_ + read_chunk <= link_buffer; }
  [[nodiscard]] bool cut() const noexcept { return cut_until_ != 0; }
  [[nodiscard]] bool open() const noexcept { return tap_.open() || !segment_.empty(); }
  [[nodiscard]] std::uint64_t last_byte() const noexcept { return last_byte_; }

  void start_cut(std::uint64_t until_monotonic) {
    cut_until_ = until_monotonic;
    ++cuts_;
  }
  // Ends the cut if its time is over (or at once with `now`); true if it did.
  bool end_cut(std::uint64_t now_monotonic, bool now = false) {
    if (cut_until_ == 0 || (!now && now_monotonic < cut_until_)) return false;
    cut_until_ = 0;
    return true;
  }
  [[nodiscard]] std::uint64_t cut_until() const noexcept { return cut_until_; }
  [[nodiscard]] std::uint64_t cut_bytes() const noexcept { return cut_bytes_; }

  // Bytes endpoint `from` sent at `time_ns`: faults, then into the buffer for `to` and through the tap.
  void carry(const std::uint8_t* bytes, std::size_t size, std::uint64_t time_ns, std::uint64_t now_monotonic,
             std::string& events, bool trace) {
    last_byte_ = now_monotonic;
    bytes_in_ += size;
    const ring_tap::sink sink = reporter(events, trace);
    for (std::size_t i = 0; i < size; ++i) {
      const std::uint8_t sent = bytes[i];
      if (!ring::is_data(sent) && ring::type_of(sent) != 0) end_segment(time_ns, events);  // a header
      if (segment_.size() < damaged_bytes_shown) segment_.push_back(sent);
      if (segment_length_++ == 0) segment_began_ = time_ns;
      bool keep = true;
      std::uint8_t byte = sent;
      if (cut_until_ != 0) {
        keep = false;
        ++cut_bytes_;
        ++segment_cut_;
      } else {
        if (faults.drop > 0 && chance(faults.drop)) {
          keep = false;
          ++dropped_;
          ++segment_dropped_;
        } else if (faults.flip > 0 && chance(faults.flip)) {
          byte = static_cast<std::uint8_t>(byte ^ (1U << bit_(random_)));
          ++flipped_;
          ++segment_flipped_;
        }
      }
      if (keep) {
        pending_.push_back(byte);
        ++segment_kept_;
        if (received_.size() < damaged_bytes_shown) received_.push_back(byte);
        tap_.push(byte, time_ns, sink);
      }
      if (!ring::is_data(sent) && ring::type_of(sent) == 0) end_segment(time_ns, events);  // an end of message
    }
    if (sent_ != 0 && sent_ == pending_.size()) {
      pending_.clear();
      sent_ = 0;
    }
  }

  // Writes what waits to `fd`. False with `error` (errno) when the endpoint failed.
  bool deliver(int fd, int& error) {
    while (waiting() != 0) {
      const ssize_t wrote = ::write(fd, pending_.data() + sent_, waiting());
      if (wrote > 0) {
        sent_ += static_cast<std::size_t>(wrote);
        bytes_out_ += static_cast<std::uint64_t>(wrote);
        continue;
      }
      if (wrote < 0 && errno == EINTR) continue;
      if (wrote < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) break;
      error = wrote < 0 ? errno : EIO;
      return false;
    }
    if (sent_ == pending_.size()) {
      pending_.clear();
      sent_ = 0;
    } else if (sent_ > link_buffer) {
      pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(sent_));
      sent_ = 0;
    }
    return true;
  }

  // The link carried nothing for the idle time: a message open at the next endpoint is cut short there.
  void idle(std::uint64_t time_ns, std::string& events, bool trace) {
    end_segment(time_ns, events);
    tap_.idle(time_ns, reporter(events, trace));
  }

  void counters(std::string& out, std::uint64_t time_ns, const std::string& from, const std::string& to) const {
    event e(out, "counters");
    e.time(time_ns).number("link", index_).text("from", from).text("to", to);
    e.number("bytes_in", bytes_in_).number("bytes_out", bytes_out_).number("bytes_waiting", waiting());
    e.number("dropped", dropped_).number("flipped", flipped_).number("cuts", cuts_).number("cut_bytes", cut_bytes_);
    e.number("messages_sent", messages_).number("messages_damaged", damaged_).number("messages_vanished", vanished_);
    tap_.add_counters(e, "received_");
    if (last_error_ != 0) e.json("last_error", "\"" + epoch_text(last_error_) + "\"");
  }

 private:
  // What the next endpoint receives, decoded: errors (and with `trace` every message) as events.
  ring_tap::sink reporter(std::string& events, bool trace) {
    return [this, &events, trace](const ring::decode_result& r, std::uint64_t t) {
      if (r.status != ring::decode_status::ok) last_error_ = t;
      if (!trace && r.status == ring::decode_status::ok) return;
      append_ring_event(events, r, [&](event& e) { e.time(t).number("link", index_); });
    };
  }

  bool chance(double p) { return std::generate_canonical<double, 53>(random_) < p; }

  // The message that `segment_` holds ends (at a header, an end of message or the idle line): if the faults
  // changed it, a "damaged" event with the bytes as they were sent.
  void end_segment(std::uint64_t time_ns, std::string& events) {
    if (segment_length_ == 0) return;
    if (!segment_.empty() && !ring::is_data(segment_.front()) && ring::type_of(segment_.front()) != 0) {
      ++messages_;
    }
    if (segment_dropped_ + segment_flipped_ + segment_cut_ != 0) {
      ++damaged_;
      const bool vanished = segment_kept_ == 0;
      if (vanished) ++vanished_;
      event e(events, "damaged");
      e.time(time_ns).number("link", index_);
      e.number("dropped", segment_dropped_).number("flipped", segment_flipped_).number("cut", segment_cut_);
      e.boolean("vanished", vanished).number("length", segment_length_);
      e.text("bytes", hex_line(segment_.data(), segment_.size()));
      e.text("received", hex_line(received_.data(), received_.size()));
      e.json("began", "\"" + epoch_text(segment_began_) + "\"");
    }
    segment_.clear();
    received_.clear();
    segment_length_ = segment_dropped_ = segment_flipped_ = segment_cut_ = segment_kept_ = 0;
  }

  std::size_t index_;
  std::size_t from_;
  std::size_t to_;
  std::mt19937_64 random_;
  std::uniform_int_distribution<unsigned> bit_{0, 7};
  ring_tap tap_;
  std::vector<std::uint8_t> pending_;
  std::size_t sent_ = 0;
  std::uint64_t cut_until_ = 0;  // monotonic ns; 0: not cut
  std::uint64_t last_byte_ = 0;  // monotonic ns
  std::uint64_t last_error_ = 0;  // epoch ns of the last frame or CRC error the next endpoint received
  std::uint64_t bytes_in_ = 0;
  std::uint64_t bytes_out_ = 0;
  std::uint64_t dropped_ = 0;
  std::uint64_t flipped_ = 0;
  std::uint64_t cuts_ = 0;
  std::uint64_t cut_bytes_ = 0;
  std::uint64_t messages_ = 0;
  std::uint64_t damaged_ = 0;
  std::uint64_t vanished_ = 0;
  // The message being sent, as sent and as received (their first bytes), and what the faults did to it.
  std::vector<std::uint8_t> segment_;
  std::vector<std::uint8_t> received_;
  std::uint64_t segment_length_ = 0;
  std::uint64_t segment_began_ = 0;  // epoch ns of the read that carried the segment's first byte
  std::uint64_t segment_dropped_ = 0;
  std::uint64_t segment_flipped_ = 0;
  std::uint64_t segment_cut_ = 0;
  std::uint64_t segment_kept_ = 0;
};

// ---- the wire ----

struct wire_settings {
  std::vector<std::string> endpoints;
  host::link_options link;
  int idle_ms = 50;
  int connect_ms = 5000;
  std::uint64_t seed = 1;
  bool json = false;
  bool trace = false;
  std::string pcap;
  std::vector<fault_settings> faults;  // per link
  std::vector<scheduled_cut> cuts;
};

void faults_event(std::string& out, int link, const fault_settings& f) {
  event e(out, "faults");
  e.time(live::now_ns());
  if (link >= 0) {
    e.signed_number("link", link);
  } else {
    e.name("link", "all");
  }
  e.real("drop", f.drop).real("flip", f.flip);
}

class wire {
 public:
  explicit wire(wire_settings settings) : settings_(std::move(settings)), log_(settings_.json) {}

  int run() {
    live::signal_watch signals;  // before anything is printed: a signal then already ends the wire in order
    std::string error;
    if (!settings_.pcap.empty() && !capture_.open(settings_.pcap, error)) return fail("ring wire: " + error);
    const std::size_t n = settings_.endpoints.size();
    endpoints_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      endpoints_[i] = std::make_unique<endpoint>();
      if (!endpoints_[i]->open(settings_.endpoints[i], settings_.link, settings_.connect_ms, error)) {
        return fail_io("ring wire: " + error);
      }
      if (!endpoints_[i]->pty_path().empty()) {
        event e(log_.text(), "pty");
        e.time(live::now_ns()).number("endpoint", i).text("path", endpoints_[i]->pty_path());
        if (!endpoints_[i]->symlink().empty()) e.text("link", endpoints_[i]->symlink());
      }
    }
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t to = (i + 1) % n;
      links_.push_back(std::make_unique<link>(
          i, i, to, settings_.seed, capture_.is_open() ? &capture_ : nullptr,
          "link " + std::to_string(i) + ": " + settings_.endpoints[i] + " -> " + settings_.endpoints[to]));
      links_.back()->faults = settings_.faults[i];
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (settings_.faults[i].drop > 0 || settings_.faults[i].flip > 0) {
        faults_event(log_.text(), static_cast<int>(i), settings_.faults[i]);
      }
    }
    started_ = monotonic_ns();
    log_.flush();

    live::line_reader input(STDIN_FILENO);
    bool input_open = true;
    std::string ended;
    bool quit = false;
    // A standard output that cannot be written ends the wire (its events are what it reports): the events
    // would otherwise be lost in silence, the paths of its ptys among them.
    while (!quit && !live::signal_watch::stop_requested() && !output_failed()) {
      if (live::signal_watch::take_report_request()) counters();
      const std::uint64_t now = monotonic_ns();
      schedule(now);
      std::vector<pollfd> fds;
      for (std::size_t i = 0; i < n; ++i) {
        short events = 0;
        if (links_[i]->room()) events = static_cast<short>(events | POLLIN);
        if (links_[(i + n - 1) % n]->waiting() != 0) events = static_cast<short>(events | POLLOUT);
        fds.push_back({endpoints_[i]->fd(), events, 0});
      }
      if (input_open) fds.push_back({STDIN_FILENO, POLLIN, 0});
      log_.flush();
      const int ready = ::poll(fds.data(), static_cast<nfds_t>(fds.size()), wait_ms(now));
      if (ready < 0) {
        if (errno == EINTR) continue;
        ended = std::string("poll: ") + std::strerror(errno);
        break;
      }
      const std::uint64_t after = monotonic_ns();
      const std::uint64_t time = live::now_ns();
      for (std::size_t i = 0; i < n && ended.empty(); ++i) {
        if ((fds[i].revents & POLLIN) != 0) {
          std::uint8_t in[read_chunk];
          const ssize_t got = ::read(endpoints_[i]->fd(), in, sizeof in);
          if (got > 0) {
            links_[i]->carry(in, static_cast<std::size_t>(got), time, after, log_.text(), settings_.trace);
          } else if (got == 0) {
            ended = host::printable(endpoints_[i]->spec()) + " closed";
          } else if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
            ended = host::printable(endpoints_[i]->spec()) + ": " + std::strerror(errno);
          }
        } else if ((fds[i].revents & (POLLHUP | POLLERR | POLLNVAL)) != 0) {
          ended = host::printable(endpoints_[i]->spec()) + " closed";
        }
      }
      for (std::size_t i = 0; i < n && ended.empty(); ++i) {
        int cause = 0;
        if (!links_[i]->deliver(endpoints_[links_[i]->to()]->fd(), cause)) {
          ended = host::printable(endpoints_[links_[i]->to()]->spec()) + ": " + std::strerror(cause);
        }
      }
      if (!ended.empty()) break;
      for (std::size_t i = 0; i < n; ++i) {
        if (links_[i]->open() &&
            after - links_[i]->last_byte() >= static_cast<std::uint64_t>(settings_.idle_ms) * 1000000U) {
          links_[i]->idle(time, log_.text(), settings_.trace);
        }
      }
      if (input_open && (fds.back().revents & (POLLIN | POLLHUP | POLLERR)) != 0) {
        input_open = input.read_some();
        std::string line;
        while (!quit && input.next(line)) quit = command(line);
      }
    }
    const std::uint64_t time = live::now_ns();
    for (auto& l : links_) l->idle(time, log_.text(), settings_.trace);
    counters();
    log_.flush();
    for (auto& e : endpoints_) e->close();
    if (!ended.empty()) return fail_io("ring wire: " + ended);
    if (output_failed()) return fail_output();
    if (!capture_.good()) return fail_io("ring wire: writing the capture " + settings_.pcap + " failed: " + capture_.cause());
    return exit_ok;
  }

 private:
  // Starts and ends the cuts whose time has come.
  void schedule(std::uint64_t now) {
    for (std::size_t i = 0; i < links_.size(); ++i) {
      if (links_[i]->end_cut(now)) {
        event(log_.text(), "cut_end")
            .time(live::now_ns())
            .number("link", i)
            .number("cut_bytes", links_[i]->cut_bytes());
      }
    }
    for (scheduled_cut& c : settings_.cuts) {
      if (c.for_ms == 0 || now < started_ + c.at_ms * 1000000U) continue;
      start_cut(c.link, c.for_ms);
      c.for_ms = 0;  // done
    }
  }

  void start_cut(std::size_t l, std::uint64_t ms) {
    links_[l]->start_cut(monotonic_ns() + ms * 1000000U);
    event(log_.text(), "cut").time(live::now_ns()).number("link", l).number("ms", ms);
  }

  // How long poll() may wait: until the next cut starts or ends, or a link's idle time is over.
  int wait_ms(std::uint64_t now) const {
    std::uint64_t next = now + 1000000000U;
    for (const auto& l : links_) {
      if (l->cut()) next = std::min(next, l->cut_until());
      if (l->open()) next = std::min(next, l->last_byte() + static_cast<std::uint64_t>(settings_.idle_ms) * 1000000U);
    }
    for (const scheduled_cut& c : settings_.cuts) {
      if (c.for_ms != 0) next = std::min(next, started_ + c.at_ms * 1000000U);
    }
    return next <= now ? 0 : static_cast<int>((next - now + 999999U) / 1000000U);
  }

  void counters() {
    const std::uint64_t time = live::now_ns();
    for (const auto& l : links_) {
      l->counters(log_.text(), time, settings_.endpoints[l->from()], settings_.endpoints[l->to()]);
    }
  }

  void reply_error(const std::string& command, const std::string& reason) {
    event(log_.text(), "error").time(live::now_ns()).text("command", command).text("reason", reason);
  }

  // One command from standard input; true for quit.
  bool command(const std::string& line) {
    const std::vector<std::string> w = live::words_of(line);
    if (w.empty() || w[0][0] == '#') return false;
    std::string error;
    if (w[0] == "quit") return true;
    if (w[0] == "counters" && w.size() == 1) {
      counters();
      return false;
    }
    if ((w[0] == "drop" || w[0] == "flip") && w.size() == 2) {
      int l = -1;
      double p = 0;
      if (!parse_probability(w[1], links_.size(), l, p, error)) {
        reply_error(w[0], error);
        return false;
      }
      for (std::size_t i = 0; i < links_.size(); ++i) {
        if (l >= 0 && static_cast<std::size_t>(l) != i) continue;
        (w[0] == "drop" ? links_[i]->faults.drop : links_[i]->faults.flip) = p;
      }
      faults_event(log_.text(), l, links_[l >= 0 ? static_cast<std::size_t>(l) : 0]->faults);
      return false;
    }
    if (w[0] == "faults" && w.size() == 2 && w[1] == "off") {
      for (auto& l : links_) l->faults = {};
      for (scheduled_cut& c : settings_.cuts) c.for_ms = 0;
      for (std::size_t i = 0; i < links_.size(); ++i) {
        if (!links_[i]->end_cut(0, true)) continue;
        event(log_.text(), "cut_end").time(live::now_ns()).number("link", i).number("cut_bytes", links_[i]->cut_bytes());
      }
      faults_event(log_.text(), -1, fault_settings{});
      return false;
    }
    if (w[0] == "cut" && w.size() == 3) {
      long long l = 0;
      long long ms = 0;
      if (!parse_integer(w[1], 0, static_cast<long long>(links_.size()) - 1, l) ||
          !parse_integer(w[2], 1, 86400000, ms)) {
        reply_error(w[0], "usage: cut L D (link 0.." + std::to_string(links_.size() - 1) + ", D milliseconds)");
        return false;
      }
      start_cut(static_cast<std::size_t>(l), static_cast<std::uint64_t>(ms));
      return false;
    }
    reply_error(w[0], "unknown command or wrong arguments (drop [L:]P, flip [L:]P, cut L D, faults off, counters, quit)");
    return false;
  }

  wire_settings settings_;
  live::event_log log_;
  live::capture_file capture_;
  std::vector<std::unique_ptr<endpoint>> endpoints_;
  std::vector<std::unique_ptr<link>> links_;
  std::uint64_t started_ = 0;
};

}  // namespace

int ring_wire_main(const words& given) {
  arguments args;
  std::string error;
  if (!parse_arguments(given, ring_wire_options(), args, error)) return fail("ring wire: " + error);
  if (args.positionals.size() < 2) return fail("ring wire needs at least two endpoints (a ring of two nodes)");
  if (args.positionals.size() > 15) return fail("ring wire: a ring holds at most 15 nodes (docs/protocol.md 1.1)");
  for (const std::string& e : args.positionals) {
    if (e == "-") return fail("ring wire: an endpoint is read and written: - is not one");
    const std::string wrong = endpoint_syntax_error(e);
    if (!wrong.empty()) return fail("ring wire: " + wrong);
  }
  const int capacities = check_ring_capacities("ring wire", ring_capacity_use::decoder);
  if (capacities != exit_ok) return capacities;
  wire_settings s;
  s.endpoints = args.positionals;
  const std::size_t links = s.endpoints.size();
  s.faults.assign(links, fault_settings{});
  long long number = 0;
  const auto integer_option = [&](const char* name, long long min, long long max, auto& out) {
    if (!args.has(name)) return true;
    if (!parse_integer(args.options.at(name), min, max, number)) {
      error = std::string(name) + " must be " + std::to_string(min) + ".." + std::to_string(max) + ", got '" +
              host::printable(args.options.at(name)) + "'";
      return false;
    }
    out = static_cast<std::remove_reference_t<decltype(out)>>(number);
    return true;
  };
  if (!integer_option("--idle-ms", 1, 60000, s.idle_ms) || !integer_option("--connect-ms", 0, 600000, s.connect_ms) ||
      !integer_option("--baud", host::min_serial_baud, host::max_serial_baud, s.link.baud) ||
      !integer_option("--seed", 0, 0x7FFFFFFFFFFFFFFF, s.seed)) {
    return fail("ring wire: " + error);
  }
  for (const char* name : {"--drop", "--flip"}) {
    if (!args.has(name)) continue;
    for (const std::string& value : values_of(args.options.at(name))) {
      int l = -1;
      double p = 0;
      if (!parse_probability(value, links, l, p, error)) return fail(std::string("ring wire: ") + name + ": " + error);
      for (std::size_t i = 0; i < links; ++i) {
        if (l >= 0 && static_cast<std::size_t>(l) != i) continue;
        (std::strcmp(name, "--drop") == 0 ? s.faults[i].drop : s.faults[i].flip) = p;
      }
    }
  }
  if (args.has("--cut")) {
    for (const std::string& value : values_of(args.options.at("--cut"))) {
      scheduled_cut c;
      if (!parse_cut(value, links, c, error)) return fail("ring wire: " + error);
      s.cuts.push_back(c);
    }
  }
  s.json = args.flag("--json");
  s.trace = args.flag("--trace");
  if (args.has("--pcap")) s.pcap = args.options.at("--pcap");
  return wire(std::move(s)).run();
}

}  // namespace trionet::cli
