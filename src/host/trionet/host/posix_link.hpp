// Host adapter: a ring node's byte port on a POSIX file descriptor (serial port, pipe, socket, pty).
//
//   trionet::host::fd_link link(fd, node);
//   for (;;) link.pump(10);   // moves what read() gives into node.receive(), node.transmit() into write()
//
// Given a ring node itself (a `motion_coordinator` or `keypad`), the link uses the node's bulk calls: what one
// read() gives goes to receive(byte_view) at once, and transmit(byte_buffer) fills what one write() takes.
// Given any other `byte_port` (e.g. one that watches a node's bytes), it calls the port a byte at a time.
//
// The node itself never blocks; `pump` waits at most `timeout_ms` in poll(). Bytes the node has handed over
// but the descriptor did not yet take are kept here and written first next time: nothing is lost on a
// short write. A pump that waits the whole `timeout_ms` without a byte tells the node its line is idle
// (docs/protocol.md 1.10): choose a timeout of a few character times at the link's bit rate.
//
// A program that waits on other descriptors too (a terminal, a socket) polls them together with
// `poll_events()`, calls `service(revents)` when the link's descriptor is ready and `idle()` when the read
// timeout has passed without a byte:
//
//   pollfd fds[2] = {{fd, link.poll_events(), 0}, {STDIN_FILENO, POLLIN, 0}};
//   if (poll(fds, 2, timeout_ms) == 0) link.idle(); else if (fds[0].revents) link.service(fds[0].revents);
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>

#include "trionet/span.hpp"
#include "trionet/transport.hpp"

namespace trionet::host {

struct pump_result {
  std::size_t received = 0;  ///< bytes read and handed to the node
  std::size_t ended = 0;     ///< messages those bytes (or the idle line) ended: delivered, forwarded or dropped,
                             ///< each counted by the node (its `receive` answers other than `incomplete`)
  std::size_t sent = 0;      ///< bytes written
  bool closed = false;       ///< the other end closed (read returned 0 or POLLHUP)
  bool line_idle = false;    ///< nothing arrived for the whole timeout while a message was open
  int error = 0;             ///< errno of a failed read/write/poll, else 0
};

class fd_link {
 public:
  /// A link that calls `node` a byte at a time.
  fd_link(int fd, byte_port& node) noexcept : fd_(fd), node_(&node) {}
  /// A link that feeds a ring node in bulk (see the file comment).
  template <class Node, class = decltype(std::declval<Node&>().receive(byte_view{})),
            class = decltype(std::declval<Node&>().transmit(byte_buffer{}))>
  fd_link(int fd, Node& node) noexcept
      : fd_(fd),
        node_(&node),
        receive_bulk_([](byte_port& port, byte_view in) noexcept { return static_cast<Node&>(port).receive(in); }),
        transmit_bulk_([](byte_port& port, byte_buffer out) noexcept {
          return static_cast<Node&>(port).transmit(out);
        }) {}

  /// One pass: wait up to `timeout_ms` for the descriptor, read what is there, write what the node has.
  pump_result pump(int timeout_ms);

  /// What poll() should wait for on the descriptor: POLLIN, and POLLOUT while there is something to write.
  [[nodiscard]] short poll_events() const noexcept;
  /// One pass after the caller's own poll() found `revents` on the descriptor: reads what is there, writes
  /// what the node has (the same as `pump` after its poll).
  pump_result service(short revents);
  /// The read timeout passed without a byte: tells the node its line is idle if a message is open
  /// (docs/protocol.md 1.10). True if it did; `ended` (if given) counts the message it ended.
  bool idle(std::size_t* ended = nullptr) noexcept;

  /// Bytes taken from the node and not yet written.
  std::size_t unsent() const noexcept { return out_length_ - out_offset_; }

 private:
  std::size_t receive(byte_view in) noexcept;  // how many messages the bytes ended
  std::size_t transmit(byte_buffer out) noexcept;

  int fd_;
  byte_port* node_;
  std::size_t (*receive_bulk_)(byte_port&, byte_view) noexcept = nullptr;  // the node's bulk calls, if any
  std::size_t (*transmit_bulk_)(byte_port&, byte_buffer) noexcept = nullptr;
  std::uint8_t out_[256] = {};
  std::size_t out_length_ = 0;
  std::size_t out_offset_ = 0;
};

/// Flow control on a serial port: none (the default), RTS/CTS lines, or XON/XOFF characters. The ring
/// carries raw 8-bit bytes, so XON/XOFF (0x11, 0x13) is only for a link that is known to need it.
enum class flow_control : std::uint8_t { none, hardware, software };

constexpr const char* to_string(flow_control flow) noexcept {
  switch (flow) {
    case flow_control::none:
      return "none";
    case flow_control::hardware:
      return "hardware";
    case flow_control::software:
      return "software";
  }
  return "unknown";
}

/// A serial port's settings as they were before `open_serial` changed them (the kernel's termios2, opaque
/// here), for `restore_serial`.
struct serial_settings {
  alignas(8) unsigned char raw[64] = {};
  bool saved = false;  ///< true once `open_serial` has stored the settings
};

/// Opens a serial port (or pty) raw: 8 data bits, no parity, 1 stop bit, no echo, no line discipline, no
/// flow control unless `flow` asks for it, non-blocking, at `baud` bits per second. Any rate 50 ..
/// 4000000 is asked for (Linux termios2 with BOTHER, so rates between the standard ones too: whether the
/// UART reaches it is the driver's business). With `saved`, the settings before the change are kept there.
/// Returns the descriptor, or -1 with `error` naming the port and the cause.
int open_serial(const std::string& path, unsigned baud, std::string& error,
                flow_control flow = flow_control::none, serial_settings* saved = nullptr);

/// Puts back the settings `open_serial` saved. False (errno set) if the port refused them.
bool restore_serial(int fd, const serial_settings& saved) noexcept;

/// The lowest and highest rates `open_serial` asks for.
constexpr unsigned min_serial_baud = 50;
constexpr unsigned max_serial_baud = 4000000;

}  // namespace trionet::host
