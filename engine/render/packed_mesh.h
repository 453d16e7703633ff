// SPDX-License-Identifier: MIT
// PackedMesh: a mesh in the vertex layout the renderer uploads, worked out on the CPU without GL,
// so it can be prepared on any thread (the split pipeline packs piece meshes on its workers) and
// handed to Renderer::uploadPacked on the GL thread, which then only copies buffers.
//
// Layout: 12 floats per vertex (position xyz, normal xyz, uv0, tangent xyzw); without normals the
// mesh gets area-weighted vertex normals, without uv0 (0, 0), without tangents (1, 0, 0, 1). A
// skinned mesh (joints and weights on every vertex) adds 4 unsigned shorts of joints, clamped to
// kMaxSkinJoints - 1, and 4 float weights per vertex. Failure: packMesh returns a PackedMesh with
// `error` set (no triangles, an index out of range) and no data.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cleave/base/status.h"
#include "cleave/geometry/mesh_data.h"

namespace cleave::render {

// Joint matrices a skinned draw can use (the size of the shaders' uniform array). Joint ids at or
// above it are clamped to the last one at upload; skeletons that large need splitting into parts.
inline constexpr uint32_t kMaxSkinJoints = 128;

// The GPU layout of a mesh, and a Status saying why it could not be packed (ok when it could).
struct PackedMesh : base::Status {
  struct SkinVertex {
    glm::u16vec4 joints;
    glm::vec4 weights;
  };
  std::vector<float> vertices;        // 12 per vertex
  std::vector<SkinVertex> skin;       // per vertex, or empty
  std::vector<uint32_t> indices;      // triangle list
  std::vector<geometry::SubMesh> submeshes;  // valid runs only; one run of material 0 when the mesh has none
  size_t vertexCount() const { return vertices.size() / 12; }
};

PackedMesh packMesh(const geometry::MeshData& mesh);

}  // namespace cleave::render
