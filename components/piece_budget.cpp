// SPDX-License-Identifier: MIT
// The piece budget (piece_budget.h): one pass over the pieces a tick, retirement in key order.
#include "cleave/components/piece_budget.h"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include <nlohmann/json.hpp>

#include "cleave/components/scene_components.h"
#include "cleave/components/skinned.h"
#include "cleave/components/split_system.h"
#include "cleave/ecs/hierarchy.h"

namespace cleave::components {

const char* toString(PieceRetirement retirement) {
  switch (retirement) {
    case PieceRetirement::Default: return "default";
    case PieceRetirement::Freeze: return "freeze";
    case PieceRetirement::Fade: return "fade";
    case PieceRetirement::Remove: return "remove";
  }
  return "?";
}

nlohmann::json toJson(const PieceBudgetStats& s) {
  return nlohmann::json{{"live", s.live},
                        {"awake", s.awake},
                        {"frozen", s.frozen},
                        {"debris", s.debris},
                        {"frozen_total", s.frozenTotal},
                        {"faded_total", s.fadedTotal},
                        {"removed_total", s.removedTotal},
                        {"thawed_total", s.thawedTotal},
                        {"debris_removed_total", s.debrisRemovedTotal},
                        {"frozen_kg", s.frozenMass},
                        {"faded_kg", s.fadedMass},
                        {"removed_kg", s.removedMass}};
}

namespace {

// One piece as the retirement key sees it (piece_budget.h, "Order").
struct Candidate {
  ecs::Entity entity;
  bool awake = false;
  uint64_t ageSeconds = 0;  // whole seconds since its split
  double volume = 0.0;
  double distance = 0.0;    // to the camera
};

bool retiresFirst(const Candidate& a, const Candidate& b) {
  if (a.awake != b.awake) return !a.awake;
  if (a.ageSeconds != b.ageSeconds) return a.ageSeconds > b.ageSeconds;
  if (a.volume != b.volume) return a.volume < b.volume;
  if (a.distance != b.distance) return a.distance > b.distance;
  return a.entity.index < b.entity.index;
}

Candidate candidateOf(const ecs::World& world, ecs::Entity e, const SplitOrigin& origin, bool awake, uint64_t tick,
                      const glm::dvec3& camera) {
  Candidate c;
  c.entity = e;
  c.awake = awake;
  c.ageSeconds = tick >= origin.tick ? (tick - origin.tick) / 60 : 0;
  if (const auto* info = world.tryGet<MassInfo>(e)) c.volume = info->volume;
  if (const auto* t = world.tryGet<ecs::Transform>(e)) c.distance = glm::length(glm::dvec3(t->position) - camera);
  return c;
}

double massOf(const ecs::World& world, ecs::Entity e) {
  const auto* info = world.tryGet<MassInfo>(e);
  return info ? info->mass : 0.0;
}

bool isPiece(const SplitOrigin& origin) { return origin.generation > 0; }

// A piece creeps when it has been slower than the creep speed for half a second (not at the top of
// a bounce, nor just made).
constexpr uint32_t kCreepTicks = 30;

}  // namespace

void PieceBudget::update(SplitWorld& w, uint64_t tick, const glm::dvec3& camera, float dt) {
  stats_.retiredThisTick = 0;
  stats_.thawedThisTick = 0;
  thawHitPieces(w, dt);
  count(w);
  thawDisturbed(w);
  advanceFades(w, dt);
  if (settings_.enabled) {
    uint32_t quota = settings_.maxRetirementsPerTick;
    freezeRestless(w, tick, quota);
    count(w);
    retireLive(w, tick, camera, quota);
    count(w);
    freezeCreeping(w, tick, camera, quota);
    count(w);
    retireAwake(w, tick, camera, quota);
    count(w);
    trimFrozen(w, tick, camera, quota);
    trimDebris(w);
    stats_.retiredThisTick = settings_.maxRetirementsPerTick - quota;
  }
  count(w);
}

bool PieceBudget::thaw(SplitWorld& w, ecs::Entity piece) {
  const auto* rb = w.world.tryGet<RigidBody>(piece);
  if (!w.world.has<Frozen>(piece) || !rb) return false;
  w.physics.setFrozen(rb->body, false);
  w.world.remove<Frozen>(piece);
  if (auto* motion = w.world.tryGet<PieceMotion>(piece)) motion->restlessTicks = 0;
  disturb(w.physics, rb->body);  // what rested on it may now fall
  stats_.thawedTotal++;
  stats_.thawedThisTick++;
  return true;
}

void PieceBudget::disturb(const physics::PhysicsWorld& physics, physics::BodyId body) {
  if (const auto box = physics.bodyBounds(body)) disturb(box->first, box->second);
}

// Frozen pieces that may have rested on a box disturbed since the last update: their bounds touch it
// (a few millimetres more: a piece resting on another touches it at the margin) and their lowest
// point lies above its middle (on it, not beside it). They thaw, or fade while the live budget is full (they would be retired
// again at once), so that nothing stays hanging in the air.
void PieceBudget::thawDisturbed(SplitWorld& w) {
  std::vector<std::pair<glm::vec3, glm::vec3>> boxes;
  boxes.swap(disturbed_);
  std::vector<ecs::Entity> near;
  const glm::vec3 slack(0.005f);
  for (const auto& [lo, hi] : boxes) {
    for (physics::BodyId body : w.physics.bodiesInBox(lo - slack, hi + slack)) {
      const auto box = w.physics.isFrozen(body) ? w.physics.bodyBounds(body) : std::nullopt;
      if (!box || box->first.y <= 0.5f * (lo.y + hi.y)) continue;
      if (const auto user = w.physics.bodyUserData(body)) near.push_back(fromUserData(*user));
    }
  }
  std::sort(near.begin(), near.end(), [](ecs::Entity a, ecs::Entity b) { return a.index < b.index; });
  near.erase(std::unique(near.begin(), near.end()), near.end());
  for (ecs::Entity e : near) {
    if (!w.world.alive(e) || !w.world.has<Frozen>(e)) continue;
    if (settings_.enabled && stats_.live >= settings_.maxLivePieces) {
      stats_.fadedTotal++;
      stats_.fadedMass += massOf(w.world, e);
      fade(w, e, settings_.fadeSeconds);  // fading disturbs its box too: what rested on it follows
      continue;
    }
    if (thaw(w, e)) stats_.live++;  // thawing disturbs its own box: the next tick goes one further up
  }
}

// Pieces awake and slower than the creep speed for restlessSeconds are frozen (piece_budget.h).
void PieceBudget::freezeRestless(SplitWorld& w, uint64_t tick, uint32_t& quota) {
  if (settings_.restlessSeconds <= 0.f) return;
  const uint32_t limit = uint32_t(settings_.restlessSeconds * 60.f);
  const float lin2 = settings_.creepLinearSpeed * settings_.creepLinearSpeed;
  std::vector<ecs::Entity> restless;
  for (auto [e, motion, rb] : w.world.view<PieceMotion, RigidBody>()) {
    const auto v = w.physics.isAwake(rb.body) ? w.physics.linearVelocity(rb.body) : std::nullopt;
    motion.restlessTicks = v && glm::dot(*v, *v) < lin2 ? motion.restlessTicks + 1 : 0;
    if (motion.restlessTicks > limit && !w.world.has<Ragdoll>(e)) restless.push_back(e);
  }
  for (size_t i = 0; i < restless.size() && quota > 0; ++i, --quota) retire(w, restless[i], PieceRetirement::Freeze, tick);
}

// A frozen piece hit in the last step by an awake body: the contact impulse would change the piece's
// speed by hitSpeed or more, and is more than twice what the hitter's weight puts on it in a step (a
// piece resting on a frozen one is not a hit). The impulse, not the hitter's speed after the step:
// a head-on hit stops the hitter.
void PieceBudget::thawHitPieces(SplitWorld& w, float dt) {
  std::vector<ecs::Entity> hit;
  const float weightPerStep = glm::length(w.physics.gravity()) * dt;
  for (const physics::ContactEvent& ev : w.physics.contactEvents()) {
    const bool frozenA = w.physics.isFrozen(ev.bodyA), frozenB = w.physics.isFrozen(ev.bodyB);
    if (frozenA == frozenB) continue;
    const physics::BodyId frozen = frozenA ? ev.bodyA : ev.bodyB;
    const physics::BodyId hitter = frozenA ? ev.bodyB : ev.bodyA;
    if (!w.physics.isAwake(hitter)) continue;
    if (ev.impulse < settings_.hitSpeed * w.physics.bodyMass(frozen).value_or(0.f)) continue;
    if (ev.impulse <= 2.f * weightPerStep * w.physics.bodyMass(hitter).value_or(0.f)) continue;
    if (const auto user = w.physics.bodyUserData(frozen)) hit.push_back(fromUserData(*user));
  }
  for (ecs::Entity e : hit)
    if (w.world.alive(e)) thaw(w, e);
}

void PieceBudget::count(SplitWorld& w) {
  stats_.live = stats_.awake = stats_.frozen = stats_.debris = 0;
  stats_.frozenMass = 0.0;
  for (auto [e, origin, rb] : w.world.view<SplitOrigin, RigidBody>()) {
    if (!isPiece(origin)) continue;
    if (w.world.has<Frozen>(e)) {
      stats_.frozen++;
      stats_.frozenMass += massOf(w.world, e);
      continue;
    }
    stats_.live++;
    if (w.physics.isAwake(rb.body)) stats_.awake++;
  }
  stats_.debris = uint32_t(w.world.count<Debris>() + w.world.count<Fading>());
}

// Live pieces over maxLivePieces, by each one's retirement.
void PieceBudget::retireLive(SplitWorld& w, uint64_t tick, const glm::dvec3& camera, uint32_t& quota) {
  if (stats_.live <= settings_.maxLivePieces || quota == 0) return;
  std::vector<Candidate> candidates;
  for (auto [e, origin, rb] : w.world.view<SplitOrigin, RigidBody>()) {
    if (!isPiece(origin) || w.world.has<Frozen>(e)) continue;
    candidates.push_back(candidateOf(w.world, e, origin, w.physics.isAwake(rb.body), tick, camera));
  }
  const size_t over = std::min<size_t>(stats_.live - settings_.maxLivePieces, quota);
  std::partial_sort(candidates.begin(), candidates.begin() + over, candidates.end(), retiresFirst);
  for (size_t i = 0; i < over; ++i) {
    const ecs::Entity e = candidates[i].entity;
    const PieceRetirement own = w.world.get<SplitOrigin>(e).retirement;
    retire(w, e, own == PieceRetirement::Default ? settings_.policy : own, tick);
    --quota;
  }
}

// While too many pieces are awake, those that barely move are frozen where they are.
void PieceBudget::freezeCreeping(SplitWorld& w, uint64_t tick, const glm::dvec3& camera, uint32_t& quota) {
  if (stats_.awake <= settings_.maxAwakePieces || quota == 0) return;
  std::vector<Candidate> candidates;
  const float lin2 = settings_.creepLinearSpeed * settings_.creepLinearSpeed;
  const float ang2 = settings_.creepAngularSpeed * settings_.creepAngularSpeed;
  for (auto [e, origin, rb] : w.world.view<SplitOrigin, RigidBody>()) {
    if (!isPiece(origin) || w.world.has<Frozen>(e) || w.world.has<Ragdoll>(e) || !w.physics.isAwake(rb.body)) continue;
    const auto v = w.physics.linearVelocity(rb.body);
    const auto a = w.physics.angularVelocity(rb.body);
    if (!v || !a || glm::dot(*v, *v) >= lin2 || glm::dot(*a, *a) >= ang2) continue;
    const auto* motion = w.world.tryGet<PieceMotion>(e);
    if (!motion || motion->restlessTicks < kCreepTicks) continue;  // slow for a moment is not creeping
    candidates.push_back(candidateOf(w.world, e, origin, true, tick, camera));
  }
  const size_t over = std::min<size_t>({stats_.awake - settings_.maxAwakePieces, quota, candidates.size()});
  std::partial_sort(candidates.begin(), candidates.begin() + over, candidates.end(), retiresFirst);
  for (size_t i = 0; i < over; ++i) {
    retire(w, candidates[i].entity, PieceRetirement::Freeze, tick);
    --quota;
  }
}

// Still more than maxAwakePieces awake (a blade through a heap makes hundreds of pieces at once):
// the excess retires in key order, each by its retirement, except that a piece moving faster than
// the creep speeds fades rather than freeze in mid-air.
void PieceBudget::retireAwake(SplitWorld& w, uint64_t tick, const glm::dvec3& camera, uint32_t& quota) {
  if (stats_.awake <= settings_.maxAwakePieces || quota == 0) return;
  std::vector<Candidate> candidates;
  for (auto [e, origin, rb] : w.world.view<SplitOrigin, RigidBody>()) {
    if (!isPiece(origin) || w.world.has<Frozen>(e) || !w.physics.isAwake(rb.body)) continue;
    candidates.push_back(candidateOf(w.world, e, origin, true, tick, camera));
  }
  const size_t over = std::min<size_t>({stats_.awake - settings_.maxAwakePieces, quota, candidates.size()});
  std::partial_sort(candidates.begin(), candidates.begin() + over, candidates.end(), retiresFirst);
  const float lin2 = settings_.creepLinearSpeed * settings_.creepLinearSpeed;
  const float ang2 = settings_.creepAngularSpeed * settings_.creepAngularSpeed;
  for (size_t i = 0; i < over; ++i) {
    const ecs::Entity e = candidates[i].entity;
    const PieceRetirement own = w.world.get<SplitOrigin>(e).retirement;
    PieceRetirement how = own == PieceRetirement::Default ? settings_.policy : own;
    const physics::BodyId body = w.world.get<RigidBody>(e).body;
    const glm::vec3 v = w.physics.linearVelocity(body).value_or(glm::vec3(0.f));
    const glm::vec3 a = w.physics.angularVelocity(body).value_or(glm::vec3(0.f));
    if (how == PieceRetirement::Freeze && (glm::dot(v, v) >= lin2 || glm::dot(a, a) >= ang2)) how = PieceRetirement::Fade;
    retire(w, e, how, tick);
    --quota;
  }
}

// Frozen pieces over maxFrozenPieces fade, in retirement order.
void PieceBudget::trimFrozen(SplitWorld& w, uint64_t tick, const glm::dvec3& camera, uint32_t& quota) {
  if (stats_.frozen <= settings_.maxFrozenPieces || quota == 0) return;
  std::vector<Candidate> candidates;
  for (auto [e, origin, frozen] : w.world.view<SplitOrigin, Frozen>())
    candidates.push_back(candidateOf(w.world, e, origin, false, tick, camera));
  const size_t over = std::min<size_t>(stats_.frozen - settings_.maxFrozenPieces, quota);
  std::partial_sort(candidates.begin(), candidates.begin() + over, candidates.end(), retiresFirst);
  for (size_t i = 0; i < over; ++i) {
    stats_.fadedTotal++;
    stats_.fadedMass += massOf(w.world, candidates[i].entity);
    fade(w, candidates[i].entity, settings_.fadeSeconds);
    --quota;
  }
}

// Render-only pieces over maxDebris: the oldest go at once (fading ones first, then falling debris).
void PieceBudget::trimDebris(SplitWorld& w) {
  if (stats_.debris <= settings_.maxDebris) return;
  std::vector<std::tuple<bool, uint64_t, uint32_t>> order;  // (not fading, made at, index)
  std::vector<ecs::Entity> byIndex;
  auto add = [&](ecs::Entity e, bool fading) {
    const auto* origin = w.world.tryGet<SplitOrigin>(e);
    order.emplace_back(!fading, origin ? origin->tick : 0, uint32_t(byIndex.size()));
    byIndex.push_back(e);
  };
  for (auto [e, f] : w.world.view<Fading>()) add(e, true);
  for (auto [e, d] : w.world.view<Debris>())
    if (!w.world.has<Fading>(e)) add(e, false);
  const size_t over = std::min<size_t>(stats_.debris - settings_.maxDebris, order.size());
  std::partial_sort(order.begin(), order.begin() + over, order.end());
  for (size_t i = 0; i < over; ++i) w.world.destroy(byIndex[std::get<2>(order[i])]);
  stats_.debrisRemovedTotal += over;
}

void PieceBudget::retire(SplitWorld& w, ecs::Entity piece, PieceRetirement how, uint64_t tick) {
  const double mass = massOf(w.world, piece);
  if (how == PieceRetirement::Freeze) {
    const auto* rb = w.world.tryGet<RigidBody>(piece);
    if (rb && !w.world.has<Ragdoll>(piece) && w.physics.setFrozen(rb->body, true)) {
      w.world.add<Frozen>(piece, Frozen{tick});
      stats_.frozenTotal++;
      return;
    }
    how = PieceRetirement::Fade;  // a ragdoll (bodies on joints) cannot freeze
  }
  if (how == PieceRetirement::Fade) {
    stats_.fadedTotal++;
    stats_.fadedMass += mass;
    fade(w, piece, settings_.fadeSeconds);
    return;
  }
  stats_.removedTotal++;
  stats_.removedMass += mass;
  if (const auto* rb = w.world.tryGet<RigidBody>(piece)) disturb(w.physics, rb->body);
  w.world.destroy(piece);
}

// The piece loses its body (the hooks free it) and what made it cuttable; it shrinks away.
void PieceBudget::fade(SplitWorld& w, ecs::Entity piece, float seconds) {
  if (const auto* rb = w.world.tryGet<RigidBody>(piece)) disturb(w.physics, rb->body);
  w.world.remove<Ragdoll>(piece);
  w.world.remove<RigidBody>(piece);
  w.world.remove<Frozen>(piece);
  w.world.remove<Splitable>(piece);
  w.world.remove<ColliderParts>(piece);
  w.world.remove<Debris>(piece);
  const auto* t = w.world.tryGet<ecs::Transform>(piece);
  w.world.add<Fading>(piece, Fading{seconds, seconds, t ? t->scale : glm::vec3(1.f)});
}

void PieceBudget::advanceFades(SplitWorld& w, float dt) {
  std::vector<ecs::Entity> done;
  for (auto [e, f, t] : w.world.view<Fading, ecs::Transform>()) {
    f.secondsLeft -= dt;
    if (f.secondsLeft <= 0.f) {
      done.push_back(e);
      continue;
    }
    // Smoothstep down, so the piece eases out rather than stopping at a size.
    const float x = f.secondsLeft / std::max(f.seconds, 1e-3f);
    t.scale = f.scale * (x * x * (3.f - 2.f * x));
  }
  for (ecs::Entity e : done) w.world.destroy(e);
  if (!done.empty() || w.world.count<Fading>() > 0) ecs::updateWorldTransforms(w.world);
}

}  // namespace cleave::components
