// SPDX-License-Identifier: MIT
// Where the demo drops a spawned object: the first free spot in front of the player, so objects
// spawned one after another stand side by side instead of piling up at one point.
#pragma once

#include <span>

#include <glm/glm.hpp>

namespace cleave::demo {

// What already stands on the floor, seen from above: a circle on the (x, z) plane, metres.
struct FloorCircle {
  glm::vec2 centre{0.f};
  float radius = 0.f;
};

// Candidates lie in rows 2.5, 3.5 and 4.5 m ahead of `eye` along the horizontal `forward`, each row
// from its middle outwards at `spacing` (1.2 m), 5 to a row. The first candidate whose circle of
// `radius` clears every `occupied` circle by 0.1 m is returned; when none does, the candidate with the
// most clearance. `forward` need not be unit length; a zero one looks along -z. Pure, no allocation.
glm::vec2 freeSpawnSpot(glm::vec2 eye, glm::vec2 forward, float radius, std::span<const FloorCircle> occupied);

}  // namespace cleave::demo
