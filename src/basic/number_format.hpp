// How numbers become text (docs/basic.md, "PRINT"). Two forms: what a program's PRINT writes, as the manual
// prints numbers (4 decimal places, or the [w,d] format), and the shortest readable form the simulator uses in
// its own reports, trace and JSON.
#pragma once

#include <string>

namespace trionet::basic {

/// PRINT x, as the manual prints a number: 4 decimal places, no padding: 1 -> "1.0000", 1/3 -> "0.3333",
/// -2.5 -> "-2.5000", 47104 -> "47104.0000"; a value that rounds to zero prints without a sign.
void append_print_number(std::string& out, double value);

/// PRINT x[w,d]: `decimals` decimal places, right-justified in `width` characters; a number wider than
/// `width` takes the room it needs. Width is clamped to 0..255, decimals to 0..15.
/// 125 [6,0] -> "   125", 0.2 [8,1] -> "     0.2", -0.01 [4,1] -> " 0.0".
void append_print_number(std::string& out, double value, int width, int decimals);

/// The simulator's own reports: rounded to 4 decimal places, then trailing zeros and a trailing point removed:
/// 0.30000000000000004 -> "0.3", 125 -> "125", 1/3 -> "0.3333", -0.00001 -> "0".
void append_value(std::string& out, double value);

inline std::string format_print_number(double value) {
  std::string out;
  append_print_number(out, value);
  return out;
}

inline std::string format_print_number(double value, int width, int decimals) {
  std::string out;
  append_print_number(out, value, width, decimals);
  return out;
}

inline std::string format_value(double value) {
  std::string out;
  append_value(out, value);
  return out;
}

}  // namespace trionet::basic
