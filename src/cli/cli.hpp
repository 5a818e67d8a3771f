// Shared pieces of the `trionet` tool (docs/cli.md): the command tables and their dispatcher, argument
// parsing, streaming input and buffered output, and JSON events. Numbers and hex are read by the host
// library's one parser (trionet/host/text.hpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "arguments.hpp"
#include "trionet/host/text.hpp"

namespace trionet::cli {

using host::format_real;
using host::hex_digit;
using host::json_string;
using host::parse_integer;

constexpr int exit_ok = 0;     ///< the input was read (wire errors are events, not failures)
constexpr int exit_io = 1;     ///< reading or writing failed
constexpr int exit_usage = 2;  ///< misuse: bad arguments
constexpr int exit_check = 3;  ///< a requested check failed (genius timing --check), or nothing was learned
constexpr int exit_limit = 4;  ///< a limit cut the work short and --fail-on-limit was given

/// Appends printf-formatted text to `out` (the tool's output is put together in strings and written with
/// write_stdout).
std::string& appendf(std::string& out, const char* format, ...) __attribute__((format(printf, 2, 3)));

/// Prints "trionet: <message>" on stderr and returns the usage exit code (2).
int fail(const std::string& message);

/// Prints "trionet: <message>" on stderr and returns the I/O failure exit code (1).
int fail_io(const std::string& message);

/// Prints "trionet: <message>" on stderr (a control character in it shown escaped).
void note(const std::string& message);

/// A limit cut the work short (a run's length, a count): prints "trionet: <message>" on stderr and returns
/// 0, or exit_limit (4) when the command line has --fail-on-limit (taken by the dispatcher for every
/// command).
int limit_reached(const std::string& message);

// ---------------------------------------------------------------------------------------------------------
// standard output

/// Writes `text` to standard output at once (stdio's buffer is flushed first, so the order holds). False
/// when writing failed, then and ever after; the cause is kept for `fail_output`. SIGPIPE is ignored by the
/// tool, so a closed pipe is such a failure (EPIPE), not a silent death.
bool write_stdout(std::string_view text);

/// True once writing standard output failed.
bool output_failed();

/// Prints "trionet: cannot write standard output: <cause>" (once, however often it is called) and returns
/// exit_io (1).
int fail_output();

/// The exit status of a command that returned `status`: stdio's standard output is flushed, and if any
/// write to standard output failed the status is exit_io with the message printed once (a command that
/// writes with printf learns of a closed output here). Called by main() after every command.
int finish_output(int status);

/// A whole finite decimal real number (see host::parse_real), any magnitude a double holds.
inline bool parse_real(std::string_view text, double& out) {
  return host::parse_real(text, -1.7976931348623157e308, 1.7976931348623157e308, out);
}

// ---------------------------------------------------------------------------------------------------------
// commands

/// One option of a command, or one of its operands: an entry of the command's option table, which
/// `parse_arguments` reads and from which the man pages and the shell completion are written
/// (`trionet --man`, `trionet --completion`: manual.cpp).
struct option {
  const char* name;        ///< "--pcap", "-o"; an operand (a word that is not an option): its name, "PORT"
  const char* value;       ///< the name of the option's value, "FILE"; nullptr for a flag and for an operand
  const char* completion;  ///< what the shell offers for the value or operand: "" nothing, "@file" file names,
                           ///< "@port" serial ports and files, "@interface" network interfaces, "@keys" key
                           ///< script words, else the words themselves ("none rtscts xonxoff"); "mc:@file" is
                           ///< "mc:" followed by a file name
  const char* help;        ///< one line for the man page
  bool repeatable = false;  ///< may be given more than once (parse_arguments joins the values with '\n')
};

/// A command's option table: its options and operands, in the order its man page lists them.
using option_list = std::vector<option>;

/// `a` followed by the entries of `b`.
option_list joined(option_list a, const option_list& b);

/// The options the dispatcher takes for every command (`--profile FILE`, `--help`).
const option_list& common_options();

/// One command of a part: `trionet <part> <name> ...`. A part lists its commands in one table; adding a
/// command is adding one entry.
struct command {
  const char* name;     ///< "decode"
  const char* summary;  ///< one line for the part's usage ("read ring bytes, print one JSON event per ...")
  const char* usage;    ///< the whole help text, printed by `trionet <part> <name> --help`
  int (*run)(const words& args);  ///< runs with the words after the name; returns the exit status
  const option_list& options;     ///< the command's option table: what `run` parses, its man page and completion
};

/// A part of the tool (ring, can, genius) and its command table.
struct part {
  const char* name;        ///< "ring"
  const char* summary;     ///< one line for the tool's usage
  const command* commands;  ///< the table
  std::size_t count;        ///< entries in the table
  const char* notes;        ///< lines printed after the command list (may be "")
};

/// Runs `trionet <part> <words...>`: no command prints the part's usage on stderr (exit 2); `--help`/`-h`
/// prints it on stdout; `--version` prints the version; `<command> ... --help` (anywhere before `--`) prints
/// the command's help; an unknown command is a usage error. The options every command takes are taken out
/// before the command runs: `--profile FILE` and `--fail-on-limit`.
int dispatch(const part& p, const words& args);

/// The part's usage text: its commands with their summaries, then its notes.
std::string part_usage(const part& p);

/// The tool's version line, "trionet 0.1.0".
std::string version_line();

extern const part ring_part;    ///< ring_cli.cpp
extern const part can_part;     ///< can_cli.cpp
extern const part genius_part;  ///< genius_cli.cpp
extern const part profile_part;  ///< profile_cli.cpp

// ---------------------------------------------------------------------------------------------------------
// arguments (arguments.hpp: the words split into options, flags and positionals)

/// Splits `args` with the options of a command's option table (its operands are positionals).
bool parse_arguments(const words& args, const option_list& options, arguments& out, std::string& error);

// ---------------------------------------------------------------------------------------------------------
// streaming input and output

/// Standard output with a buffer: events are appended to `text()` and written by `flush`, which the decoders
/// call after every read of input (so an event is out as soon as the read that completed it) and whenever
/// the buffer passes 64 KiB (so memory stays bounded).
class output {
 public:
  static constexpr std::size_t flush_at = 1U << 16U;

  output() { text_.reserve(flush_at + 16384); }

  std::string& text() { return text_; }
  /// Writes when the buffer is past `flush_at`.
  bool maybe_flush() { return text_.size() < flush_at || flush(); }
  /// Writes everything buffered to standard output (write_stdout). False if writing failed (then and ever
  /// after).
  bool flush();
  bool failed() const { return output_failed(); }

 private:
  std::string text_;
};

/// Reads standard input (or a file) in chunks of at most 64 KiB, each as soon as it is available.
class input {
 public:
  static constexpr std::size_t chunk = 1U << 16U;

  input();  ///< standard input
  ~input();
  input(const input&) = delete;
  input& operator=(const input&) = delete;

  /// Opens `path` instead (for --pcap-like readers that want a descriptor). False with `error` set.
  bool open(const std::string& path, std::string& error);
  /// The next chunk: empty at the end of input. False (with `error` set) when reading failed.
  bool read(std::string_view& data, std::string& error);

 private:
  int fd_ = 0;
  bool owned_ = false;
  std::vector<char> buffer_;
};

/// Reads standard input to its end, each chunk through `feed(std::string_view)` as soon as it is read, and
/// flushes `out` after each. Returns the exit status: 0, or 1 when reading or writing failed.
template <class Feed>
int stream_stdin(output& out, Feed&& feed) {
  input in;
  std::string error;
  std::string_view chunk;
  while (true) {
    if (!in.read(chunk, error)) {
      out.flush();
      return fail_io(error);
    }
    if (chunk.empty()) return exit_ok;
    feed(chunk);
    if (!out.flush()) return fail_output();
  }
}

/// Appends one JSON event line, `{"event":"<kind>",...}\n`, to a string as its fields are added. The line is
/// put together in a buffer of its own and appended at once (the decoders' output is their hot path).
class event {
 public:
  event(std::string& out, std::string_view kind) : out_(out) {
    put("{\"event\":\"", 10);
    put(kind.data(), kind.size());
    put("\"", 1);
  }
  ~event() {
    put("}\n", 2);
    out_.append(line_, size_);
  }
  event(const event&) = delete;
  event& operator=(const event&) = delete;

  event& number(std::string_view name, std::uint64_t value);
  event& signed_number(std::string_view name, std::int64_t value);
  /// A real number as a plain decimal (no exponent), the shortest that reads back; null if not finite.
  event& real(std::string_view name, double value);
  event& boolean(std::string_view name, bool value);
  /// A string field; the text is escaped (host::append_json_string).
  event& text(std::string_view name, std::string_view value);
  /// A string field whose value is one of the program's own names (letters, digits, '_'), never input:
  /// written without the escaping scan (the decoders' "type" fields).
  event& name(std::string_view name, std::string_view value);
  /// A field whose value is already JSON.
  event& json(std::string_view name, std::string_view value);
  /// "time": nanoseconds since 1970 (or since the start of a simulation) as a string of decimal seconds with
  /// 9 digits, "1700000000.123456789" (as Wireshark's frame.time_epoch): the position of a capture record or
  /// of a live event.
  event& time(std::uint64_t time_ns);

  /// Raw text (for host::append_json_string, which escapes into the event).
  void push_back(char c) {
    if (size_ == sizeof line_) flush_line();
    line_[size_++] = c;
  }
  /// Raw text (for host::append_json_string).
  void append(const char* text, std::size_t size) { put(text, size); }

 private:
  void key(std::string_view name);
  void flush_line() {
    out_.append(line_, size_);
    size_ = 0;
  }
  void put(const char* text, std::size_t size) {
    if (size > sizeof line_ - size_) {  // a long field: what is gathered goes first
      flush_line();
      if (size > sizeof line_) {
        out_.append(text, size);
        return;
      }
    }
    for (std::size_t i = 0; i < size; ++i) line_[size_ + i] = text[i];
    size_ += size;
  }

  std::string& out_;
  char line_[480];
  std::size_t size_ = 0;
};

/// Nanoseconds since 1970 as decimal seconds with 9 digits, "1700000000.123456789" (as Wireshark's
/// frame.time_epoch).
std::string epoch_text(std::uint64_t time_ns);

}  // namespace trionet::cli
