// SPDX-License-Identifier: MIT
// BodyDef and TriggerDef: checked descriptions of rigid bodies and sensor triggers.
//
// Units: metres, kilograms, seconds, radians; velocities in m/s and rad/s, world frame. The body
// origin is its centre of mass, so `position` is where the centre of mass is and the shape must be
// given relative to it. A def refers to a shape by handle; the body keeps the shape alive (shared,
// reference counted) until the body is destroyed, even if the shape handle is destroyed first.
#pragma once

#include <cstdint>
#include <optional>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "cleave/physics/physics_ids.h"

namespace cleave::physics {

struct BodyDef {
  ShapeId shape;
  float mass = 0.0f;  // kg; 0 = static (never moves), > 0 = dynamic
  glm::vec3 position{0.0f};                    // centre of mass in the world, metres
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // body frame to world; normalised by createBody
  glm::vec3 linearVelocity{0.0f};              // m/s, of the centre of mass
  glm::vec3 angularVelocity{0.0f};             // rad/s, world frame
  // Principal moments of inertia in kg m^2 about the centre of mass, along the body frame axes (the
  // body frame must then be the principal frame, e.g. PrincipalInertia::axes). Use it for the exact
  // inertia of a mesh; without it, Bullet's approximation for the shape is used (exact for box,
  // sphere and capsule; bounding-box based for hulls, compounds and meshes). Dynamic bodies only.
  std::optional<glm::vec3> localInertia;
  float friction = 0.5f;        // >= 0, Coulomb coefficient (combined by product)
  float restitution = 0.0f;     // [0, 1]
  float linearDamping = 0.0f;   // [0, 1], fraction of velocity lost per second
  float angularDamping = 0.0f;  // [0, 1]
  bool startAwake = true;       // false: the body starts asleep until touched or activated
  bool allowSleep = true;       // false: the body never goes to sleep
  // A body whose speeds stay below both thresholds for two seconds is ready to sleep; its island
  // sleeps when every body in it is (Bullet's rule). Defaults are Bullet's; jointed bodies that
  // jitter (ragdoll bones) need higher ones. Both finite and >= 0.
  // Continuous collision: a body that moves more than this radius (metres) in a step is swept as a
  // sphere of this radius against what it would pass through, so a small fast body does not tunnel
  // through a floor. 0 (the default): off. Finite and >= 0.
  float ccdRadius = 0.0f;
  float sleepLinearSpeed = 0.8f;   // m/s
  float sleepAngularSpeed = 1.0f;  // rad/s
  uint64_t userData = 0;        // opaque to physics (e.g. the entity id)
  // Bodies that share a non-zero group never collide with each other (the bones of one ragdoll,
  // whose capsules overlap at the joints); they still collide with every other body.
  uint64_t collisionGroup = 0;
  // A kinematic body (mass must be 0) is moved by setBodyTransform only: it pushes dynamic bodies,
  // is pushed by nothing, never sleeps, and reports the velocity implied by its last move (the
  // displacement between two steps over dt). Triggers see it like a dynamic body.
  bool kinematic = false;
};

// A sensor volume: it pushes nothing and reports the bodies whose shapes really touch it (narrow
// phase contact points), not those whose bounding boxes overlap it.
struct TriggerDef {
  ShapeId shape;  // Box, Sphere, Capsule, ConvexHull or Compound (meshes are refused)
  glm::vec3 position{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
  uint64_t userData = 0;
  // true: reports every step until destroyed. false: one-shot, reports the bodies touching it
  // during the first step after its creation, then is spent (leaves the collision world and reports
  // nothing more; the handle stays valid until destroyTrigger).
  bool persistent = true;
  bool detectStatic = false;  // also report static bodies (the ground, level geometry)
};

}  // namespace cleave::physics
