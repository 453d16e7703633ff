// SPDX-License-Identifier: MIT
// The readers report every failure as one line; the binding tells a file system failure (OSError,
// with errno so Python picks the subclass) from a refused file (ValueError) by opening the file
// first.
#include "python/mesh_io_binding.h"

#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <string>

#include <pybind11/stl/filesystem.h>

#include "cleave/assets/mesh_io.h"
#include "python/numpy_arrays.h"

namespace cleave::python {
namespace {

namespace assets = cleave::assets;
namespace geometry = cleave::geometry;

[[noreturn]] void raiseOsError(int error, const std::string& path) {
  errno = error;
  PyErr_SetFromErrnoWithFilename(PyExc_OSError, path.c_str());
  throw py::error_already_set();
}

[[noreturn]] void raiseOsError(const std::string& message) {
  PyErr_SetString(PyExc_OSError, message.c_str());
  throw py::error_already_set();
}

// OSError unless `path` names a regular file that can be opened for reading.
void checkReadable(const std::string& path) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) raiseOsError(ENOENT, path);
  if (std::filesystem::is_directory(status)) raiseOsError(EISDIR, path);
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) raiseOsError(errno, path);
  std::fclose(file);
}

py::tuple readMesh(const std::filesystem::path& file) {
  const std::string path = file.string();
  if (assets::formatFromPath(path) == assets::MeshFormat::Unknown) {
    throw py::value_error(path +
                          ": unknown mesh format (read_mesh reads .obj .off .stl .ply .gltf .glb)");
  }
  checkReadable(path);
  assets::MeshReadResult loaded;
  {
    py::gil_scoped_release release;
    loaded = assets::loadMesh(path);
  }
  if (!loaded.ok()) throw py::value_error(loaded.message);
  const geometry::MeshData& mesh = loaded.mesh;
  return py::make_tuple(fromVec3Rows(mesh.positions, false), fromTriangleList(mesh.indices),
                        fromVec3Rows(mesh.normals, true), fromVec2Rows(mesh.uv0, true));
}

void writeMesh(const std::filesystem::path& file, py::handle vertices, py::handle faces,
               py::handle normals, py::handle uvs) {
  const std::string path = file.string();
  const assets::MeshFormat format = assets::formatFromPath(path);
  if (format != assets::MeshFormat::Obj && format != assets::MeshFormat::Glb) {
    throw py::value_error(path + ": write_mesh writes .obj and .glb files");
  }
  geometry::MeshData mesh;
  mesh.positions = toVec3Rows(vertices, "vertices");
  mesh.indices = toTriangleList(faces, mesh.positions.size());
  if (!normals.is_none()) mesh.normals = toVec3Rows(normals, "normals", mesh.positions.size());
  if (!uvs.is_none()) mesh.uv0 = toVec2Rows(uvs, "uvs", mesh.positions.size());
  const std::filesystem::path parent = file.parent_path();
  std::error_code ec;
  if (!parent.empty() && !std::filesystem::is_directory(parent, ec))
    raiseOsError(ENOENT, parent.string());
  if (std::filesystem::is_directory(file, ec)) raiseOsError(EISDIR, path);
  assets::MeshWriteResult written;
  {
    py::gil_scoped_release release;
    const assets::MeshWriteOptions options;
    written = format == assets::MeshFormat::Obj ? assets::writeObj(path, mesh, options)
                                                : assets::writeGlb(path, mesh, options);
  }
  if (!written.ok()) raiseOsError(written.message);
}

constexpr const char* kReadDoc = R"doc(read_mesh(path) -> (vertices, faces, normals, uvs)

Read a mesh file with the engine's readers, chosen by the extension (case-insensitive): .obj,
.off, .stl (ascii or binary), .ply (ascii or binary), .gltf and .glb (the default scene's static
meshes, node transforms applied). Polygons are triangulated; winding is counter-clockwise seen
from outside.

Returns vertices (N x 3 float32), faces (M x 3 int64), normals (N x 3 float32 or None) and uvs
(N x 2 float32 or None).
Raises OSError (FileNotFoundError, IsADirectoryError, PermissionError) when the file cannot be
opened, ValueError for an unknown extension or a file the reader refuses, with its reason.)doc";

constexpr const char* kWriteDoc =
    R"doc(write_mesh(path, vertices, faces, normals=None, uvs=None) -> None

Write a mesh as Wavefront OBJ (.obj) or binary glTF (.glb), chosen by the extension, with the
engine's writers (the ones cleave-split --out uses). The arrays are checked as in cleave.split.
Raises ValueError for another extension or bad arrays, OSError when the file cannot be written
(its folder missing, no permission).)doc";

}  // namespace

void bindMeshIo(py::module_& module) {
  module.def("read_mesh", &readMesh, kReadDoc, py::arg("path"));
  module.def("write_mesh", &writeMesh, kWriteDoc, py::arg("path"), py::arg("vertices"),
             py::arg("faces"), py::arg("normals") = py::none(), py::arg("uvs") = py::none());
}

}  // namespace cleave::python
