// Host adapter: a ring node's byte port on a POSIX file descriptor (serial port, pipe, socket, pty).
//
//   trionet::host::fd_link link(fd, node);
//   for (;;) link.pump(10);   // moves what read() gives into node.receive(), node.transmit() into write()
//
// The node itself never blocks; `pump` waits at most `timeout_ms` in poll(). Bytes the node has handed over
// but the descriptor did not yet take are kept here and written first next time: nothing is lost on a
// short write. A pump that waits the whole `timeout_ms` without a byte tells the node its line is idle
// (docs/protocol.md 1.10): choose a timeout of a few character times at the link's bit rate.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "trionet/transport.hpp"

namespace trionet::host {

struct pump_result {
  std::size_t received = 0;  ///< bytes read and handed to the node
  std::size_t sent = 0;      ///< bytes written
  bool closed = false;       ///< the other end closed (read returned 0 or POLLHUP)
  bool line_idle = false;    ///< nothing arrived for the whole timeout while a message was open
  int error = 0;             ///< errno of a failed read/write/poll, else 0
};

class fd_link {
 public:
  fd_link(int fd, byte_port& node) noexcept : fd_(fd), node_(&node) {}

  /// One pass: wait up to `timeout_ms` for the descriptor, read what is there, write what the node has.
  pump_result pump(int timeout_ms);

  /// Bytes taken from the node and not yet written.
  std::size_t unsent() const noexcept { return out_length_ - out_offset_; }

 private:
  int fd_;
  byte_port* node_;
  std::uint8_t out_[256] = {};
  std::size_t out_length_ = 0;
  std::size_t out_offset_ = 0;
};

/// Opens a serial port (or pty) raw: 8 data bits, no parity, 1 stop bit, no flow control, non-blocking, at
/// `baud` (a standard rate: 1200 ... 230400). Returns the descriptor, or -1 with `error` saying why.
int open_serial(const std::string& path, unsigned baud, std::string& error);

}  // namespace trionet::host
