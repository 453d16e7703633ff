// SPDX-License-Identifier: MIT
// The `cleave` Python module: the split core and the mesh files of engine/assets for NumPy arrays.
// See docs/python.md.
#include <pybind11/pybind11.h>

#include "cleave_version.h"
#include "python/mesh_io_binding.h"
#include "python/split_binding.h"

PYBIND11_MODULE(cleave, module) {
  module.doc() =
      "Cleave's split core for NumPy arrays: cut a triangle mesh by a plane, cap the holes, "
      "separate "
      "the pieces and get their volume, centre of mass and inertia (split); read and write mesh "
      "files "
      "(read_mesh, write_mesh). See docs/python.md.";
  module.attr("__version__") = cleave::kVersion;
  // Each docstring starts with its own Python signature; pybind11's would show C++ handle types.
  pybind11::options options;
  options.disable_function_signatures();
  cleave::python::bindSplit(module);
  cleave::python::bindMeshIo(module);
}
