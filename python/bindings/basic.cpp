// trionet._trionet.basic: a ring of Motion Coordinators running BASIC programs and keypads on the simulated
// ring (src/sim/ring_network.hpp), as `trionet ring simulate` runs it, with the same JSON summary
// (src/sim/simulation.hpp).
#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common.hpp"
#include "embedded_files.hpp"
#include "learn/profile.hpp"
#include "ring_network.hpp"
#include "simulation.hpp"

namespace trionet::python {
namespace {

class network {
 public:
  explicit network(std::unique_ptr<host::ring_network> net) : net_(std::move(net)) {}

  void set_keys(const std::string& script) {
    std::string error;
    if (!net_->set_keys(script, error)) throw py::value_error(error);
  }

  // `sink(kind, time, node, text, display)` for every event; None: no events.
  void on_event(py::object sink) {
    if (sink.is_none()) {
      net_->on_event(nullptr);
      return;
    }
    net_->on_event([this, sink](const host::network_event& e) {
      if (failed_) return;
      try {
        sink(host::to_string(e.kind), e.time, e.node, e.text, e.display);
      } catch (py::error_already_set& error) {
        failed_ = std::move(error);
      }
    });
  }

  void step() {
    net_->step();
    raise_pending();
  }

  // Runs to the end or the limit; the JSON summary line, as `ring simulate --json` prints it. An exception
  // in the event sink stops the events and is raised when the run is over.
  std::string run(std::uint64_t max_byte_times) {
    const host::run_end end = net_->run(max_byte_times);
    raise_pending();
    return host::summary_json(*net_, end);
  }

  std::string summary(bool limit) const {
    return host::summary_json(*net_, limit ? host::run_end::limit : host::run_end::settled);
  }

  void press(std::size_t keypad, const std::string& key) {
    std::string error;
    if (!net_->press(keypad, key, error)) throw py::value_error(error);
  }

  host::ring_network& net() { return *net_; }

 private:
  void raise_pending() {
    if (!failed_) return;
    py::error_already_set e = std::move(*failed_);
    failed_.reset();
    throw e;
  }

  std::unique_ptr<host::ring_network> net_;
  std::optional<py::error_already_set> failed_;
};

}  // namespace

void bind_basic(py::module_& m) {
  // (name, title, [node specs], keys) of every network built into the tool.
  m.def("builtin_networks", [] {
    py::list out;
    for (const host::builtin_network& b : host::builtin_networks()) {
      py::list nodes;
      for (const char* n : b.nodes) nodes.append(n);
      out.append(py::make_tuple(b.name, b.title, nodes, b.keys));
    }
    return out;
  });
  // The text of a file built into the tool (examples/...), or None.
  m.def("builtin_file", [](const std::string& path) -> py::object {
    const host::embedded_file* f = host::find_embedded_file(path);
    if (f == nullptr) return py::none();
    return py::str(std::string(f->text()));
  });

  py::class_<network>(m, "Network")
      .def(py::init([](const std::vector<std::tuple<std::string, std::string, std::string>>& nodes,
                       std::uint32_t statements_per_byte_time, double bit_rate, std::uint64_t key_gap,
                       py::object profile) {
        std::vector<host::node_spec> specs;
        for (const auto& [kind, name, text] : nodes) {
          host::node_spec spec;
          spec.what = kind == "keypad" ? host::node_spec::kind::keypad : host::node_spec::kind::mc;
          spec.program_name = name;
          spec.program_text = text;
          specs.push_back(std::move(spec));
        }
        host::network_config config;
        config.statements_per_byte_time = statements_per_byte_time;
        config.bit_rate = bit_rate;
        config.key_gap = key_gap;
        if (!profile.is_none()) {
          const learn::profile& p = profile.cast<const learn::profile&>();
          config.crc = p.ring.crc;
          config.layout = p.ring.layout;
          config.keypad_codes = p.keypad.codes;
          config.key_off_code = learn::key_off_function(p.keypad.key_off);
          config.defkey = p.keypad.defkey;
          config.display = p.keypad.display;
        }
        std::string error;
        std::unique_ptr<host::ring_network> net = host::ring_network::build(specs, config, error);
        if (!net) throw py::value_error(error);
        return std::make_unique<network>(std::move(net));
      }))
      .def("set_keys", &network::set_keys)
      .def("on_event", &network::on_event)
      .def("step", &network::step)
      .def("run", &network::run)
      .def("summary", &network::summary)
      .def("press", &network::press)
      .def_property_readonly("now", [](network& n) { return n.net().now(); })
      .def_property_readonly("seconds", [](network& n) { return n.net().seconds(); })
      .def_property_readonly("settled", [](network& n) { return n.net().settled(); })
      .def_property_readonly("size", [](network& n) { return n.net().size(); })
      .def_property_readonly("keypads", [](network& n) { return n.net().keypads(); });
}

}  // namespace trionet::python
