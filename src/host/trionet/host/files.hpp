// Reading a whole input file with a bound: what every host reader of untrusted files (profiles, programs,
// lists, hex text) calls before it parses anything.
//
//   std::string text;
//   const trionet::host::file_result r = trionet::host::read_bounded_file(path, 1 << 20, text);
//   if (!r) fail(r.message(path));   // "cannot read x.json: No such file or directory"
//
// A directory and a device (/dev/zero, a tty) are refused before a byte is read; a regular file, a pipe or
// a FIFO is read to its end, but never more than `max_bytes` + 1 bytes: an endless pipe is refused with
// `too_large` after that many. Host code only (system calls).
#pragma once

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>

namespace trionet::host {

enum class file_status : std::uint8_t {
  ok,
  cannot_open,   ///< open() failed (`system_error` says why: no such file, permission denied ...)
  directory,     ///< a directory, not a file
  device,        ///< a character or block device (/dev/zero, a serial port), not a file
  too_large,     ///< more than `max_bytes` bytes
  read_failed,   ///< read() failed (`system_error`)
};

constexpr const char* to_string(file_status status) noexcept {
  switch (status) {
    case file_status::ok:
      return "ok";
    case file_status::cannot_open:
      return "cannot_open";
    case file_status::directory:
      return "directory";
    case file_status::device:
      return "device";
    case file_status::too_large:
      return "too_large";
    case file_status::read_failed:
      return "read_failed";
  }
  return "unknown";
}

struct [[nodiscard]] file_result {
  file_status status = file_status::ok;
  int system_error = 0;     ///< errno of a failed open() or read(), else 0
  std::size_t max_bytes = 0;  ///< the bound that was asked for (for the message)
  explicit operator bool() const noexcept { return status == file_status::ok; }

  /// One line for people, naming `path` (shown escaped and cut, host::printable) after `noun` when one is
  /// given, and the cause: "cannot open program x.bas: No such file or directory", "x.bas is a directory,
  /// not a file", "/dev/zero is a device, not a file", "profile big.json is larger than 1048576 bytes".
  [[nodiscard]] std::string message(const std::string& path, const std::string& noun = "") const;
};

class progress;

/// The whole content of `path` in `out` (replaced), at most `max_bytes` bytes; see the file comment. With
/// `shown`, the bytes read so far go to that progress line as they come (a large input on a slow pipe).
file_result read_bounded_file(const std::string& path, std::size_t max_bytes, std::string& out,
                              progress* shown = nullptr);

/// Opens `path` to be read as a stream, piece by piece (a capture read record by record): a directory or a
/// device is refused as by read_bounded_file, a file that cannot be opened names the cause; the reader
/// bounds what it holds.
file_result open_input_stream(const std::string& path, std::ifstream& stream);

/// The same for an open descriptor (standard input is 0): read to its end, at most `max_bytes` bytes; the
/// descriptor is not closed. A directory is refused; a device is read within the bound (standard input may
/// be a terminal).
file_result read_bounded_fd(int fd, std::size_t max_bytes, std::string& out, progress* shown = nullptr);

}  // namespace trionet::host
