// SPDX-License-Identifier: MIT
// Plain-struct components shared by the demos: what an entity looks like and how it moves.
// They hold handles into the renderer and the physics world, never GL or Bullet objects.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cleave/components/piece_budget.h"
#include "cleave/ecs/entity.h"
#include "cleave/geometry/collider_parts.h"
#include "cleave/geometry/mesh_data.h"
#include "cleave/physics/physics_ids.h"
#include "cleave/render/renderer.h"

namespace cleave::components {

// A mesh drawn at the entity's world transform times `meshOffset`. `source` is the CPU copy the
// splitter cuts; it is shared (immutable) between the entity and the renderer upload.
struct MeshRenderer {
  // Immutable once shared: the split system keeps derived data (the weld) per mesh. To change a
  // mesh, make a new one.
  std::shared_ptr<const geometry::MeshData> source;
  render::MeshHandle gpu;
  std::vector<render::Material> materials;  // indexed by submesh material id
  glm::mat4 meshOffset{1.f};                // mesh space -> entity space (scale, centre of mass shift)
  bool visible = true;
};

// The rigid body that moves the entity: the entity Transform follows the body (origin at the centre
// of mass, axes along the principal axes of inertia).
struct RigidBody {
  physics::BodyId body;
  physics::ShapeId shape;
  // The body was awake at the last transform sync (syncTransformsFromBodies reads sleeping and
  // frozen bodies once more after they stop, then leaves them alone until they wake).
  bool moving = true;
};

// The convex parts the entity's collider is made of, in the mesh space of its MeshRenderer::source
// (shared, immutable). A cut clips them by its plane into the pieces (geometry/collider_parts.h), so
// the pieces' colliders are never decomposed again.
struct ColliderParts {
  geometry::SharedColliderParts parts;
};

// Mass properties as the split system computed them (world units at the time of creation).
struct MassInfo {
  double mass = 0.0;        // kg
  double volume = 0.0;      // m^3
  double density = 0.0;     // kg/m^3
  bool closed = true;       // the mesh was closed (otherwise its convex hull gave the values)
};

// Where an entity came from: the entity it was split from (null for authored objects) and how many
// cuts deep it is.
struct SplitOrigin {
  ecs::Entity parent;
  uint64_t parentId = 0;    // the parent's id as written in the state dump
  uint32_t generation = 0;  // 0 for authored objects, +1 per cut
  uint64_t tick = 0;        // the tick the piece was made in (the piece budget's age)
  // How the piece budget retires it (piece_budget.h), from the Splitable of the object it came from.
  PieceRetirement retirement = PieceRetirement::Default;
};

// The material set an entity shows; the demo cycles it with Q/E.
struct MaterialChoice {
  int index = 0;
};

}  // namespace cleave::components
