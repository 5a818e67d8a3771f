// The man pages and the bash completion of the `trionet` tool, written from its command and option tables
// (cli.hpp), so that they say what `--help` says and what the parser takes: `trionet --man PAGE` and
// `trionet --completion bash` (the build writes them with cmake/write_manual.cmake).
#pragma once

#include <cstddef>
#include <string>

#include "cli.hpp"

namespace trionet::cli {

/// The tool's parts, in the order `trionet --help` lists them.
struct part_list {
  const part* const* parts;
  std::size_t count;
};

/// The names of the man pages, one a line: "trionet", then "trionet-<part>" for every part.
std::string manual_page_names(const part_list& parts);

/// The man page `name` (one of manual_page_names) in roff (man(7) macros). False if there is no such page.
bool manual_page(const part_list& parts, const std::string& name, std::string& page);

/// The bash completion script: parts, commands, options, and the values and operands the tables name.
std::string bash_completion(const part_list& parts);

}  // namespace trionet::cli
