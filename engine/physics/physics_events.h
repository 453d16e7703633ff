// SPDX-License-Identifier: MIT
// Results of a physics step and of queries, as plain values.
//
// Event arrays are rebuilt by each PhysicsWorld::step and sorted deterministically (by the handle
// indices involved), so two runs with the same calls give the same arrays in the same order.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "cleave/physics/physics_ids.h"

namespace cleave::physics {

enum class TriggerEventKind : uint8_t {
  Begin,  // the body touches the trigger this step and did not in the previous step
  Stay,   // the body touched it in the previous step too
  End,    // the body touched it in the previous step and no longer does (not sent for bodies or
          // triggers destroyed in between)
};
const char* toString(TriggerEventKind kind);

struct TriggerEvent {
  TriggerId trigger;
  BodyId body;
  TriggerEventKind kind = TriggerEventKind::Begin;
};

// One per touching pair of bodies (a static-dynamic pair included), with bodyA.index < bodyB.index.
struct ContactEvent {
  BodyId bodyA;
  BodyId bodyB;
  glm::vec3 point{0.0f};   // world, the deepest contact point (midway between the two surfaces)
  glm::vec3 normal{0.0f};  // world, unit, pointing from bodyA towards bodyB
  float impulse = 0.0f;    // N s, sum of the normal impulses the solver applied this step (>= 0)
  float depth = 0.0f;      // metres, deepest penetration (>= 0)
  uint32_t pointCount = 0; // contact points of the pair
};

struct RayHit {
  BodyId body;
  glm::vec3 point{0.0f};   // world
  glm::vec3 normal{0.0f};  // world, unit, facing the ray origin
  float fraction = 0.0f;   // [0, 1] along from -> to
};

struct BodyTransform {
  glm::vec3 position{0.0f};                    // centre of mass, metres
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // body frame to world
};

// Everything a state dump needs about one body.
struct BodyState {
  BodyTransform transform;
  glm::vec3 linearVelocity{0.0f};   // m/s
  glm::vec3 angularVelocity{0.0f};  // rad/s, world frame
  float mass = 0.0f;                // kg, 0 for static bodies
  bool awake = false;               // false for static and sleeping bodies
  uint64_t userData = 0;
};

}  // namespace cleave::physics
