// The tool's command-line words: options with a value (`--to 10` or `--to=10`), flags (`--json`) and
// positionals, as every command splits them (docs/cli.md). Self-contained (fuzz/cli_arguments.cpp builds it
// alone).
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

namespace trionet::cli {

/// The words after a command's name.
using words = std::vector<std::string>;

/// Command-line words split into options that take a value, bare flags and positionals.
struct arguments {
  std::map<std::string, std::string> options;
  std::set<std::string> flags;
  std::vector<std::string> positionals;

  bool has(const std::string& name) const { return options.count(name) != 0; }
  bool flag(const std::string& name) const { return flags.count(name) != 0; }
};

/// The values of a repeatable option, in the order given (parse_arguments joins them with '\n').
std::vector<std::string> values_of(const std::string& joined);

/// Splits `words` into options that take a value (`--name value` or `--name=value`; a short one such as
/// `-o FILE` only in the first form), flags (`--name`, no value) and positionals. Unknown options, a missing
/// value, a value given to a flag or a repeated option are errors; `repeatable` options collect every value,
/// joined by '\n'. "--" ends option parsing; "-" alone is a positional (standard input). Returns false with
/// `error` set on failure: one line, any word it quotes shown with host::printable.
bool parse_arguments(const words& args, const std::set<std::string>& value_options,
                     const std::set<std::string>& flag_options, arguments& out, std::string& error,
                     const std::set<std::string>& repeatable = {});

}  // namespace trionet::cli
