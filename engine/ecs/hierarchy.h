// SPDX-License-Identifier: MIT
// Scene hierarchy and transforms as plain components, plus the functions that keep them
// consistent.
//
// Units: positions in metres, rotations as unit quaternions, scale as a factor per local axis.
// A local Transform is applied as translate * rotate * scale (scale first). WorldTransform is the
// product of the parent's world matrix and the local matrix, written by updateWorldTransforms().
//
// Parent and Children are kept in step by setParent() and destroyRecursive(); code that edits them
// directly must keep them consistent itself. World::destroy() does not know about the hierarchy: it
// leaves a stale id in the parent's Children (ignored and pruned later) and a child whose Parent is
// dead, which counts as a root.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "cleave/base/status.h"
#include "cleave/ecs/entity.h"
#include "cleave/ecs/world.h"

namespace cleave::ecs {

struct Name {
  std::string value;
};

// Local transform, relative to the parent (or the world for a root).
struct Transform {
  glm::vec3 position{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // w, x, y, z; identity
  glm::vec3 scale{1.0f};
};

struct Parent {
  Entity entity;
};

// Direct children, in the order they were attached.
struct Children {
  std::vector<Entity> entities;
};

// Local-to-world matrix (column-major, GLM convention). Written by updateWorldTransforms().
struct WorldTransform {
  glm::mat4 matrix{1.0f};
};

// Outcome of a hierarchy call: ok, or InvalidArgument with a reason a person can act on.
using HierarchyStatus = base::Status;

// translate(position) * mat4(rotation) * scale(scale).
glm::mat4 localMatrix(const Transform& transform);

// The entity's parent, or kNullEntity for a root, a dead entity, or a parent that is not alive.
Entity parentOf(const World& world, Entity entity);

// Attaches `child` under `parent` (kNullEntity detaches it and makes it a root). Updates Parent of
// the child and Children of the old and the new parent (appending at the end); the child's local
// Transform is kept as is, so its world placement changes with the new parent.
// Fails (and changes nothing) if the child is not alive, the parent is neither null nor alive, the
// parent is the child, or the parent is a descendant of the child (that would make a cycle).
// Precondition: no View exists.
HierarchyStatus setParent(World& world, Entity child, Entity parent);

// Writes WorldTransform for every live entity that has a Transform, parents before children.
// Entities without a Transform count as an identity local transform when they are parents.
// Deterministic: entities are visited ascending by index. A Parent cycle (possible only through
// direct edits of Parent) is broken by treating the cycle member reached last from the
// lowest-index entry as a root; every entity still gets a transform and the status names the
// cycle. Precondition: no View exists (it may add WorldTransform components).
HierarchyStatus updateWorldTransforms(World& world);

// Destroys `root` and all its descendants (through Children, children whose Parent is the
// entity), removes `root` from its parent's Children, and returns the number of entities
// destroyed (0 if `root` is not alive). Cycle-safe. Precondition: no View exists.
size_t destroyRecursive(World& world, Entity root);

}  // namespace cleave::ecs
