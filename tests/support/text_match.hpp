// Regular expressions for the tests that read the tool's output. They are compiled in one translation unit
// (support/text_match.cpp): a file that uses std::regex itself spends seconds more compiling it.
#pragma once

#include <string>
#include <vector>

namespace trionet::test {

/// The first match of the ECMAScript `pattern` in `text`: the whole match, then each group ("" for a group
/// that took no part); empty when there is none.
std::vector<std::string> find_pattern(const std::string& text, const std::string& pattern);

/// Every match of `pattern` in `text`, each as `find_pattern` gives it, in order.
std::vector<std::vector<std::string>> find_all_patterns(const std::string& text, const std::string& pattern);

/// `text` with every match of `pattern` (only the first with `first_only`) replaced by `format` ($1, $2 ...
/// for the groups).
std::string replace_pattern(const std::string& text, const std::string& pattern, const std::string& format,
                            bool first_only = false);

}  // namespace trionet::test
