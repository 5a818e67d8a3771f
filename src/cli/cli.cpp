// The tool's shared pieces: see cli.hpp.
#include "cli.hpp"
#include "profile_cli.hpp"

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <cstdarg>
#include <charconv>
#include <cmath>
#include <cinttypes>
#include <cstdio>
#include <cstring>

namespace trionet::cli {
namespace {

bool& fail_on_limit() {
  static bool given = false;
  return given;
}

}  // namespace

namespace {

// One message line on standard error. Echoed values are host::printable already; a control character that
// reached the message another way is still shown escaped, never written raw to the terminal.
void message_line(const std::string& message) {
  std::string line = "trionet: ";
  for (const char c : message) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x20 && byte != 0x7f) {
      line += c;
      continue;
    }
    static constexpr char digits[] = "0123456789abcdef";
    line += "\\x";
    line += digits[byte >> 4U];
    line += digits[byte & 0x0FU];
  }
  line += '\n';
  std::fputs(line.c_str(), stderr);
  std::fflush(stderr);
}

}  // namespace

void note(const std::string& message) {
  message_line(message);
}

int fail(const std::string& message) {
  message_line(message);
  return exit_usage;
}

namespace {

// The first failure of standard output: its errno (0: none yet), and whether it was reported.
int output_errno = 0;
bool output_reported = false;

}  // namespace

int fail_io(const std::string& message) {
  // A command's own report of a standard output that failed is the one report, with its cause.
  if (message == "cannot write standard output") {
    if (output_errno == 0) output_errno = errno != 0 ? errno : EIO;
    return fail_output();
  }
  message_line(message);
  return exit_io;
}

std::string& appendf(std::string& out, const char* format, ...) {
  char text[512];
  va_list args;
  va_start(args, format);
  const int length = std::vsnprintf(text, sizeof text, format, args);
  va_end(args);
  if (length < 0) return out;
  if (static_cast<std::size_t>(length) < sizeof text) return out.append(text, static_cast<std::size_t>(length));
  std::string long_text(static_cast<std::size_t>(length) + 1, '\0');
  va_start(args, format);
  std::vsnprintf(long_text.data(), long_text.size(), format, args);
  va_end(args);
  long_text.pop_back();
  return out += long_text;
}

int limit_reached(const std::string& message) {
  message_line(message);
  return fail_on_limit() ? exit_limit : exit_ok;
}

bool write_stdout(std::string_view text) {
  if (output_errno != 0) return false;
  if (std::fflush(stdout) != 0) {
    output_errno = errno != 0 ? errno : EIO;
    return false;
  }
  const char* p = text.data();
  std::size_t left = text.size();
  while (left > 0) {
    const ssize_t wrote = ::write(STDOUT_FILENO, p, left);
    if (wrote < 0 && errno == EINTR) continue;
    if (wrote < 0 && errno == EAGAIN) {  // standard output left non-blocking by another program: wait
      pollfd writable{STDOUT_FILENO, POLLOUT, 0};
      (void)::poll(&writable, 1, 1000);
      continue;
    }
    if (wrote <= 0) {
      output_errno = wrote < 0 ? errno : EIO;
      return false;
    }
    p += wrote;
    left -= static_cast<std::size_t>(wrote);
  }
  return true;
}

bool output_failed() {
  return output_errno != 0;
}

int fail_output() {
  if (!output_reported) {
    output_reported = true;
    message_line(std::string("cannot write standard output: ") + std::strerror(output_errno != 0 ? output_errno : EIO));
  }
  return exit_io;
}

int finish_output(int status) {
  errno = 0;
  if (std::fflush(stdout) != 0 || std::ferror(stdout) != 0) {
    if (output_errno == 0) output_errno = errno != 0 ? errno : EIO;
  }
  if (output_errno == 0 || status == exit_usage) return status;
  return fail_output();
}

std::string version_line() {
  return std::string("trionet ") + TRIONET_VERSION;
}

std::string part_usage(const part& p) {
  std::string out = std::string("usage: trionet ") + p.name + " <command> [options]\n\ncommands:\n";
  for (std::size_t i = 0; i < p.count; ++i) {
    std::string name = p.commands[i].name;
    if (name.size() < 10) name.resize(10, ' ');
    out += "  " + name + "  " + p.commands[i].summary + "\n";
  }
  out += std::string("\nRun `trionet ") + p.name + " <command> --help` for a command's options.\n";
  out += p.notes;
  return out;
}

namespace {

bool asks_for_help(const words& args) {
  for (const std::string& word : args) {
    if (word == "--") return false;
    if (word == "--help" || word == "-h") return true;
  }
  return false;
}

std::string command_names(const part& p) {
  std::string names;
  for (std::size_t i = 0; i < p.count; ++i) {
    if (i != 0) names += i + 1 == p.count ? " or " : ", ";
    names += p.commands[i].name;
  }
  return names;
}

}  // namespace

int dispatch(const part& p, const words& args) {
  if (args.empty()) {
    std::fprintf(stderr, "trionet: %s needs a command: %s\n%s", p.name, command_names(p).c_str(),
                 part_usage(p).c_str());
    return exit_usage;
  }
  const std::string& name = args.front();
  if (name == "--help" || name == "-h" || name == "help") {
    write_stdout(part_usage(p));
    return exit_ok;
  }
  if (name == "--version") {
    write_stdout(version_line() + "\n");
    return exit_ok;
  }
  for (std::size_t i = 0; i < p.count; ++i) {
    const command& c = p.commands[i];
    if (name != c.name) continue;
    words rest(args.begin() + 1, args.end());
    if (asks_for_help(rest)) {
      write_stdout(c.usage);
      return exit_ok;
    }
    // Options every command takes, taken here: what a limit does to the exit status, and the profile in
    // effect (every command encodes and decodes with it).
    for (std::size_t at = 0; at < rest.size() && rest[at] != "--"; ++at) {
      if (rest[at] != "--fail-on-limit") continue;
      if (fail_on_limit()) return fail("option --fail-on-limit given twice");
      fail_on_limit() = true;
      rest.erase(rest.begin() + static_cast<std::ptrdiff_t>(at--));
    }
    const int loaded = take_profile_option(rest);
    if (loaded != exit_ok) return loaded;
    return c.run(rest);
  }
  return fail("unknown " + std::string(p.name) + " command '" + host::printable(name) + "' (expected " + command_names(p) + ")");
}

bool parse_arguments(const words& args, const option_list& options, arguments& out, std::string& error) {
  std::set<std::string> values;
  std::set<std::string> flags;
  std::set<std::string> repeatable;
  for (const option& o : options) {
    if (o.name[0] != '-') continue;  // an operand
    (o.value != nullptr ? values : flags).insert(o.name);
    if (o.repeatable) repeatable.insert(o.name);
  }
  return parse_arguments(args, values, flags, out, error, repeatable);
}

option_list joined(option_list a, const option_list& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

const option_list& common_options() {
  static const option_list options = {
      {"--profile", "FILE", "@file", "the wire parameters to use, a profile (JSON; trionet-profile(1))"},
      {"--fail-on-limit", nullptr, "", "exit 4, not 0, when a limit cut the run short (trionet(1), EXIT STATUS)"},
      {"--help", nullptr, "", "print the help text and exit (also -h)"},
  };
  return options;
}

// ---------------------------------------------------------------------------------------------------------
// output, input

bool output::flush() {
  if (!write_stdout(text_)) return false;
  text_.clear();
  return true;
}

input::input() : buffer_(chunk) {}

input::~input() {
  if (owned_) ::close(fd_);
}

bool input::open(const std::string& path, std::string& error) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    error = "cannot open " + host::printable(path) + ": " + std::strerror(errno);
    return false;
  }
  if (owned_) ::close(fd_);
  fd_ = fd;
  owned_ = true;
  return true;
}

bool input::read(std::string_view& data, std::string& error) {
  while (true) {
    const ssize_t got = ::read(fd_, buffer_.data(), buffer_.size());
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) {
      error = std::string("cannot read the input: ") + std::strerror(errno);
      return false;
    }
    data = std::string_view(buffer_.data(), static_cast<std::size_t>(got));
    return true;
  }
}

// ---------------------------------------------------------------------------------------------------------
// events

// Each field is put together in a small buffer and appended at once: one append per field keeps the
// decoders' output fast (scripts/decode-figures).
namespace {

std::size_t put_key(char* to, std::string_view name) {
  to[0] = ',';
  to[1] = '"';
  for (std::size_t i = 0; i < name.size(); ++i) to[2 + i] = name[i];  // names are short: no memcpy call
  to[2 + name.size()] = '"';
  to[3 + name.size()] = ':';
  return name.size() + 4;
}

// Decimal digits of `value` at `to` (room for 20); returns the end.
char* put_decimal(char* to, std::uint64_t value) {
  static constexpr char pairs[] =
      "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
      "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
      "8081828384858687888990919293949596979899";
  std::size_t digits = 1;
  for (std::uint64_t v = value; v >= 10U; v /= 10U) ++digits;
  char* end = to + digits;  // written from the end, two digits a step
  char* at = end;
  while (value >= 100U) {
    const auto pair = static_cast<std::size_t>(value % 100U) * 2U;
    value /= 100U;
    *--at = pairs[pair + 1U];
    *--at = pairs[pair];
  }
  if (value >= 10U) {
    const auto pair = static_cast<std::size_t>(value) * 2U;
    *--at = pairs[pair + 1U];
    *--at = pairs[pair];
  } else {
    *--at = static_cast<char>('0' + value);
  }
  return end;
}

}  // namespace

void event::key(std::string_view name) {
  char text[80];
  put(text, put_key(text, name.substr(0, 64)));
}

event& event::number(std::string_view name, std::uint64_t value) {
  char text[104];
  const std::size_t at = put_key(text, name.substr(0, 64));
  put(text, static_cast<std::size_t>(put_decimal(text + at, value) - text));
  return *this;
}

event& event::signed_number(std::string_view name, std::int64_t value) {
  char text[104];
  std::size_t at = put_key(text, name.substr(0, 64));
  auto magnitude = static_cast<std::uint64_t>(value);
  if (value < 0) {
    text[at++] = '-';
    magnitude = ~magnitude + 1U;  // two's complement: right for INT64_MIN too
  }
  put(text, static_cast<std::size_t>(put_decimal(text + at, magnitude) - text));
  return *this;
}

event& event::real(std::string_view name, double value) {
  char text[400];  // the key, and the longest plain decimal of a double (about 330 characters)
  const std::size_t at = put_key(text, name.substr(0, 64));
  if (!(value == value) || value > 1.7976931348623157e308 || value < -1.7976931348623157e308) {
    put(text, at);
    put("null", 4);
    return *this;
  }
  // A whole number below 10^5 in magnitude: its digits, written without the general conversion. -0 takes the general path, which keeps its sign.
  if (value > -1e5 && value < 1e5 && !(value == 0.0 && std::signbit(value)) &&
      static_cast<double>(static_cast<std::int32_t>(value)) == value) {
    std::size_t end = at;
    const auto whole = static_cast<std::int32_t>(value);
    if (whole < 0) text[end++] = '-';
    end = static_cast<std::size_t>(
        put_decimal(text + end, static_cast<std::uint64_t>(whole < 0 ? -static_cast<std::int64_t>(whole) : whole)) - text);
    put(text, end);
    return *this;
  }
  // Plain decimals, never an exponent ("0.0001", not "1e-04"): the shortest digits that read back as the
  // same double.
  const auto result = std::to_chars(text + at, text + sizeof text, value, std::chars_format::fixed);
  put(text, static_cast<std::size_t>(result.ptr - text));
  return *this;
}

event& event::boolean(std::string_view name, bool value) {
  key(name);
  if (value) {
    put("true", 4);
  } else {
    put("false", 5);
  }
  return *this;
}

event& event::text(std::string_view name, std::string_view value) {
  key(name);
  host::append_json_string(*this, value);
  return *this;
}

event& event::name(std::string_view name, std::string_view value) {
  char text[144];
  std::size_t at = put_key(text, name.substr(0, 64));
  value = value.substr(0, 64);
  text[at++] = '"';
  for (const char c : value) text[at++] = c;
  text[at++] = '"';
  put(text, at);
  return *this;
}

event& event::json(std::string_view name, std::string_view value) {
  key(name);
  put(value.data(), value.size());
  return *this;
}

event& event::time(std::uint64_t time_ns) {
  return json("time", "\"" + epoch_text(time_ns) + "\"");
}

std::string epoch_text(std::uint64_t time_ns) {
  char text[40];
  std::snprintf(text, sizeof text, "%" PRIu64 ".%09" PRIu64, time_ns / 1000000000U, time_ns % 1000000000U);
  return text;
}

}  // namespace trionet::cli
