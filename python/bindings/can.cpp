// trionet._trionet.can: the TN20-17 identifier scheme, the VR message codec and the VR-exchange node
// (include/trionet/can/). The node's port is a Python callable (python/trionet/can.py gives it a python-can
// bus), so the library's node decides what is sent and counts it.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <utility>

#include "common.hpp"
#include "trionet/can/frame.hpp"
#include "trionet/can/identifiers.hpp"
#include "trionet/can/node.hpp"
#include "trionet/can/port.hpp"
#include "trionet/can/vr_codec.hpp"
#include "trionet/q32.hpp"

namespace trionet::python {
namespace {

std::uint8_t narrow(unsigned value) {
  return static_cast<std::uint8_t>(value > 255 ? 255 : value);
}

can::byte_order order_of(unsigned order) {
  if (order > static_cast<unsigned>(can::byte_order::little_endian))
    throw py::value_error("no such byte order");
  return static_cast<can::byte_order>(order);
}

py::tuple identifier(const can::identifier_result& r) {
  return py::make_tuple(static_cast<unsigned>(r.status), r.identifier);
}

// A frame from its parts, as a bus or a log gave them (python/trionet/can.py has already put the identifier in
// 0..2^32 - 1, the DLC in 0..15 and the data in at most 8 bytes). Nothing is cut or made up:
// - an identifier with bits beyond its format (11 bits, or 29 when extended; the tool's bad_identifier) is
//   not masked into another node's identifier: the frame gets the extended and remote flags, which no node
//   listens on (a node counts it as foreign);
// - a data frame whose DLC promises more bytes than the data holds gets the DLC of the data it has (so a
//   short frame is bad_dlc, as the tool says of 028#01), never zero-filled.
can::frame frame_of(std::uint32_t id, bool extended, bool remote, unsigned dlc, const byte_view data) {
  can::frame f;
  const std::uint32_t mask = extended ? can::frame::extended_mask : can::frame::standard_mask;
  if (id > mask) {
    f.id = can::frame::extended_flag | can::frame::remote_flag;
  } else {
    f.id = id | (extended ? can::frame::extended_flag : 0U) | (remote ? can::frame::remote_flag : 0U);
  }
  if (dlc > 15) dlc = 15;
  const std::size_t given = data.size() < 8 ? data.size() : 8;
  if (!remote && (dlc < 8 ? dlc : 8U) > given) dlc = static_cast<unsigned>(given);
  f.dlc = static_cast<std::uint8_t>(dlc);
  for (std::size_t i = 0; i < given; ++i) f.data[i] = data[i];
  return f;
}

// (status, vr, negative, integer_part, fraction, value)
py::tuple decoded(const can::decode_result& r) {
  const can::vr_value& v = r.message.value;
  return py::make_tuple(static_cast<unsigned>(r.status), r.message.vr, v.negative, v.integer_part, v.fraction,
                        r ? to_double(v) : 0.0);
}

// A port that hands each frame to a Python callable (identifier, data): what it raises is kept and the
// frame counted as failed.
class python_port final : public can::port {
 public:
  explicit python_port(py::object send) : send_(std::move(send)) {}
  can::transmit_status send(const can::frame& outgoing) noexcept override {
    try {
      send_(outgoing.identifier(), to_bytes(outgoing.data, outgoing.data_length()));
      return can::transmit_status::ok;
    } catch (py::error_already_set& e) {
      if (!pending_) pending_ = std::move(e);
      return can::transmit_status::failed;
    } catch (...) {
      return can::transmit_status::failed;
    }
  }
  void raise_pending() {
    if (!pending_) return;
    py::error_already_set e = std::move(*pending_);
    pending_.reset();
    throw e;
  }

 private:
  py::object send_;
  std::optional<py::error_already_set> pending_;
};

class exchange_node {
 public:
  exchange_node(can::node_address address, py::object send, std::shared_ptr<vr_values> vr,
                can::byte_order order)
      : port_(std::move(send)), vr_(std::move(vr)), node_(address, port_, *vr_, order) {}

  unsigned send_to_node(unsigned destination, unsigned vr, double value) {
    if (vr > 255) return static_cast<unsigned>(can::send_status::vr_out_of_range);
    const can::send_status s = node_.send_to_node(narrow(destination), static_cast<std::uint16_t>(vr), value);
    if (s == can::send_status::port_failed) port_.raise_pending();
    return static_cast<unsigned>(s);
  }

  // (status, sender, receive_channel, vr, value)
  py::tuple receive(std::uint32_t id, bool extended, bool remote, unsigned dlc, py::handle data) {
    const byte_input input(data);
    const can::receive_result r = node_.receive(frame_of(id, extended, remote, dlc, input.view()));
    vr_->raise_pending();
    return py::make_tuple(static_cast<unsigned>(r.status), r.sender, r.receive_channel, r.message.vr,
                          to_double(r.message.value));
  }

  py::dict counters() const {
    const can::node_counters c = node_.counters();
    py::dict d;
    d["sent"] = c.sent;
    d["send_busy"] = c.send_busy;
    d["send_failed"] = c.send_failed;
    d["written"] = c.written;
    d["refused"] = c.refused;
    d["out_of_range"] = c.out_of_range;
    d["value_out_of_range"] = c.value_out_of_range;
    d["foreign"] = c.foreign;
    d["bad_dlc"] = c.bad_dlc;
    d["bad_sign"] = c.bad_sign;
    d["bad_fraction"] = c.bad_fraction;
    return d;
  }
  void clear_counters() { node_.clear_counters(); }
  const std::shared_ptr<vr_values>& vr() const { return vr_; }

 private:
  python_port port_;
  std::shared_ptr<vr_values> vr_;
  can::vr_exchange_node node_;
};

}  // namespace

void bind_can(py::module_& m) {
  py::dict enums;
  enums["SchemeStatus"] = enum_members<can::scheme_status>();
  enums["EncodeStatus"] = enum_members<can::encode_status>();
  enums["DecodeStatus"] = enum_members<can::decode_status>();
  enums["ByteOrder"] = enum_members<can::byte_order>();
  enums["SendStatus"] = enum_members<can::send_status>();
  enums["ReceiveStatus"] = enum_members<can::receive_status>();
  m.attr("enums") = enums;
  m.attr("MIN_NODE_COUNT") = can::min_node_count;
  m.attr("MAX_NODE_COUNT") = can::max_node_count;
  m.attr("DEFAULT_NODE_COUNT") = can::default_node_count;
  m.attr("MAX_MESSAGE_VR") = can::max_message_vr;

  // ---- identifiers: (status, value) ----
  m.def("base_identifier",
        [](unsigned n, unsigned node) { return identifier(can::base_identifier(narrow(n), narrow(node))); });
  m.def("receive_identifier", [](unsigned n, unsigned node, unsigned channel) {
    return identifier(can::receive_identifier(narrow(n), narrow(node), narrow(channel)));
  });
  m.def("exchange_identifier", [](unsigned n, unsigned sender, unsigned receiver) {
    return identifier(can::exchange_identifier(narrow(n), narrow(sender), narrow(receiver)));
  });
  m.def("transmit_identifier", [](unsigned n, unsigned sender, unsigned channel) {
    return identifier(can::transmit_identifier(narrow(n), narrow(sender), narrow(channel)));
  });
  m.def("route_of", [](unsigned n, std::uint32_t id) {
    const can::route_result r = can::route_of(narrow(n), id);
    return py::make_tuple(static_cast<unsigned>(r.status), r.value.sender, r.value.receiver,
                          r.value.receive_channel);
  });
  m.def("destination_of", [](unsigned n, unsigned sender, unsigned channel) {
    const can::node_result r = can::destination_of(narrow(n), narrow(sender), narrow(channel));
    return py::make_tuple(static_cast<unsigned>(r.status), r.node);
  });
  m.def("transmit_channel_to", [](unsigned n, unsigned sender, unsigned destination) {
    const can::channel_result r = can::transmit_channel_to(narrow(n), narrow(sender), narrow(destination));
    return py::make_tuple(static_cast<unsigned>(r.status), r.channel);
  });

  // ---- codec ----
  m.def("encode_vr", [](unsigned vr, double value, unsigned order) {
    std::uint8_t out[can::vr_message_size] = {};
    if (vr > 0xFFFF)
      return py::make_tuple(static_cast<unsigned>(can::encode_status::vr_out_of_range), py::none());
    const can::encode_status s = can::encode_vr(static_cast<std::uint16_t>(vr), value, out, order_of(order));
    if (s != can::encode_status::ok) return py::make_tuple(static_cast<unsigned>(s), py::none());
    return py::make_tuple(static_cast<unsigned>(s), to_bytes(out, sizeof out));
  });
  m.def("decode_vr_message", [](py::handle data, unsigned order) {
    const byte_input input(data);
    return decoded(can::decode_vr_message(input.view(), order_of(order)));
  });
  m.def("decode_vr_frame", [](std::uint32_t id, bool extended, bool remote, unsigned dlc, py::handle data,
                              unsigned order) {
    const byte_input input(data);
    return decoded(can::decode_vr_frame(frame_of(id, extended, remote, dlc, input.view()), order_of(order)));
  });

  // ---- node ----
  py::class_<exchange_node>(m, "VrExchangeNode")
      .def(py::init([](unsigned node_count, unsigned node, py::object send, std::shared_ptr<vr_values> vr,
                       unsigned order) {
        const can::address_result a = can::make_node_address(narrow(node_count), narrow(node));
        if (!vr) throw py::type_error("a VrExchangeNode needs a VR table (VrValues), not None");
        if (!a) throw py::value_error(can::to_string(a.status));
        return std::make_unique<exchange_node>(a.address, std::move(send), std::move(vr), order_of(order));
      }))
      .def("send_to_node", &exchange_node::send_to_node)
      .def("receive", &exchange_node::receive)
      .def("counters", &exchange_node::counters)
      .def("clear_counters", &exchange_node::clear_counters)
      .def_property_readonly("vr", &exchange_node::vr);
}

}  // namespace trionet::python
