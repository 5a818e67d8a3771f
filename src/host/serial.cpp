// Serial ports for the ring's host links: raw 8-bit, any rate, settings saved and restored (posix_link.hpp).
//
// Linux's termios2 (TCGETS2/TCSETS2 with BOTHER) sets any rate, not only the Bnnn constants; its header
// clashes with <termios.h>, so this file alone uses it and the rest of the host code never sees it.
#include <asm/ioctls.h>
#include <asm/termbits.h>
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "serial_port.hpp"
#include "trionet/host/posix_link.hpp"
#include "trionet/host/text.hpp"

extern "C" int ioctl(int fd, unsigned long request, ...) noexcept;

namespace trionet::host {

static_assert(sizeof(termios2) <= sizeof(serial_settings::raw), "serial_settings holds a termios2");

int open_serial(const std::string& path, unsigned baud, std::string& error, flow_control flow,
                serial_settings* saved) {
  if (baud < min_serial_baud || baud > max_serial_baud) {
    error = "unsupported baud rate " + std::to_string(baud) + " for " + printable(path) + " (use " +
            std::to_string(min_serial_baud) + " ... " + std::to_string(max_serial_baud) + ")";
    return -1;
  }
  const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    error = "cannot open " + printable(path) + ": " + std::strerror(errno);
    return -1;
  }
  if (!configure_serial(fd, path, baud, error, flow, saved)) {
    ::close(fd);
    return -1;
  }
  return fd;
}

bool configure_serial(int fd, const std::string& path, unsigned baud, std::string& error, flow_control flow,
                      serial_settings* saved) {
  if (baud < min_serial_baud || baud > max_serial_baud) {
    error = "unsupported baud rate " + std::to_string(baud) + " for " + printable(path) + " (use " +
            std::to_string(min_serial_baud) + " ... " + std::to_string(max_serial_baud) + ")";
    return false;
  }
  termios2 tio{};
  if (::ioctl(fd, TCGETS2, &tio) != 0) {
    error = printable(path) + " is not a serial port: " + std::strerror(errno);
    return false;
  }
  if (saved != nullptr) {
    std::memcpy(saved->raw, &tio, sizeof tio);
    saved->saved = true;
  }
  // cfmakeraw(): no input processing, no output processing, no echo, no signals, no canonical lines.
  tio.c_iflag &= ~static_cast<tcflag_t>(IGNBRK | BRKINT | PARMRK | ISTRIP | INLCR | IGNCR | ICRNL | IXON |
                                        IXOFF | IXANY);
  tio.c_oflag &= ~static_cast<tcflag_t>(OPOST);
  tio.c_lflag &= ~static_cast<tcflag_t>(ECHO | ECHONL | ICANON | ISIG | IEXTEN);
  tio.c_cflag &= ~static_cast<tcflag_t>(CSIZE | PARENB | CSTOPB | CRTSCTS | CBAUD | (CBAUD << IBSHIFT));
  tio.c_cflag |= static_cast<tcflag_t>(CS8 | CLOCAL | CREAD | BOTHER | (BOTHER << IBSHIFT));
  if (flow == flow_control::hardware) tio.c_cflag |= static_cast<tcflag_t>(CRTSCTS);
  if (flow == flow_control::software) tio.c_iflag |= static_cast<tcflag_t>(IXON | IXOFF);
  tio.c_ispeed = baud;
  tio.c_ospeed = baud;
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 0;
  if (::ioctl(fd, TCSETS2, &tio) != 0) {
    error = "cannot configure " + printable(path) + " at " + std::to_string(baud) + " baud: " + std::strerror(errno);
    if (saved != nullptr) saved->saved = false;
    return false;
  }
  return true;
}

bool restore_serial(int fd, const serial_settings& saved) noexcept {
  if (!saved.saved) return true;
  termios2 tio{};
  std::memcpy(&tio, saved.raw, sizeof tio);
  return ::ioctl(fd, TCSETS2, &tio) == 0;
}

}  // namespace trionet::host
