// SPDX-License-Identifier: MIT
// cleave.split and its Piece: geometry::splitMesh for NumPy arrays. The mesh is cut in its own
// space (identity model matrix), so pieces, volumes, centres and inertia are all in the input's
// units.
//
// Failure: bad arguments raise ValueError naming the argument and the reason; a split the core
// refuses (the plane misses the mesh, an open section with open="refuse", a cap that cannot be
// triangulated) raises cleave.SplitError, a ValueError with a `status` attribute (the core's status
// name). Nothing else escapes.
#pragma once

#include <cstdint>

#include <pybind11/pybind11.h>

namespace cleave::python {

namespace py = pybind11;

// One piece of a split, as NumPy arrays and numbers (see the docstrings in split_binding.cpp).
struct Piece {
  py::object vertices;  // N x 3 float32, in the input's space
  py::object faces;     // M x 3 int64, counter-clockwise seen from outside
  py::object normals;   // N x 3 float32, or None when the input had none
  py::object uvs;       // N x 2 float32, or None when the input had none
  py::object
      sourceTriangles;        // M int64: the input triangle each face comes from, -1 for a cap face
  int side = 0;               // +1 above the plane, -1 below
  bool closed = false;        // a closed, consistently wound surface
  bool reached = false;       // the plane cut or touched this piece
  double volume = 0.0;        // density 1
  py::object centerOfMass;    // 3 float64
  py::object inertia;         // 3 x 3 float64, about the centre of mass, density 1
  uint32_t capTriangles = 0;  // faces in the cap material (this cut's caps and earlier ones)
  uint32_t capLoops = 0;      // boundary loops capped on this piece
};

// Adds Piece, SplitError and split() to the module.
void bindSplit(py::module_& module);

}  // namespace cleave::python
