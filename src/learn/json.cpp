#include "learn/json.hpp"

#include "trionet/host/text.hpp"

namespace trionet::learn {
namespace {

class parser {
 public:
  explicit parser(std::string_view text) : text_(text) {}

  json_result run() {
    json_result result;
    if (text_.size() > max_json_bytes) {
      result.status = json_status::too_large;
      result.line = 1;
      result.column = 1;
      result.message = "more than " + std::to_string(max_json_bytes) + " bytes";
      return result;
    }
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") at_ = 3;  // a UTF-8 byte order mark
    skip_blanks();
    if (!value(result.value, 0)) return error_result();
    skip_blanks();
    if (at_ != text_.size()) {
      fail(json_status::syntax, "text after the JSON value");
      return error_result();
    }
    return result;
  }

 private:
  bool fail(json_status status, std::string message) {
    if (status_ == json_status::ok) {
      status_ = status;
      message_ = std::move(message);
      error_line_ = line_;
      error_column_ = at_ - line_start_ + 1;
    }
    return false;
  }

  json_result error_result() const {
    json_result result;
    result.status = status_;
    result.line = error_line_;
    result.column = error_column_;
    result.message = message_;
    return result;
  }

  bool done() const { return at_ >= text_.size(); }
  char peek() const { return done() ? '\0' : text_[at_]; }

  void skip_blanks() {
    while (!done()) {
      const char c = text_[at_];
      if (c == '\n') {
        ++at_;
        ++line_;
        line_start_ = at_;
      } else if (c == ' ' || c == '\t' || c == '\r') {
        ++at_;
      } else {
        break;
      }
    }
  }

  bool literal(std::string_view word) {
    if (text_.substr(at_, word.size()) != word) return fail(json_status::syntax, "expected a JSON value");
    at_ += word.size();
    return true;
  }

  bool value(json_value& out, std::size_t depth) {
    out.line = line_;
    out.column = at_ - line_start_ + 1;
    switch (peek()) {
      case '{':
        return object(out, depth + 1);
      case '[':
        return array(out, depth + 1);
      case '"':
        out.type = json_value::kind::string;
        return string(out.text);
      case 't':
        out.type = json_value::kind::boolean;
        out.boolean = true;
        return literal("true");
      case 'f':
        out.type = json_value::kind::boolean;
        return literal("false");
      case 'n':
        return literal("null");
      default:
        out.type = json_value::kind::number;
        return number(out.text);
    }
  }

  bool object(json_value& out, std::size_t depth) {
    if (depth > max_json_depth)
      return fail(json_status::too_deep, "nested deeper than " + std::to_string(max_json_depth));
    out.type = json_value::kind::object;
    ++at_;
    skip_blanks();
    if (peek() == '}') {
      ++at_;
      return true;
    }
    while (true) {
      skip_blanks();
      if (peek() != '"') return fail(json_status::syntax, "expected a key (a string)");
      std::string key;
      if (!string(key)) return false;
      for (const auto& member : out.members) {
        if (member.first == key) return fail(json_status::duplicate_key, "duplicate key \"" + host::printable(key) + "\"");
      }
      skip_blanks();
      if (peek() != ':') return fail(json_status::syntax, "expected ':' after a key");
      ++at_;
      skip_blanks();
      out.members.emplace_back(std::move(key), json_value{});
      if (!value(out.members.back().second, depth)) return false;
      skip_blanks();
      if (peek() == ',') {
        ++at_;
        continue;
      }
      if (peek() == '}') {
        ++at_;
        return true;
      }
      return fail(json_status::syntax, "expected ',' or '}'");
    }
  }

  bool array(json_value& out, std::size_t depth) {
    if (depth > max_json_depth)
      return fail(json_status::too_deep, "nested deeper than " + std::to_string(max_json_depth));
    out.type = json_value::kind::array;
    ++at_;
    skip_blanks();
    if (peek() == ']') {
      ++at_;
      return true;
    }
    while (true) {
      skip_blanks();
      out.items.emplace_back();
      if (!value(out.items.back(), depth)) return false;
      skip_blanks();
      if (peek() == ',') {
        ++at_;
        continue;
      }
      if (peek() == ']') {
        ++at_;
        return true;
      }
      return fail(json_status::syntax, "expected ',' or ']'");
    }
  }

  static int hex_digit(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  }

  bool hex4(unsigned& out) {
    out = 0;
    for (int k = 0; k < 4; ++k) {
      const int d = done() ? -1 : hex_digit(text_[at_]);
      if (d < 0) return fail(json_status::syntax, "expected four hex digits after \\u");
      out = out * 16 + static_cast<unsigned>(d);
      ++at_;
    }
    return true;
  }

  static void append_utf8(std::string& out, unsigned code) {
    if (code < 0x80) {
      out += static_cast<char>(code);
    } else if (code < 0x800) {
      out += static_cast<char>(0xC0 | (code >> 6));
      out += static_cast<char>(0x80 | (code & 0x3F));
    } else if (code < 0x10000) {
      out += static_cast<char>(0xE0 | (code >> 12));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (code & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (code >> 18));
      out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (code & 0x3F));
    }
  }

  // One UTF-8 sequence starting at at_ (its first byte is >= 0x80), checked: shortest form, no surrogates,
  // at most U+10FFFF.
  bool utf8(std::string& out) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text_[at_ + k]); };
    const unsigned first = byte(0);
    std::size_t length = 0;
    unsigned code = 0, minimum = 0;
    if (first >= 0xC2 && first <= 0xDF) {
      length = 2, code = first & 0x1F, minimum = 0x80;
    } else if (first >= 0xE0 && first <= 0xEF) {
      length = 3, code = first & 0x0F, minimum = 0x800;
    } else if (first >= 0xF0 && first <= 0xF4) {
      length = 4, code = first & 0x07, minimum = 0x10000;
    } else {
      return fail(json_status::syntax, "invalid UTF-8");
    }
    if (text_.size() - at_ < length) return fail(json_status::syntax, "invalid UTF-8");
    for (std::size_t k = 1; k < length; ++k) {
      if ((byte(k) & 0xC0) != 0x80) return fail(json_status::syntax, "invalid UTF-8");
      code = (code << 6) | (byte(k) & 0x3F);
    }
    if (code < minimum || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF))
      return fail(json_status::syntax, "invalid UTF-8");
    out.append(text_.substr(at_, length));
    at_ += length;
    return true;
  }

  bool string(std::string& out) {
    ++at_;  // the opening quote
    while (true) {
      if (done()) return fail(json_status::syntax, "unterminated string");
      const char c = text_[at_];
      if (c == '"') {
        ++at_;
        return true;
      }
      if (static_cast<unsigned char>(c) < 0x20)
        return fail(json_status::syntax, "control character in a string");
      if (static_cast<unsigned char>(c) >= 0x80) {
        if (!utf8(out)) return false;
        continue;
      }
      ++at_;
      if (c != '\\') {
        out += c;
        continue;
      }
      if (done()) return fail(json_status::syntax, "unterminated string");
      const char e = text_[at_++];
      switch (e) {
        case '"':
        case '\\':
        case '/':
          out += e;
          break;
        case 'b':
          out += '\b';
          break;
        case 'f':
          out += '\f';
          break;
        case 'n':
          out += '\n';
          break;
        case 'r':
          out += '\r';
          break;
        case 't':
          out += '\t';
          break;
        case 'u': {
          unsigned code = 0;
          if (!hex4(code)) return false;
          if (code >= 0xDC00 && code <= 0xDFFF) return fail(json_status::syntax, "unpaired surrogate");
          if (code >= 0xD800 && code <= 0xDBFF) {
            unsigned low = 0;
            if (text_.substr(at_, 2) != "\\u") return fail(json_status::syntax, "unpaired surrogate");
            at_ += 2;
            if (!hex4(low)) return false;
            if (low < 0xDC00 || low > 0xDFFF) return fail(json_status::syntax, "unpaired surrogate");
            code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
          }
          append_utf8(out, code);
          break;
        }
        default:
          --at_;
          return fail(json_status::syntax, "unknown escape in a string");
      }
    }
  }

  bool digits() {
    if (done() || text_[at_] < '0' || text_[at_] > '9') return false;
    while (!done() && text_[at_] >= '0' && text_[at_] <= '9') ++at_;
    return true;
  }

  bool number(std::string& out) {
    const std::size_t start = at_;
    if (peek() == '-') ++at_;
    if (peek() == '0') {
      ++at_;
    } else if (!digits()) {
      at_ = start;
      return fail(json_status::syntax, "expected a JSON value");
    }
    if (peek() == '.') {
      ++at_;
      if (!digits()) return fail(json_status::syntax, "expected digits after '.'");
    }
    if (peek() == 'e' || peek() == 'E') {
      ++at_;
      if (peek() == '+' || peek() == '-') ++at_;
      if (!digits()) return fail(json_status::syntax, "expected digits in the exponent");
    }
    out = std::string(text_.substr(start, at_ - start));
    return true;
  }

  std::string_view text_;
  std::size_t at_ = 0;
  std::size_t line_ = 1;
  std::size_t line_start_ = 0;
  json_status status_ = json_status::ok;
  std::string message_;
  std::size_t error_line_ = 0;
  std::size_t error_column_ = 0;
};

}  // namespace

json_result parse_json(std::string_view text) {
  return parser(text).run();
}

}  // namespace trionet::learn
