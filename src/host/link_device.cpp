// A ring link on the host, opened by name: see trionet/host/link_device.hpp.
#include "trionet/host/link_device.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "serial_port.hpp"
#include "trionet/host/text.hpp"

namespace trionet::host {

bool link_device::open(const std::string& name, const link_options& options, std::string& error) {
  close();
  name_ = name;
  if (name == "-") {
    fd_ = options.standard_stream == 1 ? 1 : 0;
    old_flags_ = ::fcntl(fd_, F_GETFL);
    if (old_flags_ >= 0) (void)::fcntl(fd_, F_SETFL, old_flags_ | O_NONBLOCK);
    kind_ = link_kind::standard_stream;
    return true;
  }
  struct stat info {};
  if (::stat(name.c_str(), &info) != 0) {
    error = "cannot open " + printable(name) + ": " + std::strerror(errno);
    return false;
  }
  if (S_ISFIFO(info.st_mode)) {
    fd_ = ::open(name.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC);
    if (fd_ < 0) {
      error = "cannot open " + printable(name) + ": " + std::strerror(errno);
      return false;
    }
    kind_ = link_kind::fifo;
    return true;
  }
  if (S_ISSOCK(info.st_mode)) {
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    if (name.size() >= sizeof address.sun_path) {
      error = "cannot connect to " + printable(name) + ": the socket path is too long";
      return false;
    }
    std::memcpy(address.sun_path, name.c_str(), name.size() + 1);
    fd_ = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    // sockaddr_un is the address type connect() expects for AF_UNIX; the cast is the socket API's contract.
    if (fd_ < 0 || ::connect(fd_, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
      error = "cannot connect to " + printable(name) + ": " + std::strerror(errno);
      close();
      return false;
    }
    (void)::fcntl(fd_, F_SETFL, O_NONBLOCK);
    kind_ = link_kind::socket;
    return true;
  }
  if (!S_ISCHR(info.st_mode)) {
    error = printable(name) + " is not a serial port, pty, FIFO or socket";
    return false;
  }
  // A serial port is this program's alone while it is open: another process's lock (flock, as a second
  // trionet takes it) or exclusive mode (TIOCEXCL, as terminal programs set it) is refused before any
  // setting changes, then the port is locked until close() puts it back. A shared open (a sender writing
  // where a monitor listens) neither takes nor checks the lock.
  fd_ = ::open(name.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) {
    // (A program that is not root finds a port in exclusive mode here: the same words as below.)
    error = errno == EBUSY ? printable(name) + " is in use: another program has it in exclusive mode"
                           : "cannot open " + printable(name) + ": " + std::strerror(errno);
    return false;
  }
  int exclusive = 0;
  if (!options.shared && ::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    error = errno == EWOULDBLOCK
                ? printable(name) + " is in use: another process holds its lock (another monitor or node on it?)"
                : "cannot lock " + printable(name) + ": " + std::strerror(errno);
  } else if (!options.shared && ::ioctl(fd_, TIOCGEXCL, &exclusive) == 0 && exclusive != 0) {
    error = printable(name) + " is in use: another program has it in exclusive mode";
  } else if (configure_serial(fd_, name, options.baud, error, options.flow, &saved_)) {
    kind_ = link_kind::serial;
    return true;
  }
  ::close(fd_);
  fd_ = -1;
  return false;
}

void link_device::close() noexcept {
  if (fd_ < 0) return;
  if (kind_ == link_kind::standard_stream) {
    if (old_flags_ >= 0) (void)::fcntl(fd_, F_SETFL, old_flags_);
  } else {
    if (kind_ == link_kind::serial) (void)restore_serial(fd_, saved_);
    ::close(fd_);  // and with it the lock
  }
  fd_ = -1;
  kind_ = link_kind::none;
  saved_ = serial_settings{};
  old_flags_ = -1;
}

bool link_device::drain() noexcept {
  if (kind_ == link_kind::serial) return ::tcdrain(fd_) == 0;
  return true;
}

}  // namespace trionet::host
