// SPDX-License-Identifier: MIT
// The systems that run each tick beside the splits: entity transforms from their bodies (physics
// sync), meshes to the renderer (with static batches), and debris, pieces too small for a body.
#pragma once

#include <glm/glm.hpp>

namespace cleave::components {

struct SplitWorld;
class StaticBatches;  // static_batches.h

// Physics sync (PhysicsSync phase): entity transforms follow their bodies.
void syncTransformsFromBodies(SplitWorld& w);

// Render phase: submits every visible MeshRenderer at WorldTransform x meshOffset; with `batches`,
// its built batches, and not the pieces they cover.
void submitMeshes(SplitWorld& w, const StaticBatches* batches = nullptr);

// Debris: pieces without collider fall under gravity, come to rest on the first body at rest their
// path meets (the floor, a frozen or sleeping piece: a ray along each step's motion), shrink away in their last half second
// and vanish after a while.
struct Debris {
  glm::vec3 velocity{0.f};
  glm::vec3 angularVelocity{0.f};
  float secondsLeft = 3.f;
  float radius = 0.f;     // m, of a ball of the piece's volume: how far above a surface it rests
  bool landed = false;
};
void updateDebris(SplitWorld& w, float dt);

}  // namespace cleave::components
