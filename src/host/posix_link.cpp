#include "trionet/host/posix_link.hpp"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace trionet::host {

pump_result fd_link::pump(int timeout_ms) {
  pump_result result;
  pollfd p{};
  p.fd = fd_;
  p.events = POLLIN;
  if (unsent() != 0 || node_->transmit_pending()) p.events = static_cast<short>(p.events | POLLOUT);
  const int ready = ::poll(&p, 1, timeout_ms);
  if (ready < 0) {
    if (errno != EINTR) result.error = errno;
    return result;
  }
  if (ready == 0) {  // nothing for timeout_ms: the line is idle (docs/protocol.md 1.10)
    if (node_->in_message()) {
      node_->line_idle();
      result.line_idle = true;
    }
    return result;
  }
  if ((p.revents & POLLIN) != 0) {
    std::uint8_t in[256];
    const ssize_t got = ::read(fd_, in, sizeof in);
    if (got > 0) {
      for (ssize_t i = 0; i < got; ++i) node_->receive(in[i]);
      result.received = static_cast<std::size_t>(got);
    } else if (got == 0) {
      result.closed = true;
    } else if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
      result.error = errno;
    }
  } else if ((p.revents & (POLLHUP | POLLERR)) != 0) {
    result.closed = true;
  }
  if ((p.revents & POLLOUT) != 0) {
    if (unsent() == 0) {
      out_offset_ = out_length_ = 0;
      std::uint8_t byte = 0;
      while (out_length_ < sizeof out_ && node_->transmit(byte)) out_[out_length_++] = byte;
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

namespace {

bool speed_of(unsigned baud, speed_t& speed) {
  switch (baud) {
    case 1200:
      speed = B1200;
      return true;
    case 2400:
      speed = B2400;
      return true;
    case 4800:
      speed = B4800;
      return true;
    case 9600:
      speed = B9600;
      return true;
    case 19200:
      speed = B19200;
      return true;
    case 38400:
      speed = B38400;
      return true;
    case 57600:
      speed = B57600;
      return true;
    case 115200:
      speed = B115200;
      return true;
    case 230400:
      speed = B230400;
      return true;
    default:
      return false;
  }
}

}  // namespace

int open_serial(const std::string& path, unsigned baud, std::string& error) {
  speed_t speed = B9600;
  if (!speed_of(baud, speed)) {
    error = "unsupported baud rate " + std::to_string(baud) + " (use 1200 ... 230400)";
    return -1;
  }
  const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    error = "cannot open " + path + ": " + std::strerror(errno);
    return -1;
  }
  termios tio{};
  if (::tcgetattr(fd, &tio) != 0) {
    error = path + " is not a serial port: " + std::strerror(errno);
    ::close(fd);
    return -1;
  }
  ::cfmakeraw(&tio);
  tio.c_cflag = static_cast<tcflag_t>((tio.c_cflag & ~static_cast<tcflag_t>(CSTOPB | PARENB | CRTSCTS)) |
                                      CS8 | CLOCAL | CREAD);
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 0;
  if (::cfsetispeed(&tio, speed) != 0 || ::cfsetospeed(&tio, speed) != 0 ||
      ::tcsetattr(fd, TCSANOW, &tio) != 0) {
    error = "cannot configure " + path + ": " + std::strerror(errno);
    ::close(fd);
    return -1;
  }
  return fd;
}

}  // namespace trionet::host
