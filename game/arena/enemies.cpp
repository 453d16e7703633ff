#include "game/arena/enemies.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "components/scene_components.h"
#include "components/split_system.h"
#include "components/splitable.h"
#include "engine/ecs/hierarchy.h"

namespace cleave::arena {

namespace {

constexpr float kFootClearance = 0.02f;  // m: bodies hover this much so they never rub the floor


glm::quat enemyRotation(const Enemy& e) {
  // The skinned kind's walk is in its clip: only the gladiators sway as they go.
  const float sway = e.hit || e.kind == EnemyKind::Skinned ? 0.f : 0.07f * std::sin(e.walkPhase);
  const float lean = e.lunge > 0.f ? 0.35f * std::sin(e.lunge / 0.4f * 3.14159265f) : 0.f;
  return glm::angleAxis(e.yaw, glm::vec3(0, 1, 0)) * glm::angleAxis(lean, glm::vec3(1, 0, 0)) *
         glm::angleAxis(sway, glm::vec3(0, 0, 1));
}

Enemy spawnGladiator(EnemyContext& c, const EnemyMeshes& meshes, glm::vec2 position, float yaw) {
  Enemy enemy;
  enemy.kind = EnemyKind::Gladiator;
  ecs::World& world = c.world;
  const ecs::Entity e = world.create();
  world.add<ecs::Name>(e, ecs::Name{"gladiator"});
  // Built at the origin so the body frame found by makeDynamicBody is the one in the enemy's frame.
  ecs::Transform t;
  world.add<ecs::Transform>(e, t);
  world.add<ecs::WorldTransform>(e, ecs::WorldTransform{ecs::localMatrix(t)});
  components::MeshRenderer mr;
  mr.source = meshes.gladiator;
  if (c.renderer) mr.gpu = c.renderer->uploadMesh(*meshes.gladiator);
  const ArenaMaterials& m = c.materials;
  mr.materials = {m.armour, m.flesh, m.skin, m.cloth};
  world.add<components::MeshRenderer>(e, std::move(mr));
  components::Splitable splitable;
  splitable.density = 1000.0;
  splitable.capMaterial = m.flesh;
  splitable.capMaterialId = 1;
  splitable.separateIslands = true;  // a cut figure falls apart into its parts,
  splitable.islands = geometry::IslandMode::Connected;  // every one of them, touching or not
  splitable.splitImpulse = 0.8;
  // Every island of a cut is a piece of one convex part, so its hull is exact: no convexity test.
  splitable.collider = components::ColliderMode::ConvexHull;
  splitable.maxDepth = 4;
  world.add<components::Splitable>(e, splitable);
  components::SplitWorld sw{world, c.physics, c.renderer};
  std::string error;
  // The living figure is moved by the game: its convex hull is collider enough (cheap to build).
  if (!components::makeDynamicBody(sw, e, splitable.density, components::ColliderMode::ConvexHull, &error)) {
    std::fprintf(stderr, "arena: gladiator has no body: %s\n", error.c_str());
    components::releaseEntityResources(sw, e);
    world.destroy(e);
    return enemy;
  }
  const ecs::Transform& bodyFrame = world.get<ecs::Transform>(e);
  enemy.bodyLocalPosition = bodyFrame.position;
  enemy.bodyLocalRotation = bodyFrame.rotation;
  enemy.entity = e;
  enemy.position = position;
  enemy.yaw = yaw;
  return enemy;
}

// The skinned enemy: the generated character (one closed skinned mesh) playing its walk clip, with a
// kinematic body (the posed hull) that the game moves every tick. A blade cuts it in the pose it
// shows; each half becomes a ragdoll (capsules per bone it keeps) that starts with the motion of the
// points it carries and falls.
Enemy spawnSkinned(EnemyContext& c, const EnemyMeshes& meshes, glm::vec2 position, float yaw) {
  Enemy enemy;
  enemy.kind = EnemyKind::Skinned;
  ecs::World& world = c.world;
  const ecs::Entity e = world.create();
  world.add<ecs::Name>(e, ecs::Name{"skinned warrior"});
  // Built at the origin, facing +z, so the body frame is the one in the enemy's own frame.
  ecs::Transform t;
  world.add<ecs::Transform>(e, t);
  world.add<ecs::WorldTransform>(e, ecs::WorldTransform{ecs::localMatrix(t)});
  components::MeshRenderer mr;
  mr.source = meshes.skinned;
  if (c.renderer) mr.gpu = c.renderer->uploadMesh(*meshes.skinned);
  mr.materials = c.materials.skinnedEnemy;
  world.add<components::MeshRenderer>(e, std::move(mr));
  // Each one starts its stride somewhere else (from its spawn point: deterministic).
  const float start = std::fmod(std::abs(position.x * 0.37f + position.y * 0.61f), 1.f);
  world.add<components::SkinnedMesh>(e, components::makeSkinnedMesh(meshes.skinnedAsset, "walk", start));
  components::Splitable splitable;
  splitable.density = 1000.0;  // the body's mass; the halves share it by posed volume
  splitable.capMaterial = c.materials.flesh;
  splitable.capMaterialId = 1;
  splitable.skinnedPieces = components::SkinnedPieceMode::Ragdoll;
  splitable.handler = "arena.gladiator";  // see ArenaGame::setup
  splitable.splitImpulse = 0.6;
  splitable.maxDepth = 3;
  world.add<components::Splitable>(e, splitable);
  components::SplitWorld sw{world, c.physics, c.renderer};
  std::string error;
  if (!components::makeSkinnedBody(sw, e, splitable.density, /*kinematic=*/true, &error)) {
    std::fprintf(stderr, "arena: skinned enemy has no body: %s\n", error.c_str());
    components::releaseEntityResources(sw, e);
    world.destroy(e);
    return enemy;
  }
  const auto& rb = world.get<components::RigidBody>(e);
  if (const auto bt = c.physics.bodyTransform(rb.body)) {
    enemy.bodyLocalPosition = bt->position;
    enemy.bodyLocalRotation = bt->rotation;
  }
  enemy.entity = e;
  enemy.position = position;
  enemy.yaw = yaw;
  return enemy;
}

}  // namespace

const EnemyKindInfo& kindInfo(EnemyKind kind) {
  static const EnemyKindInfo kGladiator{"gladiator", 1.8f, 1.25f, 6.f, 1.1f, 0.42f};
  // Slower and heavier-handed than the gladiators.
  static const EnemyKindInfo kSkinned{"skinned", 1.5f, 1.3f, 8.f, 1.4f, 0.4f};
  switch (kind) {
    case EnemyKind::Skinned:
      return kSkinned;
    case EnemyKind::Gladiator:
    case EnemyKind::Count:
      break;
  }
  return kGladiator;
}

EnemyMeshes makeEnemyMeshes(const assets::ProceduralCharacter& character) {
  EnemyMeshes meshes;
  meshes.gladiator = std::make_shared<const geometry::MeshData>(gladiatorMesh());
  meshes.skinned = std::make_shared<const geometry::MeshData>(character.mesh);
  auto asset = std::make_shared<components::SkinnedAsset>();
  asset->skeleton = character.skeleton;
  asset->clips = {character.idle, character.walk};
  meshes.skinnedAsset = std::move(asset);
  return meshes;
}

Enemy spawnEnemy(EnemyContext& c, const EnemyMeshes& meshes, EnemyKind kind, glm::vec2 position, float yaw) {
  Enemy enemy;
  switch (kind) {
    case EnemyKind::Skinned:
      enemy = spawnSkinned(c, meshes, position, yaw);
      break;
    case EnemyKind::Gladiator:
    case EnemyKind::Count:
      enemy = spawnGladiator(c, meshes, position, yaw);
      break;
  }
  if (!enemy.entity.isNull()) poseEnemy(c, enemy, glm::vec3(0.f));
  return enemy;
}

void poseEnemy(EnemyContext& c, const Enemy& enemy, glm::vec3 velocity) {
  ecs::World& world = c.world;
  auto* rb = world.tryGet<components::RigidBody>(enemy.entity);
  auto* t = world.tryGet<ecs::Transform>(enemy.entity);
  if (!rb || !t) return;
  const float bob = enemy.hit || enemy.kind == EnemyKind::Skinned ? 0.f : 0.035f * std::abs(std::sin(enemy.walkPhase));
  const glm::quat r = enemyRotation(enemy);
  const glm::vec3 base(enemy.position.x, kFootClearance + bob, enemy.position.y);
  physics::BodyTransform bt;
  bt.position = base + r * enemy.bodyLocalPosition;
  bt.rotation = glm::normalize(r * enemy.bodyLocalRotation);
  c.physics.setBodyTransform(rb->body, bt);
  c.physics.setVelocity(rb->body, velocity, glm::vec3(0.f));
  t->position = bt.position;
  t->rotation = bt.rotation;
  if (auto* wt = world.tryGet<ecs::WorldTransform>(enemy.entity)) wt->matrix = ecs::localMatrix(*t);
  // The skinned kind walks in its clip at the pace it moves, stands in its idle clip, and holds its
  // pose while a blade is on it (the cut happens in the pose it shows).
  if (auto* skin = world.tryGet<components::SkinnedMesh>(enemy.entity); skin && skin->asset) {
    const float speed = glm::length(glm::vec2(velocity.x, velocity.z));
    const bool walking = speed > 0.3f;
    const anim::AnimationClip* want = skin->asset->clip(walking ? "walk" : "idle");
    if (want && skin->animator.clip() != want) skin->animator.play(want, 0.25f);
    skin->speed = enemy.hit ? 0.f : walking ? std::clamp(speed / 2.2f, 0.6f, 1.6f) : 1.f;
  }
}

float updateEnemies(EnemyContext& c, std::vector<Enemy>& enemies, glm::vec2 player, float dt,
                    const std::vector<Obstacle>& obstacles, float arenaRadius) {
  float damage = 0.f;
  for (size_t i = 0; i < enemies.size(); ++i) {
    Enemy& e = enemies[i];
    const EnemyKindInfo& info = kindInfo(e.kind);
    e.attackTimer = std::max(0.f, e.attackTimer - dt);
    e.lunge = std::max(0.f, e.lunge - dt);
    if (e.hit && e.attackTimer > 0.f) {
      poseEnemy(c, e, glm::vec3(0.f));
      continue;
    }
    e.hit = false;  // frozen by a blade whose split never came (the plane missed): walk on
    const glm::vec2 toPlayer = player - e.position;
    const float distance = glm::length(toPlayer);
    glm::vec2 want(0.f);
    if (distance > 1e-4f) {
      const float targetYaw = std::atan2(toPlayer.x, toPlayer.y);
      float turn = targetYaw - e.yaw;
      while (turn > 3.14159265f) turn -= 6.2831853f;
      while (turn < -3.14159265f) turn += 6.2831853f;
      e.yaw += std::clamp(turn, -4.f * dt, 4.f * dt);
      if (distance > info.attackRange * 0.9f) want = toPlayer / distance;
    }
    // Crowding: keep apart from the others (earlier ones in the list win ties: deterministic).
    glm::vec2 push(0.f);
    for (size_t j = 0; j < enemies.size(); ++j) {
      if (j == i) continue;
      const glm::vec2 d = e.position - enemies[j].position;
      const float len = glm::length(d);
      const float minimum = info.radius + kindInfo(enemies[j].kind).radius;
      if (len < minimum && len > 1e-5f) push += d / len * (minimum - len);
      else if (len <= 1e-5f) push += glm::vec2(j < i ? 0.05f : -0.05f, 0.f);
    }
    glm::vec2 velocity = want * info.walkSpeed;
    glm::vec2 next = e.position + velocity * dt + push * 0.5f;
    for (const Obstacle& o : obstacles) {
      const glm::vec2 d = next - o.centre;
      const float len = glm::length(d);
      const float minimum = o.radius + info.radius;
      if (len < minimum && len > 1e-5f) next = o.centre + d / len * minimum;
    }
    const float fromCentre = glm::length(next);
    if (fromCentre > arenaRadius - info.radius) next *= (arenaRadius - info.radius) / fromCentre;
    velocity = (next - e.position) / dt;
    e.position = next;
    const float speed = glm::length(velocity);
    e.walkPhase += dt * (speed > 0.2f ? 7.5f : 2.f);
    if (distance <= info.attackRange && e.attackTimer <= 0.f) {
      e.attackTimer = info.attackSeconds;
      e.lunge = 0.4f;
      damage += info.attackDamage;
    }
    poseEnemy(c, e, glm::vec3(velocity.x, 0.f, velocity.y));
  }
  return damage;
}

}  // namespace cleave::arena
