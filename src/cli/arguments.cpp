// The tool's command-line words: see arguments.hpp.
#include "arguments.hpp"

#include "trionet/host/text.hpp"

namespace trionet::cli {

bool parse_arguments(const words& args, const std::set<std::string>& value_options,
                     const std::set<std::string>& flag_options, arguments& out, std::string& error,
                     const std::set<std::string>& repeatable) {
  bool options_done = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& word = args[i];
    if (options_done) {
      out.positionals.push_back(word);
      continue;
    }
    if (word == "--") {
      options_done = true;
      continue;
    }
    // "-o" and other short options are options only where the command has them.
    const bool long_form = word.size() > 2 && word.compare(0, 2, "--") == 0;
    if (!long_form && value_options.count(word) == 0 && flag_options.count(word) == 0) {
      out.positionals.push_back(word);
      continue;
    }
    // --name=value: the name up to the first '='.
    const std::size_t equals = long_form ? word.find('=') : std::string::npos;
    const std::string name = word.substr(0, equals);
    if (flag_options.count(name) != 0) {
      if (equals != std::string::npos) {
        error = "option " + host::printable(name) + " takes no value";
        return false;
      }
      if (!out.flags.insert(name).second) {
        error = "option " + name + " given twice";  // as for an option with a value
        return false;
      }
      continue;
    }
    if (value_options.count(name) == 0) {
      error = "unknown option " + host::printable(name);
      return false;
    }
    std::string value;
    if (equals != std::string::npos) {
      value = word.substr(equals + 1);
    } else if (i + 1 < args.size()) {
      value = args[++i];
    } else {
      error = "option " + name + " needs a value";
      return false;
    }
    auto found = out.options.find(name);
    if (found != out.options.end()) {
      if (repeatable.count(name) == 0) {
        error = "option " + name + " given twice";
        return false;
      }
      found->second += '\n';
      found->second += value;
    } else {
      out.options.emplace(name, std::move(value));
    }
  }
  return true;
}

std::vector<std::string> values_of(const std::string& joined) {
  std::vector<std::string> values;
  std::size_t at = 0;
  for (;;) {
    const std::size_t end = joined.find('\n', at);
    values.push_back(joined.substr(at, end == std::string::npos ? std::string::npos : end - at));
    if (end == std::string::npos) return values;
    at = end + 1;
  }
}

}  // namespace trionet::cli
