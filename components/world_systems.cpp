// SPDX-License-Identifier: MIT
// Per-tick systems of a world with splits (world_systems.h): transforms from bodies, meshes to the
// renderer, debris.
#include "cleave/components/world_systems.h"

#include <algorithm>

#include <glm/gtc/quaternion.hpp>

#include "cleave/components/skinned.h"
#include "cleave/components/split_system.h"
#include "cleave/components/static_batches.h"
#include "cleave/ecs/command_buffer.h"
#include "cleave/ecs/hierarchy.h"

namespace cleave::components {

void syncTransformsFromBodies(SplitWorld& w) {
  for (auto [e, rb, t] : w.world.view<RigidBody, ecs::Transform>()) {
    // Bodies at rest do not move: only awake ones (and static or kinematic ones, moved by hand) and
    // those that were awake at the last sync are read.
    const bool awake = w.physics.isAwake(rb.body);
    const bool read = awake || rb.moving || !(w.physics.bodyMass(rb.body).value_or(0.f) > 0.f);
    rb.moving = awake;
    if (!read) continue;
    const auto bt = w.physics.bodyTransform(rb.body);
    if (!bt) continue;
    t.position = bt->position;
    t.rotation = bt->rotation;
  }
  ecs::updateWorldTransforms(w.world);
}

void submitMeshes(SplitWorld& w, const StaticBatches* batches) {
  if (!w.renderer) return;
  if (batches) batches->submit();
  for (auto [e, mr, wt] : w.world.view<MeshRenderer, ecs::WorldTransform>()) {
    if (!mr.visible || !mr.gpu.valid() || mr.materials.empty()) continue;
    if (batches && batches->covers(e)) continue;
    // Skinned meshes draw in their current pose (GPU skinning).
    if (const auto* skin = w.world.tryGet<SkinnedMesh>(e); skin && !skin->jointMatrices.empty()) {
      w.renderer->submitSkinned(mr.gpu, wt.matrix * mr.meshOffset, skin->jointMatrices, mr.materials);
      continue;
    }
    const auto* info = w.world.tryGet<MassInfo>(e);
    w.renderer->submit(mr.gpu, wt.matrix * mr.meshOffset, mr.materials, info && info->closed);
  }
}

void updateDebris(SplitWorld& w, float dt) {
  ecs::CommandBuffer commands(w.world);
  const glm::vec3 gravity = w.physics.gravity();
  constexpr float kShrinkSeconds = 0.5f;
  for (auto [e, d, t] : w.world.view<Debris, ecs::Transform>()) {
    if (!d.landed) {
      d.velocity += gravity * dt;
      const glm::vec3 next = t.position + d.velocity * dt;
      const glm::vec3 along = d.velocity * dt;
      const float reach = glm::length(along);
      // The ray runs `radius` past the step so the piece stops that far above what it meets.
      auto hit = reach > 0.f ? w.physics.raycast(t.position, next + along / reach * d.radius) : std::nullopt;
      // Only what stays put holds it (static, frozen or sleeping bodies), and not from inside.
      if (hit && (hit->fraction <= 0.f || w.physics.isAwake(hit->body))) hit.reset();
      if (hit) {
        t.position = hit->point + hit->normal * d.radius;
        d.velocity = d.angularVelocity = glm::vec3(0.f);
        d.landed = true;
      } else {
        t.position = next;
      }
    }
    const float angle = glm::length(d.angularVelocity) * dt;
    if (angle > 0.f) t.rotation = glm::normalize(glm::angleAxis(angle, glm::normalize(d.angularVelocity)) * t.rotation);
    d.secondsLeft -= dt;
    if (d.secondsLeft < kShrinkSeconds) t.scale = glm::vec3(std::max(d.secondsLeft, 0.f) / kShrinkSeconds);
    if (d.secondsLeft <= 0.f || t.position.y < -50.f) commands.destroy(e);
  }
  w.world.apply(commands);
}

}  // namespace cleave::components
