// Fuzz harness: the tool's command-line parser (src/cli/arguments.cpp), as every command calls it.
//
// Input: byte 0 chooses which of a fixed set of options take a value, are flags or may repeat (one bit
// each); the rest is the command line, its words separated by NUL bytes.
// Invariants:
//   - no crash, no undefined behaviour, whatever the words (ASan/UBSan in scripts/fuzz);
//   - on success every option taken is one the command has, with the value of its last `--name value` or
//     `--name=value` (joined by '\n' where it may repeat), every flag is a flag of the command, and the
//     positionals are the other words in order (after "--" every word is one);
//   - on failure the error is one line with no control character, at most a few hundred bytes whatever the
//     words (a word it quotes is cut to 40 characters and escaped).
#include <cstddef>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "fuzz_check.hpp"

#include "../src/cli/arguments.cpp"

namespace {

const char* const names[] = {"--to", "--vr", "--value", "-o", "--json", "--raw", "--pcap", "--device"};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::uint8_t choice = data[0];
  std::set<std::string> value_options;
  std::set<std::string> flag_options;
  std::set<std::string> repeatable;
  for (std::size_t i = 0; i < 8; ++i) {
    if ((choice >> i & 1U) != 0) {
      value_options.insert(names[i]);
      if (i >= 6) repeatable.insert(names[i]);
    } else {
      flag_options.insert(names[i]);
    }
  }
  trionet::cli::words words(1);
  for (std::size_t i = 1; i < size; ++i) {
    if (data[i] == 0) {
      words.emplace_back();
    } else {
      words.back() += static_cast<char>(data[i]);
    }
  }

  trionet::cli::arguments parsed;
  std::string error;
  if (!trionet::cli::parse_arguments(words, value_options, flag_options, parsed, error, repeatable)) {
    FUZZ_CHECK(!error.empty());
    FUZZ_CHECK(trionet_fuzz::printable_line(error));
    FUZZ_CHECK(error.size() <= 400);
    return 0;
  }
  FUZZ_CHECK(error.empty());
  for (const auto& option : parsed.options) FUZZ_CHECK(value_options.count(option.first) == 1);
  for (const std::string& flag : parsed.flags) FUZZ_CHECK(flag_options.count(flag) == 1);
  // Walk the words again: the positionals are exactly the words that are no option, its value or "--".
  std::vector<std::string> positionals;
  bool done = false;
  for (std::size_t i = 0; i < words.size(); ++i) {
    const std::string& word = words[i];
    if (done) {
      positionals.push_back(word);
    } else if (word == "--") {
      done = true;
    } else if (flag_options.count(word) != 0) {
      continue;
    } else if (value_options.count(word) != 0) {
      ++i;  // its value
    } else if (word.size() > 2 && word.compare(0, 2, "--") == 0) {
      const std::string name = word.substr(0, word.find('='));
      FUZZ_CHECK(value_options.count(name) == 1 && word.find('=') != std::string::npos);
      const std::string& taken = parsed.options.at(name);
      const std::string value = word.substr(name.size() + 1);
      FUZZ_CHECK(taken.size() >= value.size());
      FUZZ_CHECK(taken.compare(taken.size() - value.size(), value.size(), value) == 0 ||
                 repeatable.count(name) == 1);
    } else {
      positionals.push_back(word);
    }
  }
  FUZZ_CHECK(positionals == parsed.positionals);
  return 0;
}
