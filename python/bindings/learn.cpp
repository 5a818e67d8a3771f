// trionet._trionet.learn: profiles (src/learn/profile.hpp) and learning a network's CRC and variable layout
// from captured frames (src/learn/ring_crc_learn.hpp, ring_layout_learn.hpp, genius_crc_learn.hpp).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <string>
#include <vector>

#include "common.hpp"
#include "learn/genius_crc_learn.hpp"
#include "learn/profile.hpp"
#include "learn/ring_capture.hpp"
#include "learn/ring_crc_learn.hpp"
#include "learn/ring_layout_learn.hpp"
#include "trionet/q32.hpp"
#include "trionet/ring/message.hpp"
#include "trionet/ring/variable_layout.hpp"

namespace trionet::python {
namespace {

// A CRC's parameters (16-bit ring or 6-bit Genius: the same fields) as a dict.
template <class Parameters>
py::dict crc_dict(const Parameters& p) {
  py::dict d;
  d["polynomial"] = p.polynomial;
  d["initial"] = p.initial;
  d["reflect_in"] = p.reflect_in;
  d["reflect_out"] = p.reflect_out;
  d["xor_out"] = p.xor_out;
  return d;
}

ring::crc16_parameters crc16_of(const py::dict& d) {
  ring::crc16_parameters p;
  p.polynomial = d["polynomial"].cast<std::uint16_t>();
  p.initial = d["initial"].cast<std::uint16_t>();
  p.reflect_in = d["reflect_in"].cast<bool>();
  p.reflect_out = d["reflect_out"].cast<bool>();
  p.xor_out = d["xor_out"].cast<std::uint16_t>();
  return p;
}

// The 14 data bytes of each frame given as a buffer of exactly 14 bytes.
std::vector<learn::variable_frame> frames_of(const py::list& list) {
  std::vector<learn::variable_frame> frames;
  for (const py::handle item : list) {
    const byte_input input(item);
    const byte_view v = input.view();
    if (v.size() != 14) throw py::value_error("a direct variable transfer's data is 14 bytes");
    learn::variable_frame f{};
    for (std::size_t i = 0; i < 14; ++i) f[i] = v[i];
    frames.push_back(f);
  }
  return frames;
}

template <class Classes, class Dict>
py::list classes_of(const Classes& classes, Dict&& dict) {
  py::list out;
  for (const auto& c : classes) {
    py::list members;
    for (const auto& m : c.members) members.append(py::make_tuple(dict(m.parameters), m.name));
    out.append(members);
  }
  return out;
}

}  // namespace

void bind_profile(py::module_& m) {
  py::dict enums;
  enums["ProfileStatus"] = enum_members<learn::profile_status>();
  enums["KeyOffRule"] = enum_members<learn::key_off_rule>();
  m.attr("enums") = enums;

  py::class_<learn::profile>(m, "ProfileData")
      .def(py::init<>())
      .def("to_json", [](const learn::profile& p) { return learn::write_profile(p); })
      .def("header",
           [](const learn::profile& p, const std::string& name) {
             const learn::header_result r = learn::profile_header(p, name);
             if (!r) throw py::value_error("namespace '" + name + "' cannot be used: " + r.reason);
             return r.text;
           })
      .def_readwrite("name", &learn::profile::name)
      .def_property_readonly("ring_max_characters",
                             [](const learn::profile& p) { return p.ring.max_characters; })
      .def_property_readonly("ring_receive_buffer",
                             [](const learn::profile& p) { return p.ring.receive_buffer; })
      .def_property_readonly("ring_crc", [](const learn::profile& p) { return crc_dict(p.ring.crc); })
      .def_property_readonly("can_node_count", [](const learn::profile& p) { return p.can.node_count; })
      .def_property_readonly("can_byte_order",
                             [](const learn::profile& p) { return static_cast<unsigned>(p.can.byte_order); })
      .def_property_readonly("genius_crc", [](const learn::profile& p) { return crc_dict(p.genius.crc); })
      .def("__eq__", [](const learn::profile& a, const learn::profile& b) { return a == b; });

  // (status, profile or None, key, message, line, column)
  m.def("read_profile", [](const std::string& text) {
    learn::profile_result r = learn::read_profile(text);
    py::object value = r ? py::cast(std::move(r.value)) : py::none();
    std::string message = r.message;
    // not_json: the JSON status, and what the reader says of it ("syntax: invalid UTF-8"), as the tool prints both.
    if (r.status == learn::profile_status::not_json)
      message = std::string(learn::to_string(r.json)) + (r.message.empty() ? "" : ": " + r.message);
    return py::make_tuple(static_cast<unsigned>(r.status), value, r.key, message, r.line, r.column);
  });
}

void bind_learn(py::module_& m) {
  py::dict enums;
  enums["CrcLearnStatus"] = enum_members<learn::crc_learn_status>();
  enums["LayoutLearnStatus"] = enum_members<learn::layout_learn_status>();
  enums["CrcInputFinding"] = enum_members<learn::crc_input_finding>();
  enums["GroupOrder"] = enum_members<ring::group_order>();
  enums["CrcInput"] = enum_members<ring::crc_input>();
  m.attr("enums") = enums;

  m.def("variable_transfers", [](py::handle stream) {
    const byte_input input(stream);
    const learn::frame_extraction found = learn::variable_transfers(input.view());
    py::list frames;
    for (const learn::variable_frame& f : found.frames) frames.append(to_bytes(f.data(), f.size()));
    return py::make_tuple(frames, found.skipped_bytes);
  });

  m.def("learn_ring_crc", [](const py::list& frame_list, bool even, std::size_t max_classes) {
    const std::vector<learn::variable_frame> frames = frames_of(frame_list);
    learn::crc_learn_options options;
    options.even_polynomials = even;
    options.max_classes = max_classes;
    const learn::crc_learn_result r = learn::learn_ring_crc(frames, options);
    py::dict d;
    d["status"] = static_cast<unsigned>(r.status);
    d["classes"] = classes_of(r.classes, [](const auto& p) { return crc_dict(p); });
    d["survivors"] = r.survivors;
    d["frames"] = r.frames;
    d["bad_frame_index"] = r.bad_frame_index;
    return d;
  });

  m.def("frame_crc_matches", [](const py::dict& crc, py::handle frame) {
    py::list one;
    one.append(frame);
    return learn::frame_crc_matches(crc16_of(crc), frames_of(one).front());
  });

  m.def("learn_ring_layout", [](const py::list& frame_list,
                                const std::vector<std::pair<unsigned, double>>& sent_list, py::object crc) {
    const std::vector<learn::variable_frame> frames = frames_of(frame_list);
    std::vector<learn::sent_variable> sent;
    for (const auto& [vr, value] : sent_list) {
      if (vr > ring::max_vr) throw py::value_error("a sent VR is 0..16383");
      const q32_result q = q32_from_double(value);
      if (!q) throw py::value_error("a sent value is outside the Q32.32 range");
      sent.push_back(learn::sent_variable{static_cast<std::uint16_t>(vr), q.raw});
    }
    learn::layout_learn_options options;
    ring::crc16_parameters given;
    if (!crc.is_none()) {
      given = crc16_of(crc.cast<py::dict>());
      options.crc = &given;
    }
    const learn::layout_learn_result r = learn::learn_layout(frames, sent, options);
    py::dict d;
    d["status"] = static_cast<unsigned>(r.status);
    d["vr_group_order"] = static_cast<unsigned>(r.layout.vr);
    d["value_group_order"] = static_cast<unsigned>(r.layout.value);
    d["crc_input"] = static_cast<unsigned>(r.layout.crc);
    py::list orders;
    for (const learn::order_fit& fit : r.orders) {
      orders.append(py::make_tuple(static_cast<unsigned>(fit.vr), static_cast<unsigned>(fit.value), fit.fits,
                                   fit.first_contradiction));
    }
    d["orders"] = orders;
    d["crc_finding"] = static_cast<unsigned>(r.crc);
    d["bad_frame_index"] = r.bad_frame_index;
    return d;
  });

  m.def("genius_crc_samples",
        [](const std::vector<std::pair<std::uint8_t, bool>>& characters, py::object profile) {
          std::vector<genius::character> in;
          in.reserve(characters.size());
          for (const auto& [byte, control] : characters) in.push_back(genius::character{byte, control});
          genius::control_layout layout;
          if (!profile.is_none()) layout = profile.cast<const learn::profile&>().genius.control;
          const learn::sample_extraction s =
              learn::genius_crc_samples(span<const genius::character>(in.data(), in.size()), layout);
          const auto samples = [](const std::vector<learn::crc6_sample>& list) {
            py::list out;
            for (const learn::crc6_sample& x : list)
              out.append(py::make_tuple(to_bytes(x.data.data(), x.data.size()), x.crc));
            return out;
          };
          return py::make_tuple(samples(s.stops), samples(s.blocks), s.skipped_characters);
        });

  m.def("learn_genius_crc", [](const std::vector<std::pair<py::object, unsigned>>& sample_list, bool even,
                               std::size_t max_classes) {
    std::vector<learn::crc6_sample> samples;
    for (const auto& [data, crc] : sample_list) {
      const byte_input input(data);
      learn::crc6_sample s;
      s.data.assign(input.view().begin(), input.view().end());
      s.crc = static_cast<std::uint8_t>(crc > 255 ? 255 : crc);
      samples.push_back(std::move(s));
    }
    learn::crc6_learn_options options;
    options.even_polynomials = even;
    options.max_classes = max_classes;
    const learn::crc6_learn_result r = learn::learn_genius_crc(samples, options);
    py::dict d;
    d["status"] = static_cast<unsigned>(r.status);
    d["classes"] = classes_of(r.classes, [](const auto& p) { return crc_dict(p); });
    d["survivors"] = r.survivors;
    d["samples"] = r.samples;
    d["bad_sample_index"] = r.bad_sample_index;
    return d;
  });
}

}  // namespace trionet::python
