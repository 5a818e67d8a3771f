// The built-in networks and the JSON summary of a run: see simulation.hpp.
#include "simulation.hpp"

#include <cmath>
#include <string>

#include "basic/number_format.hpp"
#include "trionet/host/text.hpp"

namespace trionet::host {
namespace {

const builtin_network builtins[] = {
    {"example1", "the manual's Example 1: one Motion Coordinator and two keypads",
     {"mc:examples/manual/example1.bas", "keypad", "keypad"},
     "wait=200 1:1 2:2 1:5 2:up 1:up 2:up 1:down"},
    {"example2", "the manual's Example 2: two Motion Coordinators and one keypad",
     {"mc:examples/manual/example2_three_axis.bas", "mc:examples/manual/example2_two_axis.bas", "keypad"},
     "wait=1000 1:up 1:up 1:up 1:y 1:up 1:up 1:y 1:start"},
    {"example3", "the manual's warning: a second MC prints through the keypad before it is in network mode",
     {"mc:examples/keypad_order/master.bas", "mc:examples/keypad_order/feeder.bas", "keypad"},
     ""},
    {"example3-fixed", "the same ring with the feeder waiting for the master's handshake",
     {"mc:examples/keypad_order/master_fixed.bas", "mc:examples/keypad_order/feeder_fixed.bas", "keypad"},
     ""},
};

std::string json_number(double v) {
  return std::isfinite(v) ? basic::format_value(v) : "null";
}

std::string numbers_json(const std::vector<std::size_t>& numbers) {
  std::string out = "[";
  for (std::size_t k = 0; k < numbers.size(); ++k) out += (k ? "," : "") + std::to_string(numbers[k]);
  return out + "]";
}

}  // namespace

span<const builtin_network> builtin_networks() noexcept {
  return span<const builtin_network>(builtins, sizeof builtins / sizeof builtins[0]);
}

const builtin_network* find_builtin_network(std::string_view name) noexcept {
  for (const builtin_network& b : builtin_networks()) {
    if (name == b.name) return &b;
  }
  return nullptr;
}

std::string summary_json(const ring_network& net, run_end end) {
  std::string out = "{\"byte_times\":" + std::to_string(net.now()) + ",\"seconds\":" + json_number(net.seconds()) +
                    ",\"end\":\"" + to_string(end) + "\",\"nodes\":[";
  for (std::size_t i = 1; i <= net.size(); ++i) {
    const node_report r = net.report(i);
    if (i > 1) out += ',';
    out += "{\"node\":" + std::to_string(i);
    if (r.what == node_spec::kind::keypad) {
      out += ",\"kind\":\"keypad\",\"keypad\":" + std::to_string(r.keypad_number) +
             ",\"network_mode\":" + (r.network_mode ? "true" : "false") + ",\"offset\":" + std::to_string(r.offset) +
             ",\"display\":[" + json_string(r.display[0]) + "," + json_string(r.display[1]) +
             "],\"dropped\":" + std::to_string(r.dropped) + ",\"keys_lost\":" + std::to_string(r.keys_lost) + "}";
      continue;
    }
    const bool has_program = r.state != "none";
    out += ",\"kind\":\"mc\",\"program\":" + (has_program ? json_string(r.program) : std::string("null"));
    out += ",\"state\":" + json_string(r.state);
    out += ",\"ended\":" + std::string(r.state == "running" || r.state == "waiting" ? "false" : "true");
    out += ",\"line\":" + (has_program ? std::to_string(r.line) : std::string("null"));
    out += ",\"error\":" + (r.error.empty() ? std::string("null") : json_string(r.error));
    out += ",\"netstat\":" + std::to_string(r.netstat) + ",\"wdog\":" + (r.wdog ? "true" : "false") + ",\"vr\":{";
    for (std::size_t k = 0; k < r.vrs.size(); ++k) {
      out += (k ? ",\"" : "\"") + std::to_string(r.vrs[k].first) + "\":" + json_number(r.vrs[k].second);
    }
    out += "},\"table\":{";
    for (std::size_t k = 0; k < r.table.size(); ++k) {
      out += (k ? ",\"" : "\"") + std::to_string(r.table[k].first) + "\":" + json_number(r.table[k].second);
    }
    out += "},\"variables\":{";
    for (std::size_t k = 0; k < r.variables.size(); ++k) {
      out += (k ? "," : "") + json_string(r.variables[k].first) + ":" + json_number(r.variables[k].second);
    }
    out += "},\"inputs_on\":" + numbers_json(r.inputs_on) + ",\"outputs_on\":" + numbers_json(r.outputs_on);
    out += ",\"axes\":[";
    for (std::size_t k = 0; k < r.axes.size(); ++k) {
      const axis_report& a = r.axes[k];
      out += (k ? ",{" : "{") + std::string("\"axis\":") + std::to_string(a.axis) + ",\"dpos\":" + json_number(a.dpos) +
             ",\"mpos\":" + json_number(a.mpos) + ",\"idle\":" + (a.idle ? "true" : "false") +
             ",\"mtype\":" + std::to_string(a.mtype) + ",\"vp_speed\":" + json_number(a.speed) + ",\"parameters\":{";
      for (std::size_t p = 0; p < a.parameters.size(); ++p) {
        out += (p ? "," : "") + json_string(a.parameters[p].first) + ":" + json_number(a.parameters[p].second);
      }
      out += "}}";
    }
    out += "]}";
  }
  return out + "]}";
}

}  // namespace trionet::host
