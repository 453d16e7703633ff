// SPDX-License-Identifier: MIT
#include "game/demo/spawn_spots.h"

#include <cmath>
#include <limits>

namespace cleave::demo {

namespace {

constexpr float kRows[] = {2.5f, 3.5f, 4.5f};
constexpr float kSpacing = 1.2f;
constexpr int kPerRow = 5;
constexpr float kGap = 0.1f;

// Distance from the edge of a circle of `radius` at `at` to the nearest occupied edge (negative:
// they overlap); +infinity on an empty floor.
float clearance(glm::vec2 at, float radius, std::span<const FloorCircle> occupied) {
  float least = std::numeric_limits<float>::infinity();
  for (const FloorCircle& c : occupied) least = std::fmin(least, glm::length(at - c.centre) - c.radius - radius);
  return least;
}

}  // namespace

glm::vec2 freeSpawnSpot(glm::vec2 eye, glm::vec2 forward, float radius, std::span<const FloorCircle> occupied) {
  const float length = glm::length(forward);
  const glm::vec2 ahead = length > 1e-6f ? forward / length : glm::vec2(0.f, -1.f);
  const glm::vec2 side(-ahead.y, ahead.x);
  glm::vec2 best = eye + ahead * kRows[0];
  float bestClearance = -std::numeric_limits<float>::infinity();
  for (float row : kRows) {
    for (int k = 0; k < kPerRow; ++k) {
      // 0, +1, -1, +2, -2 spacings from the row's middle.
      const float offset = float((k + 1) / 2) * (k % 2 == 1 ? 1.f : -1.f) * kSpacing;
      const glm::vec2 at = eye + ahead * row + side * offset;
      const float free = clearance(at, radius, occupied);
      if (free >= kGap) return at;
      if (free > bestClearance) {
        bestClearance = free;
        best = at;
      }
    }
  }
  return best;
}

}  // namespace cleave::demo
