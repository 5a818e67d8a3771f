// trionet.ring.Decoder and its events: ring bytes in (any buffer, no copy), one Event per message or error
// out, with the fields of `trionet ring decode --raw` (src/host/trionet/host/ring_events.hpp makes both).
//
// An Event is a small object of its own type (the CPython API, not a pybind11 class): a decoder may make
// millions of them, and this way making one is an allocation and a few stores. Its fields are computed when
// read, by the same field visitor that writes the tool's JSON.
#include <pybind11/pybind11.h>

#include <cstdint>
#include <cstring>
#include <memory>
#include <string_view>
#include <utility>

#include "common.hpp"
#include "learn/profile.hpp"
#include "learn/profile_decoder.hpp"
#include "trionet/host/ring_events.hpp"
#include "trionet/ring/decoder.hpp"

namespace trionet::python {
namespace {

// The event kind "unfinished" (a message still open at the end of the input) has no decode status: it is
// kept in `status` as this value.
constexpr std::uint8_t unfinished_status = 255;

struct event_object {
  PyObject_HEAD std::uint64_t position;  // the byte of the stream the event is about
  PyObject* text;                        // a character message's text (str), else nullptr
  std::int64_t value;
  std::uint16_t vr;
  std::uint8_t status;  // ring::decode_status, or unfinished_status
  std::uint8_t error;   // ring::frame_error
  std::uint8_t type;    // ring::message_type
  std::uint8_t hops;
  std::uint8_t offset;
  std::uint8_t mode;
};

PyTypeObject* event_type = nullptr;
PyObject* decode_status_enum = nullptr;  // the package's IntEnums, set when it imports (set_event_enums)
PyObject* frame_error_enum = nullptr;

// The decoder result an event was made from (its text viewing the event's str).
ring::decode_result result_of(const event_object* e) {
  ring::decode_result r{};
  r.status = static_cast<ring::decode_status>(e->status);
  r.error = static_cast<ring::frame_error>(e->error);
  r.msg.type = static_cast<ring::message_type>(e->type);
  r.msg.hops = e->hops;
  r.msg.vr = e->vr;
  r.msg.value = e->value;
  r.msg.offset = e->offset;
  r.msg.mode = e->mode;
  if (e->text != nullptr) {
    r.msg.text =
        byte_view(PyUnicode_1BYTE_DATA(e->text), static_cast<std::size_t>(PyUnicode_GET_LENGTH(e->text)));
  }
  return r;
}

PyObject* new_str(std::string_view text) {
  return PyUnicode_FromStringAndSize(text.data(), static_cast<Py_ssize_t>(text.size()));
}

// The str of one of the program's own names (an event kind, a message type, a frame error's reason: string
// literals, so their address identifies them), made once and shared: reading `event.type` of millions of
// events makes no new strings.
PyObject* name_str(const char* name) {
  static std::pair<const char*, PyObject*> made[64];
  for (auto& [text, str] : made) {
    if (text == nullptr) {
      str = PyUnicode_InternFromString(name);
      if (str == nullptr) return nullptr;
      text = name;
    }
    if (text == name) {
      Py_INCREF(str);
      return str;
    }
  }
  return PyUnicode_FromString(name);  // not expected: more names than the table holds
}

// Field visitors over host::ring_event_fields.

// Finds one field: `found` is a new reference to its value, or stays null.
struct field_finder {
  std::string_view key;
  PyObject* found = nullptr;
  void name(std::string_view k, std::string_view v) {
    if (k != key) return;
    // "type" and "reason" are string literals (ring_event_fields); any other name field is made for the
    // event.
    found = k == "type" || k == "reason" ? name_str(v.data()) : new_str(v);
  }
  void text(std::string_view k, std::string_view v) {
    if (k == key) found = new_str(v);
  }
  void number(std::string_view k, std::uint64_t v) {
    if (k == key) found = PyLong_FromUnsignedLongLong(v);
  }
  void real(std::string_view k, double v) {
    if (k == key) found = PyFloat_FromDouble(v);
  }
};

// Puts every field into a dict; `failed` after any error (with a Python exception set).
struct dict_filler {
  PyObject* dict;
  bool failed = false;
  void put(std::string_view k, PyObject* v) {
    if (failed) return;
    PyObject* key = v == nullptr ? nullptr : new_str(k);
    if (key == nullptr || PyDict_SetItem(dict, key, v) != 0) failed = true;
    Py_XDECREF(key);
    Py_XDECREF(v);
  }
  void name(std::string_view k, std::string_view v) { put(k, new_str(v)); }
  void text(std::string_view k, std::string_view v) { put(k, new_str(v)); }
  void number(std::string_view k, std::uint64_t v) { put(k, PyLong_FromUnsignedLongLong(v)); }
  void real(std::string_view k, double v) { put(k, PyFloat_FromDouble(v)); }
};

const char* kind_of(const event_object* e) {
  return e->status == unfinished_status ? "unfinished" : host::ring_event_kind(result_of(e));
}

PyObject* field(event_object* e, std::string_view key) {
  if (e->status == unfinished_status) Py_RETURN_NONE;
  field_finder finder{key};
  host::ring_event_fields(finder, result_of(e));
  if (finder.found != nullptr || PyErr_Occurred()) return finder.found;
  Py_RETURN_NONE;
}

void event_dealloc(PyObject* self) {
  auto* e = reinterpret_cast<event_object*>(self);
  Py_XDECREF(e->text);
  PyTypeObject* type = Py_TYPE(self);
  type->tp_free(self);
  Py_DECREF(type);
}

PyObject* get_event(PyObject* self, void*) {
  return name_str(kind_of(reinterpret_cast<event_object*>(self)));
}
PyObject* get_position(PyObject* self, void*) {
  return PyLong_FromUnsignedLongLong(reinterpret_cast<event_object*>(self)->position);
}
PyObject* get_type(PyObject* self, void*) {
  return field(reinterpret_cast<event_object*>(self), "type");
}
PyObject* get_hops(PyObject* self, void*) {
  return field(reinterpret_cast<event_object*>(self), "hops");
}
PyObject* get_text(PyObject* self, void*) {
  return field(reinterpret_cast<event_object*>(self), "text");
}
PyObject* get_vr(PyObject* self, void*) {
  return field(reinterpret_cast<event_object*>(self), "vr");
}
PyObject* get_raw(PyObject* self, void*) {
  return field(reinterpret_cast<event_object*>(self), "raw");
}
PyObject* get_value(PyObject* self, void*) {
  return field(reinterpret_cast<event_object*>(self), "value");
}
PyObject* get_offset(PyObject* self, void*) {
  return field(reinterpret_cast<event_object*>(self), "offset");
}
PyObject* get_mode(PyObject* self, void*) {
  return field(reinterpret_cast<event_object*>(self), "mode");
}
PyObject* get_reason(PyObject* self, void*) {
  return field(reinterpret_cast<event_object*>(self), "reason");
}

PyObject* enum_member(PyObject* enum_class, unsigned value) {
  if (enum_class == nullptr) return PyLong_FromUnsignedLong(value);
  return PyObject_CallFunction(enum_class, "I", value);
}
PyObject* get_status(PyObject* self, void*) {
  const auto* e = reinterpret_cast<event_object*>(self);
  if (e->status == unfinished_status) Py_RETURN_NONE;
  return enum_member(decode_status_enum, e->status);
}
PyObject* get_error(PyObject* self, void*) {
  const auto* e = reinterpret_cast<event_object*>(self);
  if (e->status != static_cast<std::uint8_t>(ring::decode_status::frame_error)) Py_RETURN_NONE;
  return enum_member(frame_error_enum, e->error);
}

PyObject* event_to_dict(PyObject* self, PyObject*) {
  auto* e = reinterpret_cast<event_object*>(self);
  PyObject* dict = PyDict_New();
  if (dict == nullptr) return nullptr;
  dict_filler filler{dict};
  filler.put("event", PyUnicode_FromString(kind_of(e)));
  filler.put("position", PyLong_FromUnsignedLongLong(e->position));
  if (e->status != unfinished_status) host::ring_event_fields(filler, result_of(e));
  if (filler.failed) {
    Py_DECREF(dict);
    return nullptr;
  }
  return dict;
}

PyObject* event_repr(PyObject* self) {
  PyObject* dict = event_to_dict(self, nullptr);
  if (dict == nullptr) return nullptr;
  PyObject* text = PyUnicode_FromString("Event(");
  PyObject* key = nullptr;
  PyObject* value = nullptr;
  Py_ssize_t at = 0;
  bool first = true;
  while (text != nullptr && PyDict_Next(dict, &at, &key, &value)) {
    PyObject* item = PyUnicode_FromFormat("%s%U=%R", first ? "" : ", ", key, value);
    first = false;
    if (item == nullptr) {
      Py_CLEAR(text);
      break;
    }
    PyUnicode_Append(&text, item);
    Py_DECREF(item);
  }
  Py_DECREF(dict);
  if (text == nullptr) return nullptr;
  PyObject* close = PyUnicode_FromString(")");
  PyUnicode_Append(&text, close);
  Py_XDECREF(close);
  return text;
}

PyObject* event_richcompare(PyObject* a, PyObject* b, int op) {
  if ((op != Py_EQ && op != Py_NE) || Py_TYPE(b) != Py_TYPE(a)) Py_RETURN_NOTIMPLEMENTED;
  PyObject* da = event_to_dict(a, nullptr);
  PyObject* db = da == nullptr ? nullptr : event_to_dict(b, nullptr);
  PyObject* result = db == nullptr ? nullptr : PyObject_RichCompare(da, db, op);
  Py_XDECREF(da);
  Py_XDECREF(db);
  return result;
}

PyGetSetDef event_getset[] = {
    {"event", get_event, nullptr,
     "The kind of event: \"message\", \"crc_error\", \"frame_error\", \"no_room\" or \"unfinished\".",
     nullptr},
    {"position", get_position, nullptr,
     "The byte of the stream the event is about, counted from 0 (the message's header; for stray data, a "
     "stray end of message or a zero-hops header, that byte). `trionet ring decode --raw` calls it "
     "\"offset\".",
     nullptr},
    {"type", get_type, nullptr, "A message's type: \"char\", \"var\", \"offset\" or \"mode\" (else None).",
     nullptr},
    {"hops", get_hops, nullptr, "Hops to the receiver, 1..15 (messages, crc_error, no_room; else None).",
     nullptr},
    {"text", get_text, nullptr, "A character message's characters, each 0..127 (else None).", nullptr},
    {"vr", get_vr, nullptr, "The VR of a direct variable transfer or a CRC error (else None).", nullptr},
    {"raw", get_raw, nullptr, "A variable's Q32.32 bits as \"0x\" and 16 hex digits (else None).", nullptr},
    {"value", get_value, nullptr, "A variable's value (else None).", nullptr},
    {"offset", get_offset, nullptr, "A keypad offset message's offset in hops, 1..15 (else None).", nullptr},
    {"mode", get_mode, nullptr, "A keypad mode message's mode, 0 or 127 (else None).", nullptr},
    {"reason", get_reason, nullptr, "A frame error's reason, e.g. \"stray_data\" (else None).", nullptr},
    {"status", get_status, nullptr, "The decoder's status as a DecodeStatus (None for \"unfinished\").",
     nullptr},
    {"error", get_error, nullptr, "A frame error's reason as a FrameError (else None).", nullptr},
    {nullptr, nullptr, nullptr, nullptr, nullptr},
};

PyMethodDef event_methods[] = {
    {"to_dict", event_to_dict, METH_NOARGS,
     "The event's fields in order, as `trionet ring decode --raw` prints them (its \"offset\" of the event "
     "is "
     "\"position\" here)."},
    {nullptr, nullptr, 0, nullptr},
};

PyType_Slot event_slots[] = {
    {Py_tp_dealloc, reinterpret_cast<void*>(event_dealloc)},
    {Py_tp_repr, reinterpret_cast<void*>(event_repr)},
    {Py_tp_richcompare, reinterpret_cast<void*>(event_richcompare)},
    {Py_tp_getset, event_getset},
    {Py_tp_methods, event_methods},
    {Py_tp_doc, const_cast<char*>("One event of a ring byte stream: a message, a CRC error, a frame error, a "
                                  "message with no room, or a message left unfinished. Made by Decoder.")},
    {0, nullptr},
};

PyType_Spec event_spec = {"trionet.ring.Event", sizeof(event_object), 0, Py_TPFLAGS_DEFAULT, event_slots};

// Makes an event (a new reference), or null with a Python exception set.
event_object* new_event(std::uint8_t status, std::uint64_t position) {
  auto* e = reinterpret_cast<event_object*>(event_type->tp_alloc(event_type, 0));
  if (e == nullptr) return nullptr;
  e->position = position;
  e->status = status;
  return e;
}

event_object* event_of(const ring::decode_result& r, std::uint64_t position) {
  event_object* e = new_event(static_cast<std::uint8_t>(r.status), position);
  if (e == nullptr) return nullptr;
  e->error = static_cast<std::uint8_t>(r.error);
  e->type = static_cast<std::uint8_t>(r.msg.type);
  e->hops = r.msg.hops;
  e->vr = r.msg.vr;
  e->value = r.msg.value;
  e->offset = r.msg.offset;
  e->mode = r.msg.mode;
  if (r.status == ring::decode_status::ok && r.msg.type == ring::message_type::character) {
    // The characters are 0..127: ASCII, one byte each.
    e->text = PyUnicode_New(static_cast<Py_ssize_t>(r.msg.text.size()), 127);
    if (e->text == nullptr) {
      Py_DECREF(e);
      return nullptr;
    }
    std::memcpy(PyUnicode_1BYTE_DATA(e->text), r.msg.text.data(), r.msg.text.size());
  }
  return e;
}

// The decoder: a stream of events over learn::profile_decoder (the library's default decoder unless a
// profile changes the CRC or the variable layout).
class decoder {
 public:
  explicit decoder(const learn::ring_profile& profile) : stream_(profile) {}

  py::list feed(py::handle data) {
    const byte_input input(data);
    const byte_view bytes = input.view();
    py::list events(0);
    PyObject* list = events.ptr();
    bool failed = false;
    stream_.push(bytes.data(), bytes.data() + bytes.size(), position_,
                 [&](const ring::decode_result& r, std::uint64_t at) {
                   if (failed) return;  // keep decoding, so that the decoder stays in step with the stream
                   event_object* e = event_of(r, at);
                   if (e == nullptr || PyList_Append(list, reinterpret_cast<PyObject*>(e)) != 0)
                     failed = true;
                   Py_XDECREF(e);
                 });
    position_ += bytes.size();
    if (failed) throw py::error_already_set();
    return events;
  }

  py::list finish() {
    py::list events(0);
    std::uint64_t at = 0;
    if (stream_.unfinished(at)) {
      stream_.decoder().reset();
      append(events, new_event(unfinished_status, at));
    }
    return events;
  }

  py::list line_idle() {
    py::list events(0);
    std::uint64_t at = 0;
    const bool open = stream_.unfinished(at);
    const ring::decode_result r = stream_.decoder().line_idle();
    if (open && r.status != ring::decode_status::incomplete) append(events, event_of(r, at));
    return events;
  }

  void reset() { stream_.decoder().reset(); }
  [[nodiscard]] std::uint64_t position() const noexcept { return position_; }
  [[nodiscard]] bool in_message() { return stream_.decoder().in_message(); }

 private:
  static void append(py::list& events, event_object* e) {
    if (e == nullptr) throw py::error_already_set();
    events.append(py::reinterpret_steal<py::object>(reinterpret_cast<PyObject*>(e)));
  }

  host::ring_event_stream<learn::profile_decoder> stream_;
  std::uint64_t position_ = 0;
};

}  // namespace

void bind_decoder(py::module_& m) {
  event_type = reinterpret_cast<PyTypeObject*>(PyType_FromSpec(&event_spec));
  if (event_type == nullptr) throw py::error_already_set();
  m.add_object("Event", py::reinterpret_borrow<py::object>(reinterpret_cast<PyObject*>(event_type)));

  m.def("set_event_enums", [](py::object status, py::object error) {
    // Kept for the life of the process, as the classes they are.
    decode_status_enum = status.release().ptr();
    frame_error_enum = error.release().ptr();
  });

  py::class_<decoder>(m, "Decoder")
      .def(py::init([](py::object profile) {
             if (profile.is_none()) return std::make_unique<decoder>(learn::ring_profile{});
             return std::make_unique<decoder>(profile.cast<const learn::profile&>().ring);
           }),
           py::arg("profile") = py::none())
      .def("feed", &decoder::feed, py::arg("data"),
           "Decodes the next bytes of the stream (any bytes-like object, read in place) and returns the "
           "events "
           "they completed, in order. TypeError for an object that is not a contiguous buffer.")
      .def(
          "finish", &decoder::finish,
          "The end of the input: an \"unfinished\" event for a message still open (then forgotten), else [].")
      .def("line_idle", &decoder::line_idle,
           "The line went idle: an open message is lost, a frame_error event with reason idle_line; else [].")
      .def("reset", &decoder::reset, "Forgets any open message, silently (e.g. after a link reset).")
      .def_property_readonly("position", &decoder::position, "Bytes fed so far.")
      .def_property_readonly("in_message", &decoder::in_message,
                             "True while a message has begun and not ended.");
}

}  // namespace trionet::python
