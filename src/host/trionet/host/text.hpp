// Text helpers shared by the host formats (candump) and the `trionet` tool: hex digits and hex bytes, whole
// and real numbers, JSON strings. One parser for each, so that every part reads numbers the same way.
// Header-only; host code (std::string).
#pragma once

#include <charconv>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <system_error>

#include "trionet/span.hpp"

namespace trionet::host {

/// The value of one hex digit (0-9, a-f, A-F), or -1.
constexpr int hex_digit(char c) noexcept {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

/// True for the blanks that separate words: space, tab, CR, LF, FF, VT.
constexpr bool is_blank(char c) noexcept {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

/// A whole hex number of 1..`max_digits` digits (at most 8), nothing else. False on anything else.
constexpr bool parse_hex_number(std::string_view text, std::size_t max_digits, std::uint32_t& out) noexcept {
  if (text.empty() || text.size() > max_digits || text.size() > 8) return false;
  std::uint32_t value = 0;
  for (char c : text) {
    const int digit = hex_digit(c);
    if (digit < 0) return false;
    value = value << 4U | static_cast<std::uint32_t>(digit);
  }
  out = value;
  return true;
}

/// An even number of hex digits ("", "11", "1122") appended to `out` as bytes. False (and `out` unchanged)
/// on an odd count or a character that is not a hex digit.
template <class Bytes>
bool parse_hex_bytes(std::string_view text, Bytes& out) {
  if (text.size() % 2 != 0) return false;
  for (char c : text) {
    if (hex_digit(c) < 0) return false;
  }
  for (std::size_t i = 0; i < text.size(); i += 2) {
    out.push_back(static_cast<std::uint8_t>(hex_digit(text[i]) << 4 | hex_digit(text[i + 1])));
  }
  return true;
}

/// A whole decimal integer ("42", "+42", "-7") in [min, max]. False on anything else ("+-7" too).
inline bool parse_integer(std::string_view text, long long min, long long max, long long& out) noexcept {
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (first != last && *first == '+') ++first;
  if (first != last && *first == '-' && first != text.data()) return false;  // "+-7": one sign at most
  long long value = 0;
  const auto [end, ec] = std::from_chars(first, last, value);
  if (ec != std::errc() || end != last || first == last || value < min || value > max) return false;
  out = value;
  return true;
}

/// A whole finite decimal real number ("99", "-2.345", "1e3") in [min, max]. False on anything else
/// (NaN, infinities, hex floats, trailing text, two signs such as "+-5").
inline bool parse_real(std::string_view text, double min, double max, double& out) noexcept {
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (first != last && *first == '+') ++first;
  if (first != last && *first == '-' && first != text.data()) return false;  // "+-5": one sign at most
  double value = 0;
  const auto [end, ec] = std::from_chars(first, last, value, std::chars_format::general);
  if (ec != std::errc() || end != last || first == last) return false;
  if (!(value >= min && value <= max)) return false;  // also false for NaN
  out = value;
  return true;
}

/// The shortest plain decimal text that reads back as the same double ("99", "2.345", "-0.5", "0.0001"; never
/// an exponent such as "1e-04"); "null" for NaN and the infinities, so that the text is always a JSON value.
inline std::string format_real(double value) {
  if (!(value == value) || value > 1.7976931348623157e308 || value < -1.7976931348623157e308) return "null";
  char text[400];  // the longest plain decimal of a double is about 330 characters
  const auto [end, ec] = std::to_chars(text, text + sizeof text, value, std::chars_format::fixed);
  return ec == std::errc() ? std::string(text, end) : std::string("null");
}

/// The length of the well-formed UTF-8 sequence of 2..4 bytes at the start of `text`, or 0: the shortest
/// form of a code point up to U+10FFFF that is not a surrogate (Unicode's table of well-formed sequences).
constexpr std::size_t utf8_sequence(std::string_view text) noexcept {
  if (text.empty()) return 0;
  const auto lead = static_cast<unsigned char>(text[0]);
  const std::size_t length = lead >= 0xC2 && lead <= 0xDF ? 2 : lead >= 0xE0 && lead <= 0xEF ? 3
                             : lead >= 0xF0 && lead <= 0xF4 ? 4 : 0;
  if (length == 0 || text.size() < length) return 0;
  for (std::size_t i = 1; i < length; ++i) {
    if ((static_cast<unsigned char>(text[i]) & 0xC0U) != 0x80U) return 0;
  }
  // The second byte's narrower range after E0 (no overlong form), ED (no surrogate), F0 (no overlong form)
  // and F4 (nothing above U+10FFFF).
  const auto second = static_cast<unsigned char>(text[1]);
  if ((lead == 0xE0 && second < 0xA0) || (lead == 0xED && second > 0x9F) || (lead == 0xF0 && second < 0x90) ||
      (lead == 0xF4 && second > 0x8F)) {
    return 0;
  }
  return length;
}

/// Appends `text` as a JSON string literal, quotes included: '"' and '\' escaped; control bytes (below 0x20,
/// and 0x7f) and bytes that are not part of well-formed UTF-8 as \u00XX; well-formed UTF-8 as it is. So any
/// input gives valid JSON, and UTF-8 text reads back unchanged. `Out` is std::string or anything with
/// `append(const char*, std::size_t)` and `push_back(char)`.
template <class Out>
void append_json_string(Out& out, std::string_view text) {
  static constexpr char digits[] = "0123456789abcdef";
  out.push_back('"');
  for (std::size_t i = 0; i < text.size(); ++i) {
    std::size_t run = i;  // a run of characters that need no escape goes out in one append
    while (run < text.size() && static_cast<unsigned char>(text[run]) >= 0x20 &&
           static_cast<unsigned char>(text[run]) < 0x7f && text[run] != '"' && text[run] != '\\') {
      ++run;
    }
    if (run != i) {
      out.append(text.data() + i, run - i);
      i = run;
      if (i == text.size()) break;
    }
    const char c = text[i];
    const auto byte = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      out.push_back('\\');
      out.push_back(c);
    } else if (byte >= 0x20 && byte < 0x7f) {
      out.push_back(c);
    } else if (const std::size_t length = byte >= 0x80 ? utf8_sequence(text.substr(i)) : 0; length != 0) {
      out.append(text.data() + i, length);
      i += length - 1;
    } else {
      const char escape[6] = {'\\', 'u', '0', '0', digits[byte >> 4U], digits[byte & 0x0FU]};
      out.append(escape, sizeof escape);
    }
  }
  out.push_back('"');
}

/// `text` as a JSON string literal (see append_json_string).
inline std::string json_string(std::string_view text) {
  std::string out;
  append_json_string(out, text);
  return out;
}

/// Ring characters for people (the text field of a capture record, the simulator's trace): `\\`, `\r`,
/// `\n`, `\t` and `\xNN` (other bytes below 32, and 127 and above) escaped, so that every character, NUL
/// included, is visible. The byte after ESC 'H' is a display position (docs/protocol.md 1.9), a number:
/// always `\xNN`.
inline std::string escaped_text(byte_view characters) {
  std::string out;
  for (std::size_t i = 0; i < characters.size(); ++i) {
    const std::uint8_t c = characters[i];
    const bool position = i >= 2 && characters[i - 2] == 27 && characters[i - 1] == 'H';
    if (position || c < 32 || c >= 127 || c == '\\') {
      static constexpr char digits[] = "0123456789abcdef";
      const char named = position ? 0 : c == '\\' ? '\\' : c == '\r' ? 'r' : c == '\n' ? 'n' : c == '\t' ? 't' : 0;
      out += '\\';
      if (named != 0) {
        out += named;
      } else {
        out += 'x';
        out += digits[c >> 4U];
        out += digits[c & 0x0FU];
      }
    } else {
      out += static_cast<char>(c);
    }
  }
  return out;
}

/// Text from outside (an argument, a file name, a value read from a file or a port) as a message shows it:
/// at most `limit` characters, then "..." when there were more; a backslash as `\\`, CR, LF and tab as
/// `\r`, `\n`, `\t`; every other control character (below 0x20, 0x7f, and the C1 controls U+0080..U+009F)
/// and every byte that is not part of well-formed UTF-8 as `\xNN`; the Unicode direction controls
/// (U+200E, U+200F, U+202A..U+202E, U+2066..U+2069) as `\uXXXX`; other well-formed UTF-8 as it is. So a
/// message never carries a control character to a terminal, and its length is bounded whatever the input:
/// the one function the tool echoes untrusted text with.
inline std::string printable(std::string_view text, std::size_t limit = 40) {
  static constexpr char digits[] = "0123456789abcdef";
  std::string out;
  std::size_t characters = 0;
  std::size_t i = 0;
  for (; i < text.size() && characters < limit; ++characters) {
    const auto byte = static_cast<unsigned char>(text[i]);
    if (byte >= 0x20 && byte < 0x7f) {
      if (byte == '\\') out += '\\';
      out += static_cast<char>(byte);
      ++i;
      continue;
    }
    const std::size_t length = byte >= 0x80 ? utf8_sequence(text.substr(i)) : 0;
    if (length != 0) {
      unsigned code = length == 2 ? byte & 0x1FU : length == 3 ? byte & 0x0FU : byte & 0x07U;
      for (std::size_t k = 1; k < length; ++k) code = code << 6U | (static_cast<unsigned char>(text[i + k]) & 0x3FU);
      const bool c1 = code >= 0x80 && code <= 0x9F;
      const bool direction = code == 0x200E || code == 0x200F || (code >= 0x202A && code <= 0x202E) ||
                             (code >= 0x2066 && code <= 0x2069);
      if (direction) {
        out += "\\u";
        for (unsigned shift = 12;; shift -= 4) {
          out += digits[code >> shift & 0xFU];
          if (shift == 0) break;
        }
      } else if (c1) {
        for (std::size_t k = 0; k < length; ++k) {
          const auto b = static_cast<unsigned char>(text[i + k]);
          out += "\\x";
          out += digits[b >> 4U];
          out += digits[b & 0x0FU];
        }
      } else {
        out.append(text.data() + i, length);
      }
      i += length;
      continue;
    }
    const char named = byte == '\r' ? 'r' : byte == '\n' ? 'n' : byte == '\t' ? 't' : 0;
    out += '\\';
    if (named != 0) {
      out += named;
    } else {
      out += 'x';
      out += digits[byte >> 4U];
      out += digits[byte & 0x0FU];
    }
    ++i;
  }
  if (i < text.size()) out += "...";
  return out;
}

}  // namespace trionet::host
