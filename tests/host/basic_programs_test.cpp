// Programs shaped like real controller programs (tests/basic/programs/*.bas), each run on its simulated ring
// and compared with what the manual's rules give (the .expected file beside it, with the reasoning in its
// '#' comment lines).
//
// A program says how it runs in comment lines at its top:
//   '@ ring: this mc:other.bas keypad mc     the nodes in ring order ("this" is the program itself)
//   '@ keys: wait=500 1:up node1:in3=on      the key and input script (docs/basic.md)
//   '@ byte-times: N                          the limit (default 2000000)
//   '@ servo-period: US                       every controller's SERVO_PERIOD (default 1000)
// The run's record is every event that is not trace-only ("node N: text"), then each keypad's display
// ("node N: display |line 1|line 2|") and how the run ended ("end: settled" or "end: limit"); a program that
// does not compile gives "refused: FILE:LINE:COLUMN: message".
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "ring_network.hpp"

namespace host = trionet::host;
namespace fs = std::filesystem;

namespace {

// From the source tree CMake names (a relative __FILE__, as Ninja gives, would not resolve where CTest runs).
fs::path programs_directory() { return fs::path(TRIONET_SOURCE_DIR) / "tests" / "basic" / "programs"; }

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::vector<std::string> lines_of(const std::string& text, bool skip_comments) {
  std::vector<std::string> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (skip_comments && (line.empty() || line[0] == '#')) continue;
    out.push_back(line);
  }
  return out;
}

// The value of "'@ key: value" in the program, or "".
std::string directive(const std::string& program, const std::string& key) {
  for (const std::string& line : lines_of(program, false)) {
    const std::string head = "'@ " + key + ":";
    if (line.compare(0, head.size(), head) == 0) {
      const std::size_t start = line.find_first_not_of(' ', head.size());
      return start == std::string::npos ? "" : line.substr(start);
    }
  }
  return "";
}

std::vector<std::string> run(const fs::path& file) {
  const std::string program = read_file(file);
  std::vector<host::node_spec> nodes;
  std::istringstream ring(directive(program, "ring"));
  std::string word;
  while (ring >> word) {
    host::node_spec node;
    if (word == "keypad") {
      node.what = host::node_spec::kind::keypad;
    } else if (word == "this") {
      node.program_name = file.filename().string();
      node.program_text = program;
    } else if (word.compare(0, 3, "mc:") == 0) {
      node.program_name = word.substr(3);
      node.program_text = read_file(file.parent_path() / node.program_name);
    }
    nodes.push_back(node);
  }
  host::network_config config;
  if (const std::string period = directive(program, "servo-period"); !period.empty()) {
    config.servo_period_us = std::stod(period);
  }
  std::string error;
  auto net = host::ring_network::build(nodes, config, error);
  if (!net) return {"refused: " + error};
  if (!net->set_keys(directive(program, "keys"), error)) return {"bad key script: " + error};
  std::vector<std::string> record;
  net->on_event([&record](const host::network_event& e) {
    if (e.kind == host::event_kind::message || e.kind == host::event_kind::frame_error ||
        e.kind == host::event_kind::display || e.kind == host::event_kind::motion) {
      return;
    }
    record.push_back("node " + std::to_string(e.node) + ": " + e.text);
  });
  const std::string limit = directive(program, "byte-times");
  const host::run_end end = net->run(limit.empty() ? 2000000 : std::stoull(limit));
  for (std::size_t i = 1; i <= net->size(); ++i) {
    const host::node_report r = net->report(i);
    if (r.what == host::node_spec::kind::keypad) {
      record.push_back("node " + std::to_string(i) + ": display |" + r.display[0] + "|" + r.display[1] + "|");
    }
  }
  record.push_back(std::string("end: ") + host::to_string(end));
  return record;
}

std::vector<fs::path> programs_with_results() {
  std::vector<fs::path> out;
  for (const auto& entry : fs::directory_iterator(programs_directory())) {
    if (entry.path().extension() == ".bas" && fs::exists(fs::path(entry.path()).replace_extension(".expected"))) {
      out.push_back(entry.path());
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST(BasicPrograms, ThereAreAtLeastTenProgramsWithTheirResults) {
  EXPECT_GE(programs_with_results().size(), 10u) << programs_directory();
}

TEST(BasicPrograms, EachGivesTheResultTheManualsRulesGive) {
  for (const fs::path& file : programs_with_results()) {
    SCOPED_TRACE(file.filename().string());
    const std::vector<std::string> expected =
        lines_of(read_file(fs::path(file).replace_extension(".expected")), true);
    const std::vector<std::string> actual = run(file);
    EXPECT_EQ(actual, expected);
    // The same program, options and script give the same run.
    EXPECT_EQ(run(file), actual);
  }
}
