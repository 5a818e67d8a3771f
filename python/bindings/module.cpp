// The extension module trionet._trionet: one submodule per part of the package (see common.hpp).
#include <pybind11/pybind11.h>

#include "common.hpp"

PYBIND11_MODULE(_trionet, m) {
  namespace py = trionet::python::py;
  m.doc() = "The C++ side of the trionet package (use trionet.ring, trionet.can, ... instead).";
  py::module_ ring = m.def_submodule("ring", "Trio Motion Coordinator fibre-optic ring");
  trionet::python::bind_ring(ring);
  trionet::python::bind_decoder(ring);
  py::module_ profile = m.def_submodule("profile", "profiles: every configurable wire parameter in one file");
  trionet::python::bind_profile(profile);
  py::module_ basic = m.def_submodule("basic", "BASIC programs on the simulated ring");
  trionet::python::bind_basic(basic);
  py::module_ can = m.def_submodule("can", "TN20-17 CAN VR exchange");
  trionet::python::bind_can(can);
  py::module_ genius = m.def_submodule("genius", "GE Genius bus");
  trionet::python::bind_genius(genius);
  py::module_ learn = m.def_submodule("learn", "learning wire parameters from captures");
  trionet::python::bind_learn(learn);
}
