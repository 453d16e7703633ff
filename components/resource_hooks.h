// SPDX-License-Identifier: MIT
// ResourceHooks: the destroy hooks by which an entity owns what its components hold. While a
// ResourceHooks lives, a component leaving an entity (World::remove, World::destroy, World::clear,
// a CommandBuffer's destroy or remove at apply time) frees what it refers to:
//   Ragdoll      its bone bodies (with the joints between them) and their capsule shapes
//   RigidBody    its body (with every joint attached to it) and its shape reference
//   MeshRenderer its GPU mesh (when a renderer is set)
//   Splitter     its trigger
// in that order for an entity that has several. Nobody calls a release function by hand.
//
// Ownership: a component owns the handles it holds; two components must not hold the same GPU
// mesh or shape reference (a ragdoll's anchor bone and its entity's RigidBody are the one
// exception: freeing a handle twice is a no-op, the second call sees a stale handle). Overwriting a
// component (World::add on one it has) frees nothing: the caller replaces the value.
//
// Lifetime: the World, the PhysicsWorld and the renderer must outlive this object; destroying it
// removes the hooks (entities left then keep their resources until those worlds go). Not
// copyable or movable (the hooks refer to it). Not thread-safe, like the World.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cleave/ecs/world.h"
#include "cleave/physics/physics_world.h"
#include "cleave/render/renderer.h"

namespace cleave::components {

// What a physics world and a renderer hold now: the figures the hooks bring back down.
struct ResourceCounts {
  uint32_t bodies = 0;
  uint32_t shapes = 0;     // shapes still allocated (PhysicsWorld::liveShapeCount)
  uint32_t joints = 0;
  uint32_t triggers = 0;
  uint32_t gpuMeshes = 0;  // 0 without a renderer
  friend bool operator==(const ResourceCounts&, const ResourceCounts&) = default;
};

// The counts of `physics` and `renderer` (either may be null: its counts are 0).
ResourceCounts countResources(const physics::PhysicsWorld* physics, const render::Renderer* renderer);
// "bodies=3 shapes=4 joints=0 triggers=1 gpu_meshes=5", for logs and the --resource-report line.
std::string toString(const ResourceCounts& counts);
// The two lines of a game's --resource-report ("resources-before: ...\nresources-after: ...\n"): the
// counts from before setup and those left once every entity was destroyed (the game prints them).
std::string resourceReport(const ResourceCounts& before, const ResourceCounts& after);

class ResourceHooks {
 public:
  // `renderer` may be null (pure simulation): GPU mesh handles are then left alone.
  ResourceHooks(ecs::World& world, physics::PhysicsWorld& physics, render::Renderer* renderer);
  ~ResourceHooks();
  ResourceHooks(const ResourceHooks&) = delete;
  ResourceHooks& operator=(const ResourceHooks&) = delete;

  // The renderer whose meshes MeshRenderer::gpu names from now on (null: none).
  void setRenderer(render::Renderer* renderer) { renderer_ = renderer; }

 private:
  ecs::World& world_;
  physics::PhysicsWorld& physics_;
  render::Renderer* renderer_ = nullptr;
  std::vector<ecs::HookId> hooks_;
};

}  // namespace cleave::components
