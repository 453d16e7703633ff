// SPDX-License-Identifier: MIT
// The split pipeline in the engine: prepare, compute on workers, commit at a fixed tick. Threads
// never change a result; the commit tick is prepare + commitDelayTicks, later for a split estimated
// longer than a tick; a target gone before its
// commit leaves nothing behind; a custom handler edits the pieces or keeps the original whole; and
// pieces carry their collider parts into their own cuts.
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "cleave/geometry/primitives.h"
#include "tests/components/sim_harness.h"

namespace cleave::components {
namespace {

using testing::scenePath;
using testing::Sim;

// FNV-1a over every entity's index, generation, position and rotation bits, in entity order.
uint64_t stateHash(Sim& sim) {
  uint64_t h = 1469598103934665603ull;
  auto mix = [&](const void* p, size_t n) {
    const auto* b = static_cast<const uint8_t*>(p);
    for (size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  };
  for (ecs::Entity e : sim.world.entities()) {
    const auto* t = sim.world.tryGet<ecs::Transform>(e);
    if (!t) continue;
    mix(&e.index, sizeof(e.index));
    mix(&e.generation, sizeof(e.generation));
    mix(&t->position, sizeof(t->position));
    mix(&t->rotation, sizeof(t->rotation));
  }
  return h;
}

void setThreads(Sim& sim, uint32_t threads, uint32_t delay = 1) {
  SplitBudgetSettings s = sim.splits.budget().settings();
  s.threads = threads;
  s.commitDelayTicks = delay;
  sim.splits.budget().setSettings(s);
}

TEST(SplitPipeline, ThreadsNeverChangeTheOutcome) {
  std::vector<uint64_t> hashes;
  std::vector<size_t> pieces;
  for (uint32_t threads : {0u, 1u, 3u}) {
    uint64_t offThread = 0;  // jobs computed by a worker, over the three scenes
    for (const char* scene : {"fifty_cubes.json", "torus_cut.json", "u_shape.json"}) {
      Sim sim;
      ASSERT_TRUE(sim.load(scenePath(scene))) << sim.scene.message;
      setThreads(sim, threads);
      // Each tick leaves the workers a moment (they run at a lower priority and, on a loaded
      // machine, would otherwise find every job taken by the main thread's wait).
      while (sim.tick < 120) {
        sim.step();
        if (threads > 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
      hashes.push_back(stateHash(sim));
      pieces.push_back(size_t(sim.splits.totalPiecesCreated()));
      offThread += sim.splits.jobsComputedOffTheCallingThread();
    }
    // The threads really ran: with workers, jobs were computed off the main thread.
    std::printf("[threads] %u: %llu jobs computed off the main thread\n", threads,
                static_cast<unsigned long long>(offThread));
    if (threads == 0) {
      EXPECT_EQ(offThread, 0u);
    } else {
      EXPECT_GT(offThread, 0u) << threads << " threads";
    }
  }
  for (size_t i = 3; i < hashes.size(); ++i) {
    EXPECT_EQ(hashes[i], hashes[i % 3]) << "scene " << i % 3 << ", run " << i / 3;
    EXPECT_EQ(pieces[i], pieces[i % 3]);
  }
  EXPECT_GT(pieces[0], 50u);
}

TEST(SplitPipeline, JobsCommitCommitDelayTicksAfterTheirPrepare) {
  for (uint32_t delay : {0u, 1u, 3u}) {
    Sim sim;
    ASSERT_TRUE(sim.load(scenePath("torus_cut.json"))) << sim.scene.message;
    setThreads(sim, 1, delay);
    uint64_t committedAt = 0, preparedAt = 0;
    while (sim.tick < 60 && committedAt == 0) {
      const uint64_t tick = sim.tick;
      sim.step();
      for (const SplitEvent& ev : sim.splits.lastEvents()) {
        if (ev.status != geometry::SplitStatus::Ok) continue;
        committedAt = tick;
        preparedAt = ev.preparedTick;
        EXPECT_EQ(ev.tick, tick);
      }
      if (committedAt == 0 && sim.tick > 33) {
        EXPECT_EQ(sim.splits.jobsInFlight(), delay > 0 ? 1u : 0u) << "tick " << tick;
      }
    }
    ASSERT_GT(committedAt, 0u) << "delay " << delay;
    EXPECT_EQ(preparedAt, 32u);  // fired at 30, its step touches at 30, gathered at 31, prepared at 32
    EXPECT_EQ(committedAt, preparedAt + delay);
  }
}

// The torus's split estimated at more worker time than a tick gives (workerMillisecondsPerCommitTick
// set below its estimate): it commits as many ticks later as the estimate needs, at most
// maxExtraCommitTicks more, on any number of threads.
TEST(SplitPipeline, ASplitEstimatedLongerThanATickCommitsLaterByWhatItNeeds) {
  for (uint32_t threads : {0u, 1u, 3u}) {
    for (const auto& [slices, cap, extra] : {std::tuple{2.5, 3u, 2u}, std::tuple{10.0, 3u, 3u}, std::tuple{10.0, 0u, 0u}}) {
      Sim sim;
      ASSERT_TRUE(sim.load(scenePath("torus_cut.json"))) << sim.scene.message;
      setThreads(sim, threads, 1);
      std::vector<SplitEvent> events = sim.runUntil(60);
      ASSERT_EQ(events.size(), 1u);
      const double estimate = events[0].estimatedWorkerMilliseconds;
      ASSERT_GT(estimate, 0.0);
      EXPECT_EQ(events[0].tick, events[0].preparedTick + 1) << "within a tick's worth: the next tick";
      // Again, with a tick's worth of worker time `slices` times smaller than the estimate.
      Sim slow;
      ASSERT_TRUE(slow.load(scenePath("torus_cut.json"))) << slow.scene.message;
      setThreads(slow, threads, 1);
      SplitBudgetSettings s = slow.splits.budget().settings();
      s.workerMillisecondsPerCommitTick = estimate / slices;
      s.maxExtraCommitTicks = cap;
      slow.splits.budget().setSettings(s);
      events = slow.runUntil(60);
      ASSERT_EQ(events.size(), 1u);
      EXPECT_EQ(events[0].preparedTick, 32u);
      EXPECT_EQ(events[0].tick, 32u + 1u + extra) << threads << " threads, " << slices << " slices, cap " << cap;
      EXPECT_EQ(events[0].status, geometry::SplitStatus::Ok);
    }
  }
}

// A sphere of 4,000 triangles and a box of 12 asked for in one tick, the sphere first: the sphere's
// split is estimated long enough to commit late, and the box's, prepared after it in the
// same tick, waits for it (commit order is request order) instead of committing the next tick.
TEST(SplitPipeline, ALateCommitHoldsBackTheSplitsPreparedAfterIt) {
  for (uint32_t threads : {0u, 2u}) {
    Sim sim;
    setThreads(sim, threads, 1);
    Splitable sp;
    const ecs::Entity sphere = testing::addSplitableBody(sim, "sphere", geometry::primitives::uvSphere(0.5f, 64, 32), sp,
                                                         500.0, glm::vec3(0.f, 3.f, 0.f));
    const ecs::Entity box = testing::addSplitableBody(sim, "box", geometry::primitives::box(glm::vec3(0.3f)), sp, 500.0,
                                                      glm::vec3(3.f, 3.f, 0.f));
    for (ecs::Entity target : {sphere, box}) {
      SplitRequest r;
      r.target = target;
      r.planeNormal = glm::dvec3(1.0, 0.0, 0.0);
      r.planeOffset = double(sim.world.get<ecs::Transform>(target).position.x) + 0.05;
      r.requestedTick = sim.tick;
      sim.splits.request(r);
    }
    SplitBudgetSettings s = sim.splits.budget().settings();
    s.workerMillisecondsPerCommitTick = 0.3;
    sim.splits.budget().setSettings(s);
    const std::vector<SplitEvent> events = sim.runUntil(sim.tick + 10);
    ASSERT_EQ(events.size(), 2u);
    EXPECT_EQ(events[0].original, sphere);
    EXPECT_EQ(events[1].original, box);
    EXPECT_EQ(events[0].preparedTick, events[1].preparedTick);
    ASSERT_GT(events[0].estimatedWorkerMilliseconds, 0.6) << "the sphere must want extra ticks";
    ASSERT_LT(events[1].estimatedWorkerMilliseconds, 0.3) << "the box must want none";
    EXPECT_GE(events[0].tick, events[0].preparedTick + 2);
    EXPECT_EQ(events[1].tick, events[0].tick) << threads << " threads";
  }
}

TEST(SplitPipeline, TargetGoneBeforeItsCommitLeavesNothingBehind) {
  Sim sim;
  ASSERT_TRUE(sim.load(scenePath("torus_cut.json"))) << sim.scene.message;
  setThreads(sim, 1, 2);
  const ecs::Entity torus = sim.scene.find("torus");
  while (sim.splits.jobsInFlight() == 0 && sim.tick < 60) sim.step();
  ASSERT_EQ(sim.splits.jobsInFlight(), 1u);
  // Gameplay destroys the object while its split computes.
  sim.world.destroy(torus);
  const size_t entities = sim.world.entities().size();
  std::vector<SplitEvent> events = sim.runUntil(sim.tick + 3);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_NE(events[0].status, geometry::SplitStatus::Ok);
  EXPECT_NE(events[0].message.find("gone"), std::string::npos) << events[0].message;
  EXPECT_TRUE(events[0].pieces.empty());
  EXPECT_EQ(sim.world.entities().size(), entities);
  EXPECT_EQ(sim.splits.totalPiecesCreated(), 0u);
}

TEST(SplitPipeline, HandlerEditsThePiecesOrKeepsTheOriginalWhole) {
  for (bool keep : {false, true}) {
    Sim sim;
    ASSERT_TRUE(sim.load(scenePath("torus_cut.json"))) << sim.scene.message;
    const ecs::Entity torus = sim.scene.find("torus");
    sim.world.get<Splitable>(torus).handler = "test.handler";
    int calls = 0;
    sim.splits.registerHandler("test.handler", [&](const SplitJob& job, SplitOutcome& out) {
      ++calls;
      EXPECT_EQ(job.request.target, torus);
      EXPECT_EQ(out.pieces.size(), 2u);
      if (keep) return HandlerDecision::KeepOriginal;
      // The upper ring flies up; the lower one becomes debris.
      for (PieceSpec& p : out.pieces) {
        if (p.side > 0) p.impulse += glm::dvec3(0.0, 2.0, 0.0);
        if (p.side < 0) p.kind = PieceKind::Debris;
      }
      return HandlerDecision::Commit;
    });
    const double mass = sim.world.get<MassInfo>(torus).mass;
    std::vector<SplitEvent> events;
    while (events.empty() && sim.tick < 60) {
      sim.step();  // stops right after the commit: the pieces have their first step's motion only
      events = sim.splits.lastEvents();
    }
    ASSERT_EQ(calls, 1);
    ASSERT_EQ(events.size(), 1u);
    if (keep) {
      EXPECT_TRUE(events[0].pieces.empty());
      EXPECT_TRUE(sim.world.alive(torus));
      EXPECT_DOUBLE_EQ(sim.world.get<MassInfo>(torus).mass, mass);
      continue;
    }
    ASSERT_EQ(events[0].pieces.size(), 2u);
    EXPECT_FALSE(sim.world.alive(torus));
    EXPECT_NEAR(events[0].piecesMass, mass, 1e-6 * mass);
    for (size_t i = 0; i < 2; ++i) {
      const ecs::Entity piece = events[0].pieces[i];
      if (events[0].kinds[i] == PieceKind::Debris) {
        EXPECT_TRUE(sim.world.has<Debris>(piece));
        EXPECT_FALSE(sim.world.has<RigidBody>(piece));
      } else {
        const auto state = sim.physics.bodyState(sim.world.get<RigidBody>(piece).body);
        ASSERT_TRUE(state);
        EXPECT_GT(state->linearVelocity.y, 1.5f);
      }
    }
  }
}

// Each refusal at commit (no handler of that name, a handler that keeps the original, a handler that
// gives a piece without a mesh) leaves the world exactly as a split that never happened: the same
// entities, places and motions as the run whose handler keeps the original, the torus whole with its
// mass, no piece made, and an event that says why.
TEST(SplitPipeline, EveryRefusalAtCommitLeavesTheOriginalWholeWithItsMassAndMotion) {
  enum class Refusal { Keep, UnknownHandler, PieceWithoutMesh };
  struct Run {
    uint64_t hash = 0;
    size_t entities = 0;
    double mass = 0.0;
    glm::vec3 velocity{0.f}, spin{0.f};
    std::string message;
    geometry::SplitStatus status = geometry::SplitStatus::Ok;
    uint64_t pieces = 0;
  };
  auto run = [](Refusal refusal) {
    Sim sim;
    EXPECT_TRUE(sim.load(scenePath("torus_cut.json"))) << sim.scene.message;
    const ecs::Entity torus = sim.scene.find("torus");
    sim.world.get<Splitable>(torus).handler = refusal == Refusal::UnknownHandler ? "nobody" : "test.handler";
    sim.splits.registerHandler("test.handler", [refusal](const SplitJob&, SplitOutcome& out) {
      if (refusal == Refusal::Keep) return HandlerDecision::KeepOriginal;
      out.pieces.back().mesh = nullptr;
      return HandlerDecision::Commit;
    });
    Run r;
    for (const SplitEvent& ev : sim.runUntil(60)) {
      r.status = ev.status;
      r.message = ev.message;
    }
    EXPECT_TRUE(sim.world.alive(torus));
    r.hash = stateHash(sim);
    r.entities = sim.world.entities().size();
    r.mass = sim.world.get<MassInfo>(torus).mass;
    const auto state = sim.physics.bodyState(sim.world.get<RigidBody>(torus).body);
    EXPECT_TRUE(state);
    if (state) r.velocity = state->linearVelocity, r.spin = state->angularVelocity;
    r.pieces = sim.splits.totalPiecesCreated();
    return r;
  };
  const Run kept = run(Refusal::Keep);
  EXPECT_EQ(kept.message, "the custom handler kept the original");
  for (Refusal refusal : {Refusal::UnknownHandler, Refusal::PieceWithoutMesh}) {
    const Run r = run(refusal);
    SCOPED_TRACE(r.message);
    EXPECT_EQ(r.status, geometry::SplitStatus::InvalidInput);
    EXPECT_NE(r.message.find(refusal == Refusal::UnknownHandler ? "no split handler named 'nobody'" : "without a mesh"),
              std::string::npos);
    EXPECT_EQ(r.pieces, 0u);
    EXPECT_EQ(r.entities, kept.entities);
    EXPECT_EQ(r.hash, kept.hash);
    EXPECT_DOUBLE_EQ(r.mass, kept.mass);
    EXPECT_EQ(r.velocity, kept.velocity);
    EXPECT_EQ(r.spin, kept.spin);
  }
}

TEST(SplitPipeline, ASecondCutOfATargetInFlightWaitsAndRunsIfTheFirstKeptItWhole) {
  Sim sim;
  ASSERT_TRUE(sim.load(scenePath("torus_cut.json"))) << sim.scene.message;
  setThreads(sim, 1, 2);
  const ecs::Entity torus = sim.scene.find("torus");
  sim.world.get<Splitable>(torus).handler = "test.second";
  int calls = 0;
  sim.splits.registerHandler("test.second", [&](const SplitJob&, SplitOutcome&) {
    return ++calls == 1 ? HandlerDecision::KeepOriginal : HandlerDecision::Commit;
  });
  while (sim.splits.jobsInFlight() == 0 && sim.tick < 60) sim.step();
  ASSERT_EQ(sim.splits.jobsInFlight(), 1u);
  // Another cut while the first computes: it must wait in the queue, not be dropped.
  sim.requestCut(torus, glm::dvec3(1, 0, 0), 0.0);
  std::vector<SplitEvent> events = sim.runUntil(sim.tick + 8);
  ASSERT_EQ(calls, 2);
  ASSERT_EQ(events.size(), 2u);
  EXPECT_TRUE(events[0].pieces.empty());  // the first kept the torus whole
  EXPECT_EQ(events[1].pieces.size(), 2u);  // the second cut it, after the first was committed
  EXPECT_GT(events[1].preparedTick, events[0].tick - 1);
  EXPECT_FALSE(sim.world.alive(torus));
}

TEST(SplitPipeline, PiecesCarryTheirPartsAndCutsOnlyClipThem) {
  Sim sim;
  ASSERT_TRUE(sim.load(scenePath("torus_cut.json"))) << sim.scene.message;
  const ecs::Entity torus = sim.scene.find("torus");
  ASSERT_TRUE(sim.world.has<ColliderParts>(torus));  // decomposed once, when its body was made
  std::vector<SplitEvent> events = sim.runUntil(40);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_TRUE(events[0].partsKnown);
  for (size_t i = 0; i < events[0].pieces.size(); ++i) {
    EXPECT_TRUE(sim.world.has<ColliderParts>(events[0].pieces[i]));
    EXPECT_LE(events[0].colliderFit[i], 1.5) << "piece " << i;
    EXPECT_GE(events[0].colliderFit[i], 0.8) << "piece " << i;
  }
  // Cut a ring again, vertically: its own parts are clipped, nothing is decomposed.
  const ecs::Entity ring = events[0].pieces[0];
  SplitRequest r;
  r.target = ring;
  r.planeNormal = glm::dvec3(1, 0, 0);
  r.planeOffset = double(sim.world.get<ecs::Transform>(ring).position.x);
  SplitWorld w = sim.sw();
  const SplitEvent again = sim.splits.splitNow(w, ring, r, sim.tick);
  ASSERT_EQ(again.status, geometry::SplitStatus::Ok) << again.message;
  EXPECT_TRUE(again.partsKnown);
  EXPECT_TRUE(again.weldKnown);
  EXPECT_EQ(again.pieces.size(), 2u);
  for (double fit : again.colliderFit) EXPECT_LE(fit, 1.5);
}

}  // namespace
}  // namespace cleave::components
