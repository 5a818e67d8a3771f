// Simulated ring networks for tests: nodes from the example programs built into the tool, or from program
// text, with every event recorded.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "embedded_files.hpp"
#include "ring_network.hpp"

namespace trionet::test {

/// A Motion Coordinator running the example program `path` (e.g. "examples/manual/example1.bas").
inline host::node_spec mc_file(const std::string& path) {
  host::node_spec node;
  node.what = host::node_spec::kind::mc;
  node.program_name = path;
  const host::embedded_file* file = host::find_embedded_file(path);
  EXPECT_NE(file, nullptr) << path << " is not built in";
  if (file != nullptr) node.program_text = std::string(file->text());
  return node;
}

/// A Motion Coordinator running `text`.
inline host::node_spec mc_text(const std::string& name, const std::string& text) {
  host::node_spec node;
  node.what = host::node_spec::kind::mc;
  node.program_name = name;
  node.program_text = text;
  return node;
}

inline host::node_spec keypad() {
  host::node_spec node;
  node.what = host::node_spec::kind::keypad;
  return node;
}

inline host::node_spec plain_mc() {
  return host::node_spec{};
}

/// A network and everything it reported.
class recorded_network {
 public:
  explicit recorded_network(const std::vector<host::node_spec>& nodes, const host::network_config& config = {}) {
    std::string error;
    net_ = host::ring_network::build(nodes, config, error);
    EXPECT_TRUE(net_ != nullptr) << error;
    if (net_) net_->on_event([this](const host::network_event& e) { events_.push_back(e); });
  }
  recorded_network(const recorded_network&) = delete;
  recorded_network& operator=(const recorded_network&) = delete;

  host::ring_network& net() { return *net_; }
  bool ok() const { return net_ != nullptr; }
  const std::vector<host::network_event>& events() const { return events_; }

  /// The events of one kind, their texts.
  std::vector<std::string> texts(host::event_kind kind) const {
    std::vector<std::string> out;
    for (const auto& e : events_) {
      if (e.kind == kind) out.push_back(e.text);
    }
    return out;
  }
  /// True if an event of `kind` has `part` in its text.
  bool saw(host::event_kind kind, const std::string& part) const {
    for (const auto& e : events_) {
      if (e.kind == kind && e.text.find(part) != std::string::npos) return true;
    }
    return false;
  }
  void keys(const std::string& script) {
    std::string error;
    EXPECT_TRUE(net_->set_keys(script, error)) << error;
  }

 private:
  std::unique_ptr<host::ring_network> net_;
  std::vector<host::network_event> events_;
};

/// A VR of a report, 0 if it is not listed (the report lists every VR that is not 0).
inline double vr_of(const host::node_report& r, std::size_t vr) {
  for (const auto& [n, value] : r.vrs) {
    if (n == vr) return value;
  }
  return 0;
}

/// A named variable of a report, or NaN if the program has none of that name.
inline double variable_of(const host::node_report& r, const std::string& name) {
  for (const auto& [n, value] : r.variables) {
    if (n == name) return value;
  }
  return std::nan("");
}

/// An axis parameter the program set to other than its default (0 if it did not).
inline double parameter_of(const host::node_report& r, const std::string& name, std::size_t axis = 0) {
  for (const host::axis_report& a : r.axes) {
    if (a.axis != axis) continue;
    for (const auto& [n, value] : a.parameters) {
      if (n == name) return value;
    }
  }
  return 0;
}

}  // namespace trionet::test
