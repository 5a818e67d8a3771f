// How a BASIC program's PRINT writes a number (docs/basic.md, "Numbers"). The one place that turns a BASIC
// value into text: PRINT, PRINT #n and the simulator's trace and summaries all use it.
#pragma once

#include <string>

namespace trionet::basic {

/// PRINT x: rounded to 4 decimal places, then trailing zeros and a trailing point removed:
/// 0.30000000000000004 -> "0.3", 125 -> "125", 1/3 -> "0.3333", -2.5 -> "-2.5", -0.00001 -> "0".
void append_number(std::string& out, double value);

/// PRINT x[w,d]: `decimals` decimal places, right-justified in `width` characters; a number wider than
/// `width` takes the room it needs. Width is clamped to 0..255, decimals to 0..15.
/// 125 [6,0] -> "   125", 0.2 [8,1] -> "     0.2", -0.01 [4,1] -> " 0.0".
void append_number(std::string& out, double value, int width, int decimals);

inline std::string format_number(double value) {
  std::string out;
  append_number(out, value);
  return out;
}

inline std::string format_number(double value, int width, int decimals) {
  std::string out;
  append_number(out, value, width, decimals);
  return out;
}

}  // namespace trionet::basic
