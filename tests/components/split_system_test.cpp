// SPDX-License-Identifier: MIT
// Headless simulations of the split components: conservation across a cut, caps with holes,
// islands, persistent and one-tick splitters, the split budget over a burst of splits, contact
// quality of new pieces, and determinism.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <cstring>
#include <set>

#include <gtest/gtest.h>

#include "cleave/components/scene_loader.h"
#include "cleave/geometry/primitives.h"
#include "cleave/log/log.h"
#include "tests/components/sim_harness.h"

namespace cleave::components {
namespace {

using testing::kDt;
using testing::Momenta;
using testing::momentaOf;
using testing::relativeError;
using testing::scenePath;
using testing::Sim;

std::string writeScene(const std::string& name, const std::string& text) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "cleave_component_scenes";
  std::filesystem::create_directories(dir);
  const std::filesystem::path path = dir / name;
  std::ofstream(path) << text;
  return path.string();
}

std::vector<SplitEvent> okEvents(const std::vector<SplitEvent>& events) {
  std::vector<SplitEvent> out;
  for (const SplitEvent& ev : events)
    if (ev.status == geometry::SplitStatus::Ok && !ev.pieces.empty()) out.push_back(ev);
  return out;
}

TEST(SplitConservation, SpinningMovingSphereKeepsMassMomentumAndAngularMomentum) {
  Sim sim;
  ASSERT_TRUE(sim.load(scenePath("spinning_sphere.json"))) << sim.scene.message;
  Momenta before, after;
  std::vector<SplitEvent> events;
  uint64_t splitTick = 0;
  while (sim.tick < 60 && events.empty()) {
    const Momenta pre = momentaOf(sim);  // the state the split sees: after the previous step
    const uint64_t tick = sim.tick;
    sim.step([&] {
      if (sim.splits.lastEvents().empty()) return;
      events = sim.splits.lastEvents();
      before = pre;
      after = momentaOf(sim);
      splitTick = tick;
    });
  }
  ASSERT_EQ(events.size(), 1u);
  ASSERT_EQ(events[0].status, geometry::SplitStatus::Ok) << events[0].message;
  // Fired at tick 10: its step touches the sphere, tick 11 gathers the request, tick 12 prepares
  // the split and tick 13 commits it (the sphere moved and turned for one step in between).
  EXPECT_EQ(events[0].preparedTick, 12u);
  EXPECT_EQ(splitTick, 13u);
  ASSERT_EQ(events[0].pieces.size(), 2u);
  ASSERT_EQ(before.bodies, 1u);
  ASSERT_EQ(after.bodies, 2u);

  const double massError = relativeError(after.mass, before.mass);
  const double linearError = relativeError(after.linear, before.linear);
  const double angularError = relativeError(after.angular, before.angular);
  std::printf("[conservation] mass %.3e  linear momentum %.3e  angular momentum %.3e (relative)\n",
              massError, linearError, angularError);
  ::testing::Test::RecordProperty("mass_relative_error", std::to_string(massError));
  ::testing::Test::RecordProperty("linear_momentum_relative_error", std::to_string(linearError));
  ::testing::Test::RecordProperty("angular_momentum_relative_error", std::to_string(angularError));
  EXPECT_LT(massError, 1e-6);
  EXPECT_LT(linearError, 1e-6);
  EXPECT_LT(angularError, 1e-4);
  // The figures are not trivially zero: the sphere really moves and spins.
  EXPECT_GT(glm::length(before.linear), 1.0);
  EXPECT_GT(glm::length(before.angular), 0.1);
  EXPECT_NEAR(events[0].piecesMass, events[0].parentMass, 1e-6 * events[0].parentMass);
}

// A piece carries the weld the split gave it, so cutting it again skips the weld; the cuts of the
// pieces keep their mass like any other.
TEST(SplitWelds, PiecesAreCutAgainWithTheWeldTheirSplitGaveThem) {
  Sim sim;
  ASSERT_TRUE(sim.load(scenePath("spinning_sphere.json"))) << sim.scene.message;
  std::vector<SplitEvent> first;
  while (sim.tick < 60 && first.empty()) first = okEvents(sim.runUntil(sim.tick + 1));
  ASSERT_EQ(first.size(), 1u);
  EXPECT_FALSE(first[0].weldKnown);  // an authored mesh cut for the first time is welded
  ASSERT_EQ(first[0].pieces.size(), 2u);
  for (ecs::Entity piece : first[0].pieces) {
    ASSERT_TRUE(sim.world.alive(piece));
    const glm::dvec3 at(sim.world.get<ecs::Transform>(piece).position);
    SplitRequest r;
    r.target = piece;
    r.planeNormal = glm::normalize(glm::dvec3(1.0, 0.2, 0.1));
    r.planeOffset = glm::dot(r.planeNormal, at);
    sim.splits.request(r);
  }
  const std::vector<SplitEvent> second = okEvents(sim.runUntil(sim.tick + 3));
  ASSERT_EQ(second.size(), 2u);
  for (const SplitEvent& ev : second) {
    EXPECT_TRUE(ev.weldKnown) << "piece " << ev.original.index << " was welded again";
    EXPECT_GE(ev.pieces.size(), 2u);
    EXPECT_NEAR(ev.piecesMass, ev.parentMass, 1e-6 * ev.parentMass);
    EXPECT_GE(ev.times.compute.setup, 0.0);
    EXPECT_LE(ev.times.compute.setup, ev.times.total());
  }
}

TEST(SplitScenes, TorusCutHorizontallyGivesTwoAnnularCapsAndComesToRest) {
  Sim sim;
  ASSERT_TRUE(sim.load(scenePath("torus_cut.json"))) << sim.scene.message;
  const auto events = okEvents(sim.runUntil(40));
  ASSERT_EQ(events.size(), 1u);
  ASSERT_EQ(events[0].pieces.size(), 2u);
  ASSERT_EQ(events[0].capLoops.size(), 2u);
  EXPECT_EQ(events[0].capLoops[0], 2u);  // an annulus: the outer border and the hole
  EXPECT_EQ(events[0].capLoops[1], 2u);
  sim.runUntil(40 + 240);  // four seconds
  const auto bodies = sim.dynamicBodies();
  ASSERT_EQ(bodies.size(), 2u);
  std::vector<float> heights;
  for (ecs::Entity e : bodies) {
    const auto state = sim.physics.bodyState(sim.world.get<RigidBody>(e).body);
    ASSERT_TRUE(state);
    EXPECT_LT(glm::length(state->linearVelocity), 0.02f) << sim.world.get<ecs::Name>(e).value;
    EXPECT_LT(glm::length(state->angularVelocity), 0.05f) << sim.world.get<ecs::Name>(e).value;
    heights.push_back(state->transform.position.y);
  }
  std::sort(heights.begin(), heights.end());
  // The lower ring lies on the floor (its centre of mass 4r/(3 pi) = 0.085 below the cut at 0.2),
  // the upper one on the lower one (0.085 above).
  EXPECT_NEAR(heights[0], 0.2f - 0.085f, 0.01f);
  EXPECT_NEAR(heights[1], 0.2f + 0.085f, 0.01f);
}

TEST(SplitScenes, UShapeCutAcrossBothArmsGivesThreeBodies) {
  Sim sim;
  ASSERT_TRUE(sim.load(scenePath("u_shape.json"))) << sim.scene.message;
  const auto events = okEvents(sim.runUntil(20));
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].pieces.size(), 3u);
  const auto bodies = sim.dynamicBodies();
  EXPECT_EQ(bodies.size(), 3u);
  for (ecs::Entity e : events[0].pieces) {
    const auto* rb = sim.world.tryGet<RigidBody>(e);
    ASSERT_NE(rb, nullptr);
    EXPECT_TRUE(sim.physics.isValid(rb->body));
  }
}

std::string rowScene(const std::string& splitter) {
  std::string entities;
  for (int i = 0; i < 5; ++i) {
    if (i) entities += ",\n";
    entities += "    {\"name\": \"cube " + std::to_string(i) +
                "\", \"mesh\": {\"primitive\": \"box\", \"half_extents\": [0.25, 0.25, 0.25]}, "
                "\"transform\": {\"position\": [" + std::to_string(-1.6 + 0.8 * i) +
                ", 0.25, 0]}, \"body\": {\"density\": 600}, \"splitable\": {\"convex\": true}}";
  }
  return "{\n  \"floor\": true,\n  \"entities\": [\n" + entities + "\n  ],\n  \"splitters\": [" + splitter +
         "]\n}\n";
}

TEST(Splitters, PersistentSplitterCutsEachObjectOfARowExactlyOncePerPass) {
  Sim sim;
  ASSERT_TRUE(sim.load(writeScene("row_persistent.json",
                                  rowScene(R"({"name": "disc", "lifetime": "persistent", "half_extents": [0.3, 0.02, 1],
                                             "transform": {"position": [-3, 0.25, 0]}, "velocity": [3, 0, 0],
                                             "end_tick": 150})"))))
      << sim.scene.message;
  const ecs::Entity disc = sim.scene.splitters.at(0).entity;
  ASSERT_TRUE(sim.world.alive(disc));
  const auto events = sim.runUntil(149);
  const auto ok = okEvents(events);
  std::set<std::string> cut;
  for (const SplitEvent& ev : ok) cut.insert(ev.originalName);
  EXPECT_EQ(ok.size(), 5u);
  EXPECT_EQ(cut, (std::set<std::string>{"cube 0", "cube 1", "cube 2", "cube 3", "cube 4"}));
  EXPECT_EQ(sim.world.get<Splitter>(disc).cuts, 5u);  // no request for its own pieces
  EXPECT_EQ(sim.dynamicBodies().size(), 10u);
  sim.runUntil(151);
  EXPECT_FALSE(sim.world.alive(disc));  // gone at its end tick
}

TEST(Splitters, OneTickSplitterCutsOnlyWhatItTouchesInItsTick) {
  Sim sim;
  ASSERT_TRUE(sim.load(writeScene("row_one_tick.json",
                                  rowScene(R"({"name": "swing", "lifetime": "one_tick", "half_extents": [0.3, 0.02, 1],
                                             "transform": {"position": [0, 0.25, 0]}, "fire_tick": 10})"))))
      << sim.scene.message;
  const auto events = sim.runUntil(60);
  const auto ok = okEvents(events);
  ASSERT_EQ(ok.size(), 1u);
  EXPECT_EQ(ok[0].originalName, "cube 2");
  EXPECT_EQ(ok[0].preparedTick, 12u);
  EXPECT_EQ(ok[0].tick, 13u);
  for (const char* name : {"cube 0", "cube 1", "cube 3", "cube 4"})
    EXPECT_TRUE(sim.world.alive(sim.scene.find(name))) << name;
  EXPECT_FALSE(sim.world.alive(sim.scene.find("cube 2")));
  EXPECT_EQ(sim.world.count<Splitter>(), 0u);  // the one-tick splitter is gone
  EXPECT_EQ(sim.dynamicBodies().size(), 6u);
}

// A box without its +x face: open, so a cap cannot close the section of a horizontal cut.
geometry::MeshData openBox() {
  geometry::MeshData open = geometry::primitives::box(glm::vec3(0.3f));
  std::vector<uint32_t> kept;
  for (size_t t = 0; t + 2 < open.indices.size(); t += 3) {
    const glm::vec3 a = open.positions[open.indices[t]], b = open.positions[open.indices[t + 1]],
                    c = open.positions[open.indices[t + 2]];
    if (glm::normalize(glm::cross(b - a, c - a)).x > 0.9f) continue;
    kept.insert(kept.end(), {open.indices[t], open.indices[t + 1], open.indices[t + 2]});
  }
  EXPECT_EQ(kept.size(), open.indices.size() - 6);
  open.indices = kept;
  return open;
}

// An open box on a dynamic body at height 3, its Splitable with `mode`.
ecs::Entity addOpenBox(Sim& sim, geometry::OpenSectionMode mode) {
  Splitable sp;
  sp.openSections = mode;
  return testing::addSplitableBody(sim, "open box", openBox(), sp, 500.0, glm::vec3(0.f, 3.f, 0.f));
}

TEST(SplitFailure, OpenMeshKeepsTheOriginalWholeWithItsMassAndMomentumWhenAskedToRefuse) {
  Sim sim;
  const ecs::Entity e = addOpenBox(sim, geometry::OpenSectionMode::Refuse);
  ASSERT_TRUE(sim.world.has<RigidBody>(e));
  const physics::BodyId body = sim.world.get<RigidBody>(e).body;
  sim.physics.setVelocity(body, glm::vec3(1.f, 0.f, 0.5f), glm::vec3(0.f, 2.f, 1.f));
  const double mass = sim.world.get<MassInfo>(e).mass;

  // The failure is reported through the host's log sink (library code does not print).
  std::vector<std::string> logged;
  log::ScopedSink sink([&](log::Level level, std::string_view source, std::string_view message) {
    if (level == log::Level::Warning && source == "cleave") logged.emplace_back(message);
  });
  sim.requestCut(e, glm::dvec3(0, 1, 0), 3.0);
  sim.step();
  EXPECT_TRUE(sim.splits.lastEvents().empty());  // requested in this tick: prepared in the next one
  sim.step();
  EXPECT_TRUE(sim.splits.lastEvents().empty());  // prepared: its outcome is committed in the next one
  const Momenta pre = momentaOf(sim);
  Momenta post;
  sim.step([&] { post = momentaOf(sim); });
  ASSERT_EQ(sim.splits.lastEvents().size(), 1u);
  const SplitEvent& ev = sim.splits.lastEvents()[0];
  ASSERT_EQ(logged.size(), 1u);
  EXPECT_NE(logged[0].find("kept whole"), std::string::npos) << logged[0];
  EXPECT_EQ(ev.status, geometry::SplitStatus::OpenSection);
  EXPECT_FALSE(ev.message.empty());
  EXPECT_TRUE(ev.pieces.empty());
  EXPECT_EQ(sim.splits.budget().stats().failed, 1u);
  ASSERT_TRUE(sim.world.alive(e));
  EXPECT_EQ(sim.world.get<RigidBody>(e).body, body);
  EXPECT_EQ(sim.world.get<MassInfo>(e).mass, mass);
  EXPECT_EQ(post.bodies, 1u);
  EXPECT_EQ(post.mass, pre.mass);
  EXPECT_EQ(post.linear, pre.linear);
  EXPECT_EQ(post.angular, pre.angular);
}

TEST(SplitOpenArt, OpenMeshIsCutByDefaultWithItsOpenChainReported) {
  Sim sim;
  const ecs::Entity e = addOpenBox(sim, geometry::OpenSectionMode::CapClosedLoops);
  ASSERT_TRUE(sim.world.has<RigidBody>(e));
  sim.requestCut(e, glm::dvec3(0, 1, 0), 3.0);
  std::vector<SplitEvent> events = sim.runUntil(sim.tick + 3);
  ASSERT_EQ(events.size(), 1u);
  const SplitEvent& ev = events[0];
  ASSERT_EQ(ev.status, geometry::SplitStatus::Ok) << ev.message;
  EXPECT_EQ(ev.openChains, 1u);
  ASSERT_EQ(ev.pieces.size(), 2u);
  EXPECT_FALSE(sim.world.alive(e));
  double volume = 0.0;
  for (ecs::Entity piece : ev.pieces) {
    const MassInfo& info = sim.world.get<MassInfo>(piece);
    EXPECT_FALSE(info.closed);  // open along the chain: the mass of its convex hull
    volume += info.volume;
    EXPECT_TRUE(sim.world.has<RigidBody>(piece));
  }
  EXPECT_NEAR(volume, 0.6 * 0.6 * 0.6, 1e-6);  // the hulls of two boxes: the whole box
}

struct BudgetRun {
  uint32_t ticksWithSplits = 0;
  uint32_t executed = 0;
  uint32_t failed = 0;
  double maxCharged = 0.0;
  double maxUsed = 0.0;
  double maxSplit = 0.0;
  uint64_t firstTick = 0, lastTick = 0;
  uint32_t stoppedEarly = 0;  // ticks that left work waiting with no budget spent
  uint32_t overran = 0;       // ticks that began a split with their budget already spent
};

// What the budget decided in one tick with splits, checked: with work left, a tick stops only once
// a budget is spent (or the split cap is reached), and it begins its last split while still under
// the budget (`lastCharge` is what that split was charged). Returns what went wrong, or nothing.
std::string budgetDecisionProblem(const SplitBudgetStats& st, const SplitBudgetSettings& s, double lastCharge) {
  const bool spent = st.millisecondsCharged >= s.millisecondsPerTick ||
                     st.workerMillisecondsCharged >= s.workerMillisecondsPerTick ||
                     st.executed >= s.maxSplitsPerTick;
  if (st.deferred > 0 && !spent) return "stopped with budget left while work waited";
  if (st.executed > 1 && st.millisecondsCharged - lastCharge >= s.millisecondsPerTick - 1e-12)
    return "began a split with its budget spent";
  return {};
}

TEST(SplitBudget, DecisionCheckSeesATickThatStopsEarlyAndOneThatOverruns) {
  SplitBudgetSettings s;
  s.millisecondsPerTick = 2.0;
  SplitBudgetStats st;
  st.executed = 3;
  st.millisecondsCharged = 2.1;
  st.deferred = 4;
  EXPECT_EQ(budgetDecisionProblem(st, s, 0.3), "");        // spent, and began its last split at 1.8
  st.millisecondsCharged = 1.5;
  EXPECT_NE(budgetDecisionProblem(st, s, 0.3), "");        // work waits, 0.5 ms of budget left
  st.millisecondsCharged = 2.9;
  EXPECT_NE(budgetDecisionProblem(st, s, 0.3), "");        // its last split began at 2.6
}

BudgetRun runFiftyCubes(Sim& sim, bool deterministic) {
  EXPECT_TRUE(sim.load(scenePath("fifty_cubes.json"))) << sim.scene.message;
  SplitBudgetSettings s = sim.splits.budget().settings();
  s.deterministic = deterministic;
  sim.splits.budget().setSettings(s);
  BudgetRun run;
  while (sim.tick < 120) {
    sim.step();
    const SplitBudgetStats& st = sim.splits.budget().stats();
    if (st.executed == 0) continue;
    if (run.ticksWithSplits == 0) run.firstTick = sim.tick - 1;
    run.lastTick = sim.tick - 1;
    run.ticksWithSplits++;
    run.executed += st.executed;
    run.failed += st.failed;
    run.maxCharged = std::max(run.maxCharged, st.millisecondsCharged);
    run.maxUsed = std::max(run.maxUsed, st.millisecondsUsed);
    run.maxSplit = st.maxSplitMilliseconds;
    const double lastCharge = deterministic ? s.estimatedMainMilliseconds : st.lastSplitMilliseconds;
    const std::string problem = budgetDecisionProblem(st, s, lastCharge);
    run.stoppedEarly += problem.rfind("stopped", 0) == 0;
    run.overran += problem.rfind("began", 0) == 0;
  }
  return run;
}

TEST(SplitBudgetScene, FiftyCubesInOneTickSpreadOverTicksWithinTheBudget) {
  Sim sim;
  const BudgetRun run = runFiftyCubes(sim, /*deterministic=*/true);
  const SplitBudgetSettings& s = sim.splits.budget().settings();
  ASSERT_DOUBLE_EQ(s.millisecondsPerTick, 2.0);
  // One split of a cube is charged the scene's main-thread estimate, 0.3 ms.
  const double oneSplit = s.estimatedMainMilliseconds;
  std::printf("[budget] deterministic: %u splits over %u ticks (%llu..%llu), max charged %.3f ms/tick "
              "(budget %.1f, one split %.3f), max measured %.3f ms/tick\n",
              run.executed, run.ticksWithSplits, (unsigned long long)run.firstTick,
              (unsigned long long)run.lastTick, run.maxCharged, s.millisecondsPerTick, oneSplit, run.maxUsed);
  ::testing::Test::RecordProperty("ticks_with_splits", int(run.ticksWithSplits));
  ::testing::Test::RecordProperty("max_charged_ms", std::to_string(run.maxCharged));
  EXPECT_EQ(run.executed, 50u);
  EXPECT_EQ(run.failed, 0u);
  EXPECT_EQ(run.firstTick, 7u);  // fired at 5, gathered at 6, first splits at 7
  EXPECT_GT(run.ticksWithSplits, 1u);
  EXPECT_EQ(run.ticksWithSplits, 8u);  // 7 splits (2.1 ms charged) per tick
  EXPECT_LE(run.maxCharged, s.millisecondsPerTick + oneSplit + 1e-9);
  EXPECT_EQ(run.stoppedEarly, 0u);
  EXPECT_EQ(run.overran, 0u);
  EXPECT_EQ(sim.dynamicBodies().size(), 100u);
}

TEST(SplitBudgetScene, FiftyCubesWithMeasuredTimeStayWithinOneSplitOfTheBudget) {
  Sim sim;
  const BudgetRun run = runFiftyCubes(sim, /*deterministic=*/false);
  const SplitBudgetSettings& s = sim.splits.budget().settings();
  std::printf("[budget] measured: %u splits over %u ticks, max %.3f ms/tick, longest split %.3f ms\n",
              run.executed, run.ticksWithSplits, run.maxUsed, run.maxSplit);
  EXPECT_EQ(run.executed, 50u);
  EXPECT_LE(run.maxCharged, s.millisecondsPerTick + run.maxSplit + 1e-9);
  // The decisions, on measured time: whatever the machine, no tick stopped with budget left while
  // cubes waited, and none began a split with its budget spent.
  EXPECT_EQ(run.stoppedEarly, 0u);
  EXPECT_EQ(run.overran, 0u);
}

// Bodies sit above the floor at every tick and new pieces start without deep interpenetration.
void expectNoTunnellingNorDeepStarts(const std::string& scene, uint64_t ticks, float minCentreHeight) {
  Sim sim;
  ASSERT_TRUE(sim.load(scenePath(scene))) << sim.scene.message;
  float lowest = 1e9f;
  float deepestStart = 0.f;
  float deepestAny = 0.f;
  uint32_t pieces = 0;
  std::set<uint32_t> fresh;  // body indices created by this tick's splits
  while (sim.tick < ticks) {
    sim.step(
        [&] {
          fresh.clear();
          for (const SplitEvent& ev : sim.splits.lastEvents())
            for (ecs::Entity p : ev.pieces)
              if (const auto* rb = sim.world.tryGet<RigidBody>(p)) {
                fresh.insert(rb->body.index);
                ++pieces;
              }
        },
        [&] {
          for (const physics::ContactEvent& c : sim.physics.contactEvents()) {
            deepestAny = std::max(deepestAny, c.depth);
            if (fresh.count(c.bodyA.index) || fresh.count(c.bodyB.index))
              deepestStart = std::max(deepestStart, c.depth);
          }
        });
    for (ecs::Entity e : sim.dynamicBodies()) {
      const auto bt = sim.physics.bodyTransform(sim.world.get<RigidBody>(e).body);
      lowest = std::min(lowest, bt->position.y);
    }
  }
  std::printf("[contacts] %s: %u pieces, deepest first-step contact %.2f mm, deepest contact %.2f mm, "
              "lowest centre of mass %.3f m over %llu ticks\n",
              scene.c_str(), pieces, deepestStart * 1000.f, deepestAny * 1000.f, lowest,
              (unsigned long long)ticks);
  EXPECT_GT(pieces, 0u);
  EXPECT_LT(deepestStart, 0.005f);  // 5 mm
  EXPECT_LT(deepestAny, 0.02f);
  EXPECT_GT(lowest, minCentreHeight);
}

TEST(SplitContacts, FiftyCubesNoDeepStartsNoTunnellingInTenSeconds) {
  // The thinnest pieces are 0.2 m slabs: their centre of mass never gets below 0.1 m on the floor.
  expectNoTunnellingNorDeepStarts("fifty_cubes.json", 600, 0.05f);
}

TEST(SplitContacts, TorusNoDeepStartsNoTunnellingInTenSeconds) {
  expectNoTunnellingNorDeepStarts("torus_cut.json", 600, 0.05f);
}

struct Snapshot {
  std::vector<uint64_t> hashes;
  std::vector<std::pair<glm::vec3, glm::quat>> transforms;
  size_t entities = 0;
};

Snapshot runForDeterminism() {
  Sim sim;
  EXPECT_TRUE(sim.load(scenePath("fifty_cubes.json"))) << sim.scene.message;
  Snapshot snap;
  SplitWorld w = sim.sw();
  for (; sim.tick < 120; ++sim.tick) {
    runSceneTick(w, sim.splits, sim.runner, sim.tick, kDt, sim.camera);
    snap.hashes.push_back(sim.physics.stateHash());
  }
  for (ecs::Entity e : sim.world.entities()) {
    if (const auto* t = sim.world.tryGet<ecs::Transform>(e)) snap.transforms.push_back({t->position, t->rotation});
  }
  snap.entities = sim.world.size();
  return snap;
}

// Every runner takes the tick in the one order (kTickOrder): a shatter's sixteen cells, over a limit
// of two wakings a tick, are woken two a tick by runSceneTick as by Simulation::step, never more (a
// runner that woke the queue twice in a tick would wake four).
TEST(TickOrder, EveryRunnerWakesQueuedPiecesAtMostTheLimitATick) {
  for (const bool sceneTick : {true, false}) {
    SCOPED_TRACE(sceneTick ? "runSceneTick" : "Simulation::step");
    Sim sim;
    ASSERT_TRUE(sim.load(scenePath("shatter_block.json"))) << sim.scene.message;
    SplitBudgetSettings s = sim.splits.budget().settings();
    s.maxActivationsPerTick = 2;
    sim.splits.budget().setSettings(s);
    SplitWorld w = sim.sw();
    size_t queuedBefore = 0, mostQueued = 0, woken = 0;
    for (; sim.tick < 60; ++sim.tick) {
      if (sceneTick) {
        runSceneTick(w, sim.splits, sim.runner, sim.tick, kDt, sim.camera);
      } else {
        sim.runner.update(w, sim.tick, kDt);
        sim.simulation.step(sim.tick, kDt, sim.camera);
      }
      const size_t queued = sim.splits.activationsQueued();
      if (queued < queuedBefore) {
        EXPECT_LE(queuedBefore - queued, 2u) << "tick " << sim.tick;
        woken += queuedBefore - queued;
      }
      mostQueued = std::max(mostQueued, queued);
      queuedBefore = queued;
    }
    EXPECT_GE(mostQueued, 10u) << "the shatter's cells were not throttled";
    EXPECT_EQ(woken, mostQueued);
    EXPECT_EQ(queuedBefore, 0u);
  }
}

TEST(SplitDeterminism, SplitSceneTwiceGivesTheSameBits) {
  const Snapshot a = runForDeterminism();
  const Snapshot b = runForDeterminism();
  ASSERT_EQ(a.hashes.size(), b.hashes.size());
  for (size_t k = 0; k < a.hashes.size(); ++k) ASSERT_EQ(a.hashes[k], b.hashes[k]) << "tick " << k;
  EXPECT_EQ(a.entities, b.entities);
  EXPECT_GT(a.entities, 100u);  // the pieces are there
  ASSERT_EQ(a.transforms.size(), b.transforms.size());
  for (size_t k = 0; k < a.transforms.size(); ++k) {
    EXPECT_EQ(std::memcmp(&a.transforms[k].first, &b.transforms[k].first, sizeof(glm::vec3)), 0) << k;
    EXPECT_EQ(std::memcmp(&a.transforms[k].second, &b.transforms[k].second, sizeof(glm::quat)), 0) << k;
  }
}

}  // namespace
}  // namespace cleave::components
