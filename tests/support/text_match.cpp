// Regular expressions for the tests (support/text_match.hpp): std::regex, each pattern compiled once.
#include "support/text_match.hpp"

#include <map>
#include <mutex>
#include <regex>

namespace trionet::test {
namespace {

const std::regex& compiled(const std::string& pattern) {
  static std::mutex guard;
  static std::map<std::string, std::regex> patterns;
  const std::lock_guard<std::mutex> lock(guard);
  auto found = patterns.find(pattern);
  if (found == patterns.end()) found = patterns.emplace(pattern, std::regex(pattern)).first;
  return found->second;  // (a std::map's elements stay where they are)
}

std::vector<std::string> groups_of(const std::smatch& m) {
  std::vector<std::string> groups;
  for (const auto& group : m) groups.push_back(group.matched ? group.str() : std::string());
  return groups;
}

}  // namespace

std::vector<std::string> find_pattern(const std::string& text, const std::string& pattern) {
  std::smatch m;
  if (!std::regex_search(text, m, compiled(pattern))) return {};
  return groups_of(m);
}

std::vector<std::vector<std::string>> find_all_patterns(const std::string& text, const std::string& pattern) {
  std::vector<std::vector<std::string>> all;
  const std::regex& re = compiled(pattern);
  for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator(); ++it) {
    all.push_back(groups_of(*it));
  }
  return all;
}

std::string replace_pattern(const std::string& text, const std::string& pattern, const std::string& format,
                            bool first_only) {
  return std::regex_replace(text, compiled(pattern), format,
                            first_only ? std::regex_constants::format_first_only : std::regex_constants::format_default);
}

}  // namespace trionet::test
