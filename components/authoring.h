// SPDX-License-Identifier: MIT
// Authoring: what a level or a game makes before anything is cut. Splitter entities with their
// triggers, bodies for authored objects (one mesh, or a parent and the meshes of its children) from
// their meshes' exact mass properties, the physics shape of a planned collider, and an entity put
// on the body made for it. Split commits use the last two for the pieces' bodies.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "cleave/base/status.h"
#include "cleave/components/scene_components.h"
#include "cleave/components/split_job.h"
#include "cleave/components/splitable.h"
#include "cleave/ecs/world.h"
#include "cleave/geometry/mass_properties.h"
#include "cleave/physics/physics_world.h"

namespace cleave::components {

struct SplitWorld;
class SplitSystem;

// Creates a splitter entity (Name, Transform, WorldTransform and `splitter`, whose lifetime and
// player flag are kept) with a trigger of `shape` at `position`/`rotation`: persistent for a
// persistent splitter, one-shot otherwise. Its plane is the local +Y axis through `position`.
// Returns kNullEntity, creating nothing, when the shape cannot be built.
ecs::Entity createSplitter(SplitWorld& w, const std::string& name, const physics::ShapeDef& shape,
                           const glm::vec3& position, const glm::quat& rotation, Splitter splitter);

// Creates the rigid body and collider for an authored object with a MeshRenderer, from its mesh's
// exact mass properties (density from its Splitable, or `density`). Sets RigidBody, MassInfo and the
// mesh offset so the body origin is the centre of mass. InvalidArgument with a reason on failure
// (no mesh, no volume, no collider, a body the bridge refuses).
// With `splits`, the collider parts come from its cache (shared by every instance of the mesh) and
// the entity keeps them (ColliderParts) for its cuts.
base::Status makeDynamicBody(SplitWorld& w, ecs::Entity e, double density, ColliderMode collider,
                             SplitSystem* splits = nullptr);

// The physics shape of a planned collider (hulls: one prepared hull or a compound of them; or the
// concave mesh). The bridge's status with the reason when none can be built (DegenerateShape when
// there is no part at all).
physics::Result<physics::ShapeId> createPlannedShape(physics::PhysicsWorld& physics,
                                                     const std::vector<HullSpec>& hulls,
                                                     const std::vector<glm::vec3>& concavePositions,
                                                     const std::vector<uint32_t>& concaveIndices);

// Puts an authored entity on the body just made for it: its Transform moves to the body's pose
// (unit scale) and it gets RigidBody and MassInfo (mass, volume, density, closed from `props`).
// The mesh offset is the caller's.
void placeOnBody(SplitWorld& w, ecs::Entity e, const physics::BodyDef& def, physics::BodyId body,
                 physics::ShapeId shape, double mass, const geometry::MassProperties& props, double density);

}  // namespace cleave::components
