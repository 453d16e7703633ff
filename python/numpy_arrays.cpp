// SPDX-License-Identifier: MIT
// Checks every element before conversion: the split core treats malformed data as a precondition or
// a status, and the module promises ValueError with the element named, never an assert or a crash.
#include "python/numpy_arrays.h"

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>

namespace cleave::python {
namespace {

py::module_ numpy() { return py::module_::import("numpy"); }

std::string text(py::handle object) { return py::str(object).cast<std::string>(); }

std::string numberText(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.9g", value);
  return buffer;
}

// numpy.asarray(object), or ValueError naming the argument and numpy's reason (ragged lists, ...).
py::object asArray(py::handle object, const std::string& name) {
  if (object.is_none()) throw py::value_error(name + " must be an array, not None");
  try {
    return numpy().attr("asarray")(object);
  } catch (py::error_already_set& error) {
    throw py::value_error(name + " is not an array of numbers: " + text(error.value()));
  }
}

std::vector<py::ssize_t> shapeOf(const py::object& array) {
  std::vector<py::ssize_t> shape;
  for (py::handle extent : py::tuple(array.attr("shape")))
    shape.push_back(extent.cast<py::ssize_t>());
  return shape;
}

// The array as an N x columns array of a real-number dtype (integers when `integersOnly`),
// converted to a C-contiguous array of `target` dtype; or ValueError.
py::buffer_info checkedRows(py::handle object, const std::string& name, py::ssize_t columns,
                            size_t rows, bool integersOnly, const char* target) {
  const py::object array = asArray(object, name);
  const std::string kind = array.attr("dtype").attr("kind").cast<std::string>();
  const bool integer = kind == "i" || kind == "u";
  if (integersOnly ? !integer : !(integer || kind == "f")) {
    throw py::value_error(name + " must be an array of " +
                          (integersOnly ? "integers" : "real numbers") + ", not of dtype " +
                          text(array.attr("dtype")));
  }
  const std::vector<py::ssize_t> shape = shapeOf(array);
  if (shape.size() != 2 || shape[1] != columns) {
    throw py::value_error(name + " must have shape (N, " + std::to_string(columns) + "), not " +
                          text(array.attr("shape")));
  }
  if (shape[0] == 0) throw py::value_error(name + " is empty");
  if (rows != 0 && static_cast<size_t>(shape[0]) != rows) {
    throw py::value_error(name + " has " + std::to_string(shape[0]) + " rows but there are " +
                          std::to_string(rows) + " vertices");
  }
  py::buffer converted = numpy().attr("ascontiguousarray")(array, target);
  return converted.request();
}

// Every element as a finite float32, or ValueError naming it.
template <int Columns>
std::vector<glm::vec<Columns, float>> realRows(py::handle object, const char* name, size_t rows) {
  const py::buffer_info info = checkedRows(object, name, Columns, rows, false, "float64");
  const double* values = static_cast<const double*>(info.ptr);
  std::vector<glm::vec<Columns, float>> out(static_cast<size_t>(info.shape[0]));
  for (size_t r = 0; r < out.size(); ++r) {
    for (int c = 0; c < Columns; ++c) {
      const double value = values[r * Columns + static_cast<size_t>(c)];
      if (!(std::fabs(value) <=
            FLT_MAX)) {  // NaN, infinite or beyond float32: the message says which
        const std::string where =
            std::string(name) + "[" + std::to_string(r) + ", " + std::to_string(c) + "]";
        if (std::isnan(value)) throw py::value_error(where + " is NaN");
        if (std::isinf(value)) throw py::value_error(where + " is infinite");
        throw py::value_error(where + " = " + numberText(value) + " does not fit a float32");
      }
      out[r][c] = static_cast<float>(value);
    }
  }
  return out;
}

// The face indices as one integer type, each checked against the vertex count.
template <class Integer>
std::vector<uint32_t> indexRows(const py::buffer_info& info, size_t vertexCount) {
  const Integer* values = static_cast<const Integer*>(info.ptr);
  const size_t count = static_cast<size_t>(info.shape[0]) * 3;
  std::vector<uint32_t> out(count);
  for (size_t k = 0; k < count; ++k) {
    const Integer value = values[k];
    if (value < 0 || static_cast<uint64_t>(value) >= vertexCount) {
      throw py::value_error("faces[" + std::to_string(k / 3) + ", " + std::to_string(k % 3) +
                            "] = " + std::to_string(value) + " is out of range (" +
                            std::to_string(vertexCount) + " vertices, indices from 0)");
    }
    out[k] = static_cast<uint32_t>(value);
  }
  return out;
}

// A new C-contiguous numpy array of `dtype` and the given shape, and its buffer to fill.
py::object emptyArray(py::tuple shape, const char* dtype, py::buffer_info& info) {
  py::object array = numpy().attr("empty")(shape, dtype);
  info = py::reinterpret_borrow<py::buffer>(array).request(true);
  return array;
}

template <int Columns>
py::object fromRows(std::span<const glm::vec<Columns, float>> rows, bool noneIfEmpty) {
  if (rows.empty() && noneIfEmpty) return py::none();
  py::buffer_info info;
  py::object array = emptyArray(py::make_tuple(rows.size(), Columns), "float32", info);
  float* data = static_cast<float*>(info.ptr);
  for (size_t r = 0; r < rows.size(); ++r) {
    for (int c = 0; c < Columns; ++c) data[r * Columns + static_cast<size_t>(c)] = rows[r][c];
  }
  return array;
}

}  // namespace

std::vector<glm::vec3> toVec3Rows(py::handle object, const char* name, size_t rows) {
  return realRows<3>(object, name, rows);
}

std::vector<glm::vec2> toVec2Rows(py::handle object, const char* name, size_t rows) {
  return realRows<2>(object, name, rows);
}

std::vector<uint32_t> toTriangleList(py::handle object, size_t vertexCount) {
  const py::object array = asArray(object, "faces");
  // Unsigned faces are read as uint64 so that a huge value is reported as it is, not as negative.
  const bool isUnsigned =
      py::hasattr(array, "dtype") && array.attr("dtype").attr("kind").cast<std::string>() == "u";
  const py::buffer_info info =
      checkedRows(array, "faces", 3, 0, true, isUnsigned ? "uint64" : "int64");
  if (static_cast<size_t>(info.shape[0]) > std::numeric_limits<uint32_t>::max() / 3) {
    throw py::value_error("faces: too many triangles for 32-bit indices");
  }
  return isUnsigned ? indexRows<uint64_t>(info, vertexCount)
                    : indexRows<int64_t>(info, vertexCount);
}

glm::dvec3 toNormal(py::handle object) {
  const py::object array = asArray(object, "normal");
  const std::string kind = array.attr("dtype").attr("kind").cast<std::string>();
  const std::vector<py::ssize_t> shape = shapeOf(array);
  if (!(kind == "i" || kind == "u" || kind == "f") || shape.size() != 1 || shape[0] != 3) {
    throw py::value_error("normal must be three real numbers, not an array of dtype " +
                          text(array.attr("dtype")) + " and shape " + text(array.attr("shape")));
  }
  py::buffer converted = numpy().attr("ascontiguousarray")(array, "float64");
  const py::buffer_info info = converted.request();
  const double* values = static_cast<const double*>(info.ptr);
  const glm::dvec3 normal(values[0], values[1], values[2]);
  if (!std::isfinite(normal.x) || !std::isfinite(normal.y) || !std::isfinite(normal.z)) {
    throw py::value_error("normal must be finite");
  }
  const double length = glm::length(normal);
  if (!(length > 0.0) || !std::isfinite(length)) throw py::value_error("normal must not be zero");
  return normal;
}

py::object fromVec3Rows(std::span<const glm::vec3> rows, bool noneIfEmpty) {
  return fromRows<3>(rows, noneIfEmpty);
}

py::object fromVec2Rows(std::span<const glm::vec2> rows, bool noneIfEmpty) {
  return fromRows<2>(rows, noneIfEmpty);
}

py::object fromTriangleList(std::span<const uint32_t> indices) {
  py::buffer_info info;
  py::object array = emptyArray(py::make_tuple(indices.size() / 3, 3), "int64", info);
  int64_t* data = static_cast<int64_t*>(info.ptr);
  for (size_t k = 0; k < indices.size() / 3 * 3; ++k) data[k] = indices[k];
  return array;
}

py::object fromVector(const glm::dvec3& v) {
  py::buffer_info info;
  py::object array = emptyArray(py::make_tuple(3), "float64", info);
  std::memcpy(info.ptr, &v[0], 3 * sizeof(double));
  return array;
}

py::object fromMatrix(const glm::dmat3& m) {
  py::buffer_info info;
  py::object array = emptyArray(py::make_tuple(3, 3), "float64", info);
  double* data = static_cast<double*>(info.ptr);
  for (int row = 0; row < 3; ++row) {
    for (int column = 0; column < 3; ++column)
      data[row * 3 + column] = m[column][row];  // glm: m[column][row]
  }
  return array;
}

py::object fromInt64(std::span<const int64_t> values) {
  py::buffer_info info;
  py::object array = emptyArray(py::make_tuple(values.size()), "int64", info);
  if (!values.empty()) std::memcpy(info.ptr, values.data(), values.size() * sizeof(int64_t));
  return array;
}

}  // namespace cleave::python
