// SPDX-License-Identifier: MIT
// MeshData: the plain triangle mesh that flows through the whole split core.
//
// Units: metres. Winding: triangles are counter-clockwise seen from outside (their normal, by the
// right-hand rule, points out of the solid). Every per-vertex array is either empty (the attribute is
// absent) or has exactly positions.size() entries. Indices form a triangle list (a multiple of 3).
// The mesh owns its arrays; nothing in here points elsewhere.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/type_precision.hpp>

namespace cleave::geometry {

// A contiguous run of the index array drawn with one material.
struct SubMesh {
  uint32_t firstIndex = 0;  // into MeshData::indices; a multiple of 3
  uint32_t indexCount = 0;  // a multiple of 3
  uint32_t materialId = 0;  // opaque to the split core; the cap submesh carries the cap material id
};

struct MeshData {
  std::vector<glm::vec3> positions;  // required
  std::vector<glm::vec3> normals;    // unit length, optional
  std::vector<glm::vec4> tangents;   // xyz unit tangent, w = handedness (+1 or -1), optional
  std::vector<glm::vec2> uv0;        // optional
  std::vector<glm::vec2> uv1;        // optional
  std::vector<glm::vec4> colors;     // linear RGBA, optional
  std::vector<glm::u16vec4> joints;  // skin joint indices (4 influences), optional
  std::vector<glm::vec4> weights;    // skin weights summing to 1, optional (present iff joints is)
  std::vector<uint32_t> indices;     // triangle list, counter-clockwise seen from outside
  // Material runs over `indices`, in order, covering it without gaps. Empty means one run of
  // material 0 over all indices.
  std::vector<SubMesh> submeshes;

  size_t vertexCount() const { return positions.size(); }
  size_t triangleCount() const { return indices.size() / 3; }
  bool empty() const { return indices.empty(); }
};

}  // namespace cleave::geometry
