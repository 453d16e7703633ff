// SPDX-License-Identifier: MIT
// The match of the arena sample as a state machine (see MatchState): menu, starting, the grace period
// and the pauses between waves (intermission), the waves, defeat, and the reset that gives every
// match a clean arena. The numbers it plays by are ArenaTuning's.
#include <algorithm>
#include <cmath>

#include "cleave/components/split_system.h"
#include "game/arena/arena_game.h"
#include "game/arena/arena_layout.h"

namespace cleave::arena {

namespace {

// In wave 1 (one gate, one after another) the skinned warriors are spread through the line: with
// 6 enemies and 2 skinned, the second and the fifth.
bool skinnedInFirstWave(int i, int count, int skinned) {
  for (int k = 0; k < skinned; ++k)
    if (i == k * count / skinned + 1) return true;
  return false;
}

}  // namespace

void ArenaGame::gameplay(app::TickContext& c) {
  const float dt = float(c.dt);
  hurtFlash_ = std::max(0.f, hurtFlash_ - dt);
  if (swing_.ticksLeft > 0) --swing_.ticksLeft;
  if (c.input.pressed(input::Key::F1)) toggleInspector(c);
  updateCamera(dt);
  switch (state_) {
    case MatchState::Menu:
      updateMenu(c);
      playerSpeed_ = 0.f;
      break;
    case MatchState::Starting:
      if (c.tick >= stateTick_ + ticksOf(tuning_.match.startingSeconds)) {
        removeEntity(quitCube_);  // the menu is over: the cube that was not chosen goes
        quitCube_ = {};
        enterIntermission(c.tick, tuning_.match.graceSeconds);
      }
      break;
    case MatchState::Intermission:
      updatePlayer(c);
      updateWeapons(c);
      updateIntermission(c);
      break;
    case MatchState::Playing:
      updatePlayer(c);
      updateWeapons(c);
      updateWaves(c);
      break;
    case MatchState::Defeated:
      updateDefeat(c);
      break;
    case MatchState::Quitting:
      if (c.tick >= stateTick_ + ticksOf(tuning_.match.quitSeconds)) c.app.requestQuit();
      break;
  }
  updateDisc(c);
  updateHammer(c);
  // The player's body follows the player (it shoves pieces aside but is never cut).
  if (const auto* rb = c.world.tryGet<components::RigidBody>(player_)) {
    physics_->setBodyTransform(rb->body, physics::BodyTransform{glm::vec3(playerPosition_.x, 0.87f, playerPosition_.y),
                                                                glm::quat(1.f, 0.f, 0.f, 0.f)});
    physics_->setVelocity(rb->body, glm::vec3(0.f), glm::vec3(0.f));
  }
}

void ArenaGame::startWave(uint64_t tick) {
  ++wave_;
  waveBannerTick_ = tick;
  state_ = MatchState::Playing;
  stateTick_ = tick;
  // Wave 1 comes through the north gate, one after another; later waves through the four gates in
  // turn, one arrival after another, the skinned warriors last (WaveTuning).
  const WaveTuning& t = tuning_.waves;
  const int gladiators = std::max(0, t.gladiators + (wave_ - 1) * t.gladiatorsPerWave);
  const int skinned = std::max(0, t.skinned + (wave_ - 1) * t.skinnedPerWave);
  const int count = gladiators + skinned;
  const bool first = wave_ == 1;
  const float gap = first ? t.arrivalSeconds : t.laterArrivalSeconds;
  for (int i = 0; i < count; ++i) {
    const int gate = first ? 0 : i % 4;
    const int slot = first ? i : i / 4;
    const float angle = float(gate) * kPi * 0.5f;
    const glm::vec2 inward = -compass(angle);
    const glm::vec2 side(-inward.y, inward.x);
    const float lateral = ((slot % 2) ? 1.f : -1.f) * (0.7f + 0.9f * float(slot / 2)) + (nextRandom() - 0.5f) * 0.3f;
    PendingSpawn s;
    const bool isSkinned = first ? skinnedInFirstWave(i, count, skinned) : i >= gladiators;
    s.kind = isSkinned ? EnemyKind::Skinned : EnemyKind::Gladiator;
    s.position = compass(angle) * (kArenaRadius - 1.2f) + side * lateral;
    s.yaw = std::atan2(inward.x, inward.y);
    s.tick = tick + ticksOf(t.firstArrivalSeconds + float(i) * gap);
    pendingSpawns_.push_back(s);
  }
}

void ArenaGame::updateWaves(app::TickContext& c) {
  EnemyContext ec = enemyContext();
  for (size_t i = 0; i < pendingSpawns_.size();) {
    if (pendingSpawns_[i].tick > c.tick) {
      ++i;
      continue;
    }
    const PendingSpawn s = pendingSpawns_[i];
    pendingSpawns_.erase(pendingSpawns_.begin() + long(i));
    Enemy e = spawnEnemy(ec, enemyMeshes_, s.kind, s.position, s.yaw);
    if (e.entity.isNull()) continue;
    e.spawnTick = c.tick;
    c.world.add<ArenaTag>(e.entity, ArenaTag{ArenaTag::Enemy});
    enemies_.push_back(e);
  }
  if (enemies_.empty() && pendingSpawns_.empty()) {
    enterIntermission(c.tick, tuning_.match.intermissionSeconds);
    return;
  }
  const EnemyField field{playerPosition_, kPlayerRadius, &pillars_, kArenaRadius};
  const int damage = updateEnemies(ec, enemies_, field, tuning_, float(c.dt));
  if (damage > 0) {
    health_ = std::max(0, health_ - damage);
    hurtFlash_ = 0.35f;
    if (health_ == 0) enterDefeat(c.tick);
  }
}

void ArenaGame::enterIntermission(uint64_t tick, float seconds) {
  state_ = MatchState::Intermission;
  stateTick_ = tick;
  nextWaveTick_ = tick + ticksOf(seconds);
  refillTick_ = tick + ticksOf(tuning_.match.refillDelaySeconds);
}

void ArenaGame::updateIntermission(app::TickContext& c) {
  // The health bar fills up at one pace (empty to full in refillSeconds), and is full when the
  // next wave begins whatever the pause.
  const int full = tuning_.player.health;
  if (c.tick >= refillTick_ && health_ < full) {
    const int fillTicks = int(std::max<uint64_t>(1, ticksOf(tuning_.match.refillSeconds)));
    health_ = std::min(full, health_ + (full + fillTicks - 1) / fillTicks);
  }
  if (c.tick < nextWaveTick_) return;
  health_ = full;
  startWave(c.tick);
}

void ArenaGame::enterDefeat(uint64_t tick) {
  state_ = MatchState::Defeated;
  stateTick_ = tick;
  // Nobody else comes through the gates, and the player's weapons are gone.
  pendingSpawns_.clear();
  if (disc_.active) removeEntity(disc_.splitter);
  disc_ = Disc{};
  swing_ = Swing{};
  hammer_ = Hammer{};
}

void ArenaGame::updateDefeat(app::TickContext& c) {
  playerSpeed_ = 0.f;
  EnemyContext ec = enemyContext();
  cheerEnemies(ec, enemies_, playerPosition_, float(c.dt));
  if (c.tick <= stateTick_ + ticksOf(tuning_.match.defeatMenuDelaySeconds)) return;
  if (!c.input.pressed(input::Key::Enter) && !c.input.pressed(input::MouseButton::Left)) return;
  resetToMenu(c.tick);
  updateCamera(float(c.dt));
}

void ArenaGame::clearArena() {
  // Everything the last match left on the sand: enemies, the disc, every piece (with its body, its
  // ragdoll's bone bodies and its GPU mesh: removeEntity), the props whole or broken, the menu cubes.
  for (const Enemy& e : enemies_) removeEntity(e.entity);
  enemies_.clear();
  pendingSpawns_.clear();
  if (disc_.active) removeEntity(disc_.splitter);
  disc_ = Disc{};
  swing_ = Swing{};
  hammer_ = Hammer{};
  ecs::World& world = app_->world();
  std::vector<ecs::Entity> doomed, pieces;
  for (auto [e, tag] : world.view<ArenaTag>()) {
    if (tag.kind == ArenaTag::Piece) pieces.push_back(e);
    if (tag.kind == ArenaTag::Prop || tag.kind == ArenaTag::MenuCube) doomed.push_back(e);
  }
  for (ecs::Entity e : pieces) removeEntity(e);
  piecesRemoved_ += pieces.size();
  for (ecs::Entity e : doomed) removeEntity(e);
  startCube_ = quitCube_ = {};
}

void ArenaGame::resetToMenu(uint64_t tick) {
  clearArena();
  match_ = MatchStats{};
  health_ = tuning_.player.health;
  wave_ = 0;
  nextWaveTick_ = refillTick_ = waveBannerTick_ = 0;
  playerPosition_ = glm::vec2(0.f);
  playerYaw_ = 0.f;
  playerSpeed_ = 0.f;
  hurtFlash_ = 0.f;
  state_ = MatchState::Menu;
  stateTick_ = tick;
  spawnProps();
  spawnMenuCubes();
}

}  // namespace cleave::arena
