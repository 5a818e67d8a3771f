// What the binding files share: enum tables for the Python package's enum.IntEnum classes, byte buffers
// without copies, the VR table Python code reads, and one bind function per part.
//
// The extension module `trionet._trionet` is the C++ side of the package: it returns statuses as numbers and
// leaves the Pythonic surface (exceptions, IntEnums, docstrings) to the package's Python modules
// (python/trionet/), except where speed matters (the ring decoder's events are made here).
#pragma once

#include <pybind11/pybind11.h>

#include <cstddef>
#include <cstdint>
#include <exception>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "trionet/span.hpp"
#include "trionet/vr.hpp"

namespace trionet::python {

namespace py = pybind11;

/// Every enumerator of `E` as (name, value), in value order: the values 0..255 whose `to_string` is not
/// "unknown". The Python package makes an enum.IntEnum of them, so names and values are the C++ enum's.
template <class E>
py::list enum_members() {
  py::list members;
  for (unsigned value = 0; value < 256; ++value) {
    const char* name = to_string(static_cast<E>(value));
    if (std::string(name) != "unknown") members.append(py::make_tuple(name, value));
  }
  return members;
}

/// A read-only view of any object with the buffer protocol whose items are bytes (bytes, bytearray,
/// memoryview, array('B'), mmap), held for as long as this object lives; no copy. Raises TypeError for
/// anything else and for a buffer that is not contiguous.
class byte_input {
 public:
  explicit byte_input(py::handle object) {
    if (PyObject_GetBuffer(object.ptr(), &buffer_, PyBUF_SIMPLE) != 0) throw py::error_already_set();
  }
  ~byte_input() { PyBuffer_Release(&buffer_); }
  byte_input(const byte_input&) = delete;
  byte_input& operator=(const byte_input&) = delete;

  [[nodiscard]] byte_view view() const noexcept {
    return byte_view(static_cast<const std::uint8_t*>(buffer_.buf), static_cast<std::size_t>(buffer_.len));
  }

 private:
  Py_buffer buffer_{};
};

/// Bytes as a Python bytes object (one copy: the result is immutable and owns its memory).
inline py::bytes to_bytes(const std::uint8_t* data, std::size_t size) {
  return py::bytes(reinterpret_cast<const char*>(data), size);
}

/// VR(): a table of doubles of any size (1..16384) that Python reads as a memoryview without a copy, written
/// by the network through an optional write policy, a Python callable (vr, value) whose answer is taken as
/// Python truth (bool(answer): True, 1, "yes" write; False, 0, None refuse). An exception in the policy, or in
/// bool(answer), refuses the write and is raised again by the call that fed the node (`raise_pending`).
class vr_values final : public vr_store {
 public:
  explicit vr_values(std::size_t size) : values_(size, 0.0) {}

  vr_write_status write(std::uint16_t vr, const network_value& value) noexcept override {
    if (vr >= values_.size()) return vr_write_status::out_of_range;
    const double v = value.to_double();
    if (!policy_.is_none()) {
      try {
        const py::object answer = policy_(vr, v);
        const int truth = PyObject_IsTrue(answer.ptr());
        if (truth < 0) throw py::error_already_set();
        if (truth == 0) return vr_write_status::refused;
      } catch (py::error_already_set& e) {
        if (!pending_) pending_ = std::move(e);
        return vr_write_status::refused;
      } catch (const std::exception& e) {  // not a Python exception (pybind11's own): kept as a RuntimeError
        if (!pending_) {
          PyErr_SetString(PyExc_RuntimeError, e.what());
          pending_ = py::error_already_set();
        }
        return vr_write_status::refused;
      }
    }
    values_[vr] = v;
    return vr_write_status::ok;
  }

  /// The policy (None: every write in range is applied).
  void set_policy(py::object policy) { policy_ = std::move(policy); }
  [[nodiscard]] const py::object& policy() const noexcept { return policy_; }

  /// Raises the first exception a policy raised since the last call, if any.
  void raise_pending() {
    if (!pending_) return;
    py::error_already_set e = std::move(*pending_);
    pending_.reset();
    e.restore();
    throw py::error_already_set();
  }

  std::vector<double>& values() noexcept { return values_; }

 private:
  std::vector<double> values_;
  py::object policy_ = py::none();
  std::optional<py::error_already_set> pending_;
};

void bind_ring(py::module_& m);
void bind_decoder(py::module_& m);
void bind_basic(py::module_& m);
void bind_can(py::module_& m);
void bind_genius(py::module_& m);
void bind_learn(py::module_& m);
void bind_profile(py::module_& m);

}  // namespace trionet::python
