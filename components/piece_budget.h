// SPDX-License-Identifier: MIT
// PieceBudget: the other half of the thesis's resource manager. The SplitBudget bounds the work of
// the splits in a tick; the piece budget bounds what the splits leave behind, so that a session of
// cutting never slows: at most `maxLivePieces` pieces simulated, at most `maxAwakePieces` of them
// awake, at most `maxDebris` render-only pieces, at most `maxFrozenPieces` frozen ones.
//
// A piece is an entity made by a split (SplitOrigin::generation > 0). Authored objects are never
// retired. Each tick, after the physics step and the transform sync (PhysicsSync phase), update():
//   1. thaws frozen pieces that an awake body hit in the last step (hitSpeed), and those
//      next to something that went away (disturb): they are simulated again, at rest, and fall or
//      tumble as the hit makes them; freezes pieces that stay awake without settling (restless);
//   2. retires live pieces over maxLivePieces by their retirement (below); freezes awake pieces
//      that barely move (creep) while more than maxAwakePieces are awake, and if that is not
//      enough, retires the excess awake pieces in key order (a moving piece fades rather than
//      freeze in mid-air);
//   3. fades frozen pieces over maxFrozenPieces, removes the oldest debris over maxDebris, and lets
//      fading pieces shrink away.
// At most maxRetirementsPerTick pieces are frozen or retired in one tick (pieces faded because what
// held them went away while the live budget is full excepted); the rest wait for the next ticks.
// Ages and times count fixed ticks of 1/60 s, and "above" is along +y (the engine's up).
//
// Retirement (per piece: SplitOrigin::retirement, copied from the Splitable of the object it came
// from; Default takes the settings' policy):
//   Freeze  the body leaves the simulation where it lies (PhysicsWorld::setFrozen): drawn, collided
//           with, cut again like any piece, thawed when hit. Pieces on joints (ragdolls) fade.
//   Fade    the body goes at once (its mass and momentum are counted as gone); the mesh stays drawn
//           for fadeSeconds, shrinking to nothing about its centre of mass, then the entity goes.
//   Remove  the entity goes at once.
//
// Order (the retirement key, total and deterministic): sleeping pieces before awake ones; then the
// older before the younger, by whole seconds since their split; then the smaller volume before the
// larger; then the farther from the camera before the nearer; then the lower entity index. A frozen
// piece's key is the same with "frozen" in place of "sleeping"; debris goes oldest first.
//
// Accounting: every piece retired is counted with its mass (PieceBudgetStats), so mass and momentum
// checks of a replay can add what left the simulation back in. Deterministic: the budget reads only
// the world, the physics state and the tick, never a clock, so a replay gives the same state on any
// number of split threads.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>

#include "cleave/ecs/world.h"
#include "cleave/physics/physics_world.h"

namespace cleave::components {

struct SplitWorld;  // split_system.h

enum class PieceRetirement : uint8_t {
  Default,  // the piece budget's policy (Splitable only)
  Freeze,
  Fade,
  Remove,
};
const char* toString(PieceRetirement retirement);

struct PieceBudgetSettings {
  bool enabled = true;  // false: nothing is retired (the counts are still kept)
  uint32_t maxLivePieces = 400;    // simulated pieces, awake or asleep (frozen and debris not counted)
  uint32_t maxAwakePieces = 96;    // beyond: creeping pieces freeze, then the excess retires in key order
  uint32_t maxFrozenPieces = 1500; // beyond: frozen pieces fade, in retirement order
  uint32_t maxDebris = 96;         // render-only pieces (Debris and fading); beyond: the oldest go
  uint32_t maxRetirementsPerTick = 48;
  PieceRetirement policy = PieceRetirement::Freeze;  // for pieces whose retirement is Default
  float fadeSeconds = 1.0f;        // a fading piece shrinks away in this time
  // m/s: a frozen piece thaws when an awake body's contact impulse would change its speed by this
  // much (impulse over the piece's mass) and is more than twice the hitter's weight over a step.
  float hitSpeed = 0.1f;
  // Creep: an awake piece slower than both for half a second is frozen while more than
  // maxAwakePieces are awake.
  float creepLinearSpeed = 0.25f;  // m/s
  float creepAngularSpeed = 1.0f;  // rad/s
  // An awake piece slower than creepLinearSpeed for this long is frozen whatever the limits: Bullet
  // puts a piece to sleep after 2 s below its thresholds, so one still awake then is trembling in a
  // heap or spinning on the spot, and would keep its island awake for good. 0: never.
  float restlessSeconds = 3.0f;
  // The smallest piece that gets a rigid body; smaller ones become render-only debris (as
  // Splitable::smallPieces says). Thickness is the piece's smallest extent along its principal axes:
  // slivers thinner than this spin and sink in the solver whatever their volume.
  double minBodyVolume = 1e-5;     // m^3 (10 cm^3) (the larger of this and Splitable::minPieceVolume counts)
  double minBodyThickness = 0.015; // m
};

struct PieceBudgetStats {
  // Now (after the last update).
  uint32_t live = 0;     // simulated pieces
  uint32_t awake = 0;    // of which awake
  uint32_t frozen = 0;
  uint32_t debris = 0;   // render-only: Debris and fading pieces
  double frozenMass = 0.0;  // kg, of the pieces frozen now (out of the simulation, still in the world)
  // Over the whole run: how many times pieces were frozen, faded, removed, thawed; and the mass that
  // left the world by fading (from the simulation or frozen) and by removal. Simulated mass + frozen
  // mass + faded + removed (+ debris, which never had a body) is what the splits made.
  uint64_t frozenTotal = 0, fadedTotal = 0, removedTotal = 0, thawedTotal = 0, debrisRemovedTotal = 0;
  double fadedMass = 0.0, removedMass = 0.0;  // kg
  uint32_t retiredThisTick = 0;
  uint32_t thawedThisTick = 0;
};

// How long a simulated piece has been awake without settling (the piece budget keeps it).
struct PieceMotion {
  uint32_t restlessTicks = 0;  // consecutive ticks awake and slower than the creep speed
};

// A frozen piece (its body is frozen in the physics world).
struct Frozen {
  uint64_t tick = 0;  // when it was frozen
};

// A piece fading out (no body): drawn shrinking to nothing, then destroyed.
struct Fading {
  float secondsLeft = 1.f;
  float seconds = 1.f;
  glm::vec3 scale{1.f};  // the scale it had when it started fading
};

// The stats as a JSON object (live, awake, frozen, debris, and the run's totals with their mass), for
// state dumps and benchmarks.
nlohmann::json toJson(const PieceBudgetStats& stats);

class PieceBudget {
 public:
  explicit PieceBudget(PieceBudgetSettings settings = {}) : settings_(settings) {}
  const PieceBudgetSettings& settings() const { return settings_; }
  void setSettings(const PieceBudgetSettings& settings) { settings_ = settings; }
  const PieceBudgetStats& stats() const { return stats_; }

  // One tick's work (see the header comment), after the physics step and the transform sync.
  void update(SplitWorld& w, uint64_t tick, const glm::dvec3& camera, float dt);

  // Returns a frozen piece to the simulation (a hit, a cut, gameplay). False when it is not frozen.
  bool thaw(SplitWorld& w, ecs::Entity piece);

  // Something that held pieces up left the box [lo, hi] (a body cut, faded, removed or thawed): the
  // frozen pieces whose bounds touch it thaw at the next update, so nothing stays hanging in the air.
  // Thawing spreads one neighbour further each tick.
  void disturb(glm::vec3 lo, glm::vec3 hi) { disturbed_.emplace_back(lo, hi); }
  // Disturbs the box of a body (nothing for a stale handle).
  void disturb(const physics::PhysicsWorld& physics, physics::BodyId body);

 private:
  void thawHitPieces(SplitWorld& w, float dt);
  void thawDisturbed(SplitWorld& w);
  void freezeRestless(SplitWorld& w, uint64_t tick, uint32_t& quota);
  void count(SplitWorld& w);
  void retireLive(SplitWorld& w, uint64_t tick, const glm::dvec3& camera, uint32_t& quota);
  void freezeCreeping(SplitWorld& w, uint64_t tick, const glm::dvec3& camera, uint32_t& quota);
  void retireAwake(SplitWorld& w, uint64_t tick, const glm::dvec3& camera, uint32_t& quota);
  void trimFrozen(SplitWorld& w, uint64_t tick, const glm::dvec3& camera, uint32_t& quota);
  void trimDebris(SplitWorld& w);
  void retire(SplitWorld& w, ecs::Entity piece, PieceRetirement how, uint64_t tick);
  void fade(SplitWorld& w, ecs::Entity piece, float seconds);
  void advanceFades(SplitWorld& w, float dt);

  PieceBudgetSettings settings_;
  PieceBudgetStats stats_;
  std::vector<std::pair<glm::vec3, glm::vec3>> disturbed_;
};

}  // namespace cleave::components
