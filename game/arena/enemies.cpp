// SPDX-License-Identifier: MIT
#include "game/arena/enemies.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cleave/components/scene_components.h"
#include "cleave/components/split_system.h"
#include "cleave/components/splitable_object.h"
#include "cleave/components/splitable.h"
#include "cleave/ecs/hierarchy.h"
#include "game/arena/arena_layout.h"

namespace cleave::arena {

namespace {

constexpr float kFootClearance = 0.02f;  // m: bodies hover this much so they never rub the floor


constexpr float kTurnRate = 4.f;      // rad/s
constexpr float kCheerRate = 7.85f;   // rad/s of walkPhase while cheering: a hop every 0.4 s
constexpr float kCheerHop = 0.12f;    // m, the gladiators' hop
constexpr float kCheerLean = 0.12f;   // rad, thrown back at the top of the hop

bool cheering(const Enemy& e) { return e.behaviour == EnemyBehaviour::Cheer; }

glm::quat enemyRotation(const Enemy& e) {
  // The skinned kind's walk and cheer are in its clips: only the gladiators sway and lean.
  const bool still = e.hit || e.kind == EnemyKind::Skinned;
  const float sway = still || cheering(e) ? 0.f : 0.07f * std::sin(e.walkPhase);
  float lean = e.lunge > 0.f ? 0.35f * std::sin(e.lunge / 0.4f * kPi) : 0.f;
  if (!still && cheering(e)) lean = -kCheerLean * std::abs(std::sin(e.walkPhase));
  return glm::angleAxis(e.yaw, glm::vec3(0, 1, 0)) * glm::angleAxis(lean, glm::vec3(1, 0, 0)) *
         glm::angleAxis(sway, glm::vec3(0, 0, 1));
}

Enemy spawnGladiator(EnemyContext& c, const EnemyMeshes& meshes, glm::vec2 position, float yaw) {
  Enemy enemy;
  enemy.kind = EnemyKind::Gladiator;
  ecs::World& world = c.world;
  const ArenaMaterials& m = c.materials;
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
  components::SplitWorld sw{world, c.physics, c.renderer};
  // Built at the origin so the body frame found by makeDynamicBody is the one in the enemy's frame.
  const ecs::Entity e = components::createSplitableObject(
      sw, {"gladiator", ecs::Transform{}, meshes.gladiator, {m.armour, m.flesh, m.skin, m.cloth}, splitable});
  // The living figure is moved by the game: its convex hull is collider enough (cheap to build).
  const base::Status made =
      components::makeDynamicBody(sw, e, splitable.density, components::ColliderMode::ConvexHull);
  if (!made.ok()) {
    std::fprintf(stderr, "arena: gladiator has no body: %s\n", made.message.c_str());
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
  components::Splitable splitable;
  splitable.density = 1000.0;  // the body's mass; the halves share it by posed volume
  splitable.capMaterial = c.materials.flesh;
  splitable.capMaterialId = 1;
  splitable.skinnedPieces = components::SkinnedPieceMode::Ragdoll;
  splitable.handler = "arena.gladiator";  // see ArenaGame::setup
  splitable.splitImpulse = 0.6;
  splitable.maxDepth = 3;
  components::SplitWorld sw{world, c.physics, c.renderer};
  // Built at the origin, facing +z, so the body frame is the one in the enemy's own frame.
  const ecs::Entity e = components::createSplitableObject(
      sw, {"skinned warrior", ecs::Transform{}, meshes.skinned, c.materials.skinnedEnemy, splitable});
  // Each one starts its stride somewhere else (from its spawn point: deterministic).
  const float start = std::fmod(std::abs(position.x * 0.37f + position.y * 0.61f), 1.f);
  world.add<components::SkinnedMesh>(e, components::makeSkinnedMesh(meshes.skinnedAsset, "walk", start));
  const base::Status made = components::makeSkinnedBody(sw, e, splitable.density, /*kinematic=*/true);
  if (!made.ok()) {
    std::fprintf(stderr, "arena: skinned enemy has no body: %s\n", made.message.c_str());
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

const char* kindName(EnemyKind kind) {
  switch (kind) {
    case EnemyKind::Skinned: return "skinned";
    case EnemyKind::Gladiator:
    case EnemyKind::Count: break;
  }
  return "gladiator";
}

const EnemyTuning& kindTuning(const ArenaTuning& tuning, EnemyKind kind) {
  return kind == EnemyKind::Skinned ? tuning.skinned : tuning.gladiator;
}

const char* toString(EnemyBehaviour behaviour) {
  switch (behaviour) {
    case EnemyBehaviour::Approach: return "approach";
    case EnemyBehaviour::Wait: return "wait";
    case EnemyBehaviour::Strike: return "strike";
    case EnemyBehaviour::Frozen: return "frozen";
    case EnemyBehaviour::Cheer: return "cheer";
  }
  return "?";
}

anim::AnimationClip makeCheerClip(const anim::Skeleton& skeleton) {
  constexpr float kPeriod = 0.8f;
  constexpr int kKeys = 16;
  anim::AnimationClip clip;
  clip.name = "cheer";
  // One looping channel of `joint`, key k at phase 2 pi k / kKeys (the last key repeats the first).
  auto loop = [&](const char* joint, anim::ChannelPath path, auto valueAt) {
    const int32_t j = skeleton.find(joint);
    if (j < 0) return;
    anim::Channel channel;
    channel.joint = uint32_t(j);
    channel.path = path;
    for (int k = 0; k <= kKeys; ++k) {
      channel.times.push_back(kPeriod * float(k) / float(kKeys));
      channel.values.push_back(valueAt(2.f * kPi * float(k % kKeys) / float(kKeys)));
    }
    clip.channels.push_back(std::move(channel));
  };
  auto turn = [](float angle, glm::vec3 axis) {
    const glm::quat q = glm::angleAxis(angle, axis);
    return glm::vec4(q.x, q.y, q.z, q.w);
  };
  const glm::vec3 forward(0.f, 0.f, 1.f), across(1.f, 0.f, 0.f);
  // The arms hang 35 degrees out in the rest pose; about +z the left arm (+x) swings up over the head.
  for (float side : {1.f, -1.f}) {
    const bool left = side > 0.f;
    loop(left ? "left_upper_arm" : "right_upper_arm", anim::ChannelPath::Rotation,
         [&, side](float p) { return turn(side * (2.45f + 0.25f * std::sin(p)), forward); });
    loop(left ? "left_forearm" : "right_forearm", anim::ChannelPath::Rotation,
         [&, side](float p) { return turn(side * (0.25f + 0.2f * std::sin(p)), forward); });
  }
  loop("chest", anim::ChannelPath::Rotation, [&](float p) { return turn(-0.1f - 0.06f * std::sin(p), across); });
  loop("head", anim::ChannelPath::Rotation, [&](float p) { return turn(-0.2f + 0.05f * std::sin(p), across); });
  const int32_t hips = skeleton.find("hips");
  const glm::vec3 rest = hips >= 0 ? skeleton.joints[size_t(hips)].rest.translation : glm::vec3(0.f);
  loop("hips", anim::ChannelPath::Translation,
       [&](float p) { return glm::vec4(rest + glm::vec3(0.f, 0.06f * std::max(0.f, std::sin(p)), 0.f), 0.f); });
  clip.updateDuration();
  return clip;
}

EnemyMeshes makeEnemyMeshes(const assets::ProceduralCharacter& character) {
  EnemyMeshes meshes;
  meshes.gladiator = std::make_shared<const geometry::MeshData>(gladiatorMesh());
  meshes.skinned = std::make_shared<const geometry::MeshData>(character.mesh);
  auto asset = std::make_shared<components::SkinnedAsset>();
  asset->skeleton = character.skeleton;
  asset->clips = {character.idle, character.walk, makeCheerClip(character.skeleton)};
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
  const float wave = std::abs(std::sin(enemy.walkPhase));
  const bool still = enemy.hit || enemy.kind == EnemyKind::Skinned;
  const float bob = still ? 0.f : (cheering(enemy) ? kCheerHop : 0.035f) * wave;
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
  // The skinned kind walks in its clip at the pace it moves, stands in its idle clip, cheers in its
  // cheer clip, and holds its pose while a blade is on it (the cut happens in the pose it shows).
  if (auto* skin = world.tryGet<components::SkinnedMesh>(enemy.entity); skin && skin->asset) {
    const float speed = glm::length(glm::vec2(velocity.x, velocity.z));
    const bool walking = speed > 0.3f;
    const char* clip = cheering(enemy) ? "cheer" : walking ? "walk" : "idle";
    const anim::AnimationClip* want = skin->asset->clip(clip);
    if (want && skin->animator.clip() != want) skin->animator.play(want, 0.25f);
    skin->speed = enemy.hit ? 0.f : walking ? std::clamp(speed / 2.2f, 0.6f, 1.6f) : 1.f;
  }
}

namespace {

// Turns the enemy towards `target` at most kTurnRate a second.
void turnTowards(Enemy& e, glm::vec2 target, float dt) {
  const glm::vec2 to = target - e.position;
  if (glm::length(to) <= 1e-4f) return;
  float turn = std::atan2(to.x, to.y) - e.yaw;
  while (turn > kPi) turn -= 2.f * kPi;
  while (turn < -kPi) turn += 2.f * kPi;
  e.yaw += std::clamp(turn, -kTurnRate * dt, kTurnRate * dt);
}

// Which enemies may strike this tick: the nearest maxAttackers that are not frozen, those already
// engaged before the others (so a newcomer does not take the place of one winding up); ties go to
// the earlier one in the list (deterministic).
std::vector<bool> strikers(const std::vector<Enemy>& enemies, glm::vec2 player, int maxAttackers) {
  std::vector<size_t> order;
  for (size_t i = 0; i < enemies.size(); ++i)
    if (!enemies[i].hit) order.push_back(i);
  auto key = [&](size_t i) { return glm::length(enemies[i].position - player) - (enemies[i].engaged ? 100.f : 0.f); };
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return key(a) < key(b); });
  std::vector<bool> may(enemies.size(), false);
  for (size_t k = 0; k < order.size() && k < size_t(std::max(maxAttackers, 0)); ++k) may[order[k]] = true;
  return may;
}

// Keeps enemy i apart from the others: the push that separates overlapping floor circles.
glm::vec2 crowdPush(const std::vector<Enemy>& enemies, size_t i, const ArenaTuning& tuning) {
  glm::vec2 push(0.f);
  const float radius = kindTuning(tuning, enemies[i].kind).radius;
  for (size_t j = 0; j < enemies.size(); ++j) {
    if (j == i) continue;
    const glm::vec2 d = enemies[i].position - enemies[j].position;
    const float len = glm::length(d);
    const float minimum = radius + kindTuning(tuning, enemies[j].kind).radius;
    if (len < minimum && len > 1e-5f) push += d / len * (minimum - len);
    else if (len <= 1e-5f) push += glm::vec2(j < i ? 0.05f : -0.05f, 0.f);
  }
  return push;
}

// `next` moved out of a round obstacle, for a floor circle of `radius`.
glm::vec2 pushOut(glm::vec2 next, float radius, const Obstacle& o) {
  const glm::vec2 d = next - o.centre;
  const float len = glm::length(d);
  const float minimum = o.radius + radius;
  return len < minimum && len > 1e-5f ? o.centre + d / len * minimum : next;
}

// `next` moved out of the pillars and the player and inside the wall, for a floor circle of `radius`.
glm::vec2 keepOnFloor(glm::vec2 next, float radius, const EnemyField& field) {
  if (field.obstacles)
    for (const Obstacle& o : *field.obstacles) next = pushOut(next, radius, o);
  next = pushOut(next, radius, Obstacle{field.player, field.playerRadius});
  const float fromCentre = glm::length(next);
  if (fromCentre > field.arenaRadius - radius) next *= (field.arenaRadius - radius) / fromCentre;
  return next;
}

// The blow of an enemy `distance` from the player: a wind-up when it steps into range, then a blow
// every attackSeconds while it stays there. Sets its behaviour; returns the damage dealt.
int strike(Enemy& e, const EnemyTuning& kind, float distance, bool mayStrike) {
  if (!mayStrike || distance > kind.attackRange) {
    if (!mayStrike || distance > kind.attackRange * 1.2f) e.engaged = false;
    e.behaviour = mayStrike ? EnemyBehaviour::Approach : EnemyBehaviour::Wait;
    return 0;
  }
  e.behaviour = EnemyBehaviour::Strike;
  if (!e.engaged) {
    e.engaged = true;
    e.attackTimer = std::max(e.attackTimer, kind.windupSeconds);
  }
  if (e.attackTimer > 0.f) return 0;
  e.attackTimer = kind.attackSeconds;
  e.lunge = 0.4f;
  return kind.attackDamage;
}

}  // namespace

int updateEnemies(EnemyContext& c, std::vector<Enemy>& enemies, const EnemyField& field, const ArenaTuning& tuning,
                  float dt) {
  int damage = 0;
  const std::vector<bool> may = strikers(enemies, field.player, tuning.match.maxAttackers);
  for (size_t i = 0; i < enemies.size(); ++i) {
    Enemy& e = enemies[i];
    const EnemyTuning& kind = kindTuning(tuning, e.kind);
    e.attackTimer = std::max(0.f, e.attackTimer - dt);
    e.lunge = std::max(0.f, e.lunge - dt);
    if (e.hit && e.attackTimer > 0.f) {
      e.behaviour = EnemyBehaviour::Frozen;
      poseEnemy(c, e, glm::vec3(0.f));
      continue;
    }
    e.hit = false;  // frozen by a blade whose split never came (the plane missed): walk on
    const glm::vec2 toPlayer = field.player - e.position;
    const float distance = glm::length(toPlayer);
    turnTowards(e, field.player, dt);
    // Those whose turn it is walk into range; the others stop where they wait.
    const float standOff = may[i] ? kind.attackRange * 0.9f : tuning.match.waitDistance;
    const glm::vec2 want = distance > standOff && distance > 1e-4f ? toPlayer / distance : glm::vec2(0.f);
    const glm::vec2 next = keepOnFloor(e.position + want * kind.walkSpeed * dt + crowdPush(enemies, i, tuning) * 0.5f,
                                       kind.radius, field);
    const glm::vec2 velocity = (next - e.position) / dt;
    e.position = next;
    e.walkPhase += dt * (glm::length(velocity) > 0.2f ? 7.5f : 2.f);
    damage += strike(e, kind, distance, may[i]);
    if (e.behaviour != EnemyBehaviour::Strike && glm::length(want) > 0.f) e.behaviour = EnemyBehaviour::Approach;
    poseEnemy(c, e, glm::vec3(velocity.x, 0.f, velocity.y));
  }
  return damage;
}

void cheerEnemies(EnemyContext& c, std::vector<Enemy>& enemies, glm::vec2 player, float dt) {
  for (Enemy& e : enemies) {
    e.lunge = 0.f;
    e.engaged = false;
    e.attackTimer = std::max(0.f, e.attackTimer - dt);
    if (e.hit && e.attackTimer > 0.f) {
      e.behaviour = EnemyBehaviour::Frozen;
      poseEnemy(c, e, glm::vec3(0.f));
      continue;
    }
    e.hit = false;
    e.behaviour = EnemyBehaviour::Cheer;
    turnTowards(e, player, dt);
    e.walkPhase += dt * kCheerRate;
    poseEnemy(c, e, glm::vec3(0.f));
  }
}

void freezeEnemy(Enemy& enemy, float seconds) {
  enemy.hit = true;
  enemy.engaged = false;
  enemy.lunge = 0.f;
  enemy.attackTimer = seconds;
  enemy.behaviour = EnemyBehaviour::Frozen;
}

}  // namespace cleave::arena
