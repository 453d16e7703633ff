// SPDX-License-Identifier: MIT
// The arena's floor plan, shared by the files of ArenaGame: its size and the two directions on the
// sand. Units: metres and radians; the floor is the plane y = 0, seen from above north is -z, east +x.
#pragma once

#include <cmath>

#include <glm/glm.hpp>

namespace cleave::arena {

inline constexpr float kPi = 3.14159265358979f;
inline constexpr float kArenaRadius = 12.0f;  // m, the inner face of the wall
inline constexpr float kPlayerRadius = 0.35f;  // m, the player's circle on the floor

// Compass direction on the floor: angle 0 is north (-z), pi/2 east (+x); the four gates are at
// 0, pi/2, pi and 3 pi / 2.
inline glm::vec2 compass(float angle) { return glm::vec2(std::sin(angle), -std::cos(angle)); }

// The floor direction a figure with this yaw faces: (sin yaw, cos yaw), yaw 0 facing +z (south).
inline glm::vec2 forwardOf(float yaw) { return glm::vec2(std::sin(yaw), std::cos(yaw)); }

}  // namespace cleave::arena
