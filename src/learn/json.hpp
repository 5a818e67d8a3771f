// A strict JSON reader (RFC 8259) for profiles (the writer escapes strings with host::json_string).
//
// Strict: one value, nothing after it but blanks; no comments, trailing commas or duplicate object keys;
// strings of valid UTF-8 with the standard escapes (a surrogate pair for characters above U+FFFF); numbers
// in the JSON grammar, kept as text so the schema decides what it accepts. Bounded: at most `max_json_bytes`
// of input and `max_json_depth` nested arrays and objects; every error gives its line and column.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace trionet::learn {

constexpr std::size_t max_json_bytes = 1u << 20;
constexpr std::size_t max_json_depth = 32;

struct json_value {
  enum class kind : std::uint8_t { null, boolean, number, string, array, object };
  kind type = kind::null;
  bool boolean = false;
  std::string text;               ///< a string's contents (UTF-8), or a number as written
  std::vector<json_value> items;  ///< array
  std::vector<std::pair<std::string, json_value>> members;  ///< object, in the order written
  std::size_t line = 0;                                     ///< where the value starts (1-based)
  std::size_t column = 0;
};

constexpr const char* to_string(json_value::kind kind) noexcept {
  switch (kind) {
    case json_value::kind::null:
      return "null";
    case json_value::kind::boolean:
      return "boolean";
    case json_value::kind::number:
      return "number";
    case json_value::kind::string:
      return "string";
    case json_value::kind::array:
      return "array";
    case json_value::kind::object:
      return "object";
  }
  return "unknown";
}

enum class json_status : std::uint8_t {
  ok,
  syntax,     ///< not JSON (`message` says what was expected)
  too_large,  ///< more than max_json_bytes
  too_deep,   ///< more than max_json_depth nested arrays and objects
  duplicate_key,
};

constexpr const char* to_string(json_status status) noexcept {
  switch (status) {
    case json_status::ok:
      return "ok";
    case json_status::syntax:
      return "syntax";
    case json_status::too_large:
      return "too_large";
    case json_status::too_deep:
      return "too_deep";
    case json_status::duplicate_key:
      return "duplicate_key";
  }
  return "unknown";
}

struct [[nodiscard]] json_result {
  json_status status = json_status::ok;
  json_value value;
  std::size_t line = 0;  ///< of the error
  std::size_t column = 0;
  std::string message;
  explicit operator bool() const noexcept { return status == json_status::ok; }
};

[[nodiscard]] json_result parse_json(std::string_view text);

}  // namespace trionet::learn
