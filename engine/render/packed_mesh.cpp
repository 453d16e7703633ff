// SPDX-License-Identifier: MIT
#include "cleave/render/packed_mesh.h"

#include <cstring>

namespace cleave::render {

PackedMesh packMesh(const geometry::MeshData& mesh) {
  PackedMesh out;
  const size_t n = mesh.positions.size();
  if (n == 0 || mesh.indices.empty() || mesh.indices.size() % 3 != 0) {
    out.setFailure(base::StatusCode::InvalidArgument, "mesh has no triangles");
    return out;
  }
  for (uint32_t i : mesh.indices) {
    if (i >= n) {
      out.setFailure(base::StatusCode::InvalidArgument, "mesh index out of range");
      return out;
    }
  }
  // Flat normals when the mesh has none: accumulate face normals per vertex.
  std::vector<glm::vec3> computed;
  if (mesh.normals.size() != n) {
    computed.assign(n, glm::vec3(0.f));
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      const glm::vec3 a = mesh.positions[mesh.indices[t]], b = mesh.positions[mesh.indices[t + 1]],
                      c = mesh.positions[mesh.indices[t + 2]];
      const glm::vec3 fn = glm::cross(b - a, c - a);
      for (int k = 0; k < 3; ++k) computed[mesh.indices[t + k]] += fn;
    }
    for (auto& v : computed) {
      const float len = glm::length(v);
      v = len > 0.f ? v / len : glm::vec3(0, 1, 0);
    }
  }
  const std::vector<glm::vec3>& normals = computed.empty() ? mesh.normals : computed;
  out.vertices.resize(n * 12);
  for (size_t i = 0; i < n; ++i) {
    float* v = &out.vertices[i * 12];
    std::memcpy(v, &mesh.positions[i], 12);
    std::memcpy(v + 3, &normals[i], 12);
    const glm::vec2 uv = mesh.uv0.size() == n ? mesh.uv0[i] : glm::vec2(0.f);
    v[6] = uv.x;
    v[7] = uv.y;
    const glm::vec4 t = mesh.tangents.size() == n ? mesh.tangents[i] : glm::vec4(1, 0, 0, 1);
    std::memcpy(v + 8, &t, 16);
  }
  if (mesh.joints.size() == n && mesh.weights.size() == n) {
    out.skin.resize(n);
    for (size_t i = 0; i < n; ++i) {
      out.skin[i].joints = glm::min(mesh.joints[i], glm::u16vec4(uint16_t(kMaxSkinJoints - 1)));
      out.skin[i].weights = mesh.weights[i];
    }
  }
  out.indices = mesh.indices;
  if (mesh.submeshes.empty()) {
    out.submeshes.push_back({0, uint32_t(mesh.indices.size()), 0});
  } else {
    for (const auto& s : mesh.submeshes) {
      if (s.indexCount == 0 || uint64_t(s.firstIndex) + s.indexCount > mesh.indices.size()) continue;
      out.submeshes.push_back(s);
    }
  }
  return out;
}

}  // namespace cleave::render
