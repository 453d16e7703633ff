// SPDX-License-Identifier: MIT
#include "cleave/ecs/hierarchy.h"

#include <algorithm>

#include <glm/gtc/matrix_transform.hpp>

namespace cleave::ecs {
namespace {

HierarchyStatus failure(std::string reason) {
  return HierarchyStatus::failure(base::StatusCode::InvalidArgument, std::move(reason));
}

// Removes `child` and every dead id from the parent's Children list.
void detachFromChildren(World& world, Entity parent, Entity child) {
  Children* children = world.tryGet<Children>(parent);
  if (children == nullptr) return;
  std::erase_if(children->entities,
                [&](Entity e) { return e == child || !world.alive(e); });
}

}  // namespace

glm::mat4 localMatrix(const Transform& transform) {
  glm::mat4 matrix = glm::translate(glm::mat4(1.0f), transform.position);
  matrix *= glm::mat4_cast(transform.rotation);
  return glm::scale(matrix, transform.scale);
}

Entity parentOf(const World& world, Entity entity) {
  const Parent* parent = world.tryGet<Parent>(entity);
  if (parent == nullptr || !world.alive(parent->entity)) return kNullEntity;
  return parent->entity;
}

HierarchyStatus setParent(World& world, Entity child, Entity parent) {
  if (!world.alive(child))
    return failure("setParent: child " + toString(child) + " is not alive");
  if (!parent.isNull() && !world.alive(parent))
    return failure("setParent: parent " + toString(parent) + " is not alive");
  if (parent == child)
    return failure("setParent: " + toString(child) + " cannot be its own parent");
  // Walk up from the new parent; reaching the child means the child is an ancestor of the parent.
  // The step limit keeps the walk finite even if direct edits have already made a cycle.
  size_t steps = 0;
  for (Entity up = parent; !up.isNull() && steps <= world.size();
       up = parentOf(world, up), ++steps) {
    if (up == child)
      return failure("setParent: " + toString(parent) + " is a descendant of " + toString(child) +
                     "; attaching would make a cycle");
  }

  const Entity oldParent = parentOf(world, child);
  if (!oldParent.isNull()) detachFromChildren(world, oldParent, child);
  if (parent.isNull()) {
    world.remove<Parent>(child);
    return {};
  }
  world.add<Parent>(child, Parent{parent});
  if (!world.has<Children>(parent)) world.add<Children>(parent, Children{});
  Children& children = world.get<Children>(parent);
  std::erase_if(children.entities, [&](Entity e) { return !world.alive(e); });
  if (std::find(children.entities.begin(), children.entities.end(), child) ==
      children.entities.end())
    children.entities.push_back(child);
  return {};
}

HierarchyStatus updateWorldTransforms(World& world) {
  enum class Mark : uint8_t { Unvisited, OnChain, Done };
  const uint32_t slots = world.slotCount();
  std::vector<Mark> marks(slots, Mark::Unvisited);
  std::vector<glm::mat4> worldOf(slots, glm::mat4(1.0f));
  std::vector<Entity> chain;
  std::string errors;

  const std::vector<Entity> entities = world.entities();
  for (const Entity start : entities) {
    if (marks[start.index] == Mark::Done) continue;
    // Walk up until a computed ancestor, a root, or an entity already on this chain (a cycle).
    chain.clear();
    glm::mat4 base(1.0f);
    Entity current = start;
    while (true) {
      if (marks[current.index] == Mark::Done) {
        base = worldOf[current.index];
        break;
      }
      if (marks[current.index] == Mark::OnChain) {
        // chain.back()'s parent closes the cycle; chain.back() becomes a root (base = identity).
        std::string cycle;
        auto first = std::find(chain.begin(), chain.end(), current);
        for (auto it = first; it != chain.end(); ++it) cycle += toString(*it) + " -> ";
        cycle += toString(current);
        if (!errors.empty()) errors += "; ";
        errors += "parent cycle " + cycle + "; " + toString(chain.back()) + " treated as a root";
        break;
      }
      marks[current.index] = Mark::OnChain;
      chain.push_back(current);
      const Entity parent = parentOf(world, current);
      if (parent.isNull()) break;
      current = parent;
    }
    // Compute from the top of the chain down.
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      const Transform* local = world.tryGet<Transform>(*it);
      if (local != nullptr) base = base * localMatrix(*local);
      worldOf[it->index] = base;
      marks[it->index] = Mark::Done;
    }
  }

  for (const Entity entity : entities) {
    if (!world.has<Transform>(entity)) continue;
    if (WorldTransform* out = world.tryGet<WorldTransform>(entity)) {
      out->matrix = worldOf[entity.index];
    } else {
      world.add<WorldTransform>(entity, WorldTransform{worldOf[entity.index]});
    }
  }
  if (!errors.empty()) return failure("updateWorldTransforms: " + errors);
  return {};
}

size_t destroyRecursive(World& world, Entity root) {
  if (!world.alive(root)) return 0;
  const Entity parent = parentOf(world, root);
  if (!parent.isNull()) detachFromChildren(world, parent, root);

  // Pre-order walk; `visited` makes it terminate even on inconsistent (cyclic) data.
  std::vector<bool> visited(world.slotCount(), false);
  std::vector<Entity> order;
  std::vector<Entity> stack{root};
  visited[root.index] = true;
  while (!stack.empty()) {
    const Entity entity = stack.back();
    stack.pop_back();
    order.push_back(entity);
    if (const Children* children = world.tryGet<Children>(entity)) {
      for (auto it = children->entities.rbegin(); it != children->entities.rend(); ++it) {
        if (world.alive(*it) && !visited[it->index] && parentOf(world, *it) == entity) {
          visited[it->index] = true;
          stack.push_back(*it);
        }
      }
    }
  }
  for (const Entity entity : order) world.destroy(entity);
  return order.size();
}

}  // namespace cleave::ecs
