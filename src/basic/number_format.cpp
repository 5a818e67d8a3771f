#include "basic/number_format.hpp"

#include <cstdio>
#include <cstring>

namespace trionet::basic {
namespace {

// A value that rounds to zero prints without a sign ("-0.0" would only confuse an operator).
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

}  // namespace

void append_number(std::string& out, double value) {
  char text[400];  // the largest double has 309 integer digits
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

void append_number(std::string& out, double value, int width, int decimals) {
  char text[600];
  const int w = clamp(width, 0, 255);
  const int d = clamp(decimals, 0, 15);
  int length = std::snprintf(text, sizeof text, "%.*f", d, value);
  if (length <= 0 || static_cast<std::size_t>(length) >= sizeof text) return;
  drop_sign_of_zero(text, length);
  if (length < w) out.append(static_cast<std::size_t>(w - length), ' ');
  out.append(text, static_cast<std::size_t>(length));
}

}  // namespace trionet::basic
