#include "basic/number_format.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>

namespace trionet::basic {
namespace {

// A value that rounds to zero prints without a sign ("-0.0000" would only confuse an operator).
void drop_sign_of_zero(char* text, int& length) {
  if (text[0] != '-') return;
  for (int i = 1; i < length; ++i) {
    if (text[i] != '0' && text[i] != '.' && text[i] != ' ') return;
  }
  std::memmove(text, text + 1, static_cast<std::size_t>(length));  // the terminator moves too
  --length;
}

int clamp(int value, int low, int high) {
  return value < low ? low : (value > high ? high : value);
}

// NaN and infinities cannot come from the manual's arithmetic; they print as words rather than as garbage.
bool append_not_finite(std::string& out, double value) {
  if (std::isfinite(value)) return false;
  out += std::isnan(value) ? "nan" : (value > 0 ? "inf" : "-inf");
  return true;
}

}  // namespace

void append_print_number(std::string& out, double value) {
  append_print_number(out, value, 0, 4);
}

void append_print_number(std::string& out, double value, int width, int decimals) {
  if (append_not_finite(out, value)) return;
  char text[600];  // the largest double has 309 integer digits, then up to 15 decimals
  const int w = clamp(width, 0, 255);
  const int d = clamp(decimals, 0, 15);
  int length = std::snprintf(text, sizeof text, "%.*f", d, value);
  if (length <= 0 || static_cast<std::size_t>(length) >= sizeof text) return;
  drop_sign_of_zero(text, length);
  if (length < w) out.append(static_cast<std::size_t>(w - length), ' ');
  out.append(text, static_cast<std::size_t>(length));
}

void append_value(std::string& out, double value) {
  if (append_not_finite(out, value)) return;
  char text[400];
  int length = std::snprintf(text, sizeof text, "%.4f", value);
  if (length <= 0 || static_cast<std::size_t>(length) >= sizeof text) return;
  if (std::strchr(text, '.') != nullptr) {
    while (text[length - 1] == '0') --length;
    if (text[length - 1] == '.') --length;
    text[length] = '\0';
  }
  drop_sign_of_zero(text, length);
  out.append(text, static_cast<std::size_t>(length));
}

}  // namespace trionet::basic
