#include "trionet/host/posix_link.hpp"

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace trionet::host {

short fd_link::poll_events() const noexcept {
  return static_cast<short>(POLLIN | (unsent() != 0 || node_->transmit_pending() ? POLLOUT : 0));
}

bool fd_link::idle(std::size_t* ended) noexcept {
  if (!node_->in_message()) return false;
  const bool answered = node_->line_idle() != ring::receive_status::incomplete;
  if (ended != nullptr) *ended += answered;
  return true;
}

pump_result fd_link::pump(int timeout_ms) {
  pump_result result;
  pollfd p{};
  p.fd = fd_;
  p.events = poll_events();
  const int ready = ::poll(&p, 1, timeout_ms);
  if (ready < 0) {
    if (errno != EINTR) result.error = errno;
    return result;
  }
  if (ready == 0) {  // nothing for timeout_ms: the line is idle (docs/protocol.md 1.10)
    result.line_idle = idle(&result.ended);
    return result;
  }
  return service(p.revents);
}

pump_result fd_link::service(short revents) {
  pump_result result;
  if ((revents & POLLIN) != 0) {
    std::uint8_t in[256];
    const ssize_t got = ::read(fd_, in, sizeof in);
    if (got > 0) {
      result.ended = receive(byte_view(in, static_cast<std::size_t>(got)));
      result.received = static_cast<std::size_t>(got);
    } else if (got == 0) {
      result.closed = true;
    } else if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
      result.error = errno;
    }
  } else if ((revents & (POLLHUP | POLLERR)) != 0) {
    result.closed = true;
  }
  if ((revents & POLLOUT) != 0) {
    if (unsent() == 0) {
      out_offset_ = 0;
      out_length_ = transmit(byte_buffer(out_, sizeof out_));
    }
    if (unsent() != 0) {
      const ssize_t wrote = ::write(fd_, out_ + out_offset_, unsent());
      if (wrote > 0) {
        out_offset_ += static_cast<std::size_t>(wrote);
        result.sent = static_cast<std::size_t>(wrote);
      } else if (wrote < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
        result.error = errno;
      }
    }
  }
  return result;
}

std::size_t fd_link::receive(byte_view in) noexcept {
  if (receive_bulk_ != nullptr) return receive_bulk_(*node_, in);
  std::size_t ended = 0;
  for (std::uint8_t byte : in) ended += node_->receive(byte) != ring::receive_status::incomplete;
  return ended;
}

std::size_t fd_link::transmit(byte_buffer out) noexcept {
  if (transmit_bulk_ != nullptr) return transmit_bulk_(*node_, out);
  std::size_t n = 0;
  while (n < out.size() && node_->transmit(out[n])) ++n;
  return n;
}

}  // namespace trionet::host
