// SPDX-License-Identifier: MIT
#include "cleave/components/resource_hooks.h"

#include "cleave/components/scene_components.h"
#include "cleave/components/skinned.h"
#include "cleave/components/splitable.h"

namespace cleave::components {

ResourceHooks::ResourceHooks(ecs::World& world, physics::PhysicsWorld& physics, render::Renderer* renderer)
    : world_(world), physics_(physics), renderer_(renderer) {
  // The order is the one physics has always seen for a destroyed piece (bone bodies, then the
  // body, then the trigger): bodies freed in another order would take other slots afterwards.
  hooks_.push_back(world_.onDestroy<Ragdoll>(
      [this](ecs::World&, ecs::Entity, Ragdoll& ragdoll) { releaseRagdoll(physics_, ragdoll); }));
  hooks_.push_back(world_.onDestroy<RigidBody>([this](ecs::World&, ecs::Entity, RigidBody& rb) {
    physics_.destroyBody(rb.body);
    physics_.destroyShape(rb.shape);
  }));
  hooks_.push_back(world_.onDestroy<MeshRenderer>([this](ecs::World&, ecs::Entity, MeshRenderer& mr) {
    if (renderer_) renderer_->destroyMesh(mr.gpu);
  }));
  hooks_.push_back(world_.onDestroy<Splitter>(
      [this](ecs::World&, ecs::Entity, Splitter& splitter) { physics_.destroyTrigger(splitter.trigger); }));
}

ResourceHooks::~ResourceHooks() {
  for (ecs::HookId id : hooks_) world_.removeHook(id);
}

ResourceCounts countResources(const physics::PhysicsWorld* physics, const render::Renderer* renderer) {
  ResourceCounts c;
  if (physics) {
    c.bodies = physics->bodyCount();
    c.shapes = physics->liveShapeCount();
    c.joints = physics->jointCount();
    c.triggers = physics->triggerCount();
  }
  if (renderer) c.gpuMeshes = renderer->liveMeshCount();
  return c;
}

std::string toString(const ResourceCounts& c) {
  return "bodies=" + std::to_string(c.bodies) + " shapes=" + std::to_string(c.shapes) +
         " joints=" + std::to_string(c.joints) + " triggers=" + std::to_string(c.triggers) +
         " gpu_meshes=" + std::to_string(c.gpuMeshes);
}

std::string resourceReport(const ResourceCounts& before, const ResourceCounts& after) {
  return "resources-before: " + toString(before) + "\nresources-after: " + toString(after) + "\n";
}

}  // namespace cleave::components
