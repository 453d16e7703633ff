// SPDX-License-Identifier: MIT
// Generational handles for physics objects (bodies, shapes, triggers, joints).
//
// A handle is an index into a slot table plus the generation the slot had when the object was
// created. Destroying an object bumps the slot's generation, so a handle kept after destroy is
// detected as stale by every PhysicsWorld call (which then returns false, nullopt or an error) even
// when the slot has been reused by a newer object. A default-constructed handle is null (generation
// 0) and never refers to anything. Handles are plain values: copy them freely, compare them, use
// them as ordered map keys. They are only meaningful for the PhysicsWorld that made them.
#pragma once

#include <compare>
#include <cstdint>

namespace cleave::physics {

template <class Tag>
struct Handle {
  uint32_t index = 0;
  uint32_t generation = 0;  // 0 = null handle; live objects have generation >= 1

  constexpr bool isNull() const { return generation == 0; }
  friend constexpr auto operator<=>(const Handle&, const Handle&) = default;
};

struct BodyTag;
struct ShapeTag;
struct TriggerTag;
struct JointTag;

using BodyId = Handle<BodyTag>;        // a rigid body (static or dynamic)
using ShapeId = Handle<ShapeTag>;      // a collision shape, shareable between bodies and triggers
using TriggerId = Handle<TriggerTag>;  // a sensor volume that reports touching bodies
using JointId = Handle<JointTag>;      // a constraint between two bodies (cone-twist or hinge)

}  // namespace cleave::physics
