#include "learn/crc_catalogue.hpp"

#include <charconv>

namespace trionet::learn {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

bool parse_hex(std::string_view s, std::uint64_t& out) {
  if (s.size() < 3 || s[0] != '0' || (s[1] != 'x' && s[1] != 'X') || s.size() > 18) return false;
  const char* first = s.data() + 2;
  const char* last = s.data() + s.size();
  const auto parsed = std::from_chars(first, last, out, 16);
  return parsed.ec == std::errc() && parsed.ptr == last;
}

}  // namespace

catalogue_result parse_crc_catalogue(std::string_view text) {
  catalogue_result result;
  std::size_t line_number = 0;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    std::string_view line = trim(text.substr(0, end));
    text = end == std::string_view::npos ? std::string_view{} : text.substr(end + 1);
    ++line_number;
    if (line.empty() || line.front() == '#') continue;
    const auto fail = [&](catalogue_status status, std::string_view detail) {
      result.status = status;
      result.line = line_number;
      result.detail = std::string(detail);
      result.entries.clear();
      return result;
    };
    enum : unsigned { width, poly, init, refin, refout, xorout, check, name, count };
    std::uint64_t values[count] = {};
    bool seen[count] = {};
    catalogue_entry entry;
    while (!line.empty()) {
      std::size_t word_end = line.find(' ');
      if (line.substr(0, word_end).find('"') != std::string_view::npos) {  // a quoted value may hold blanks
        const std::size_t quote = line.find('"');
        const std::size_t closing = line.find('"', quote + 1);
        if (closing == std::string_view::npos) return fail(catalogue_status::bad_field, line);
        word_end = line.find(' ', closing);
      }
      const std::string_view word = line.substr(0, word_end);
      line = word_end == std::string_view::npos ? std::string_view{} : trim(line.substr(word_end));
      const std::size_t equals = word.find('=');
      if (equals == std::string_view::npos) return fail(catalogue_status::bad_field, word);
      const std::string_view key = word.substr(0, equals);
      const std::string_view value = word.substr(equals + 1);
      if (key == "residue" || key == "alias") continue;
      unsigned field = count;
      if (key == "width") field = width;
      if (key == "poly") field = poly;
      if (key == "init") field = init;
      if (key == "refin") field = refin;
      if (key == "refout") field = refout;
      if (key == "xorout") field = xorout;
      if (key == "check") field = check;
      if (key == "name") field = name;
      if (field == count || seen[field]) return fail(catalogue_status::bad_field, word);
      seen[field] = true;
      if (field == name) {
        if (value.size() < 2 || value.front() != '"' || value.back() != '"')
          return fail(catalogue_status::bad_field, word);
        entry.name = std::string(value.substr(1, value.size() - 2));
      } else if (field == refin || field == refout) {
        if (value != "true" && value != "false") return fail(catalogue_status::bad_field, word);
        values[field] = value == "true" ? 1 : 0;
      } else if (field == width) {
        const auto parsed = std::from_chars(value.data(), value.data() + value.size(), values[field], 10);
        if (parsed.ec != std::errc() || parsed.ptr != value.data() + value.size())
          return fail(catalogue_status::bad_field, word);
      } else if (!parse_hex(value, values[field])) {
        return fail(catalogue_status::bad_field, word);
      }
    }
    for (unsigned field = 0; field < count; ++field) {
      static constexpr const char* names[count] = {"width",  "poly",   "init",  "refin",
                                                   "refout", "xorout", "check", "name"};
      if (!seen[field]) return fail(catalogue_status::missing_field, names[field]);
    }
    if (values[width] < 1 || values[width] > 16) return fail(catalogue_status::out_of_range, "width");
    const std::uint64_t limit = (std::uint64_t{1} << values[width]) - 1;
    for (unsigned field : {poly, init, xorout, check}) {
      if (values[field] > limit) return fail(catalogue_status::out_of_range, entry.name);
    }
    entry.width = static_cast<unsigned>(values[width]);
    entry.polynomial = static_cast<std::uint16_t>(values[poly]);
    entry.initial = static_cast<std::uint16_t>(values[init]);
    entry.reflect_in = values[refin] != 0;
    entry.reflect_out = values[refout] != 0;
    entry.xor_out = static_cast<std::uint16_t>(values[xorout]);
    entry.check = static_cast<std::uint16_t>(values[check]);
    result.entries.push_back(std::move(entry));
  }
  return result;
}

extern const char* const crc_catalogue_text;  // crc_catalogue.txt, built in (crc_catalogue_text.cpp)

const std::vector<catalogue_entry>& crc_catalogue() {
  static const std::vector<catalogue_entry> entries = parse_crc_catalogue(crc_catalogue_text).entries;
  return entries;
}

}  // namespace trionet::learn
