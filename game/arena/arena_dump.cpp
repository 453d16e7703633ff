// SPDX-License-Identifier: MIT
// The arena's fields in the state dump (--dump-state, JSON lines): per entity what it is, its mass
// and motion, and for enemies their kind and behaviour; per line the match, the run's figures, the
// engine resources alive, the split log and the budget. docs/arena.md lists the fields.
#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "cleave/components/skinned.h"
#include "cleave/components/split_system.h"
#include "game/arena/arena_game.h"

namespace cleave::arena {

namespace {

const char* tagName(ArenaTag::Kind k) {
  switch (k) {
    case ArenaTag::Level: return "level";
    case ArenaTag::Prop: return "prop";
    case ArenaTag::MenuCube: return "menu_cube";
    case ArenaTag::Enemy: return "enemy";
    case ArenaTag::Piece: return "piece";
    case ArenaTag::Player: return "player";
    case ArenaTag::Weapon: return "weapon";
  }
  return "?";
}

}  // namespace

void ArenaGame::dumpEntity(ecs::Entity e, nlohmann::json& out) {
  ecs::World& world = app_->world();
  if (const auto* tag = world.tryGet<ArenaTag>(e)) out["kind"] = tagName(tag->kind);
  if (const auto* mi = world.tryGet<components::MassInfo>(e)) {
    out["mass"] = mi->mass;
    out["volume"] = mi->volume;
  }
  if (const auto* rb = world.tryGet<components::RigidBody>(e)) {
    if (const auto state = physics_->bodyState(rb->body)) {
      out["center_of_mass"] = {state->transform.position.x, state->transform.position.y, state->transform.position.z};
      out["linear_velocity"] = {state->linearVelocity.x, state->linearVelocity.y, state->linearVelocity.z};
      out["angular_velocity"] = {state->angularVelocity.x, state->angularVelocity.y, state->angularVelocity.z};
    }
  }
  if (const auto* origin = world.tryGet<components::SplitOrigin>(e)) out["split_from"] = origin->parentId;
  if (const auto* f = world.tryGet<Fading>(e)) out["born_tick"] = f->bornTick;
  if (const auto* ragdoll = world.tryGet<components::Ragdoll>(e)) out["ragdoll_bones"] = ragdoll->bones.size();
  for (const Enemy& en : enemies_)
    if (en.entity == e) dumpEnemy(en, out);
}

void ArenaGame::dumpEnemy(const Enemy& enemy, nlohmann::json& out) {
  out["enemy_kind"] = kindName(enemy.kind);
  out["hit"] = enemy.hit;
  out["behaviour"] = toString(enemy.behaviour);
  out["spawn_tick"] = enemy.spawnTick;
  if (const auto* skin = app_->world().tryGet<components::SkinnedMesh>(enemy.entity); skin && skin->animator.clip())
    out["clip"] = skin->animator.clip()->name;
  // How far its up axis leans from the vertical, in degrees, from its body as physics has it (a
  // figure that topples over shows it here whatever the game meant to do with it).
  glm::quat rotation = app_->world().get<ecs::Transform>(enemy.entity).rotation;
  if (const auto* rb = app_->world().tryGet<components::RigidBody>(enemy.entity))
    if (const auto state = physics_->bodyState(rb->body)) rotation = state->transform.rotation;
  const glm::vec3 up = rotation * glm::inverse(enemy.bodyLocalRotation) * glm::vec3(0.f, 1.f, 0.f);
  out["tilt_deg"] = std::acos(std::clamp(double(up.y), -1.0, 1.0)) * 180.0 / 3.14159265358979323846;
}

nlohmann::json ArenaGame::dumpMatch() {
  nlohmann::json arena = {{"state", toString(state_)},
                          {"matches_started", matchesStarted_},
                          {"score", match_.score},
                          {"wave", wave_},
                          {"health", health_},
                          {"max_health", tuning_.player.health},
                          {"next_wave_tick", state_ == MatchState::Intermission ? nextWaveTick_ : 0},
                          {"enemies_killed", match_.enemiesKilled},
                          {"enemies_alive", enemies_.size()},
                          {"enemies_to_come", pendingSpawns_.size()},
                          {"props_broken", match_.propsBroken},
                          {"disc_throws", match_.discThrows},
                          {"sword_swings", match_.swordSwings},
                          {"spin_attacks", match_.spinAttacks},
                          {"hammer_blows", match_.hammerBlows},
                          {"max_enemies_hit_in_one_tick", match_.maxEnemiesHitInOneTick},
                          {"max_kills_in_one_tick", match_.maxKillsInOneTick},
                          {"pieces_spawned", piecesSpawned_},
                          {"pieces_removed", piecesRemoved_},
                          {"ragdoll_pieces_spawned", ragdollPiecesSpawned_},
                          {"ragdoll_pieces_removed", ragdollPiecesRemoved_},
                          {"ragdoll_pieces_cut", ragdollPiecesCut_},
                          {"ragdoll_bodies_leaked", ragdollBodiesLeaked_},
                          {"player", {playerPosition_.x, playerPosition_.y}}};
  // Kills per enemy kind, in total and by the weapon whose blade touched the enemy.
  nlohmann::json kills = nlohmann::json::object();
  for (size_t k = 0; k < kKindCount; ++k) {
    nlohmann::json perKind = {{"total", match_.killsByKind[k][0]}};
    for (size_t w = 1; w < kWeaponCount; ++w) perKind[kWeaponNames[w]] = match_.killsByKind[k][w];
    kills[kindName(EnemyKind(k))] = std::move(perKind);
  }
  arena["kills_by_kind"] = std::move(kills);
  // The numbers the match plays by, so that a check reads them instead of repeating them.
  arena["tuning"] = {{"grace_seconds", tuning_.match.graceSeconds},
                     {"intermission_seconds", tuning_.match.intermissionSeconds},
                     {"arrival_seconds", tuning_.waves.arrivalSeconds},
                     {"later_arrival_seconds", tuning_.waves.laterArrivalSeconds},
                     {"max_attackers", tuning_.match.maxAttackers}};
  // What is alive in the engine: a match that leaves nothing behind comes back to the same figures.
  arena["resources"] = {{"entities", app_->world().size()},
                        {"bodies", physics_->bodyCount()},
                        {"shapes", physics_->liveShapeCount()},
                        {"joints", physics_->jointCount()},
                        {"gpu_meshes", app_->renderer().liveMeshCount()}};
  return arena;
}

void ArenaGame::dumpFrame(nlohmann::json& line) {
  line["arena"] = dumpMatch();
  inspector_.writeJson(line["inspector"]);
  line["inspector"]["notice"] = inspectorNotice_;
  nlohmann::json splits;
  splitLog_.writeJson(splits);
  line["splits"] = std::move(splits);
  line["piece_budget"] = components::toJson(splits_->pieces().stats());
  const auto& stats = splits_->budget().stats();
  line["budget"] = {{"deferred_total", splitStats_.deferredTotal},
                    {"max_queue", splitStats_.maxQueue},
                    {"max_split_ms", stats.maxSplitMilliseconds},
                    {"max_split_ms_in_a_tick", splitStats_.maxMsInATick},
                    {"max_split_work_ms_in_a_tick", splitStats_.maxWorkMsInATick},
                    {"max_split_wait_ms_in_a_tick", splitStats_.maxWaitMsInATick},
                    {"ms_per_tick", splits_->budget().settings().millisecondsPerTick},
                    {"max_splits_per_tick", splits_->budget().settings().maxSplitsPerTick},
                    {"max_charged_ms_in_a_tick", splitStats_.maxChargedMsInATick},
                    {"max_estimate_ms", stats.maxChargeMilliseconds},
                    {"queue", stats.queueLength}};
}

}  // namespace cleave::arena
