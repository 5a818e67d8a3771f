#include "learn/profile.hpp"

#include <charconv>
#include <cstdio>
#include <cstring>
#include <initializer_list>

#include "trionet/host/text.hpp"

namespace trionet::learn {
namespace {

constexpr const char* order_names[] = {"least_significant_first", "most_significant_first"};
constexpr const char* crc_input_names[] = {"as_sent", "least_significant_first"};
constexpr const char* key_off_names[] = {"plus_64", "same"};
constexpr const char* carriage_return_names[] = {"other_line_unless_at_line_start", "other_line",
                                                 "line_start", "ignored"};
constexpr const char* line_feed_names[] = {"ignored", "next_line"};
constexpr const char* byte_order_names[] = {"big_endian", "little_endian"};
constexpr const char* tag_position_names[] = {"high", "low"};
constexpr const char* control_names[] = {"start", "stop", "start_of_block", "end_of_block"};
constexpr const char* from_codes = "from_codes";

std::string join(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}

class reader {
 public:
  explicit reader(profile_result& result) : result_(result) {}

  bool fail(profile_status status, const std::string& key, std::string message, const json_value& at) {
    result_.status = status;
    result_.key = key;
    result_.message = std::move(message);
    result_.line = at.line;
    result_.column = at.column;
    return false;
  }

  bool object(const json_value& v, const std::string& path, std::initializer_list<const char*> keys) {
    if (v.type != json_value::kind::object) return wrong_type(v, path, "an object");
    for (const auto& member : v.members) {
      bool known = false;
      for (const char* k : keys) known = known || member.first == k;
      if (!known)
        return fail(profile_status::unknown_key, join(path, host::printable(member.first)), "not a key of the schema",
                    member.second);
    }
    return true;
  }

  static const json_value* find(const json_value& v, std::string_view key) {
    for (const auto& member : v.members) {
      if (member.first == key) return &member.second;
    }
    return nullptr;
  }

  bool wrong_type(const json_value& v, const std::string& path, const char* expected) {
    return fail(profile_status::wrong_type, path,
                std::string("expected ") + expected + ", got " + to_string(v.type), v);
  }

  bool integer(const json_value& v, const std::string& path, long long min, long long max, long long& out) {
    const std::string range = std::to_string(min) + ".." + std::to_string(max);
    if (v.type != json_value::kind::number || v.text.find_first_of(".eE") != std::string::npos)
      return wrong_type(v, path, ("an integer " + range).c_str());
    const auto parsed = std::from_chars(v.text.data(), v.text.data() + v.text.size(), out);
    if (parsed.ec != std::errc() || out < min || out > max)
      return fail(profile_status::out_of_range, path, "expected " + range + ", got " + host::printable(v.text), v);
    return true;
  }

  // A CRC parameter of `bits` bits: "0x" and hex digits, or an integer.
  bool parameter(const json_value& v, const std::string& path, unsigned bits, std::uint16_t& out) {
    const long long max = (1LL << bits) - 1;
    if (v.type == json_value::kind::number) {
      long long n = 0;
      if (!integer(v, path, 0, max, n)) return false;
      out = static_cast<std::uint16_t>(n);
      return true;
    }
    const std::string expected = "a " + std::to_string(bits) + "-bit value (\"0x...\" or an integer)";
    if (v.type != json_value::kind::string) return wrong_type(v, path, expected.c_str());
    const std::string& t = v.text;
    unsigned long long n = 0;
    const bool hex_form = t.size() > 2 && t.size() <= 2 + 16 && t[0] == '0' && (t[1] == 'x' || t[1] == 'X');
    const auto parsed =
        hex_form ? std::from_chars(t.data() + 2, t.data() + t.size(), n, 16) : std::from_chars_result{};
    if (!hex_form || parsed.ec != std::errc() || parsed.ptr != t.data() + t.size())
      return fail(profile_status::wrong_type, path, "expected " + expected + ", got \"" + host::printable(t) + "\"", v);
    if (n > static_cast<unsigned long long>(max))
      return fail(profile_status::out_of_range, path,
                  "expected at most " + std::to_string(max) + ", got " + host::printable(t), v);
    out = static_cast<std::uint16_t>(n);
    return true;
  }

  bool boolean(const json_value& v, const std::string& path, bool& out) {
    if (v.type != json_value::kind::boolean) return wrong_type(v, path, "true or false");
    out = v.boolean;
    return true;
  }

  template <std::size_t N>
  bool choice(const json_value& v, const std::string& path, const char* const (&names)[N], std::size_t& out) {
    std::string list;
    for (const char* name : names) list += (list.empty() ? "\"" : ", \"") + std::string(name) + "\"";
    if (v.type != json_value::kind::string) return wrong_type(v, path, ("one of " + list).c_str());
    for (std::size_t i = 0; i < N; ++i) {
      if (v.text == names[i]) {
        out = i;
        return true;
      }
    }
    return fail(profile_status::out_of_range, path, "expected one of " + list + ", got \"" + host::printable(v.text) + "\"",
                v);
  }

  // A raw keypad character: an integer 0..127 or a string of one such character.
  bool character(const json_value& v, const std::string& path, std::uint8_t& out) {
    if (v.type == json_value::kind::number) {
      long long n = 0;
      if (!integer(v, path, 0, 127, n)) return false;
      out = static_cast<std::uint8_t>(n);
      return true;
    }
    if (v.type != json_value::kind::string)
      return wrong_type(v, path, "a character (0..127, or a one-character string)");
    if (v.text.size() != 1 || static_cast<unsigned char>(v.text[0]) > 127)
      return fail(profile_status::out_of_range, path, "expected one character 0..127, got \"" + host::printable(v.text) + "\"",
                  v);
    out = static_cast<std::uint8_t>(v.text[0]);
    return true;
  }

  bool crc16(const json_value& v, const std::string& path, ring::crc16_parameters& out) {
    if (!object(v, path, {"polynomial", "initial", "reflect_in", "reflect_out", "xor_out"})) return false;
    if (auto m = find(v, "polynomial"); m && !parameter(*m, join(path, "polynomial"), 16, out.polynomial))
      return false;
    if (auto m = find(v, "initial"); m && !parameter(*m, join(path, "initial"), 16, out.initial))
      return false;
    if (auto m = find(v, "reflect_in"); m && !boolean(*m, join(path, "reflect_in"), out.reflect_in))
      return false;
    if (auto m = find(v, "reflect_out"); m && !boolean(*m, join(path, "reflect_out"), out.reflect_out))
      return false;
    if (auto m = find(v, "xor_out"); m && !parameter(*m, join(path, "xor_out"), 16, out.xor_out))
      return false;
    return true;
  }

  bool crc6(const json_value& v, const std::string& path, genius::crc6_parameters& out) {
    if (!object(v, path, {"polynomial", "initial", "reflect_in", "reflect_out", "xor_out"})) return false;
    std::uint16_t value = 0;
    if (auto m = find(v, "polynomial")) {
      if (!parameter(*m, join(path, "polynomial"), 6, value)) return false;
      out.polynomial = static_cast<std::uint8_t>(value);
    }
    if (auto m = find(v, "initial")) {
      if (!parameter(*m, join(path, "initial"), 6, value)) return false;
      out.initial = static_cast<std::uint8_t>(value);
    }
    if (auto m = find(v, "reflect_in"); m && !boolean(*m, join(path, "reflect_in"), out.reflect_in))
      return false;
    if (auto m = find(v, "reflect_out"); m && !boolean(*m, join(path, "reflect_out"), out.reflect_out))
      return false;
    if (auto m = find(v, "xor_out")) {
      if (!parameter(*m, join(path, "xor_out"), 6, value)) return false;
      out.xor_out = static_cast<std::uint8_t>(value);
    }
    return true;
  }

  bool ring_part(const json_value& v, ring_profile& out) {
    const std::string path = "ring";
    if (!object(
            v, path,
            {"crc", "vr_group_order", "value_group_order", "crc_input", "max_characters", "receive_buffer"}))
      return false;
    if (auto m = find(v, "crc"); m && !crc16(*m, join(path, "crc"), out.crc)) return false;
    std::size_t index = 0;
    if (auto m = find(v, "vr_group_order")) {
      if (!choice(*m, join(path, "vr_group_order"), order_names, index)) return false;
      out.layout.vr = static_cast<ring::group_order>(index);
    }
    if (auto m = find(v, "value_group_order")) {
      if (!choice(*m, join(path, "value_group_order"), order_names, index)) return false;
      out.layout.value = static_cast<ring::group_order>(index);
    }
    if (auto m = find(v, "crc_input")) {
      if (!choice(*m, join(path, "crc_input"), crc_input_names, index)) return false;
      out.layout.crc = static_cast<ring::crc_input>(index);
    }
    long long n = 0;
    const auto limit = static_cast<long long>(max_characters_limit);
    if (auto m = find(v, "max_characters")) {
      if (!integer(*m, join(path, "max_characters"), static_cast<long long>(min_characters), limit, n))
        return false;
      out.max_characters = static_cast<std::size_t>(n);
    }
    if (auto m = find(v, "receive_buffer")) {
      if (!integer(*m, join(path, "receive_buffer"), static_cast<long long>(min_characters), limit, n))
        return false;
      out.receive_buffer = static_cast<std::size_t>(n);
    }
    return true;
  }

  bool keypad_part(const json_value& v, keypad_profile& out) {
    const std::string path = "keypad";
    if (!object(v, path, {"codes", "defkey", "key_off", "display"})) return false;
    if (auto m = find(v, "codes")) {
      const std::string codes_path = join(path, "codes");
      if (!object(*m, codes_path,
                  {"0", "1", "2", "3", "4", "5", "6", "7", "8", "9", "up", "down", "clear", "yes", "no",
                   "point", "start", "stop"}))
        return false;
      for (std::size_t k = 0; k < ring::key_count; ++k) {
        if (auto c = find(*m, keypad_key_names[k]);
            c && !character(*c, join(codes_path, keypad_key_names[k]), out.codes.raw[k]))
          return false;
      }
      for (std::size_t k = 0; k < ring::key_count; ++k) {
        for (std::size_t other = 0; other < k; ++other) {
          if (out.codes.raw[k] == out.codes.raw[other]) {
            const json_value* at = find(*m, keypad_key_names[k]);
            if (at == nullptr) at = find(*m, keypad_key_names[other]);
            return fail(profile_status::duplicate_code, join(codes_path, keypad_key_names[k]),
                        std::string("sends the same character as key \"") + keypad_key_names[other] + "\"",
                        at ? *at : *m);
          }
        }
      }
    }
    out.defkey = ring::make_default_defkey(out.codes);
    if (auto m = find(v, "defkey")) {
      const std::string defkey_path = join(path, "defkey");
      if (m->type == json_value::kind::string) {
        if (m->text != from_codes)
          return fail(profile_status::out_of_range, defkey_path,
                      std::string("expected \"") + from_codes + "\" or 128 values, got \"" + host::printable(m->text) + "\"",
                      *m);
      } else if (m->type != json_value::kind::array) {
        return wrong_type(*m, defkey_path, "\"from_codes\" or an array of 128 values 0..255");
      } else if (m->items.size() != 128) {
        return fail(profile_status::out_of_range, defkey_path,
                    "expected 128 values, got " + std::to_string(m->items.size()), *m);
      } else {
        for (std::size_t c = 0; c < 128; ++c) {
          long long n = 0;
          if (!integer(m->items[c], defkey_path + "[" + std::to_string(c) + "]", 0, 255, n)) return false;
          out.defkey.value[c] = static_cast<std::uint8_t>(n);
        }
      }
    }
    if (auto m = find(v, "key_off")) {
      std::size_t index = 0;
      if (!choice(*m, join(path, "key_off"), key_off_names, index)) return false;
      out.key_off = static_cast<key_off_rule>(index);
    }
    if (auto m = find(v, "display"); m && !display(*m, join(path, "display"), out.display)) return false;
    return true;
  }

  bool display(const json_value& v, const std::string& path, ring::display_model& out) {
    if (!object(v, path, {"carriage_return", "line_feed", "position_base"})) return false;
    std::size_t index = 0;
    if (auto m = find(v, "carriage_return")) {
      if (!choice(*m, join(path, "carriage_return"), carriage_return_names, index)) return false;
      out.carriage_return = static_cast<ring::carriage_return_rule>(index);
    }
    if (auto m = find(v, "line_feed")) {
      if (!choice(*m, join(path, "line_feed"), line_feed_names, index)) return false;
      out.line_feed = static_cast<ring::line_feed_rule>(index);
    }
    if (auto m = find(v, "position_base")) {
      long long n = 0;
      if (!integer(*m, join(path, "position_base"), 0, ring::max_position_base, n)) return false;
      out.position_base = static_cast<std::uint8_t>(n);
    }
    return true;
  }

  bool control(const json_value& v, const std::string& path, genius::control_layout& out) {
    if (!object(v, path, {"start", "stop", "start_of_block", "end_of_block", "tag_position"})) return false;
    std::uint8_t* const tags[] = {&out.start, &out.stop, &out.start_of_block, &out.end_of_block};
    for (std::size_t i = 0; i < 4; ++i) {
      long long n = 0;
      if (auto m = find(v, control_names[i])) {
        if (!integer(*m, join(path, control_names[i]), 0, 3, n)) return false;
        *tags[i] = static_cast<std::uint8_t>(n);
      }
    }
    for (std::size_t i = 0; i < 4; ++i) {
      for (std::size_t other = 0; other < i; ++other) {
        if (*tags[i] == *tags[other]) {
          const json_value* at = find(v, control_names[i]);
          if (at == nullptr) at = find(v, control_names[other]);
          return fail(profile_status::duplicate_code, join(path, control_names[i]),
                      std::string("has the same tag as \"") + control_names[other] + "\"", at ? *at : v);
        }
      }
    }
    if (auto m = find(v, "tag_position")) {
      std::size_t index = 0;
      if (!choice(*m, join(path, "tag_position"), tag_position_names, index)) return false;
      out.position = static_cast<genius::tag_position>(index);
    }
    return true;
  }

  bool run(const json_value& root, profile& out) {
    if (!object(root, "", {"trionet_profile", "name", "ring", "keypad", "can", "genius"})) return false;
    const json_value* version = find(root, "trionet_profile");
    if (version == nullptr)
      return fail(profile_status::missing_key, "trionet_profile",
                  "a profile starts with \"trionet_profile\": 1", root);
    if (version->type != json_value::kind::number || version->text != std::to_string(profile_version)) {
      if (version->type != json_value::kind::number)
        return wrong_type(*version, "trionet_profile", "the integer 1");
      return fail(profile_status::unsupported_version, "trionet_profile",
                  "this library reads version " + std::to_string(profile_version) + ", got " + host::printable(version->text),
                  *version);
    }
    if (auto m = find(root, "name")) {
      if (m->type != json_value::kind::string) return wrong_type(*m, "name", "a string");
      out.name = m->text;
    }
    if (auto m = find(root, "ring"); m && !ring_part(*m, out.ring)) return false;
    if (auto m = find(root, "keypad"); m && !keypad_part(*m, out.keypad)) return false;
    if (auto m = find(root, "can")) {
      if (!object(*m, "can", {"node_count", "byte_order"})) return false;
      if (auto count = find(*m, "node_count")) {
        long long n = 0;
        if (!integer(*count, "can.node_count", 2, 11, n)) return false;
        out.can.node_count = static_cast<std::uint8_t>(n);
      }
      if (auto order = find(*m, "byte_order")) {
        std::size_t index = 0;
        if (!choice(*order, "can.byte_order", byte_order_names, index)) return false;
        out.can.byte_order = static_cast<can::byte_order>(index);
      }
    }
    if (auto m = find(root, "genius")) {
      if (!object(*m, "genius", {"crc6", "control"})) return false;
      if (auto crc = find(*m, "crc6"); crc && !crc6(*crc, "genius.crc6", out.genius.crc)) return false;
      if (auto layout = find(*m, "control");
          layout && !control(*layout, "genius.control", out.genius.control))
        return false;
    }
    return true;
  }

 private:
  profile_result& result_;
};

std::string hex(unsigned value, int digits) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%0*x", digits, value);
  return text;
}

std::string boolean_text(bool b) {
  return b ? "true" : "false";
}

std::string character_json(std::uint8_t c) {
  if (c >= 32 && c <= 126) return host::json_string(std::string(1, static_cast<char>(c)));
  return std::to_string(c);
}

bool same_defkey(const ring::defkey_table& a, const ring::defkey_table& b) {
  return std::memcmp(a.value, b.value, sizeof a.value) == 0;
}

bool is_identifier(std::string_view word) {
  if (word.empty()) return false;
  const auto alpha = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; };
  if (!alpha(word[0])) return false;
  for (char c : word) {
    if (!alpha(c) && !(c >= '0' && c <= '9')) return false;
  }
  return true;
}

}  // namespace

bool operator==(const profile& a, const profile& b) noexcept {
  return a.name == b.name && a.ring.crc == b.ring.crc && a.ring.layout == b.ring.layout &&
         a.ring.max_characters == b.ring.max_characters && a.ring.receive_buffer == b.ring.receive_buffer &&
         std::memcmp(a.keypad.codes.raw, b.keypad.codes.raw, sizeof a.keypad.codes.raw) == 0 &&
         same_defkey(a.keypad.defkey, b.keypad.defkey) && a.keypad.key_off == b.keypad.key_off &&
         a.keypad.display == b.keypad.display && a.can.node_count == b.can.node_count &&
         a.can.byte_order == b.can.byte_order && a.genius.crc == b.genius.crc &&
         a.genius.control == b.genius.control;
}

profile_result read_profile(std::string_view json) {
  profile_result result;
  const json_result parsed = parse_json(json);
  if (!parsed) {
    result.status = profile_status::not_json;
    result.json = parsed.status;
    result.message = parsed.message;
    result.line = parsed.line;
    result.column = parsed.column;
    return result;
  }
  reader r(result);
  profile p;
  if (r.run(parsed.value, p)) result.value = std::move(p);
  return result;
}

std::string write_profile(const profile& p) {
  const auto crc16 = [](const ring::crc16_parameters& c) {
    return "{\"polynomial\": \"" + hex(c.polynomial, 4) + "\", \"initial\": \"" + hex(c.initial, 4) +
           "\", \"reflect_in\": " + boolean_text(c.reflect_in) +
           ", \"reflect_out\": " + boolean_text(c.reflect_out) + ", \"xor_out\": \"" + hex(c.xor_out, 4) +
           "\"}";
  };
  std::string out = "{\n";
  out += "  \"trionet_profile\": " + std::to_string(profile_version) + ",\n";
  out += "  \"name\": " + host::json_string(p.name) + ",\n";
  out += "  \"ring\": {\n";
  out += "    \"crc\": " + crc16(p.ring.crc) + ",\n";
  out += "    \"vr_group_order\": \"" + std::string(to_string(p.ring.layout.vr)) + "\",\n";
  out += "    \"value_group_order\": \"" + std::string(to_string(p.ring.layout.value)) + "\",\n";
  out += "    \"crc_input\": \"" + std::string(to_string(p.ring.layout.crc)) + "\",\n";
  out += "    \"max_characters\": " + std::to_string(p.ring.max_characters) + ",\n";
  out += "    \"receive_buffer\": " + std::to_string(p.ring.receive_buffer) + "\n";
  out += "  },\n";
  out += "  \"keypad\": {\n";
  out += "    \"codes\": {";
  for (std::size_t k = 0; k < ring::key_count; ++k) {
    out += std::string(k == 0 ? "" : ", ") + "\"" + keypad_key_names[k] +
           "\": " + character_json(p.keypad.codes.raw[k]);
  }
  out += "},\n";
  if (same_defkey(p.keypad.defkey, ring::make_default_defkey(p.keypad.codes))) {
    out += std::string("    \"defkey\": \"") + from_codes + "\",\n";
  } else {
    out += "    \"defkey\": [";
    for (std::size_t c = 0; c < 128; ++c) {
      out += (c == 0 ? "" : (c % 16 == 0 ? ",\n               " : ", ")) +
             std::to_string(p.keypad.defkey.value[c]);
    }
    out += "],\n";
  }
  out += "    \"key_off\": \"" + std::string(to_string(p.keypad.key_off)) + "\",\n";
  const ring::display_model& d = p.keypad.display;
  out += "    \"display\": {\"carriage_return\": \"" + std::string(to_string(d.carriage_return)) +
         "\", \"line_feed\": \"" + to_string(d.line_feed) +
         "\", \"position_base\": " + std::to_string(d.position_base) + "}\n";
  out += "  },\n";
  out += "  \"can\": {\"node_count\": " + std::to_string(p.can.node_count) + ", \"byte_order\": \"" +
         to_string(p.can.byte_order) + "\"},\n";
  const genius::crc6_parameters& g = p.genius.crc;
  const genius::control_layout& l = p.genius.control;
  out += "  \"genius\": {\n";
  out += "    \"crc6\": {\"polynomial\": \"" + hex(g.polynomial, 2) + "\", \"initial\": \"" +
         hex(g.initial, 2) + "\", \"reflect_in\": " + boolean_text(g.reflect_in) +
         ", \"reflect_out\": " + boolean_text(g.reflect_out) + ", \"xor_out\": \"" + hex(g.xor_out, 2) +
         "\"},\n";
  out += "    \"control\": {\"start\": " + std::to_string(l.start) + ", \"stop\": " + std::to_string(l.stop) +
         ", \"start_of_block\": " + std::to_string(l.start_of_block) +
         ", \"end_of_block\": " + std::to_string(l.end_of_block) + ", \"tag_position\": \"" +
         to_string(l.position) + "\"}\n";
  out += "  }\n";
  out += "}\n";
  return out;
}

namespace {

// Why `name` cannot be the header's namespace though its components are identifiers, empty when it can: a
// C++17 keyword or alternative token as a component (g++ rejects the header), or trionet as one (the library's
// own namespace: the header would define its policies there, or hide the trionet:: it names).
std::string namespace_problem(const std::string& name) {
  static const char* const keywords[] = {
      "alignas", "alignof", "and", "and_eq", "asm", "auto", "bitand", "bitor", "bool", "break", "case", "catch",
      "char", "char16_t", "char32_t", "class", "compl", "const", "constexpr", "const_cast", "continue",
      "decltype", "default", "delete", "do", "double", "dynamic_cast", "else", "enum", "explicit", "export",
      "extern", "false", "float", "for", "friend", "goto", "if", "inline", "int", "long", "mutable", "namespace",
      "new", "noexcept", "not", "not_eq", "nullptr", "operator", "or", "or_eq", "private", "protected", "public",
      "register", "reinterpret_cast", "return", "short", "signed", "sizeof", "static", "static_assert",
      "static_cast", "struct", "switch", "template", "this", "thread_local", "throw", "true", "try", "typedef",
      "typeid", "typename", "union", "unsigned", "using", "virtual", "void", "volatile", "wchar_t", "while",
      "xor", "xor_eq"};
  std::size_t at = 0;
  for (;;) {
    const std::size_t separator = name.find("::", at);
    const std::string component = name.substr(at, separator == std::string::npos ? std::string::npos : separator - at);
    for (const char* k : keywords) {
      if (component == k) return "'" + component + "' is a C++ keyword";
    }
    if (component == "trionet") {
      return at == 0 ? "it is or lies inside the library's own namespace trionet"
                     : "a namespace named trionet would hide the library's trionet:: that the header names";
    }
    if (separator == std::string::npos) return "";
    at = separator + 2;
  }
}

}  // namespace

header_result profile_header(const profile& p, std::string_view namespace_name) {
  header_result result;
  std::string_view rest = namespace_name;
  while (true) {
    const std::size_t separator = rest.find("::");
    if (!is_identifier(rest.substr(0, separator))) {
      result.status = header_status::bad_namespace;
      result.reason = "it is not a C++ namespace name (identifiers joined by ::)";
      return result;
    }
    if (separator == std::string_view::npos) break;
    rest = rest.substr(separator + 2);
  }
  const std::string ns(namespace_name);
  result.reason = namespace_problem(ns);
  if (!result.reason.empty()) {
    result.status = header_status::bad_namespace;
    return result;
  }
  const std::string ring_ns = "trionet::ring::";
  const auto order = [&](ring::group_order o) { return ring_ns + "group_order::" + to_string(o); };
  const ring::crc16_parameters& c = p.ring.crc;
  const genius::crc6_parameters& g = p.genius.crc;
  std::string h;
  h += "// Generated by trionet from a profile (docs/profile.md): the wire parameters of one network as\n";
  h += "// constexpr policies for a firmware build. Profile name: " + host::json_string(p.name) + "\n";
  h += "#pragma once\n\n";
  h += "#include <cstddef>\n#include <cstdint>\n\n";
  h += "#include \"trionet/can/node.hpp\"\n";
  h += "#include \"trionet/can/vr_codec.hpp\"\n";
  h += "#include \"trionet/genius/crc6.hpp\"\n";
  h += "#include \"trionet/genius/transmission.hpp\"\n";
  h += "#include \"trionet/ring/crc.hpp\"\n";
  h += "#include \"trionet/ring/decoder.hpp\"\n";
  h += "#include \"trionet/ring/keypad.hpp\"\n";
  h += "#include \"trionet/ring/keypad_codes.hpp\"\n";
  h += "#include \"trionet/ring/motion_coordinator.hpp\"\n";
  h += "#include \"trionet/ring/variable_layout.hpp\"\n\n";
  h += "namespace " + ns + " {\n\n";
  h += "// ---- ring (docs/protocol.md 1.3-1.6) ----\n";
  h += "/// The CRC of a direct variable transfer in the table form of your choice; by default as the "
       "library's\n";
  h += "/// default CRC: sliced where pointers are 64-bit, one table elsewhere.\n";
  h += "template <trionet::ring::crc_table Table = (UINTPTR_MAX > 0xFFFFFFFFu ? "
       "trionet::ring::crc_table::sliced\n";
  h += "                                                                     : "
       "trionet::ring::crc_table::lookup)>\n";
  h += "using ring_crc_with = trionet::ring::crc16<" + hex(c.polynomial, 4) + ", " + hex(c.initial, 4) +
       ", " + hex(c.xor_out, 4) + ", Table, " + boolean_text(c.reflect_in) + ", " +
       boolean_text(c.reflect_out) + ">;\n";
  h += "using ring_crc = ring_crc_with<>;\n";
  h += "using ring_layout = " + ring_ns + "variable_layout<" + order(p.ring.layout.vr) + ",\n    " +
       order(p.ring.layout.value) + ", " + ring_ns + "crc_input::" + to_string(p.ring.layout.crc) + ">;\n";
  h += "inline constexpr std::size_t ring_max_characters = " + std::to_string(p.ring.max_characters) + ";\n";
  h += "inline constexpr std::size_t ring_receive_buffer = " + std::to_string(p.ring.receive_buffer) + ";\n";
  h += "using ring_decoder = trionet::ring::decoder<ring_max_characters, ring_crc, ring_layout>;\n";
  h += "template <std::size_t ForwardCapacity = 16, std::size_t TransmitCapacity = 32>\n";
  h += "using motion_coordinator = trionet::ring::motion_coordinator<ring_receive_buffer, ForwardCapacity,\n";
  h += "    TransmitCapacity, ring_max_characters, ring_crc, ring_layout>;\n";
  h += "template <std::size_t ForwardCapacity = 16, std::size_t TransmitCapacity = 16>\n";
  h += "using keypad = trionet::ring::keypad<ForwardCapacity, TransmitCapacity, ring_max_characters, "
       "ring_crc,\n";
  h += "    ring_layout>;\n\n";
  h += "// ---- keypad (docs/protocol.md 1.6-1.8): pass keypad_config to a keypad, defkey to an MC ----\n";
  h += "inline constexpr trionet::ring::keypad_codes keypad_codes = {{";
  for (std::size_t k = 0; k < ring::key_count; ++k) {
    h += (k == 0 ? "" : (k % 9 == 0 ? ",\n    " : ", ")) + std::to_string(p.keypad.codes.raw[k]);
  }
  h += "}};\n";
  h += "inline constexpr trionet::ring::defkey_table defkey = {{";
  for (std::size_t i = 0; i < 128; ++i) {
    h += (i == 0 ? "" : (i % 16 == 0 ? ",\n    " : ", ")) + std::to_string(p.keypad.defkey.value[i]);
  }
  h += "}};\n";
  const ring::display_model& d = p.keypad.display;
  h += "inline constexpr trionet::ring::display_model keypad_display_model = {\n";
  h += "    trionet::ring::carriage_return_rule::" + std::string(to_string(d.carriage_return)) +
       ", trionet::ring::line_feed_rule::" + to_string(d.line_feed) + ", " + std::to_string(d.position_base) +
       "};\n";
  h += "inline constexpr trionet::ring::keypad_config keypad_config = {&keypad_codes, trionet::ring::" +
       std::string(p.keypad.key_off == key_off_rule::same ? "same_key_off_code" : "default_key_off_code") +
       ", keypad_display_model};\n\n";
  h += "// ---- CAN (docs/protocol.md 2.1, 2.2): can_node has the byte order fixed at compile time; or pass\n";
  h += "// can_byte_order to a vr_exchange_node and the codec calls ----\n";
  h += "inline constexpr std::uint8_t can_node_count = " + std::to_string(p.can.node_count) + ";\n";
  h += "inline constexpr trionet::can::byte_order can_byte_order = trionet::can::byte_order::" +
       std::string(to_string(p.can.byte_order)) + ";\n";
  h += "using can_node = trionet::can::basic_vr_exchange_node<trionet::can::fixed_byte_order<can_byte_order>>;\n\n";
  h += "// ---- Genius (docs/protocol.md 3.2) ----\n";
  h += "using genius_crc = trionet::genius::crc6<" + hex(g.polynomial, 2) + ", " + hex(g.initial, 2) + ", " +
       boolean_text(g.reflect_in) + ", " + boolean_text(g.reflect_out) + ", " + hex(g.xor_out, 2) + ">;\n";
  const genius::control_layout& l = p.genius.control;
  h += "/// Pass to encode_transmission and to a transmission_parser or transmission_receiver.\n";
  h += "inline constexpr trionet::genius::control_layout genius_control = {" + std::to_string(l.start) +
       ", " + std::to_string(l.stop) + ", " + std::to_string(l.start_of_block) + ", " +
       std::to_string(l.end_of_block) + ", trionet::genius::tag_position::" + to_string(l.position) +
       "};\n\n";
  h += "}  // namespace " + ns + "\n";
  result.text = std::move(h);
  return result;
}

}  // namespace trionet::learn
