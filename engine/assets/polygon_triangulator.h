// SPDX-License-Identifier: MIT
// Internal to engine/assets: triangulation of the polygon faces of the text mesh formats.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "cleave/geometry/cap_triangulator.h"

namespace cleave::assets::detail {

// Triangulates the polygon faces of a file. A convex face is fanned from its first corner; any
// other face is ear-clipped in its plane, because the fan of a concave face folds over itself and
// makes the mesh intersect itself (see geometry::CapTriangulator::triangulateFace). Scratch memory
// is kept between faces.
class PolygonTriangulator {
 public:
  // Appends the triangles of the face whose vertices are `polygon` to `indices`; corners[k] is the
  // position of polygon[k]. When corners does not give one position per vertex the face is fanned.
  void append(std::span<const uint32_t> polygon, std::span<const glm::vec3> corners,
              std::vector<uint32_t>& indices);
  // The same with the corners looked up in `positions`. A face with a vertex that has no position
  // yet (a PLY file may list its faces before its vertices) is fanned; the index check of
  // finish() reports a vertex that never comes.
  void appendIndexed(std::span<const uint32_t> polygon, std::span<const glm::vec3> positions,
                     std::vector<uint32_t>& indices);

 private:
  geometry::CapTriangulator triangulator_;
  std::vector<uint32_t> triangles_;
  std::vector<glm::vec3> corners_;
};

}  // namespace cleave::assets::detail
