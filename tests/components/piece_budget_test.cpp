// SPDX-License-Identifier: MIT
// The piece budget (components/piece_budget.h): which pieces it retires first (the documented key),
// what each retirement does (freeze, fade, remove; per piece or by policy), the mass it accounts
// for, thawing frozen pieces that are hit or lose what held them up, the debris and live limits,
// pieces that come to rest, the same state on any number of split threads; and two things the
// feature changed beside it: slivers become debris, and a persistent blade only asks for bodies its
// plane crosses.
//
// Pieces are either really split (splitNow, splitters, scenes) or, where the key needs exact ages,
// sizes and places, made as a split leaves them: a body made through the bridge (MassInfo,
// Transform, RigidBody) with a SplitOrigin one cut deep.
#include <algorithm>
#include <cstdio>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "cleave/components/piece_budget.h"
#include "cleave/geometry/primitives.h"
#include "tests/components/sim_harness.h"

namespace cleave::components {
namespace {

using testing::kDt;
using testing::scenePath;
using testing::Sim;

// One whole tick with the piece budget: the scene's gameplay, then Simulation::step (the harness's
// Sim::step leaves the budget's settle stage out).
void tick(Sim& sim) {
  SplitWorld w = sim.sw();
  sim.runner.update(w, sim.tick, kDt);
  sim.simulation.step(sim.tick, kDt, sim.camera);
  ++sim.tick;
}

void ticks(Sim& sim, int n) {
  for (int i = 0; i < n; ++i) tick(sim);
}

// The budget's own tick, alone, at `tick` seen from `camera`.
void settleOnce(Sim& sim, uint64_t tick, glm::dvec3 camera = glm::dvec3(0.0), float dt = float(kDt)) {
  SplitWorld w = sim.sw();
  sim.splits.pieces().update(w, tick, camera, dt);
}

template <class Edit>
void editBudget(Sim& sim, Edit edit) {
  PieceBudgetSettings s = sim.splits.pieces().settings();
  edit(s);
  sim.splits.pieces().setSettings(s);
}

// A static floor whose top is y = 0 (no entity: nothing the budget could retire).
void addFloor(Sim& sim) {
  const physics::ShapeId shape = sim.physics.createShape(physics::ShapeDef::box(glm::vec3(30.f, 0.5f, 30.f))).value();
  physics::BodyDef def;
  def.shape = shape;
  def.position = glm::vec3(0.f, -0.5f, 0.f);
  ASSERT_TRUE(sim.physics.createBody(def).ok());
  sim.physics.destroyShape(shape);
}

// Teleports an entity's body and transform (so that sizes are computed at one place, then spread).
void moveTo(Sim& sim, ecs::Entity e, glm::vec3 position) {
  auto& t = sim.world.get<ecs::Transform>(e);
  t.position = position;
  sim.world.get<ecs::WorldTransform>(e).matrix = ecs::localMatrix(t);
  ASSERT_TRUE(sim.physics.setBodyTransform(sim.world.get<RigidBody>(e).body, physics::BodyTransform{position, t.rotation}));
}

// A piece as a split leaves it: a box of half extents `half` on a dynamic body (500 kg/m^3), one
// cut deep, made in tick `madeTick`, at `position`. Boxes of one size are built at the origin and
// then moved, so that their volumes are bit-identical.
ecs::Entity addPiece(Sim& sim, glm::vec3 half, glm::vec3 position, uint64_t madeTick,
                     PieceRetirement retirement = PieceRetirement::Default, double density = 500.0) {
  Splitable sp;
  sp.density = density;
  const ecs::Entity e = testing::addSplitableBody(sim, "piece", geometry::primitives::box(half), sp, density, glm::vec3(0.f));
  SplitOrigin origin;
  origin.generation = 1;
  origin.tick = madeTick;
  origin.retirement = retirement;
  sim.world.add<SplitOrigin>(e, origin);
  sim.world.add<PieceMotion>(e, PieceMotion{});
  moveTo(sim, e, position);
  return e;
}

physics::BodyId bodyOf(Sim& sim, ecs::Entity e) { return sim.world.get<RigidBody>(e).body; }

// The pieces (of `among`) the budget froze.
std::set<ecs::Entity> frozenOf(Sim& sim, const std::vector<ecs::Entity>& among) {
  std::set<ecs::Entity> out;
  for (ecs::Entity e : among)
    if (sim.world.alive(e) && sim.world.has<Frozen>(e)) out.insert(e);
  return out;
}

// Pieces simulated now, counted from the world (not from the budget's stats).
uint32_t livePieces(Sim& sim) {
  uint32_t n = 0;
  for (auto [e, origin, rb] : sim.world.view<SplitOrigin, RigidBody>())
    if (origin.generation > 0 && !sim.world.has<Frozen>(e)) ++n;
  return n;
}

uint32_t awakePieces(Sim& sim) {
  uint32_t n = 0;
  for (auto [e, origin, rb] : sim.world.view<SplitOrigin, RigidBody>())
    if (origin.generation > 0 && sim.physics.isAwake(rb.body)) ++n;
  return n;
}

// Retire `count` of `pieces` by freezing, in one update at `tick` seen from the origin.
void retireByFreezing(Sim& sim, const std::vector<ecs::Entity>& pieces, uint32_t count, uint64_t tick) {
  editBudget(sim, [&](PieceBudgetSettings& s) {
    s.policy = PieceRetirement::Freeze;
    s.maxLivePieces = uint32_t(pieces.size()) - count;
    s.maxRetirementsPerTick = 100;
  });
  settleOnce(sim, tick);
}

// ---- the retirement key ----
// Each test sets two groups apart by one rule of the key only: the group that must go first is tied
// with the other on the rules before it and loses on every rule after it, so any other order (or a
// rule left out) retires the wrong group.

TEST(PieceBudget, SleepingPiecesRetireBeforeAwakeOnes) {
  Sim sim;
  sim.physics.setGravity(glm::vec3(0.f));
  // The awake ones are older, smaller, farther from the camera and lower in index.
  const ecs::Entity awake0 = addPiece(sim, glm::vec3(0.2f), glm::vec3(10, 0, 0), 0);
  const ecs::Entity awake1 = addPiece(sim, glm::vec3(0.2f), glm::vec3(-10, 0, 0), 0);
  const ecs::Entity asleep0 = addPiece(sim, glm::vec3(0.3f), glm::vec3(5, 0, 0), 120);
  const ecs::Entity asleep1 = addPiece(sim, glm::vec3(0.3f), glm::vec3(-5, 0, 0), 120);
  for (int i = 0; i < 180; ++i) ASSERT_EQ(sim.physics.step(kDt), physics::PhysicsStatus::Ok);  // all fall asleep
  for (ecs::Entity e : {awake0, awake1, asleep0, asleep1}) ASSERT_FALSE(sim.physics.isAwake(bodyOf(sim, e)));
  sim.physics.activate(bodyOf(sim, awake0));
  sim.physics.activate(bodyOf(sim, awake1));
  retireByFreezing(sim, {awake0, awake1, asleep0, asleep1}, 2, 600);
  EXPECT_EQ(frozenOf(sim, {awake0, awake1, asleep0, asleep1}), (std::set<ecs::Entity>{asleep0, asleep1}));
}

TEST(PieceBudget, OlderPiecesRetireBeforeYoungerOnes) {
  Sim sim;
  sim.physics.setGravity(glm::vec3(0.f));
  // Made later (higher index), larger and nearer, but 10 s old against 5 s.
  const ecs::Entity young0 = addPiece(sim, glm::vec3(0.2f), glm::vec3(10, 0, 0), 300);
  const ecs::Entity young1 = addPiece(sim, glm::vec3(0.2f), glm::vec3(-10, 0, 0), 300);
  const ecs::Entity old0 = addPiece(sim, glm::vec3(0.3f), glm::vec3(5, 0, 0), 0);
  const ecs::Entity old1 = addPiece(sim, glm::vec3(0.3f), glm::vec3(-5, 0, 0), 0);
  retireByFreezing(sim, {young0, young1, old0, old1}, 2, 600);
  EXPECT_EQ(frozenOf(sim, {young0, young1, old0, old1}), (std::set<ecs::Entity>{old0, old1}));
}

TEST(PieceBudget, AgeCountsInWholeSecondsSoTheSmallerOfTwoEquallyOldGoesFirst) {
  Sim sim;
  sim.physics.setGravity(glm::vec3(0.f));
  // 2.9 s and 2.1 s old: both "2 seconds". The younger is smaller (and nearer, and made later).
  const uint64_t now = 600;
  const ecs::Entity older = addPiece(sim, glm::vec3(0.3f), glm::vec3(10, 0, 0), now - 174);
  const ecs::Entity smaller = addPiece(sim, glm::vec3(0.2f), glm::vec3(5, 0, 0), now - 126);
  retireByFreezing(sim, {older, smaller}, 1, now);
  EXPECT_EQ(frozenOf(sim, {older, smaller}), (std::set<ecs::Entity>{smaller}));
}

TEST(PieceBudget, SmallerPiecesRetireBeforeLargerOnes) {
  Sim sim;
  sim.physics.setGravity(glm::vec3(0.f));
  // The same age; the small ones are nearer and made later.
  const ecs::Entity large0 = addPiece(sim, glm::vec3(0.3f), glm::vec3(10, 0, 0), 60);
  const ecs::Entity large1 = addPiece(sim, glm::vec3(0.3f), glm::vec3(-10, 0, 0), 60);
  const ecs::Entity small0 = addPiece(sim, glm::vec3(0.2f), glm::vec3(5, 0, 0), 60);
  const ecs::Entity small1 = addPiece(sim, glm::vec3(0.2f), glm::vec3(-5, 0, 0), 60);
  retireByFreezing(sim, {large0, large1, small0, small1}, 2, 600);
  EXPECT_EQ(frozenOf(sim, {large0, large1, small0, small1}), (std::set<ecs::Entity>{small0, small1}));
}

TEST(PieceBudget, FartherPiecesRetireBeforeNearerOnes) {
  Sim sim;
  sim.physics.setGravity(glm::vec3(0.f));
  // The same age and size; the far ones are made later. The camera is at the origin.
  const ecs::Entity near0 = addPiece(sim, glm::vec3(0.25f), glm::vec3(3, 0, 0), 60);
  const ecs::Entity near1 = addPiece(sim, glm::vec3(0.25f), glm::vec3(0, 0, -3), 60);
  const ecs::Entity far0 = addPiece(sim, glm::vec3(0.25f), glm::vec3(-8, 0, 0), 60);
  const ecs::Entity far1 = addPiece(sim, glm::vec3(0.25f), glm::vec3(0, 8, 0), 60);
  ASSERT_EQ(sim.world.get<MassInfo>(near0).volume, sim.world.get<MassInfo>(far1).volume);
  retireByFreezing(sim, {near0, near1, far0, far1}, 2, 600);
  EXPECT_EQ(frozenOf(sim, {near0, near1, far0, far1}), (std::set<ecs::Entity>{far0, far1}));
}

TEST(PieceBudget, OnAFullTieTheLowerEntityIndexRetiresFirst) {
  Sim sim;
  sim.physics.setGravity(glm::vec3(0.f));
  // The same age, size and distance (5 m, exactly) from the camera at the origin.
  std::vector<ecs::Entity> pieces;
  for (glm::vec3 at : {glm::vec3(5, 0, 0), glm::vec3(-5, 0, 0), glm::vec3(0, 0, 5), glm::vec3(0, 5, 0)})
    pieces.push_back(addPiece(sim, glm::vec3(0.25f), at, 60));
  std::vector<ecs::Entity> byIndex = pieces;
  std::sort(byIndex.begin(), byIndex.end(), [](ecs::Entity a, ecs::Entity b) { return a.index < b.index; });
  retireByFreezing(sim, pieces, 2, 600);
  EXPECT_EQ(frozenOf(sim, pieces), (std::set<ecs::Entity>{byIndex[0], byIndex[1]}));
}

// ---- what each retirement does ----

TEST(PieceBudget, FreezeLeavesThePieceDrawnAndCollidableWhereItLies) {
  Sim sim;
  const ecs::Entity piece = addPiece(sim, glm::vec3(0.25f), glm::vec3(0, 3, 0), 0);  // in mid-air
  const physics::BodyId body = bodyOf(sim, piece);
  editBudget(sim, [](PieceBudgetSettings& s) {
    s.policy = PieceRetirement::Freeze;
    s.maxLivePieces = 0;
  });
  settleOnce(sim, 60);
  ASSERT_TRUE(sim.world.alive(piece));
  EXPECT_TRUE(sim.world.has<Frozen>(piece));
  EXPECT_EQ(sim.world.get<Frozen>(piece).tick, 60u);
  EXPECT_TRUE(sim.physics.isFrozen(body));
  EXPECT_TRUE(sim.world.has<MeshRenderer>(piece));  // still drawn
  EXPECT_TRUE(sim.world.has<RigidBody>(piece));     // still a collider
  EXPECT_EQ(sim.splits.pieces().stats().frozen, 1u);
  EXPECT_EQ(sim.splits.pieces().stats().live, 0u);
  EXPECT_EQ(sim.splits.pieces().stats().frozenTotal, 1u);
  ticks(sim, 30);
  EXPECT_EQ(sim.world.get<ecs::Transform>(piece).position, glm::vec3(0, 3, 0));  // it did not fall
}

TEST(PieceBudget, FadeDropsTheBodyAndShrinksThePieceAwayInFadeSeconds) {
  Sim sim;
  const ecs::Entity piece = addPiece(sim, glm::vec3(0.25f), glm::vec3(0, 3, 0), 0);
  const physics::BodyId body = bodyOf(sim, piece);
  editBudget(sim, [](PieceBudgetSettings& s) {
    s.policy = PieceRetirement::Fade;
    s.maxLivePieces = 0;
    s.fadeSeconds = 0.5f;
  });
  settleOnce(sim, 60);
  ASSERT_TRUE(sim.world.alive(piece));
  EXPECT_TRUE(sim.world.has<Fading>(piece));
  EXPECT_FALSE(sim.world.has<RigidBody>(piece));
  EXPECT_FALSE(sim.physics.isValid(body));  // the hooks freed it
  EXPECT_TRUE(sim.world.has<MeshRenderer>(piece));
  EXPECT_EQ(sim.splits.pieces().stats().debris, 1u);
  EXPECT_EQ(sim.splits.pieces().stats().fadedTotal, 1u);
  // It shrinks every tick and is gone after 0.5 s (30 ticks), not before.
  float scale = sim.world.get<ecs::Transform>(piece).scale.x;
  int ticksAlive = 0;
  for (uint64_t t = 61; t < 100 && sim.world.alive(piece); ++t) {
    settleOnce(sim, t);
    if (!sim.world.alive(piece)) break;
    ++ticksAlive;
    const float now = sim.world.get<ecs::Transform>(piece).scale.x;
    EXPECT_LT(now, scale) << "tick " << t;
    scale = now;
  }
  EXPECT_FALSE(sim.world.alive(piece));
  EXPECT_GE(ticksAlive, 28);
  EXPECT_LE(ticksAlive, 30);
}

TEST(PieceBudget, RemoveDestroysThePieceAtOnce) {
  Sim sim;
  const ecs::Entity piece = addPiece(sim, glm::vec3(0.25f), glm::vec3(0, 3, 0), 0);
  const physics::BodyId body = bodyOf(sim, piece);
  editBudget(sim, [](PieceBudgetSettings& s) {
    s.policy = PieceRetirement::Remove;
    s.maxLivePieces = 0;
  });
  settleOnce(sim, 60);
  EXPECT_FALSE(sim.world.alive(piece));
  EXPECT_FALSE(sim.physics.isValid(body));
  EXPECT_EQ(sim.splits.pieces().stats().removedTotal, 1u);
}

TEST(PieceBudget, AuthoredObjectsAreNeverRetired) {
  Sim sim;
  Splitable sp;
  const ecs::Entity authored =
      testing::addSplitableBody(sim, "crate", geometry::primitives::box(glm::vec3(0.25f)), sp, 500.0, glm::vec3(0, 3, 0));
  sim.world.add<SplitOrigin>(authored, SplitOrigin{});  // generation 0
  editBudget(sim, [](PieceBudgetSettings& s) {
    s.policy = PieceRetirement::Remove;
    s.maxLivePieces = 0;
  });
  settleOnce(sim, 60);
  EXPECT_TRUE(sim.world.alive(authored));
  EXPECT_EQ(sim.splits.pieces().stats().live, 0u);
}

TEST(PieceBudget, EachPiecesOwnRetirementOverridesThePolicy) {
  Sim sim;
  const ecs::Entity removed = addPiece(sim, glm::vec3(0.25f), glm::vec3(-2, 3, 0), 0, PieceRetirement::Remove);
  const ecs::Entity faded = addPiece(sim, glm::vec3(0.25f), glm::vec3(0, 3, 0), 0, PieceRetirement::Fade);
  const ecs::Entity byPolicy = addPiece(sim, glm::vec3(0.25f), glm::vec3(2, 3, 0), 0, PieceRetirement::Default);
  editBudget(sim, [](PieceBudgetSettings& s) {
    s.policy = PieceRetirement::Freeze;
    s.maxLivePieces = 0;
  });
  settleOnce(sim, 60);
  EXPECT_FALSE(sim.world.alive(removed));
  ASSERT_TRUE(sim.world.alive(faded));
  EXPECT_TRUE(sim.world.has<Fading>(faded));
  ASSERT_TRUE(sim.world.alive(byPolicy));
  EXPECT_TRUE(sim.world.has<Frozen>(byPolicy));
}

// The Splitable's retirement reaches the pieces of a real cut (SplitOrigin::retirement) with the
// tick of the cut, and decides over the policy.
TEST(PieceBudget, TheSplitablesRetirementIsCarriedToItsPiecesAndUsed) {
  Sim sim;
  sim.physics.setGravity(glm::vec3(0.f));
  Splitable sp;
  sp.retirement = PieceRetirement::Fade;
  const ecs::Entity crate =
      testing::addSplitableBody(sim, "crate", geometry::primitives::box(glm::vec3(0.5f)), sp, 500.0, glm::vec3(0, 3, 0));
  SplitWorld w = sim.sw();
  SplitRequest r;
  r.planeNormal = glm::dvec3(1, 0, 0);
  r.planeOffset = 0.1;
  const SplitEvent ev = sim.splits.splitNow(w, crate, r, 42);
  ASSERT_EQ(ev.status, geometry::SplitStatus::Ok) << ev.message;
  ASSERT_EQ(ev.pieces.size(), 2u);
  for (ecs::Entity piece : ev.pieces) {
    EXPECT_EQ(sim.world.get<SplitOrigin>(piece).retirement, PieceRetirement::Fade);
    EXPECT_EQ(sim.world.get<SplitOrigin>(piece).tick, 42u);
    EXPECT_EQ(sim.world.get<SplitOrigin>(piece).generation, 1u);
  }
  editBudget(sim, [](PieceBudgetSettings& s) {
    s.policy = PieceRetirement::Freeze;
    s.maxLivePieces = 0;
  });
  settleOnce(sim, 43);
  for (ecs::Entity piece : ev.pieces) {
    ASSERT_TRUE(sim.world.alive(piece));
    EXPECT_TRUE(sim.world.has<Fading>(piece));
    EXPECT_FALSE(sim.world.has<Frozen>(piece));
  }
}

// ---- accounting ----

TEST(PieceBudget, RetiredMassIsAccountedByHowThePiecesLeft) {
  Sim sim;
  sim.physics.setGravity(glm::vec3(0.f));
  // Six pieces of different masses, two of each retirement.
  const PieceRetirement hows[] = {PieceRetirement::Freeze, PieceRetirement::Fade, PieceRetirement::Remove,
                                  PieceRetirement::Freeze, PieceRetirement::Fade, PieceRetirement::Remove};
  double frozen = 0.0, faded = 0.0, removed = 0.0;
  for (int i = 0; i < 6; ++i) {
    const ecs::Entity e = addPiece(sim, glm::vec3(0.1f + 0.03f * float(i)), glm::vec3(float(i) * 2.f, 0, 0), 0, hows[i],
                                   300.0 + 170.0 * i);
    const double mass = sim.world.get<MassInfo>(e).mass;
    ASSERT_GT(mass, 0.0);
    (hows[i] == PieceRetirement::Freeze ? frozen : hows[i] == PieceRetirement::Fade ? faded : removed) += mass;
  }
  editBudget(sim, [](PieceBudgetSettings& s) { s.maxLivePieces = 0; });
  settleOnce(sim, 60);
  const PieceBudgetStats& stats = sim.splits.pieces().stats();
  EXPECT_EQ(stats.frozenTotal, 2u);
  EXPECT_EQ(stats.fadedTotal, 2u);
  EXPECT_EQ(stats.removedTotal, 2u);
  EXPECT_NEAR(stats.frozenMass, frozen, 1e-9 * frozen);
  EXPECT_NEAR(stats.fadedMass, faded, 1e-9 * faded);
  EXPECT_NEAR(stats.removedMass, removed, 1e-9 * removed);
}

// ---- thawing ----

// A frozen piece on the floor and a 2 kg ball shot head-on at its side at 8 m/s. The hit is read
// from the contact impulse (15 N s here: over hitSpeed x the piece's 62.5 kg, and over twice the
// ball's weight in a step): after the step the solver has already stopped the ball, so a rule on the
// hitter's speed would miss it.
TEST(PieceBudget, AFrozenPieceHitByAFastBodyThaws) {
  Sim sim;
  addFloor(sim);
  const ecs::Entity piece = addPiece(sim, glm::vec3(0.25f), glm::vec3(0, 0.25f, 0), 0);
  ticks(sim, 5);
  retireByFreezing(sim, {piece}, 1, sim.tick);
  ASSERT_TRUE(sim.world.has<Frozen>(piece));
  editBudget(sim, [](PieceBudgetSettings& s) { s.maxLivePieces = 400; });
  const physics::ShapeId ballShape = sim.physics.createShape(physics::ShapeDef::sphere(0.15f)).value();
  physics::BodyDef ball;
  ball.shape = ballShape;
  ball.mass = 2.f;
  ball.position = glm::vec3(-2.f, 0.25f, 0.f);
  ball.linearVelocity = glm::vec3(8.f, 0.f, 0.f);
  ASSERT_TRUE(sim.physics.createBody(ball).ok());
  sim.physics.destroyShape(ballShape);
  // It reaches the piece in about 0.2 s.
  for (int i = 0; i < 40 && sim.world.has<Frozen>(piece); ++i) tick(sim);
  EXPECT_FALSE(sim.world.has<Frozen>(piece));
  EXPECT_FALSE(sim.physics.isFrozen(bodyOf(sim, piece)));
  EXPECT_GE(sim.splits.pieces().stats().thawedTotal, 1u);
}

// The other side of the rule: a box set down gently on a frozen piece is a touch, not a hit.
TEST(PieceBudget, AFrozenPieceTouchedGentlyStaysFrozen) {
  Sim sim;
  addFloor(sim);
  const ecs::Entity piece = addPiece(sim, glm::vec3(0.25f), glm::vec3(0, 0.25f, 0), 0);
  ticks(sim, 5);
  retireByFreezing(sim, {piece}, 1, sim.tick);
  ASSERT_TRUE(sim.world.has<Frozen>(piece));
  editBudget(sim, [](PieceBudgetSettings& s) { s.maxLivePieces = 400; });
  const physics::ShapeId boxShape = sim.physics.createShape(physics::ShapeDef::box(glm::vec3(0.1f))).value();
  physics::BodyDef box;
  box.shape = boxShape;
  box.mass = 1.f;
  box.position = glm::vec3(0.f, 0.5f + 0.1f + 0.002f, 0.f);
  const physics::BodyId resting = sim.physics.createBody(box).value();
  sim.physics.destroyShape(boxShape);
  ticks(sim, 60);
  EXPECT_TRUE(sim.world.has<Frozen>(piece));
  EXPECT_NEAR(sim.physics.bodyTransform(resting)->position.y, 0.6f, 0.01f);  // it rests on the piece
}

// A frozen slab on a pillar; the pillar is cut down its middle and its halves pushed apart: the
// slab must thaw and fall to the floor, not hang where the pillar was.
TEST(PieceBudget, AFrozenPieceOnAPieceThatIsCutThawsAndFalls) {
  Sim sim;
  addFloor(sim);
  Splitable pillarSplit;
  pillarSplit.splitImpulse = 3.0;  // m/s, each half away from the cut
  const ecs::Entity pillar = testing::addSplitableBody(sim, "pillar", geometry::primitives::box(glm::vec3(0.3f)),
                                                       pillarSplit, 500.0, glm::vec3(0, 0.3f, 0));
  const ecs::Entity slab = addPiece(sim, glm::vec3(0.25f, 0.05f, 0.25f), glm::vec3(0, 0.65f, 0), 0);
  ticks(sim, 30);
  ASSERT_NEAR(sim.world.get<ecs::Transform>(slab).position.y, 0.65f, 0.01f);  // on the pillar
  retireByFreezing(sim, {slab}, 1, sim.tick);  // the pillar is authored: only the slab is a piece
  ASSERT_TRUE(sim.world.has<Frozen>(slab));
  editBudget(sim, [](PieceBudgetSettings& s) { s.maxLivePieces = 400; });
  sim.requestCut(pillar, glm::dvec3(1, 0, 0), 0.0);
  ticks(sim, 90);
  ASSERT_FALSE(sim.world.alive(pillar));  // it was cut
  EXPECT_FALSE(sim.world.has<Frozen>(slab));
  EXPECT_LT(sim.world.get<ecs::Transform>(slab).position.y, 0.2f);  // on the floor
}

// The same with the piece underneath removed by the budget.
TEST(PieceBudget, AFrozenPieceOnAPieceThatIsRemovedThawsAndFalls) {
  Sim sim;
  addFloor(sim);
  const ecs::Entity base = addPiece(sim, glm::vec3(0.3f), glm::vec3(0, 0.3f, 0), 30, PieceRetirement::Remove);
  const ecs::Entity slab = addPiece(sim, glm::vec3(0.25f, 0.05f, 0.25f), glm::vec3(0, 0.65f, 0), 0);
  ticks(sim, 30);
  ASSERT_NEAR(sim.world.get<ecs::Transform>(slab).position.y, 0.65f, 0.01f);
  // Both awake and under a second old: the slab, the smaller, is frozen first (one over a limit of one).
  retireByFreezing(sim, {base, slab}, 1, sim.tick);
  ASSERT_TRUE(sim.world.has<Frozen>(slab));
  ASSERT_FALSE(sim.world.has<Frozen>(base));
  // Then the base goes (its own retirement: Remove).
  editBudget(sim, [](PieceBudgetSettings& s) { s.maxLivePieces = 0; });
  settleOnce(sim, sim.tick);
  ASSERT_FALSE(sim.world.alive(base));
  // Room again for live pieces: the slab thaws at the next update and falls.
  editBudget(sim, [](PieceBudgetSettings& s) { s.maxLivePieces = 400; });
  ticks(sim, 60);
  EXPECT_FALSE(sim.world.has<Frozen>(slab));
  EXPECT_LT(sim.world.get<ecs::Transform>(slab).position.y, 0.1f);
}

// ---- limits ----

// Render-only debris (no body) made at different ticks: the oldest go beyond maxDebris.
TEST(PieceBudget, DebrisOverTheLimitGoesOldestFirst) {
  Sim sim;
  std::vector<std::pair<uint64_t, ecs::Entity>> debris;
  for (uint64_t made : {10u, 50u, 20u, 40u, 30u}) {
    const ecs::Entity e = sim.world.create();
    sim.world.add<ecs::Transform>(e, ecs::Transform{});
    sim.world.add<SplitOrigin>(e, SplitOrigin{{}, 0, 1, made, PieceRetirement::Default});
    Debris d;
    d.secondsLeft = 100.f;
    sim.world.add<Debris>(e, d);
    debris.emplace_back(made, e);
  }
  editBudget(sim, [](PieceBudgetSettings& s) { s.maxDebris = 2; });
  settleOnce(sim, 100);
  for (auto [made, e] : debris) EXPECT_EQ(sim.world.alive(e), made >= 40u) << "made at " << made;
  EXPECT_EQ(sim.splits.pieces().stats().debrisRemovedTotal, 3u);
  EXPECT_EQ(sim.splits.pieces().stats().debris, 2u);
}

// Fading pieces are on their way out already: over maxDebris they go before falling debris, even
// younger ones.
TEST(PieceBudget, FadingPiecesGoBeforeFallingDebris) {
  Sim sim;
  const ecs::Entity oldDebris = sim.world.create();
  sim.world.add<ecs::Transform>(oldDebris, ecs::Transform{});
  sim.world.add<SplitOrigin>(oldDebris, SplitOrigin{{}, 0, 1, 0, PieceRetirement::Default});
  sim.world.add<Debris>(oldDebris, Debris{});
  const ecs::Entity fading = addPiece(sim, glm::vec3(0.2f), glm::vec3(0, 3, 0), 50, PieceRetirement::Fade);
  editBudget(sim, [](PieceBudgetSettings& s) {
    s.maxLivePieces = 0;
    s.maxDebris = 1;
    s.fadeSeconds = 10.f;
  });
  settleOnce(sim, 100);
  EXPECT_FALSE(sim.world.alive(fading));
  EXPECT_TRUE(sim.world.alive(oldDebris));
}

// Fifty cubes cut in one swing: 100 pieces in a few ticks, never more than 12 of them simulated
// after the budget's tick.
TEST(PieceBudget, LivePiecesNeverExceedTheLimitAfterAnUpdate) {
  Sim sim;
  ASSERT_TRUE(sim.load(scenePath("fifty_cubes.json"))) << sim.scene.message;
  editBudget(sim, [](PieceBudgetSettings& s) { s.maxLivePieces = 12; });
  uint32_t most = 0;
  for (int i = 0; i < 240; ++i) {
    tick(sim);
    const uint32_t live = livePieces(sim);
    ASSERT_LE(live, 12u) << "tick " << sim.tick;
    EXPECT_EQ(sim.splits.pieces().stats().live, live) << "tick " << sim.tick;
    most = std::max(most, live);
  }
  EXPECT_GE(sim.splits.totalPiecesCreated(), 100u);  // the limit was really pressed
  EXPECT_EQ(most, 12u);
}

// The same swing with room for all 100 pieces but only 16 awake: the pieces fly apart, so none
// creeps, and the excess must still retire in the update that sees it.
TEST(PieceBudget, AwakePiecesNeverExceedTheLimitAfterAnUpdate) {
  Sim sim;
  ASSERT_TRUE(sim.load(scenePath("fifty_cubes.json"))) << sim.scene.message;
  editBudget(sim, [](PieceBudgetSettings& s) {
    s.maxLivePieces = 1000;
    s.maxAwakePieces = 16;
    s.maxRetirementsPerTick = 200;
  });
  uint32_t most = 0;
  for (int i = 0; i < 240; ++i) {
    tick(sim);
    const uint32_t awake = awakePieces(sim);
    ASSERT_LE(awake, 16u) << "tick " << sim.tick;
    EXPECT_EQ(sim.splits.pieces().stats().awake, awake) << "tick " << sim.tick;
    most = std::max(most, awake);
  }
  EXPECT_GE(sim.splits.totalPiecesCreated(), 100u);
  EXPECT_EQ(most, 16u);
  EXPECT_GT(sim.splits.pieces().stats().fadedTotal, 0u);  // pieces in flight faded
}

// Over the awake limit, a piece that barely moves freezes where it is; one in flight fades rather
// than hang in the air, though the policy says freeze.
TEST(PieceBudget, OverTheAwakeLimitAMovingPieceFadesAndASlowOneFreezes) {
  Sim sim;
  const ecs::Entity flying = addPiece(sim, glm::vec3(0.25f), glm::vec3(0, 3, 0), 0);
  const ecs::Entity slow = addPiece(sim, glm::vec3(0.25f), glm::vec3(2, 3, 0), 0);
  ASSERT_TRUE(sim.physics.setVelocity(bodyOf(sim, flying), glm::vec3(0.f, 2.f, 0.f), glm::vec3(0.f)));
  ASSERT_TRUE(sim.physics.setVelocity(bodyOf(sim, slow), glm::vec3(0.1f, 0.f, 0.f), glm::vec3(0.f)));
  editBudget(sim, [](PieceBudgetSettings& s) {
    s.policy = PieceRetirement::Freeze;
    s.maxAwakePieces = 0;
  });
  settleOnce(sim, 60);
  EXPECT_TRUE(sim.world.has<Fading>(flying));
  EXPECT_FALSE(sim.world.has<RigidBody>(flying));
  EXPECT_TRUE(sim.world.has<Frozen>(slow));
  EXPECT_EQ(sim.splits.pieces().stats().awake, 0u);
  EXPECT_EQ(sim.splits.pieces().stats().frozenTotal, 1u);
  EXPECT_EQ(sim.splits.pieces().stats().fadedTotal, 1u);
}

// ---- coming to rest ----

// A 1 m crate held 0.3 m above the floor shattered into 40 rigid cells that fall in a heap. Heaped
// cells tremble: without the budget every one of them is still awake at 6 s (they keep each other's
// island awake); with it, restless pieces are frozen and 5.5 s after the blow none is awake.
TEST(PieceBudget, AHeapOfFortyShatteredPiecesIsAtRestAfterFiveAndAHalfSeconds) {
  Sim sim;
  addFloor(sim);
  Splitable sp;
  sp.density = 600.0;
  sp.minPieceVolume = 0.0;
  testing::addSplitableBody(sim, "crate", geometry::primitives::box(glm::vec3(0.5f)), sp, sp.density, glm::vec3(0, 0.8f, 0));
  Splitter hammer;
  hammer.kind = SplitterKind::Shatter;
  hammer.shatter.cells = 40;
  hammer.shatter.seed = 11;
  hammer.halfExtents = glm::vec3(1.f);
  SplitWorld w = sim.sw();
  ASSERT_NE(createSplitter(w, "hammer", physics::ShapeDef::box(hammer.halfExtents), glm::vec3(0.1f, 0.8f, 0.f),
                           glm::quat(1.f, 0.f, 0.f, 0.f), hammer),
            ecs::kNullEntity);
  ticks(sim, 330);
  uint32_t pieces = 0;
  for (auto [e, origin, rb] : sim.world.view<SplitOrigin, RigidBody>()) pieces += origin.generation > 0 ? 1u : 0u;
  std::printf("[ budget ] %u pieces with bodies, %u frozen, %u awake, %u debris\n", pieces,
              sim.splits.pieces().stats().frozen, awakePieces(sim), sim.splits.pieces().stats().debris);
  EXPECT_GE(pieces, 35u);  // the cells are there (a sliver or two may be debris)
  EXPECT_EQ(awakePieces(sim), 0u);
  EXPECT_EQ(sim.splits.pieces().stats().awake, 0u);
}

// ---- determinism ----

// Fifty cubes cut in one swing, with limits tight enough that pieces are frozen, faded, thawed by
// what falls on them and trimmed, on `threads` split threads.
std::vector<uint64_t> scriptedSession(uint32_t threads, PieceBudgetStats& stats) {
  Sim sim;
  EXPECT_TRUE(sim.load(scenePath("fifty_cubes.json"))) << sim.scene.message;
  SplitBudgetSettings budget = sim.splits.budget().settings();
  budget.threads = threads;
  sim.splits.budget().setSettings(budget);
  editBudget(sim, [](PieceBudgetSettings& s) {
    s.maxLivePieces = 80;
    s.maxAwakePieces = 10;
    s.maxFrozenPieces = 60;
    s.maxDebris = 4;
    s.restlessSeconds = 1.f;
  });
  std::vector<uint64_t> hashes;
  for (int i = 0; i < 300; ++i) {
    if (i == 150) {  // a second swing through the heap cuts frozen and live pieces again
      Splitter swing;
      swing.halfExtents = glm::vec3(6.f, 0.02f, 3.f);
      SplitWorld w = sim.sw();
      createSplitter(w, "swing", physics::ShapeDef::box(swing.halfExtents), glm::vec3(0.f, 0.1f, 0.f),
                     glm::angleAxis(0.3f, glm::vec3(0.f, 0.f, 1.f)), swing);
    }
    tick(sim);
    hashes.push_back(sim.physics.stateHash());
  }
  stats = sim.splits.pieces().stats();
  return hashes;
}

TEST(PieceBudget, TheSameSessionGivesTheSameStateOnZeroOneAndThreeThreads) {
  PieceBudgetStats s0, s1, s3;
  const std::vector<uint64_t> h0 = scriptedSession(0, s0), h1 = scriptedSession(1, s1), h3 = scriptedSession(3, s3);
  ASSERT_EQ(h0.size(), h1.size());
  ASSERT_EQ(h0.size(), h3.size());
  for (size_t k = 0; k < h0.size(); ++k) {
    ASSERT_EQ(h0[k], h1[k]) << "tick " << k << " (1 thread)";
    ASSERT_EQ(h0[k], h3[k]) << "tick " << k << " (3 threads)";
  }
  // The budget really worked in the session, the same way each time.
  EXPECT_GT(s0.frozenTotal, 0u);
  EXPECT_GT(s0.thawedTotal, 0u);  // the second swing cut pieces that frozen ones rested on
  EXPECT_GT(s0.fadedTotal + s0.removedTotal + s0.debrisRemovedTotal, 0u);
  for (const PieceBudgetStats* s : {&s1, &s3}) {
    EXPECT_EQ(s->frozenTotal, s0.frozenTotal);
    EXPECT_EQ(s->fadedTotal, s0.fadedTotal);
    EXPECT_EQ(s->thawedTotal, s0.thawedTotal);
    EXPECT_EQ(s->debrisRemovedTotal, s0.debrisRemovedTotal);
    EXPECT_EQ(s->frozenMass, s0.frozenMass);
  }
  std::printf("[ budget ] session: frozen %llu faded %llu removed %llu thawed %llu debris removed %llu\n",
              (unsigned long long)s0.frozenTotal, (unsigned long long)s0.fadedTotal,
              (unsigned long long)s0.removedTotal, (unsigned long long)s0.thawedTotal,
              (unsigned long long)s0.debrisRemovedTotal);
}

// ---- the minimum body size ----

// A 1 m cube cut 1 cm below its top: the 1 cm slab (10 litres, well over minBodyVolume) is thinner
// than minBodyThickness and becomes debris; with no minimum thickness it is a body.
TEST(PieceBudget, ASliverThinnerThanTheMinimumThicknessBecomesDebris) {
  for (double thickness : {0.015, 0.0}) {
    Sim sim;
    sim.physics.setGravity(glm::vec3(0.f));
    editBudget(sim, [&](PieceBudgetSettings& s) { s.minBodyThickness = thickness; });
    Splitable sp;
    const ecs::Entity cube =
        testing::addSplitableBody(sim, "cube", geometry::primitives::box(glm::vec3(0.5f)), sp, 500.0, glm::vec3(0.f));
    SplitWorld w = sim.sw();
    SplitRequest r;
    r.planeNormal = glm::dvec3(0, 1, 0);
    r.planeOffset = 0.49;
    const SplitEvent ev = sim.splits.splitNow(w, cube, r, 1);
    ASSERT_EQ(ev.status, geometry::SplitStatus::Ok) << ev.message;
    ASSERT_EQ(ev.pieces.size(), 2u);
    uint32_t debris = 0;
    for (size_t k = 0; k < ev.pieces.size(); ++k) {
      const bool isDebris = ev.kinds[k] == PieceKind::Debris;
      debris += isDebris ? 1u : 0u;
      EXPECT_EQ(sim.world.has<Debris>(ev.pieces[k]), isDebris);
      EXPECT_EQ(sim.world.has<RigidBody>(ev.pieces[k]), !isDebris);
      if (isDebris) {
        EXPECT_LT(sim.world.get<MassInfo>(ev.pieces[k]).volume, 0.011);  // the slab
      }
    }
    EXPECT_EQ(debris, thickness > 0.0 ? 1u : 0u) << "minBodyThickness " << thickness;
  }
}

// ---- persistent blades ask only when their plane crosses a body ----

// A 0.5 m cube on the floor (top at y = 0.5) and a persistent blade whose trigger box is 0.6 m
// thick, centred at `height`: at 0.7 the box overlaps the cube's top 10 cm but its plane passes
// above the cube.
struct Blade {
  Sim sim;
  ecs::Entity cube, blade;
  physics::BodyId cubeBody;

  explicit Blade(float height) {
    addFloor(sim);
    Splitable sp;
    sp.convexHint = true;
    cube = testing::addSplitableBody(sim, "cube", geometry::primitives::box(glm::vec3(0.25f)), sp, 500.0,
                                     glm::vec3(0.f, 0.25f, 0.f));
    cubeBody = sim.world.get<RigidBody>(cube).body;
    Splitter s;
    s.lifetime = SplitterLifetime::Persistent;
    s.halfExtents = glm::vec3(1.f, 0.3f, 1.f);
    SplitWorld w = sim.sw();
    blade = createSplitter(w, "blade", physics::ShapeDef::box(s.halfExtents), glm::vec3(0.f, height, 0.f),
                           glm::quat(1.f, 0.f, 0.f, 0.f), s);
  }
  void moveBladeTo(float height) {
    auto& t = sim.world.get<ecs::Transform>(blade);
    t.position.y = height;
    sim.world.get<ecs::WorldTransform>(blade).matrix = ecs::localMatrix(t);
    sim.physics.setTriggerTransform(sim.world.get<Splitter>(blade).trigger, physics::BodyTransform{t.position, t.rotation});
  }
  bool touched() {
    for (const physics::TriggerEvent& ev : sim.physics.triggerEvents())
      if (ev.body == cubeBody && ev.kind != physics::TriggerEventKind::End) return true;
    return false;
  }
};

TEST(PieceBudget, PersistentBladeDoesNotAskForABodyItsPlaneMisses) {
  Blade b(0.7f);
  bool touched = false;
  for (int i = 0; i < 30; ++i) {
    tick(b.sim);
    touched = touched || b.touched();
    EXPECT_EQ(b.sim.splits.budget().queueLength(), 0u) << "tick " << b.sim.tick;
  }
  EXPECT_TRUE(touched);  // its trigger box does touch the cube
  EXPECT_EQ(b.sim.world.get<Splitter>(b.blade).cuts, 0u);
  EXPECT_TRUE(b.sim.world.alive(b.cube));
}

// The blade, touching the cube all along, is lowered until its plane crosses it: the touch goes on
// (Stay) and the cut is asked for then, once.
TEST(PieceBudget, PersistentBladeAsksOnceItsPlaneCrossesABodyItKeepsTouching) {
  Blade b(0.7f);
  ticks(b.sim, 10);
  ASSERT_TRUE(b.touched());
  ASSERT_EQ(b.sim.world.get<Splitter>(b.blade).cuts, 0u);
  b.moveBladeTo(0.6f);  // still above the cube's top (its box still overlaps it)
  ticks(b.sim, 5);
  EXPECT_EQ(b.sim.world.get<Splitter>(b.blade).cuts, 0u);
  b.moveBladeTo(0.3f);  // the plane now passes through the cube
  ticks(b.sim, 10);
  EXPECT_EQ(b.sim.world.get<Splitter>(b.blade).cuts, 1u);
  EXPECT_FALSE(b.sim.world.alive(b.cube));  // cut
}

}  // namespace
}  // namespace cleave::components
