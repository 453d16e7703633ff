// SPDX-License-Identifier: MIT
// Live tuning (components/live_tuning.h), the path every inspector edit takes: a Splitable changed
// through it is honoured by the object's next split (caps, cap UVs, collider, density, split
// impulse, islands) and inherited by the pieces; bad values are refused and change nothing; budget
// edits apply from the next tick and keep what the inspector does not edit.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>

#include "cleave/components/live_tuning.h"
#include "cleave/geometry/primitives.h"
#include "tests/components/sim_harness.h"

namespace {

using namespace cleave;
using namespace cleave::components;
using namespace cleave::components::testing;

// The cubes' split events, by the entity they cut (runs until each target was cut or 30 ticks).
std::vector<SplitEvent> cutEach(Sim& sim, const std::vector<ecs::Entity>& targets) {
  for (ecs::Entity e : targets) {
    const double x = sim.world.get<ecs::Transform>(e).position.x;
    sim.requestCut(e, glm::dvec3(1.0, 0.0, 0.0), x);  // through the middle, across x
  }
  std::vector<SplitEvent> found(targets.size());
  for (int t = 0; t < 30; ++t) {
    for (const SplitEvent& ev : sim.runUntil(sim.tick + 1))
      for (size_t k = 0; k < targets.size(); ++k)
        if (ev.original == targets[k] && ev.status == geometry::SplitStatus::Ok) found[k] = ev;
  }
  return found;
}

// The UVs of the cap triangles of a piece (the submesh of the cap material id).
std::vector<glm::vec2> capUvs(const ecs::World& world, ecs::Entity piece, uint32_t capMaterialId) {
  std::vector<glm::vec2> uvs;
  const geometry::MeshData& mesh = *world.get<MeshRenderer>(piece).source;
  for (const geometry::SubMesh& run : mesh.submeshes) {
    if (run.materialId != capMaterialId) continue;
    for (uint32_t i = run.firstIndex; i < run.firstIndex + run.indexCount; ++i)
      uvs.push_back(mesh.uv0[mesh.indices[i]]);
  }
  return uvs;
}

double speedAlongX(Sim& sim, ecs::Entity piece) {
  const auto state = sim.physics.bodyState(sim.world.get<RigidBody>(piece).body);
  return state ? double(state->linearVelocity.x) : std::nan("");
}

std::optional<physics::ShapeType> shapeOf(Sim& sim, ecs::Entity piece) {
  return sim.physics.shapeType(sim.world.get<RigidBody>(piece).shape);
}

TEST(LiveTuning, ASplitableEditedThroughTheInspectorPathIsHonouredByTheNextSplit) {
  Sim sim;
  const geometry::MeshData cube = geometry::primitives::box(glm::vec3(0.5f));
  Splitable plain;  // density 500, caps world-planar at 1 per metre, no impulse
  const ecs::Entity control = addSplitableBody(sim, "control", cube, plain, 500.0, {-3.f, 5.f, 0.f});
  const ecs::Entity hollow = addSplitableBody(sim, "hollow", cube, plain, 500.0, {0.f, 5.f, 0.f});
  const ecs::Entity normalised = addSplitableBody(sim, "normalised", cube, plain, 500.0, {3.f, 5.f, 0.f});

  SplitableTuning h = tuningOf(sim.world.get<Splitable>(hollow));
  EXPECT_FALSE(h.hollow);
  h.hollow = true;
  h.density = 2000.0;
  h.splitImpulse = 4.0;
  ASSERT_TRUE(applySplitableTuning(sim.world, hollow, h).ok());
  SplitableTuning n = tuningOf(sim.world.get<Splitable>(normalised));
  n.capUvMode = geometry::CapUvMode::NormalizedBounds;
  n.collider = ColliderMode::ConcaveMesh;
  ASSERT_TRUE(applySplitableTuning(sim.world, normalised, n).ok());
  EXPECT_EQ(tuningOf(sim.world.get<Splitable>(hollow)), h);

  const std::vector<SplitEvent> events = cutEach(sim, {control, hollow, normalised});
  for (const SplitEvent& ev : events) ASSERT_EQ(ev.pieces.size(), 2u) << ev.originalName;
  const uint32_t capId = plain.capMaterialId;
  // The control: capped, 500 kg/m^3, world-planar cap UVs (the cap spans -0.5..0.5 m), no push.
  for (ecs::Entity piece : events[0].pieces) {
    const std::vector<glm::vec2> uvs = capUvs(sim.world, piece, capId);
    ASSERT_FALSE(uvs.empty());
    float lowest = 1.f;
    for (const glm::vec2& uv : uvs) lowest = std::min({lowest, uv.x, uv.y});
    EXPECT_LT(lowest, -0.4f);
    EXPECT_NEAR(sim.world.get<MassInfo>(piece).density, 500.0, 1e-9);
    EXPECT_NE(shapeOf(sim, piece), physics::ShapeType::ConcaveMesh);
  }
  EXPECT_NEAR(speedAlongX(sim, events[0].pieces[0]) - speedAlongX(sim, events[0].pieces[1]), 0.0, 0.5);
  // Hollow: no cap triangles, 2000 kg/m^3, the halves pushed apart at 4 m/s each, settings inherited.
  for (ecs::Entity piece : events[1].pieces) {
    EXPECT_TRUE(capUvs(sim.world, piece, capId).empty()) << "a hollow piece has a cap";
    EXPECT_NEAR(sim.world.get<MassInfo>(piece).density, 2000.0, 1e-9);
    ASSERT_TRUE(sim.world.has<Splitable>(piece));
    EXPECT_EQ(tuningOf(sim.world.get<Splitable>(piece)), h);
  }
  EXPECT_GT(std::abs(speedAlongX(sim, events[1].pieces[0]) - speedAlongX(sim, events[1].pieces[1])), 7.0);
  // Normalised: cap UVs within the unit square over each cap; a GImpact mesh collider.
  for (ecs::Entity piece : events[2].pieces) {
    EXPECT_EQ(shapeOf(sim, piece), physics::ShapeType::ConcaveMesh);
    const std::vector<glm::vec2> uvs = capUvs(sim.world, piece, capId);
    ASSERT_FALSE(uvs.empty());
    for (const glm::vec2& uv : uvs) {
      EXPECT_GE(std::min(uv.x, uv.y), -1e-5f);
      EXPECT_LE(std::max(uv.x, uv.y), 1.f + 1e-5f);
    }
  }
}

// Islands through the same path: two spheres apart, cut across both. One piece per side gives two
// pieces; every connected part its own piece gives four.
TEST(LiveTuning, IslandChoiceEditedLiveSetsThePieceCountOfTheNextSplit) {
  Sim sim;
  const geometry::MeshData spheres = geometry::primitives::twoDisjointSpheres(0.4f, 0.3f, 16, 8);
  const ecs::Entity whole = addSplitableBody(sim, "whole sides", spheres, Splitable{}, 500.0, {-4.f, 5.f, 0.f});
  const ecs::Entity parts = addSplitableBody(sim, "every part", spheres, Splitable{}, 500.0, {4.f, 5.f, 0.f});
  SplitableTuning t = tuningOf(sim.world.get<Splitable>(whole));
  t.separateIslands = false;
  ASSERT_TRUE(applySplitableTuning(sim.world, whole, t).ok());
  t.separateIslands = true;
  t.islands = geometry::IslandMode::Connected;
  ASSERT_TRUE(applySplitableTuning(sim.world, parts, t).ok());
  for (ecs::Entity e : {whole, parts}) sim.requestCut(e, glm::dvec3(0.0, 1.0, 0.0), 5.0 - 0.1);
  size_t wholePieces = 0, partPieces = 0;
  for (const SplitEvent& ev : sim.runUntil(sim.tick + 4)) {
    if (ev.original == whole) wholePieces = ev.pieces.size();
    if (ev.original == parts) partPieces = ev.pieces.size();
  }
  EXPECT_EQ(wholePieces, 2u);
  EXPECT_EQ(partPieces, 4u);
}

TEST(LiveTuning, OutOfRangeValuesAreRefusedWithTheSettingAndChangeNothing) {
  Sim sim;
  const ecs::Entity e = addSplitableBody(sim, "cube", geometry::primitives::box(glm::vec3(0.5f)), Splitable{}, 500.0,
                                         {0.f, 2.f, 0.f});
  const SplitableTuning before = tuningOf(sim.world.get<Splitable>(e));
  struct Case {
    const char* word;
    void (*edit)(SplitableTuning&);
  };
  const Case cases[] = {
      {"density", [](SplitableTuning& t) { t.density = std::numeric_limits<double>::quiet_NaN(); }},
      {"density", [](SplitableTuning& t) { t.density = 0.0; }},
      {"impulse", [](SplitableTuning& t) { t.splitImpulse = -1.0; }},
      {"cap UV", [](SplitableTuning& t) { t.capUvPerMetre = 0.0; }},
      {"collider", [](SplitableTuning& t) { t.collider = ColliderMode(9); }},
  };
  for (const Case& c : cases) {
    SplitableTuning t = before;
    t.hollow = true;  // a good change next to the bad one is not written either
    c.edit(t);
    const TuningResult r = applySplitableTuning(sim.world, e, t);
    EXPECT_FALSE(r.ok()) << c.word;
    EXPECT_NE(r.message.find(c.word), std::string::npos) << r.message;
    EXPECT_EQ(tuningOf(sim.world.get<Splitable>(e)), before) << c.word;
  }
  sim.world.destroy(e);
  EXPECT_FALSE(applySplitableTuning(sim.world, e, before).ok());
}

TEST(LiveTuning, BudgetEditsApplyFromTheNextTickAndKeepTheRest) {
  Sim sim;
  const geometry::MeshData cube = geometry::primitives::box(glm::vec3(0.5f));
  std::vector<ecs::Entity> cubes;
  for (int k = 0; k < 3; ++k)
    cubes.push_back(addSplitableBody(sim, "cube", cube, Splitable{}, 500.0, {3.f * float(k), 5.f, 0.f}));
  SplitBudgetSettings edit = sim.splits.budget().settings();
  const uint32_t threads = edit.threads;
  edit.maxSplitsPerTick = 1;
  edit.threads = threads + 7;  // not an inspector setting: kept as it was
  ASSERT_TRUE(applyBudgetTuning(sim.splits.budget(), edit).ok());
  EXPECT_EQ(sim.splits.budget().settings().threads, threads);
  EXPECT_EQ(sim.splits.budget().settings().maxSplitsPerTick, 1u);
  for (ecs::Entity e : cubes) sim.requestCut(e, glm::dvec3(1.0, 0.0, 0.0), sim.world.get<ecs::Transform>(e).position.x);
  uint32_t most = 0, done = 0;
  for (int t = 0; t < 10; ++t) {
    sim.step();
    most = std::max(most, sim.splits.budget().stats().executed);
    done += sim.splits.budget().stats().executed;
  }
  EXPECT_EQ(most, 1u) << "more than one split in a tick with maxSplitsPerTick 1";
  EXPECT_EQ(done, 3u);
  edit.maxSplitsPerTick = 0;
  EXPECT_FALSE(applyBudgetTuning(sim.splits.budget(), edit).ok());
  EXPECT_EQ(sim.splits.budget().settings().maxSplitsPerTick, 1u);
}

}  // namespace
