// trionet._trionet.ring: the ring's encoders, Q32.32, the Motion Coordinator and keypad nodes, and the
// simulator (include/trionet/ring/). Statuses come back as numbers; python/trionet/ring.py makes them
// IntEnums and exceptions.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common.hpp"
#include "learn/profile.hpp"
#include "trionet/q32.hpp"
#include "trionet/ring/bytes.hpp"
#include "trionet/ring/crc.hpp"
#include "trionet/ring/decoder.hpp"
#include "trionet/ring/encode.hpp"
#include "trionet/ring/keypad.hpp"
#include "trionet/ring/motion_coordinator.hpp"
#include "trionet/ring/simulator.hpp"
#include "trionet/ring/variable_layout.hpp"

namespace trionet::python {
namespace {

// (status, frame bytes or None)
py::tuple encoded(const ring::encode_result& r, const std::uint8_t* frame) {
  if (!r) return py::make_tuple(static_cast<unsigned>(r.status), py::none());
  return py::make_tuple(static_cast<unsigned>(r.status), to_bytes(frame, r.length));
}

// Encodes `m` with the profile's CRC and variable layout (the library's defaults without a profile).
py::tuple encode_message(const ring::message& m, const py::object& profile) {
  std::uint8_t frame[ring::framing_length + ring::default_max_characters];
  if (m.type == ring::message_type::character && m.text.size() > ring::default_max_characters) {
    // Longer than a decoder accepts: encoded all the same when asked (the encoder has no limit of its own).
    std::vector<std::uint8_t> big(ring::framing_length + m.text.size());
    return encoded(ring::encode(byte_buffer(big.data(), big.size()), m), big.data());
  }
  if (profile.is_none()) return encoded(ring::encode(frame, m), frame);
  const learn::ring_profile& p = profile.cast<const learn::profile&>().ring;
  const ring::crc16_runtime crc(p.crc);
  return ring::with_variable_layout(p.layout, [&](auto layout) {
    return encoded(ring::encode<ring::crc16_runtime, decltype(layout)>(frame, m, crc), frame);
  });
}

// Counters as dicts, with the C++ field names.
py::dict counters_of(const ring::motion_coordinator_counters& c) {
  py::dict d;
  d["frame_errors"] = c.frame_errors;
  d["crc_errors"] = c.crc_errors;
  d["character_messages"] = c.character_messages;
  d["receive_overflows"] = c.receive_overflows;
  d["variables_written"] = c.variables_written;
  d["variables_refused"] = c.variables_refused;
  d["variables_out_of_range"] = c.variables_out_of_range;
  d["variables_value_out_of_range"] = c.variables_value_out_of_range;
  d["keypad_messages_ignored"] = c.keypad_messages_ignored;
  d["sends_refused"] = c.sends_refused;
  return d;
}

py::dict counters_of(const ring::keypad_counters& c) {
  py::dict d;
  d["frame_errors"] = c.frame_errors;
  d["crc_errors"] = c.crc_errors;
  d["dropped_in_local_mode"] = c.dropped_in_local_mode;
  d["display_messages"] = c.display_messages;
  d["variables_ignored"] = c.variables_ignored;
  d["keys_sent"] = c.keys_sent;
  d["keys_lost"] = c.keys_lost;
  return d;
}

py::dict counters_of(const ring::link_counters& c) {
  py::dict d;
  d["forwards_lost"] = c.forwards_lost;
  d["forwards_cut"] = c.forwards_cut;
  d["forwards_ended_idle"] = c.forwards_ended_idle;
  d["messages_forwarded"] = c.messages_forwarded;
  d["messages_dropped"] = c.messages_dropped;
  d["messages_sent"] = c.messages_sent;
  return d;
}

// What every ring node offers Python: the byte port (bytes in, bytes out) and the ring's NETSTAT.
class ring_node {
 public:
  virtual ~ring_node() = default;
  virtual byte_port& port() noexcept = 0;
  // Exceptions a VR write policy raised while the node was fed (none for a keypad).
  virtual void raise_pending() {}

  void receive(py::handle data) {
    const byte_input input(data);
    byte_port& p = port();
    for (const std::uint8_t byte : input.view()) p.receive(byte);
    raise_pending();
  }
  py::bytes transmit(std::size_t limit) {
    std::string out;
    std::uint8_t byte = 0;
    byte_port& p = port();
    while (out.size() < limit && p.transmit(byte)) out.push_back(static_cast<char>(byte));
    return py::bytes(out);
  }
  void line_idle() {
    port().line_idle();
    raise_pending();
  }
  bool transmit_pending() { return port().transmit_pending(); }
  bool in_message() { return port().in_message(); }
};

class motion_coordinator_node final : public ring_node {
 public:
  explicit motion_coordinator_node(std::shared_ptr<vr_values> vr) : vr_(std::move(vr)), node_(*vr_) {}
  byte_port& port() noexcept override { return node_; }
  void raise_pending() override { vr_->raise_pending(); }
  ring::motion_coordinator<>& node() noexcept { return node_; }
  const std::shared_ptr<vr_values>& vr() const noexcept { return vr_; }

 private:
  std::shared_ptr<vr_values> vr_;  // before the node, which holds a reference to it
  ring::motion_coordinator<> node_;
};

class keypad_node final : public ring_node {
 public:
  byte_port& port() noexcept override { return node_; }
  ring::keypad<>& node() noexcept { return node_; }

 private:
  ring::keypad<> node_;
};

class simulator {
 public:
  explicit simulator(std::uint32_t idle_byte_times) : ring_(idle_byte_times) {}

  bool add(ring_node& node) {
    if (!ring_.add(node.port())) return false;
    nodes_.push_back(&node);
    return true;
  }

  // Runs `byte_times` steps; `trace(time, link, sent, received, delivered)` for every byte if not None.
  void run(std::uint64_t byte_times, const py::object& trace) {
    if (trace.is_none()) {
      for (std::uint64_t t = 0; t < byte_times; ++t) {
        ring_.step();
        raise_pending();
      }
      return;
    }
    for (std::uint64_t t = 0; t < byte_times; ++t) {
      // The step is finished whatever the trace does; its first exception is raised after it.
      std::optional<py::error_already_set> failed;
      ring_.step([&](const ring::link_byte& b) {
        if (failed) return;
        try {
          trace(b.time, b.link, b.sent, b.received, b.delivered);
        } catch (py::error_already_set& e) {
          failed = std::move(e);
        }
      });
      raise_pending();
      if (failed) throw std::move(*failed);
    }
  }

  ring::simulator<>& ring() noexcept { return ring_; }

 private:
  void raise_pending() {
    for (ring_node* node : nodes_) node->raise_pending();
  }

  ring::simulator<> ring_;
  std::vector<ring_node*> nodes_;  // kept alive by the Python objects (keep_alive on add)
};

}  // namespace

void bind_ring(py::module_& m) {
  py::dict enums;
  enums["MessageType"] = enum_members<ring::message_type>();
  enums["EncodeStatus"] = enum_members<ring::encode_status>();
  enums["DecodeStatus"] = enum_members<ring::decode_status>();
  enums["FrameError"] = enum_members<ring::frame_error>();
  enums["SendStatus"] = enum_members<ring::send_status>();
  enums["GetStatus"] = enum_members<ring::get_status>();
  enums["KeyStatus"] = enum_members<ring::key_status>();
  enums["Key"] = enum_members<ring::key>();
  enums["VrWriteStatus"] = enum_members<vr_write_status>();
  enums["Q32Status"] = enum_members<q32_status>();
  m.attr("enums") = enums;

  m.attr("MIN_HOPS") = ring::min_hops;
  m.attr("MAX_HOPS") = ring::max_hops;
  m.attr("MAX_VR") = ring::max_vr;
  m.attr("MAX_CHARACTERS") = ring::default_max_characters;
  m.attr("FIRST_BASIC_ADDRESS") = ring::first_basic_address;
  m.attr("LAST_BASIC_ADDRESS") = ring::last_basic_address;

  // ---- encoders: (status, bytes or None) ----
  m.def("encode_characters", [](unsigned hops, py::handle text, py::object profile) {
    const byte_input input(text);
    if (hops > 255)
      return py::make_tuple(static_cast<unsigned>(ring::encode_status::hops_out_of_range), py::none());
    return encode_message(ring::message::characters(static_cast<std::uint8_t>(hops), input.view()), profile);
  });
  m.def("encode_variable", [](unsigned hops, unsigned vr, std::int64_t raw, py::object profile) {
    if (hops > 255)
      return py::make_tuple(static_cast<unsigned>(ring::encode_status::hops_out_of_range), py::none());
    if (vr > ring::max_vr)
      return py::make_tuple(static_cast<unsigned>(ring::encode_status::vr_out_of_range), py::none());
    return encode_message(
        ring::message::variable(static_cast<std::uint8_t>(hops), static_cast<std::uint16_t>(vr), raw),
        profile);
  });
  m.def("encode_keypad_offset", [](unsigned hops, unsigned offset) {
    if (hops > 255)
      return py::make_tuple(static_cast<unsigned>(ring::encode_status::hops_out_of_range), py::none());
    if (offset > 255)
      return py::make_tuple(static_cast<unsigned>(ring::encode_status::offset_out_of_range), py::none());
    return encode_message(
        ring::message::keypad_offset(static_cast<std::uint8_t>(hops), static_cast<std::uint8_t>(offset)),
        py::none());
  });
  m.def("encode_keypad_mode", [](unsigned hops, unsigned mode) {
    if (hops > 255)
      return py::make_tuple(static_cast<unsigned>(ring::encode_status::hops_out_of_range), py::none());
    if (mode > 255)
      return py::make_tuple(static_cast<unsigned>(ring::encode_status::mode_out_of_range), py::none());
    return encode_message(
        ring::message::keypad_mode(static_cast<std::uint8_t>(hops), static_cast<std::uint8_t>(mode)),
        py::none());
  });

  // ---- Q32.32 ----
  m.def("q32_from_double", [](double value) {
    const q32_result r = q32_from_double(value);
    return py::make_tuple(static_cast<unsigned>(r.status), r.raw);
  });
  m.def("q32_to_double", [](std::int64_t raw) { return q32_to_double(raw); });

  // ---- VR() ----
  py::class_<vr_values, std::shared_ptr<vr_values>>(m, "VrValues", py::buffer_protocol())
      .def(py::init<std::size_t>())
      .def_buffer([](vr_values& v) {
        return py::buffer_info(v.values().data(), static_cast<py::ssize_t>(sizeof(double)),
                               py::format_descriptor<double>::format(), 1,
                               {static_cast<py::ssize_t>(v.values().size())},
                               {static_cast<py::ssize_t>(sizeof(double))});
      })
      .def("__len__", [](vr_values& v) { return v.values().size(); })
      .def("get", [](vr_values& v, std::size_t vr) { return v.values().at(vr); })
      .def("set", [](vr_values& v, std::size_t vr, double value) { v.values().at(vr) = value; })
      .def("write",
           [](vr_values& v, unsigned vr, double value) {
             const q32_result q = q32_from_double(value);
             if (!q) return static_cast<unsigned>(vr_write_status::value_out_of_range);
             const vr_write_status s =
                 v.write(static_cast<std::uint16_t>(vr > 65535 ? 65535 : vr), network_value::from_q32(q.raw));
             v.raise_pending();
             return static_cast<unsigned>(s);
           })
      .def_property("policy", &vr_values::policy, &vr_values::set_policy);

  // ---- nodes ----
  py::class_<ring_node>(m, "RingNode")
      .def("receive", &ring_node::receive, py::arg("data"))
      .def("transmit", &ring_node::transmit, py::arg("limit"))
      .def("line_idle", &ring_node::line_idle)
      .def_property_readonly("transmit_pending", &ring_node::transmit_pending)
      .def_property_readonly("in_message", &ring_node::in_message);

  py::class_<motion_coordinator_node, ring_node>(m, "MotionCoordinator")
      .def(py::init([](std::shared_ptr<vr_values> vr) {
        if (!vr) throw py::type_error("a MotionCoordinator needs a VR table (VrValues), not None");
        return std::make_unique<motion_coordinator_node>(std::move(vr));
      }))
      .def_property_readonly("vr", &motion_coordinator_node::vr)
      .def("print",
           [](motion_coordinator_node& n, int address, py::handle text) {
             const byte_input input(text);
             const ring::print_result r = n.node().print(address, input.view());
             return py::make_tuple(static_cast<unsigned>(r.status), r.queued);
           })
      .def("send_variable",
           [](motion_coordinator_node& n, int address, unsigned vr, double value) {
             if (vr > ring::max_vr) return static_cast<unsigned>(ring::send_status::vr_out_of_range);
             return static_cast<unsigned>(
                 n.node().send_variable(address, static_cast<std::uint16_t>(vr), value));
           })
      .def("send_keypad_offset",
           [](motion_coordinator_node& n, int address, int offset) {
             return static_cast<unsigned>(n.node().send_keypad_offset(address, offset));
           })
      .def("send_keypad_mode",
           [](motion_coordinator_node& n, int address, int mode) {
             return static_cast<unsigned>(n.node().send_keypad_mode(address, mode));
           })
      .def("key", [](motion_coordinator_node& n, int channel) { return n.node().key(channel); })
      .def("get",
           [](motion_coordinator_node& n, int channel) {
             const ring::get_result r = n.node().get(channel);
             return py::make_tuple(static_cast<unsigned>(r.status), r.value);
           })
      .def_property_readonly("characters_waiting",
                             [](motion_coordinator_node& n) { return n.node().characters_waiting(); })
      .def_property_readonly("netstat", [](motion_coordinator_node& n) { return n.node().netstat(); })
      .def("clear_netstat", [](motion_coordinator_node& n) { n.node().clear_netstat(); })
      .def_property_readonly("transmit_free",
                             [](motion_coordinator_node& n) { return n.node().transmit_free(); })
      .def("counters", [](motion_coordinator_node& n) { return counters_of(n.node().counters()); })
      .def("clear_counters", [](motion_coordinator_node& n) { n.node().clear_counters(); })
      .def("forwarding_counters",
           [](motion_coordinator_node& n) { return counters_of(n.node().forwarding_counters()); });

  py::class_<keypad_node, ring_node>(m, "Keypad")
      .def(py::init<>())
      .def("press",
           [](keypad_node& n, unsigned k) {
             if (k >= ring::key_count) throw py::value_error("no such key");
             return static_cast<unsigned>(n.node().press(static_cast<ring::key>(k)));
           })
      .def("release",
           [](keypad_node& n, unsigned k) {
             if (k >= ring::key_count) throw py::value_error("no such key");
             return static_cast<unsigned>(n.node().release(static_cast<ring::key>(k)));
           })
      .def_property_readonly("network_mode", [](keypad_node& n) { return n.node().network_mode(); })
      .def_property_readonly("offset", [](keypad_node& n) { return n.node().offset(); })
      .def_property_readonly("mode", [](keypad_node& n) { return n.node().mode(); })
      .def_property_readonly("display",
                             [](keypad_node& n) {
                               const ring::keypad_display& d = n.node().display();
                               return py::make_tuple(std::string(d.line(0)), std::string(d.line(1)));
                             })
      .def_property_readonly("cursor", [](keypad_node& n) { return n.node().display().cursor(); })
      .def_property_readonly("cursor_visible",
                             [](keypad_node& n) { return n.node().display().cursor_visible(); })
      .def_property_readonly("netstat", [](keypad_node& n) { return n.node().netstat(); })
      .def("clear_netstat", [](keypad_node& n) { n.node().clear_netstat(); })
      .def("counters", [](keypad_node& n) { return counters_of(n.node().counters()); })
      .def("clear_counters", [](keypad_node& n) { n.node().clear_counters(); })
      .def("forwarding_counters", [](keypad_node& n) { return counters_of(n.node().forwarding_counters()); });

  py::class_<simulator>(m, "Simulator")
      .def(py::init<std::uint32_t>())
      .def("add", &simulator::add, py::keep_alive<1, 2>())
      .def("run", &simulator::run)
      .def_property_readonly("size", [](simulator& s) { return s.ring().size(); })
      .def_property_readonly("now", [](simulator& s) { return s.ring().now(); })
      .def_property_readonly("bytes_delivered", [](simulator& s) { return s.ring().bytes_delivered(); })
      .def_property_readonly("idle_byte_times", [](simulator& s) { return s.ring().idle_byte_times(); })
      .def_property_readonly("quiet", [](simulator& s) { return s.ring().quiet(); })
      .def("drop_next", [](simulator& s, std::size_t link) { s.ring().drop_next(link); })
      .def("flip_next",
           [](simulator& s, std::size_t link, std::uint8_t mask) { s.ring().flip_next(link, mask); })
      .def("cut", [](simulator& s, std::size_t link, bool cut) { s.ring().cut(link, cut); });
}

}  // namespace trionet::python
