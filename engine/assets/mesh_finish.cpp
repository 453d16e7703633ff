// SPDX-License-Identifier: MIT
// The readers' common tail (see mesh_finish.h).
#include "cleave/assets/mesh_finish.h"

#include <cmath>

#include "cleave/assets/mesh_reader.h"

namespace cleave::assets::detail {

void normalizeNormals(MeshReadResult& result, const std::string& name) {
  std::vector<glm::vec3>& normals = result.mesh.normals;
  bool degenerate = false;
  for (glm::vec3& n : normals) {
    const float length = glm::length(n);
    if (length > 0.f && std::isfinite(length))
      n /= length;
    else
      degenerate = true;
  }
  if (degenerate) {
    normals.clear();
    result.warnings.push_back(name +
                              ": a normal has zero length or is not finite; normals dropped");
  }
}

namespace {

bool finite(const glm::vec2& v) { return std::isfinite(v.x) && std::isfinite(v.y); }
bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
bool finite(const glm::vec4& v) { return finite(glm::vec3(v)) && std::isfinite(v.w); }

template <typename T>
std::string checkAttribute(const std::vector<T>& values, size_t vertexCount, const char* what) {
  if (!values.empty() && values.size() != vertexCount) {
    return std::string(what) + " count differs from the vertex count";
  }
  for (size_t i = 0; i < values.size(); ++i) {
    if (!finite(values[i])) {
      return std::string(what) + " of vertex " + std::to_string(i) + " is not finite";
    }
  }
  return {};
}

}  // namespace

MeshReadResult finish(MeshReadResult result, const std::string& name) {
  const geometry::MeshData& mesh = result.mesh;
  const size_t vertexCount = mesh.positions.size();
  if (mesh.indices.empty()) {
    return failure(name, "no triangles in the file");
  }
  if (mesh.indices.size() % 3 != 0) {
    return failure(name, "index count is not a multiple of 3");
  }
  for (size_t i = 0; i < mesh.indices.size(); ++i) {
    if (mesh.indices[i] >= vertexCount) {
      return failure(name, "triangle " + std::to_string(i / 3) + ": vertex index " +
                               std::to_string(mesh.indices[i]) + " out of range (" +
                               std::to_string(vertexCount) + " vertices)");
    }
  }
  for (size_t i = 0; i < vertexCount; ++i) {
    if (!finite(mesh.positions[i])) {
      return failure(name, "vertex " + std::to_string(i) + " has a non-finite coordinate");
    }
  }
  std::string problem = checkAttribute(mesh.normals, vertexCount, "normal");
  if (problem.empty()) problem = checkAttribute(mesh.uv0, vertexCount, "texture coordinate");
  if (problem.empty()) problem = checkAttribute(mesh.colors, vertexCount, "colour");
  if (!problem.empty()) return failure(name, problem);
  if (!mesh.submeshes.empty()) {
    uint64_t next = 0;
    for (const geometry::SubMesh& sub : mesh.submeshes) {
      if (sub.firstIndex != next || sub.indexCount % 3 != 0) {
        return failure(name, "material runs do not cover the triangles in order");
      }
      next += sub.indexCount;
    }
    if (next != mesh.indices.size()) {
      return failure(name, "material runs do not cover the triangles in order");
    }
  }
  if (result.materialNames.empty()) result.materialNames.push_back("default");
  result.code = base::StatusCode::Ok;
  result.message.clear();
  return result;
}

}  // namespace cleave::assets::detail
