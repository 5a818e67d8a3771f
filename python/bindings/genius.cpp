// trionet._trionet.genius: characters and 11-bit words, CRC-6, transmissions (encoder and streaming parser),
// bus-access timing and GE's scan time (include/trionet/genius/).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <string>
#include <vector>

#include "common.hpp"
#include "learn/profile.hpp"
#include "trionet/genius/bus_access.hpp"
#include "trionet/genius/character.hpp"
#include "trionet/genius/crc6.hpp"
#include "trionet/genius/scan_time.hpp"
#include "trionet/genius/transmission.hpp"

namespace trionet::python {
namespace {

// The CRC-6 and control layout of a profile (the library's defaults without one).
struct genius_wire {
  genius::crc6_runtime crc{};
  genius::control_layout layout{};
  explicit genius_wire(const py::object& profile) {
    if (profile.is_none()) return;
    const learn::genius_profile& p = profile.cast<const learn::profile&>().genius;
    crc = genius::crc6_runtime(p.crc);
    layout = p.control;
  }
};

// A transmission's segments from Python: (block, destination, data bytes) tuples. The bytes are copied into
// `storage` (the segments view them).
struct segments_in {
  std::vector<std::vector<std::uint8_t>> storage;
  std::vector<genius::segment> segments;
  explicit segments_in(const py::list& list) {
    storage.reserve(list.size());
    for (const py::handle item : list) {
      const auto t = item.cast<py::tuple>();
      if (t.size() != 3) throw py::value_error("a segment is (block, destination, data)");
      const byte_input data(t[2]);
      storage.emplace_back(data.view().begin(), data.view().end());
      const unsigned destination = t[1].cast<unsigned>();
      segments.push_back(genius::segment{t[0].cast<bool>(),
                                         static_cast<std::uint8_t>(destination > 255 ? 255 : destination),
                                         byte_view(storage.back().data(), storage.back().size())});
    }
  }
};

py::dict timing_dict(const genius::bus_timing& t) {
  py::dict d;
  d["rate"] = static_cast<unsigned>(t.bus_rate);
  d["bit_time_us"] = t.bit_time_us;
  d["skip_us"] = t.skip_us;
  d["propagation_us_per_2000ft"] = t.propagation_us_per_2000ft;
  d["detection_us"] = t.detection_us;
  return d;
}

genius::rate rate_of(unsigned r) {
  if (r > static_cast<unsigned>(genius::rate::baud_38k4)) throw py::value_error("no such rate");
  return static_cast<genius::rate>(r);
}

genius::bus_timing timing_of(const py::dict& d) {
  genius::bus_timing t;
  t.bus_rate = rate_of(d["rate"].cast<unsigned>());
  t.bit_time_us = d["bit_time_us"].cast<double>();
  t.skip_us = d["skip_us"].cast<double>();
  t.propagation_us_per_2000ft = d["propagation_us_per_2000ft"].cast<double>();
  t.detection_us = d["detection_us"].cast<double>();
  return t;
}

// Devices from (sba, position_ft, data_bytes) tuples.
std::vector<genius::device_position> devices_of(const py::list& list) {
  std::vector<genius::device_position> out;
  for (const py::handle item : list) {
    const auto t = item.cast<py::tuple>();
    genius::device_position d;
    const unsigned sba = t[0].cast<unsigned>();
    d.sba = static_cast<std::uint8_t>(sba > 255 ? 255 : sba);
    d.position_ft = t[1].cast<double>();
    const unsigned bytes = t[2].cast<unsigned>();
    d.data_bytes = static_cast<std::uint16_t>(bytes > 65535 ? 65535 : bytes);
    out.push_back(d);
  }
  return out;
}

// A streaming transmission parser with a profile's CRC and layout.
class parser {
 public:
  explicit parser(const py::object& profile)
      : parser_(genius_wire(profile).crc, genius_wire(profile).layout) {}

  // (status, transmission or None): the transmission is (sender, broadcast, destination, [(block,
  // destination, bytes)]).
  py::tuple push(std::uint8_t byte, bool control) {
    const genius::parse_status s = parser_.push(genius::character{byte, control});
    if (s != genius::parse_status::ok) return py::make_tuple(static_cast<unsigned>(s), py::none());
    const genius::transmission& t = parser_.received();
    py::list segments;
    for (const genius::segment& seg : t.segments) {
      segments.append(py::make_tuple(seg.block, seg.destination, to_bytes(seg.data.data(), seg.data.size())));
    }
    return py::make_tuple(static_cast<unsigned>(s),
                          py::make_tuple(t.sender, t.broadcast, t.destination, segments));
  }
  unsigned push_framing_error() { return static_cast<unsigned>(parser_.push_framing_error()); }
  py::dict counts() const {
    py::dict d;
    for (std::size_t i = 0; i < genius::parse_status_count; ++i) {
      const auto s = static_cast<genius::parse_status>(i);
      d[genius::to_string(s)] = parser_.count(s);
    }
    return d;
  }
  std::uint32_t errors() const { return parser_.errors(); }
  bool in_transmission() const { return parser_.in_transmission(); }
  void reset() { parser_.reset(); }
  void clear_counters() { parser_.clear_counters(); }

 private:
  genius::transmission_parser<256, 16, genius::crc6_runtime> parser_;
};

}  // namespace

void bind_genius(py::module_& m) {
  py::dict enums;
  enums["CharacterStatus"] = enum_members<genius::character_status>();
  py::list control_kinds = enum_members<genius::control_kind>();  // "unknown" is also to_string's fallback
  control_kinds.append(py::make_tuple("unknown", static_cast<unsigned>(genius::control_kind::unknown)));
  enums["ControlKind"] = control_kinds;
  enums["EncodeStatus"] = enum_members<genius::encode_status>();
  enums["ParseStatus"] = enum_members<genius::parse_status>();
  enums["Rate"] = enum_members<genius::rate>();
  enums["LayoutStatus"] = enum_members<genius::layout_status>();
  enums["ScanTimeStatus"] = enum_members<genius::scan_time_status>();
  m.attr("enums") = enums;
  m.attr("MAX_SBA") = genius::max_sba;

  // ---- characters ----
  m.def("encode_character", [](std::uint8_t byte, bool control) {
    return genius::encode_character(genius::character{byte, control});
  });
  m.def("decode_character", [](unsigned word) {
    const genius::character_result r =
        genius::decode_character(static_cast<std::uint16_t>(word > 0xFFFF ? 0xFFFF : word));
    return py::make_tuple(static_cast<unsigned>(r.status), r.value.byte, r.value.control);
  });

  // ---- CRC-6 ----
  m.def("crc6", [](py::handle data, py::object profile) {
    const byte_input input(data);
    return genius_wire(profile).crc.compute(input.view());
  });

  // ---- transmissions ----
  m.def("encode_transmission", [](unsigned sender, bool broadcast, unsigned destination,
                                  const py::list& segment_list, py::object profile) {
    const segments_in segments(segment_list);
    genius::transmission t;
    t.sender = static_cast<std::uint8_t>(sender > 255 ? 255 : sender);
    t.broadcast = broadcast;
    t.destination = static_cast<std::uint8_t>(destination > 255 ? 255 : destination);
    t.segments = span<const genius::segment>(segments.segments.data(), segments.segments.size());
    const genius::encode_result length = genius::encoded_length(t);
    if (!length) return py::make_tuple(static_cast<unsigned>(length.status), py::none());
    std::vector<genius::character> out(length.length);
    const genius_wire wire(profile);
    const genius::encode_result r = genius::encode_transmission(
        span<genius::character>(out.data(), out.size()), t, wire.crc, wire.layout);
    if (!r) return py::make_tuple(static_cast<unsigned>(r.status), py::none());
    py::list characters;
    for (const genius::character& c : out) characters.append(py::make_tuple(c.byte, c.control));
    return py::make_tuple(static_cast<unsigned>(r.status), characters);
  });
  m.def("read_control", [](std::uint8_t byte, py::object profile) {
    const genius::control_fields f = genius::read_control(byte, genius_wire(profile).layout);
    return py::make_tuple(static_cast<unsigned>(f.kind), f.sba, f.broadcast, f.crc);
  });

  py::class_<parser>(m, "TransmissionParser")
      .def(py::init<py::object>())
      .def("push", &parser::push)
      .def("push_framing_error", &parser::push_framing_error)
      .def("counts", &parser::counts)
      .def_property_readonly("errors", &parser::errors)
      .def_property_readonly("in_transmission", &parser::in_transmission)
      .def("reset", &parser::reset)
      .def("clear_counters", &parser::clear_counters);
  m.def("is_error", [](unsigned status) {
    return status < genius::parse_status_count && genius::is_error(static_cast<genius::parse_status>(status));
  });

  // ---- bus access ----
  m.def("rate_properties", [](unsigned r) {
    const genius::rate_properties p = genius::properties(rate_of(r));
    py::dict d;
    d["name"] = p.name;
    d["description"] = p.description;
    d["baud"] = p.baud;
    d["skip_bits"] = p.skip_bits;
    d["max_length_ft"] = p.max_length_ft;
    d["max_devices"] = p.max_devices;
    return d;
  });
  m.def("default_timing", [](unsigned r) { return timing_dict(genius::default_timing(rate_of(r))); });
  m.def("analyse_turns", [](const py::list& device_list, const py::dict& timing, unsigned after) {
    const std::vector<genius::device_position> devices = devices_of(device_list);
    const genius::turn_analysis a =
        genius::analyse_turns(span<const genius::device_position>(devices.data(), devices.size()),
                              timing_of(timing), static_cast<std::uint8_t>(after > 255 ? 255 : after));
    py::dict d;
    d["status"] = static_cast<unsigned>(a.status);
    d["after"] = a.after;
    py::list turns;
    for (std::size_t i = 0; i < a.turn_count; ++i) {
      turns.append(py::make_tuple(a.turns[i].sba, a.turns[i].position_ft, a.turns[i].start_us));
    }
    d["turns"] = turns;
    py::list margins;
    for (std::size_t i = 0; i < a.margin_count; ++i) {
      const genius::turn_margin& g = a.margins[i];
      margins.append(py::make_tuple(g.first, g.second, g.margin_us, g.too_small));
    }
    d["margins"] = margins;
    d["too_small_count"] = a.too_small_count;
    d["bus_length_ft"] = a.bus_length_ft;
    d["longer_than_rate_allows"] = a.longer_than_rate_allows;
    d["more_devices_than_rate_allows"] = a.more_devices_than_rate_allows;
    return d;
  });
  m.def("simulate_scan", [](const py::list& device_list, const py::dict& timing, unsigned after) {
    const std::vector<genius::device_position> devices = devices_of(device_list);
    const genius::bus_scan s =
        genius::simulate_scan(span<const genius::device_position>(devices.data(), devices.size()),
                              timing_of(timing), static_cast<std::uint8_t>(after > 255 ? 255 : after));
    py::dict d;
    d["status"] = static_cast<unsigned>(s.status);
    py::list transmissions;
    for (std::size_t i = 0; i < s.count; ++i) {
      const genius::scan_transmission& t = s.transmissions[i];
      transmissions.append(py::make_tuple(t.sba, t.start_us, t.end_us, t.collided));
    }
    d["transmissions"] = transmissions;
    d["collisions"] = s.collisions;
    d["complete"] = s.complete;
    return d;
  });

  // ---- scan time ----
  m.def("device_scan_time_ns",
        [](unsigned r, std::uint32_t io_bytes) { return genius::device_scan_time_ns(rate_of(r), io_bytes); });
  m.def("bus_scan_time", [](unsigned r, const std::vector<std::uint32_t>& io_bytes) {
    const genius::scan_time_result s =
        genius::bus_scan_time(rate_of(r), span<const std::uint32_t>(io_bytes.data(), io_bytes.size()));
    return py::make_tuple(static_cast<unsigned>(s.status), s.sum_ns, s.io_bytes, s.devices);
  });
}

}  // namespace trionet::python
