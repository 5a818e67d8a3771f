// Reading a whole input file with a bound: see trionet/host/files.hpp.
#include "trionet/host/files.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "trionet/host/progress.hpp"
#include "trionet/host/text.hpp"

namespace trionet::host {
namespace {

// Reads `fd` to its end into `out`, refusing more than `max_bytes`.
file_result read_all(int fd, std::size_t max_bytes, std::string& out, progress* shown) {
  file_result result;
  result.max_bytes = max_bytes;
  out.clear();
  char chunk[65536];
  while (true) {
    // Never more than one byte past the bound: that byte is what says the input is too large.
    const std::size_t room = max_bytes - out.size() + 1;
    const ssize_t got = ::read(fd, chunk, room < sizeof chunk ? room : sizeof chunk);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) {
      result.status = file_status::read_failed;
      result.system_error = errno;
      out.clear();
      return result;
    }
    if (got == 0) return result;
    if (out.size() + static_cast<std::size_t>(got) > max_bytes) {
      result.status = file_status::too_large;
      out.clear();
      return result;
    }
    out.append(chunk, static_cast<std::size_t>(got));
    if (shown != nullptr) shown->update(static_cast<double>(out.size()));
  }
}

}  // namespace

std::string file_result::message(const std::string& path, const std::string& noun) const {
  const std::string name = (noun.empty() ? "" : noun + " ") + printable(path);
  switch (status) {
    case file_status::ok:
      return name + ": read";
    case file_status::cannot_open:
      return "cannot open " + name + ": " + std::strerror(system_error);
    case file_status::directory:
      return name + " is a directory, not a file";
    case file_status::device:
      return name + " is a device, not a file";
    case file_status::too_large:
      return name + " is larger than " + std::to_string(max_bytes) + " bytes";
    case file_status::read_failed:
      return "cannot read " + name + ": " + std::strerror(system_error);
  }
  return name + ": " + to_string(status);
}

namespace {

// True when `path` names a FIFO (stat follows a symbolic link, as open() does).
bool names_fifo(const std::string& path) {
  struct stat info {};
  return ::stat(path.c_str(), &info) == 0 && S_ISFIFO(info.st_mode);
}

// Opens `path` to be read as a file: a directory or a device is refused before a byte is read (O_NONBLOCK:
// a device that waits for a carrier does not hang in open()). A FIFO is opened once, without O_NONBLOCK, to
// wait for its writer as any reader of a FIFO does: a first descriptor closed and a second opened would lose
// what a quick writer wrote in between, and then wait for a writer for ever. `fd` is the descriptor when the
// result is ok, else -1.
file_result open_file(const std::string& path, std::size_t max_bytes, int& fd) {
  file_result result;
  result.max_bytes = max_bytes;
  fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | (names_fifo(path) ? 0 : O_NONBLOCK));
  if (fd < 0) {
    result.status = file_status::cannot_open;
    result.system_error = errno;
    return result;
  }
  struct stat info {};
  if (::fstat(fd, &info) != 0) {
    result.status = file_status::read_failed;
    result.system_error = errno;
  } else if (S_ISDIR(info.st_mode)) {
    result.status = file_status::directory;
  } else if (S_ISCHR(info.st_mode) || S_ISBLK(info.st_mode)) {
    result.status = file_status::device;
  } else {  // a file or a FIFO
    const int flags = ::fcntl(fd, F_GETFL);
    if (flags >= 0) (void)::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
    return result;
  }
  ::close(fd);
  fd = -1;
  return result;
}

}  // namespace

file_result read_bounded_file(const std::string& path, std::size_t max_bytes, std::string& out,
                              progress* shown) {
  out.clear();
  int fd = -1;
  file_result result = open_file(path, max_bytes, fd);
  if (!result) return result;
  result = read_all(fd, max_bytes, out, shown);
  ::close(fd);
  return result;
}

file_result open_input_stream(const std::string& path, std::ifstream& stream) {
  file_result result;
  if (!names_fifo(path)) {  // (a FIFO is opened once, by the stream: see open_file)
    int fd = -1;
    result = open_file(path, 0, fd);
    if (!result) return result;
    ::close(fd);
  }
  stream.open(path, std::ios::binary);
  if (!stream) {
    result.status = file_status::cannot_open;
    result.system_error = errno != 0 ? errno : EIO;
  }
  return result;
}

file_result read_bounded_fd(int fd, std::size_t max_bytes, std::string& out, progress* shown) {
  out.clear();
  struct stat info {};
  if (::fstat(fd, &info) == 0 && S_ISDIR(info.st_mode)) {
    file_result result;
    result.max_bytes = max_bytes;
    result.status = file_status::directory;
    return result;
  }
  return read_all(fd, max_bytes, out, shown);
}

}  // namespace trionet::host
