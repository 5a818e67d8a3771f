// A ring link on the host, opened by name: a serial port or pty, a FIFO, a Unix socket, or standard
// input/output. What `trionet ring monitor|send|join PORT` talk to.
//
//   trionet::host::link_device port;
//   if (!port.open("/dev/ttyUSB0", {125000}, error)) ...   // raw 8-bit, the old settings kept
//   trionet::host::fd_link link(port.fd(), node);           // posix_link.hpp
//   ...
//   port.close();                                           // the serial settings as they were
//
//   name                  opened as
//   a tty (serial, pty)   raw, no echo, no line discipline, the rate asked, no flow control unless asked
//                         (as open_serial); refused, naming the port, while another process holds its
//                         lock (flock) or has it in exclusive mode (TIOCEXCL); then locked until close()
//                         puts back the settings from before and releases it. `shared` (a sender that
//                         writes where a monitor listens) neither takes nor checks the lock
//   a FIFO                read and write, non-blocking (bytes written to it are read back by whoever reads)
//   a Unix stream socket  connected (e.g. `socat UNIX-LISTEN:ring.sock,fork ...`)
//   "-"                   standard input (reading) or standard output (writing), as the command says
//
// Host code only (system calls).
#pragma once

#include <cstdint>
#include <string>

#include "trionet/host/posix_link.hpp"

namespace trionet::host {

/// What a link device turned out to be.
enum class link_kind : std::uint8_t { none, serial, fifo, socket, standard_stream };

constexpr const char* to_string(link_kind kind) noexcept {
  switch (kind) {
    case link_kind::none:
      return "none";
    case link_kind::serial:
      return "serial";
    case link_kind::fifo:
      return "fifo";
    case link_kind::socket:
      return "socket";
    case link_kind::standard_stream:
      return "standard_stream";
  }
  return "unknown";
}

/// How to open a link device.
struct link_options {
  unsigned baud = 125000;                  ///< serial ports: bits per second (the ring's rate by default)
  flow_control flow = flow_control::none;  ///< serial ports: flow control
  int standard_stream = 0;                 ///< "-": 0 (standard input) or 1 (standard output)
  bool shared = false;                     ///< serial ports: opened beside the command that holds it (no lock)
};

/// An open link device: its descriptor (non-blocking), what it is, and for a serial port its old settings.
/// Not copyable; closes (and restores) on destruction.
class link_device {
 public:
  link_device() = default;
  ~link_device() { close(); }
  link_device(const link_device&) = delete;
  link_device& operator=(const link_device&) = delete;

  /// Opens `name`. False with `error` naming the device and the cause.
  bool open(const std::string& name, const link_options& options, std::string& error);
  /// Puts back a serial port's settings and closes the descriptor (standard streams stay open).
  void close() noexcept;
  /// Waits until everything written has left the host: tcdrain() on a serial port or pty; writes to a pipe
  /// or socket are complete when write() returns. False (errno set) on failure.
  bool drain() noexcept;

  [[nodiscard]] int fd() const noexcept { return fd_; }
  [[nodiscard]] link_kind kind() const noexcept { return kind_; }
  [[nodiscard]] const std::string& name() const noexcept { return name_; }

 private:
  int fd_ = -1;
  link_kind kind_ = link_kind::none;
  std::string name_;
  serial_settings saved_;
  int old_flags_ = -1;  // a standard stream's file status flags, put back on close
};

}  // namespace trionet::host
