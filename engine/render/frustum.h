// SPDX-License-Identifier: MIT
// Frustum: the six planes of a view-projection matrix (OpenGL clip space, -w <= x, y, z <= w), to
// leave out of a pass what cannot reach its image. A bounding sphere is outside when it lies wholly
// behind one plane; the test is conservative (a sphere near a corner may pass and be clipped by the
// rasterizer), never the other way, so culling never changes a picture.
#pragma once

#include <algorithm>
#include <array>
#include <utility>

#include <glm/glm.hpp>

namespace cleave::render {

struct Frustum {
  std::array<glm::vec4, 6> planes{};  // (normal, d): inside where dot(normal, p) + d >= 0, normal unit

  static Frustum fromMatrix(const glm::mat4& m) {
    const glm::vec4 row0(m[0][0], m[1][0], m[2][0], m[3][0]);
    const glm::vec4 row1(m[0][1], m[1][1], m[2][1], m[3][1]);
    const glm::vec4 row2(m[0][2], m[1][2], m[2][2], m[3][2]);
    const glm::vec4 row3(m[0][3], m[1][3], m[2][3], m[3][3]);
    Frustum f;
    f.planes = {row3 + row0, row3 - row0, row3 + row1, row3 - row1, row3 + row2, row3 - row2};
    for (glm::vec4& p : f.planes) {
      const float length = glm::length(glm::vec3(p));
      if (length > 0.f) p /= length;
    }
    return f;
  }

  bool touchesSphere(const glm::vec3& centre, float radius) const {
    for (const glm::vec4& p : planes)
      if (glm::dot(glm::vec3(p), centre) + p.w < -radius) return false;
    return true;
  }
};

// A mesh-space bounding sphere carried into world space by `model` (its radius by the largest
// scale of the model's axes).
inline std::pair<glm::vec3, float> worldSphere(const glm::mat4& model, const glm::vec3& centre, float radius) {
  const float scale = std::max({glm::length(glm::vec3(model[0])), glm::length(glm::vec3(model[1])),
                                glm::length(glm::vec3(model[2]))});
  return {glm::vec3(model * glm::vec4(centre, 1.f)), radius * scale};
}

}  // namespace cleave::render
