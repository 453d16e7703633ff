// SPDX-License-Identifier: MIT
// NumPy arrays to and from the plain arrays of the split core, for the `cleave` Python module.
//
// Input: anything numpy.asarray accepts (arrays, nested lists). Vertices, normals and UVs must hold
// real numbers (any integer or floating dtype), faces integers; every value is checked (shape,
// dtype, finite, within float32's range, index in range) before it reaches the core, so bad input
// raises ValueError naming the argument, the element and the reason instead of reaching an assert.
// Positions are stored as float32 by the core: float64 input is rounded to the nearest float32.
//
// Output: new arrays owning their memory (float32 for per-vertex data, int64 for faces).
//
// Method: arrays are made and converted by numpy's own functions (asarray, ascontiguousarray,
// empty) and read or written through the buffer protocol, never through pybind11/numpy.h, whose
// struct layouts in older pybind11 releases (Debian's 2.10) predate numpy 2's: the module works
// with numpy 1 and 2 alike.
//
// Failure: every function throws pybind11::value_error (ValueError in Python); nothing else
// escapes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>
#include <pybind11/pybind11.h>

namespace cleave::python {

namespace py = pybind11;

// An N x `columns` array of real numbers as float32 rows. `rows` 0 accepts any N >= 1, otherwise
// exactly `rows` rows are required (normals and UVs match the vertices). `name` is used in
// messages.
std::vector<glm::vec3> toVec3Rows(py::handle object, const char* name, size_t rows = 0);
std::vector<glm::vec2> toVec2Rows(py::handle object, const char* name, size_t rows);

// An M x 3 array of integers (M >= 1), each in [0, vertexCount), as a flat triangle list.
std::vector<uint32_t> toTriangleList(py::handle object, size_t vertexCount);

// A plane normal: three finite real numbers, not all zero, in double precision.
glm::dvec3 toNormal(py::handle object);

// N x 3 / N x 2 float32 arrays; None for an empty (absent) attribute when `noneIfEmpty`.
py::object fromVec3Rows(std::span<const glm::vec3> rows, bool noneIfEmpty);
py::object fromVec2Rows(std::span<const glm::vec2> rows, bool noneIfEmpty);
// M x 3 int64 array from a triangle list.
py::object fromTriangleList(std::span<const uint32_t> indices);
// New C-contiguous numpy arrays of float64 (3, or 3 x 3 from a glm column-major matrix) and int64.
py::object fromVector(const glm::dvec3& v);
py::object fromMatrix(const glm::dmat3& m);
py::object fromInt64(std::span<const int64_t> values);

}  // namespace cleave::python
