// SPDX-License-Identifier: MIT
// PhysicsWorld: the Bullet bridge. Rigid bodies, shared collision shapes, sensor triggers, ray
// casts, and contact/trigger events read as plain arrays after each step.
//
// Model: Box2D v3 / Jolt style. Everything is addressed by generational handles (physics_ids.h);
// creation goes through checked defs (shape_def.h, body_def.h) and returns a Result with a reason
// on failure; queries with a stale handle return false / nullopt. Nothing in here throws or crashes
// on bad input. Bullet types never leave engine/physics.
//
// Stepping: step(dt) advances exactly one fixed substep of dt seconds (no accumulator, no
// interpolation); the caller owns the fixed-tick loop. Determinism: the same sequence of calls on a
// fresh world gives bit-identical transforms, velocities and events (Bullet's solver is run without
// randomisation; all outputs are ordered by handle index).
//
// Ownership: the world owns every Bullet object. Shapes are reference counted: the shape handle
// holds one reference, every body or trigger using the shape holds one; the shape is freed when the
// handle was destroyed and the last user is gone. Destroying the world frees everything.
//
// Not thread-safe: use one world from one thread at a time.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "cleave/physics/body_def.h"
#include "cleave/physics/joint_def.h"
#include "cleave/physics/physics_events.h"
#include "cleave/physics/physics_ids.h"
#include "cleave/physics/physics_result.h"
#include "cleave/physics/shape_def.h"

namespace cleave::physics {

struct WorldDef {
  glm::vec3 gravity{0.0f, -9.81f, 0.0f};  // m/s^2
  int solverIterations = 10;              // sequential impulse iterations per step, >= 1
};

class PhysicsWorld {
 public:
  // An invalid def (non-finite gravity, iterations < 1) is clamped to the defaults; use
  // setGravity afterwards to get a status.
  explicit PhysicsWorld(const WorldDef& def = {});
  ~PhysicsWorld();
  PhysicsWorld(const PhysicsWorld&) = delete;
  PhysicsWorld& operator=(const PhysicsWorld&) = delete;
  // A moved-from world may only be destroyed or assigned to.
  PhysicsWorld(PhysicsWorld&&) noexcept;
  PhysicsWorld& operator=(PhysicsWorld&&) noexcept;

  // ---- world ----
  // Fails (InvalidArgument) on a non-finite vector. Wakes nothing; sleeping bodies keep sleeping.
  PhysicsStatus setGravity(glm::vec3 gravity);
  glm::vec3 gravity() const;
  // One substep of dt seconds. Fails (InvalidArgument) unless 0 < dt <= 1 and finite; then nothing
  // moves and the event arrays are emptied. Rebuilds contactEvents() and triggerEvents().
  PhysicsStatus step(double dt);
  uint64_t stepCount() const;  // successful steps so far

  // ---- shapes ----
  // Validates the def (see shape_def.h) and builds the shape. Errors: InvalidArgument,
  // DegenerateShape.
  Result<ShapeId> createShape(const ShapeDef& def);
  // Releases the handle's reference; the shape lives on while bodies or triggers use it. Returns
  // false for a stale handle.
  bool destroyShape(ShapeId shape);
  bool isValid(ShapeId shape) const;
  std::optional<ShapeType> shapeType(ShapeId shape) const;
  // Collision margin of a convex shape (the hull margin chosen by createShape), metres; for meshes
  // the triangle margin. nullopt for a stale handle.
  std::optional<float> shapeMargin(ShapeId shape) const;
  // Vertex count of a convex hull after reduction and shrinking (0 for other shapes).
  std::optional<uint32_t> hullVertexCount(ShapeId shape) const;
  // Shapes still allocated, including those whose handle was destroyed but that bodies still use.
  uint32_t liveShapeCount() const;

  // ---- bodies ----
  // Errors: StaleHandle (shape), InvalidArgument (non-finite or out-of-range values, inertia with
  // mass 0), UnsupportedCombination (StaticMesh with mass > 0).
  Result<BodyId> createBody(const BodyDef& def);
  // Removes the body from the world, with its contacts and every joint attached to it. Returns
  // false for a stale handle.
  bool destroyBody(BodyId body);
  bool isValid(BodyId body) const;
  uint32_t bodyCount() const;

  std::optional<BodyTransform> bodyTransform(BodyId body) const;
  std::optional<glm::vec3> linearVelocity(BodyId body) const;
  std::optional<glm::vec3> angularVelocity(BodyId body) const;
  std::optional<BodyState> bodyState(BodyId body) const;
  std::optional<float> bodyMass(BodyId body) const;  // kg, 0 for static
  // Principal moments in kg m^2 in the body frame as used by the solver (0 for static).
  std::optional<glm::vec3> bodyLocalInertia(BodyId body) const;
  std::optional<uint64_t> bodyUserData(BodyId body) const;
  // False for static bodies, sleeping bodies and stale handles.
  bool isAwake(BodyId body) const;

  // True for a body created with BodyDef::kinematic.
  bool isKinematic(BodyId body) const;

  // Teleports the body (centre of mass) and wakes it. For a kinematic body this is how it moves: the
  // next step derives its velocity from the move. False for a stale handle or a non-finite
  // transform; a zero quaternion is refused, others are normalised.
  bool setBodyTransform(BodyId body, const BodyTransform& transform);
  // Sets both velocities and wakes the body. False for stale handles, static bodies or non-finite
  // values.
  bool setVelocity(BodyId body, glm::vec3 linear, glm::vec3 angular);
  // Applies an impulse (N s) at a world point, changing linear and angular velocity, and wakes the
  // body. False for stale handles, static bodies or non-finite values.
  bool applyImpulse(BodyId body, glm::vec3 impulse, glm::vec3 worldPoint);
  // Wakes a sleeping body (a frozen one is thawed first). False for stale handles and static bodies.
  bool activate(BodyId body);

  // ---- freezing (bodies a game stops simulating but keeps in the world) ----
  // A frozen dynamic body leaves the simulation where it is: it becomes a static collider (awake
  // bodies rest on it and bounce off it; it never moves), its velocities are zeroed, and its mass and
  // inertia are kept for its return. It never pairs with static or other frozen bodies, so a heap of
  // frozen bodies costs the broadphase and the solver nothing among itself, while triggers and ray
  // casts still see it. setFrozen(body, false) returns it to the simulation awake and at rest;
  // setVelocity, applyImpulse and activate thaw a frozen body first. Freezing a frozen body (or
  // thawing a thawed one) changes nothing and returns true. False for stale handles, static,
  // kinematic and jointed bodies (a joint needs both of its bodies simulated).
  bool setFrozen(BodyId body, bool frozen);
  bool isFrozen(BodyId body) const;
  uint32_t frozenBodyCount() const;

  // The interval [min, max] (x, y) covered by the body's collision shape, margin included, along a
  // world direction (need not be unit; the interval is in units of its length): the plane
  // dot(direction, x) = d crosses the body when min < d < max. Hulls and compounds of hulls are
  // projected exactly; other shapes by their world bounding box (a wider interval). nullopt for a
  // stale handle or a zero or non-finite direction.
  std::optional<glm::vec2> extentAlong(BodyId body, glm::vec3 direction) const;
  // The body's world bounding box (min, max) as the broadphase holds it, margins included.
  std::optional<std::pair<glm::vec3, glm::vec3>> bodyBounds(BodyId body) const;
  // Bodies whose broadphase bounds overlap the box [lo, hi] (static, sleeping and frozen ones
  // included; triggers not), in handle order.
  std::vector<BodyId> bodiesInBox(glm::vec3 lo, glm::vec3 hi) const;

  // ---- joints (constraints between two bodies, see joint_def.h) ----
  // Errors: StaleHandle (a body), InvalidArgument (same body twice, both bodies static or
  // kinematic, non-finite frames, a zero quaternion, spans or limits out of range).
  Result<JointId> createJoint(const JointDef& def);
  // Removes the constraint. False for a stale handle (also after one of its bodies was destroyed,
  // which destroys the joint with it).
  bool destroyJoint(JointId joint);
  bool isValid(JointId joint) const;
  uint32_t jointCount() const;
  // The joint's frames in the world now; nullopt for a stale handle.
  std::optional<JointState> jointState(JointId joint) const;

  // ---- triggers ----
  // Errors: StaleHandle (shape), InvalidArgument, UnsupportedCombination (mesh shapes).
  Result<TriggerId> createTrigger(const TriggerDef& def);
  bool destroyTrigger(TriggerId trigger);
  bool isValid(TriggerId trigger) const;
  uint32_t triggerCount() const;  // triggers not destroyed yet (spent one-shot triggers included)
  // Moves the trigger (e.g. a blade); the new pose is used by the next step.
  bool setTriggerTransform(TriggerId trigger, const BodyTransform& transform);
  std::optional<BodyTransform> triggerTransform(TriggerId trigger) const;
  std::optional<uint64_t> triggerUserData(TriggerId trigger) const;
  // True once a one-shot trigger has had its step. False for persistent and stale triggers.
  bool isTriggerSpent(TriggerId trigger) const;

  // ---- events of the last step (views stay valid until the next step or destroy call) ----
  std::span<const TriggerEvent> triggerEvents() const;
  std::span<const ContactEvent> contactEvents() const;

  // ---- queries ----
  // Closest body hit by the segment from -> to (triggers are ignored). nullopt when nothing is hit
  // or the segment is degenerate/non-finite.
  std::optional<RayHit> raycast(glm::vec3 from, glm::vec3 to) const;

  // FNV-1a over the bit patterns of every live body's handle, transform and velocities in index
  // order: equal hashes from two runs mean bit-identical simulations.
  uint64_t stateHash() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cleave::physics
