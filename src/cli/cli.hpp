// Shared pieces of the host-side `trionet` tool: argument parsing, number parsing and JSON output.
// Each protocol part has its own entry point (<part>_cli.cpp); main.cpp dispatches on the first word.
#pragma once

#include <charconv>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace trionet::cli {

constexpr int exit_ok = 0;
constexpr int exit_usage = 2;

/// Prints "trionet: <message>" on stderr and returns the usage exit code (2).
inline int fail(const std::string& message) {
  std::fprintf(stderr, "trionet: %s\n", message.c_str());
  return exit_usage;
}

/// Command-line words split into `--name value` options, bare `--flag`s and positionals.
struct arguments {
  std::map<std::string, std::string> options;
  std::set<std::string> flags;
  std::vector<std::string> positionals;

  bool has(const std::string& name) const { return options.count(name) != 0; }
};

/// Splits `words` into options that take a value, flags, and positionals. Unknown options, a missing value
/// or a repeated option are errors; `repeatable` options collect every value, joined by '\n'.
/// "--" ends option parsing. Returns false with `error` set on failure.
inline bool parse_arguments(const std::vector<std::string>& words, const std::set<std::string>& value_options,
                            const std::set<std::string>& flag_options, arguments& out, std::string& error,
                            const std::set<std::string>& repeatable = {}) {
  bool options_done = false;
  for (std::size_t i = 0; i < words.size(); ++i) {
    const std::string& word = words[i];
    const bool looks_like_option = word.size() > 2 && word.compare(0, 2, "--") == 0;
    if (options_done || !looks_like_option) {
      if (word == "--" && !options_done) {
        options_done = true;
        continue;
      }
      out.positionals.push_back(word);
      continue;
    }
    if (flag_options.count(word) != 0) {
      out.flags.insert(word);
      continue;
    }
    if (value_options.count(word) == 0) {
      error = "unknown option " + word;
      return false;
    }
    if (i + 1 >= words.size()) {
      error = "option " + word + " needs a value";
      return false;
    }
    const std::string& value = words[++i];
    auto found = out.options.find(word);
    if (found != out.options.end()) {
      if (repeatable.count(word) == 0) {
        error = "option " + word + " given twice";
        return false;
      }
      found->second += '\n';
      found->second += value;
    } else {
      out.options.emplace(word, value);
    }
  }
  return true;
}

/// Parses a whole decimal integer in [min, max]. Returns false on anything else.
inline bool parse_integer(std::string_view text, long long min, long long max, long long& out) {
  long long value = 0;
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (first != last && *first == '+') ++first;
  auto [end, ec] = std::from_chars(first, last, value);
  if (ec != std::errc() || end != last || first == last) return false;
  if (value < min || value > max) return false;
  out = value;
  return true;
}

/// Parses a whole finite decimal real number ("99", "-2.345", "1e3").
inline bool parse_real(std::string_view text, double& out) {
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (first != last && *first == '+') ++first;
  double value = 0;
  auto [end, ec] = std::from_chars(first, last, value, std::chars_format::general);
  if (ec != std::errc() || end != last || first == last) return false;
  if (!(value == value) || value > 1.7976931348623157e308 || value < -1.7976931348623157e308) return false;
  out = value;
  return true;
}

/// The shortest decimal text that reads back as the same double ("99", "2.345", "-0.5").
inline std::string format_real(double value) {
  char text[32];
  auto [end, ec] = std::to_chars(text, text + sizeof text, value);
  (void)ec;
  return std::string(text, end);
}

/// `text` as a JSON string literal, quotes included; bytes below 0x20, '"' and '\' are escaped.
inline std::string json_string(std::string_view text) {
  std::string out = "\"";
  for (char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (byte < 0x20 || byte == 0x7f) {
      char escape[8];
      std::snprintf(escape, sizeof escape, "\\u%04x", byte);
      out += escape;
    } else {
      out += c;
    }
  }
  out += '"';
  return out;
}

/// Reads all of standard input.
inline std::string read_stdin() {
  std::string all;
  char chunk[4096];
  std::size_t got = 0;
  while ((got = std::fread(chunk, 1, sizeof chunk, stdin)) > 0) all.append(chunk, got);
  return all;
}

int ring_main(const std::vector<std::string>& args);
int can_main(const std::vector<std::string>& args);
int genius_main(const std::vector<std::string>& args);

}  // namespace trionet::cli
