// SPDX-License-Identifier: MIT
// Polygon faces to triangles (see polygon_triangulator.h).
#include "cleave/assets/polygon_triangulator.h"

namespace cleave::assets::detail {

void PolygonTriangulator::append(std::span<const uint32_t> polygon,
                                 std::span<const glm::vec3> corners,
                                 std::vector<uint32_t>& indices) {
  if (polygon.size() == 3 || corners.size() != polygon.size()) {
    for (size_t k = 1; k + 1 < polygon.size(); ++k) {
      indices.insert(indices.end(), {polygon[0], polygon[k], polygon[k + 1]});
    }
    return;
  }
  triangles_.clear();
  triangulator_.triangulateFace(corners, triangles_);
  for (uint32_t k : triangles_) indices.push_back(polygon[k]);
}

void PolygonTriangulator::appendIndexed(std::span<const uint32_t> polygon,
                                        std::span<const glm::vec3> positions,
                                        std::vector<uint32_t>& indices) {
  corners_.clear();
  for (uint32_t id : polygon) {
    if (id < positions.size()) corners_.push_back(positions[id]);
  }
  append(polygon, corners_, indices);
}

}  // namespace cleave::assets::detail
