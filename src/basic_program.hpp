// A tiny cooperative runner for Trio BASIC programs written in C++ line by line, for the simulator, the
// examples and the tests. Host side only (std::function, std::string).
//
// Each line returns what BASIC would do next: go on, wait (a blocking PRINT#, GET# or WAIT UNTIL that
// cannot complete yet), GOTO, GOSUB or RETURN. `run` executes lines until one waits or a budget runs out,
// so a program shares time with the ring like a Motion Coordinator's BASIC task.
#pragma once

#include <cstdio>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "trionet/ring/motion_coordinator.hpp"

namespace trionet::basic {

struct step {
  enum class kind { next, wait, jump, gosub, ret } what = kind::next;
  std::string label;
};

inline step next() {
  return {};
}
inline step wait() {
  return {step::kind::wait, {}};
}
inline step go_to(std::string label) {
  return {step::kind::jump, std::move(label)};
}
inline step gosub(std::string label) {
  return {step::kind::gosub, std::move(label)};
}
inline step ret() {
  return {step::kind::ret, {}};
}

class program {
 public:
  using line_fn = std::function<step()>;

  void line(line_fn fn) { lines_.push_back({{}, std::move(fn)}); }
  void line(std::string label, line_fn fn) { lines_.push_back({std::move(label), std::move(fn)}); }

  /// Runs lines until one waits, the program ends, or `budget` lines have run. Returns false once ended.
  bool run(int budget = 64) {
    for (int n = 0; n < budget && pc_ < lines_.size(); ++n) {
      const step s = lines_[pc_].fn();
      switch (s.what) {
        case step::kind::next:
          ++pc_;
          break;
        case step::kind::wait:
          return true;
        case step::kind::jump:
          pc_ = find(s.label);
          break;
        case step::kind::gosub:
          returns_.push_back(pc_ + 1);
          pc_ = find(s.label);
          break;
        case step::kind::ret:
          if (returns_.empty()) {
            std::fprintf(stderr, "basic: RETURN without GOSUB\n");
            pc_ = lines_.size();
          } else {
            pc_ = returns_.back();
            returns_.pop_back();
          }
          break;
      }
    }
    return pc_ < lines_.size();
  }

  /// The label of the line about to run (or of the nearest labelled line before it).
  std::string where() const {
    for (std::size_t i = pc_ + 1; i-- > 0;) {
      if (i < lines_.size() && !lines_[i].label.empty()) return lines_[i].label;
    }
    return {};
  }

 private:
  struct entry {
    std::string label;
    line_fn fn;
  };

  std::size_t find(const std::string& label) const {
    for (std::size_t i = 0; i < lines_.size(); ++i) {
      if (lines_[i].label == label) return i;
    }
    std::fprintf(stderr, "basic: no label '%s'\n", label.c_str());
    return lines_.size();
  }

  std::vector<entry> lines_;
  std::vector<std::size_t> returns_;
  std::size_t pc_ = 0;
};

// ---- PRINT items ----

inline std::string chr(int c) {
  return std::string(1, static_cast<char>(c));
}
/// CURSOR(p): CHR(27);"H";CHR(p).
inline std::string cursor(int p) {
  return chr(27) + "H" + chr(p);
}
/// value[w,d]: right-aligned in w characters with d decimals.
inline std::string number(double value, int width, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%*.*f", width, decimals, value);
  return text;
}
/// What PRINT appends when its item list does not end with ';'.
inline const std::string crlf = "\r\n";

// ---- blocking statements on a Motion Coordinator ----

/// PRINT #n,text: waits while the transmit queue has no room for the whole message, as BASIC does.
template <class Node>
step print(Node& mc, int n, const std::string& text) {
  if (mc.transmit_free() < text.size() + ring::framing_length) return wait();
  const auto result = mc.print(n, byte_view(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
  if (result.status != ring::send_status::ok)
    std::fprintf(stderr, "basic: PRINT #%d: %s\n", n, ring::to_string(result.status));
  return next();
}

/// SEND(n,1,vr,value).
template <class Node>
step send_variable(Node& mc, int n, int vr, double value) {
  if (mc.transmit_free() < ring::framing_length + ring::variable_data_length) return wait();
  const auto result = mc.send_variable(n, static_cast<std::uint16_t>(vr), value);
  if (result != ring::send_status::ok)
    std::fprintf(stderr, "basic: SEND(%d,1,%d): %s\n", n, vr, ring::to_string(result));
  return next();
}

/// SEND(n,2,offset).
template <class Node>
step send_keypad_offset(Node& mc, int n, int offset) {
  if (mc.transmit_free() < ring::framing_length + 1) return wait();
  const auto result = mc.send_keypad_offset(n, offset);
  if (result != ring::send_status::ok)
    std::fprintf(stderr, "basic: SEND(%d,2,%d): %s\n", n, offset, ring::to_string(result));
  return next();
}

/// GET #channel,var: waits for a character.
template <class Node>
step get(Node& mc, int channel, double& var) {
  const ring::get_result r = mc.get(channel);
  if (!r) return wait();
  var = r.value;
  return next();
}

}  // namespace trionet::basic
