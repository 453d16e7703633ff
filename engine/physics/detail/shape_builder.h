// SPDX-License-Identifier: MIT
// Private (not installed): turns a checked ShapeDef into Bullet collision shapes.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <btBulletDynamicsCommon.h>

#include "cleave/physics/physics_result.h"
#include "cleave/physics/shape_def.h"

namespace cleave::physics::detail {

// A built shape and everything it points into. Member order matters: `shape` is destroyed first
// because it refers to `children` (compound) or `mesh` (meshes).
struct BuiltShape {
  std::unique_ptr<btStridingMeshInterface> mesh;
  std::vector<std::unique_ptr<btCollisionShape>> children;
  std::unique_ptr<btCollisionShape> shape;
  ShapeType type = ShapeType::Box;
  float margin = 0.0f;
  uint32_t hullVertices = 0;
};

struct BuildOutcome {
  PhysicsStatus status = PhysicsStatus::Ok;
  std::string reason;
  BuiltShape built;
};

BuildOutcome buildShape(const ShapeDef& def);

}  // namespace cleave::physics::detail
