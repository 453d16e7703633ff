// SPDX-License-Identifier: MIT
// Shatter splitters (SplitterKind::Shatter, components/shatter.h): what their trigger touches is
// broken into Voronoi cells as a split job (computed on workers, committed at the commit tick), the
// pieces rigid bodies with the parent's mass and momentum, the same pieces on 0 or 2 threads.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <thread>
#include <vector>

#include "cleave/geometry/mass_properties.h"
#include "cleave/geometry/primitives.h"
#include "tests/components/sim_harness.h"

namespace cleave::components {
namespace {

using testing::Sim;

// A 1 m crate (600 kg/m^3; or another mesh) on a dynamic body at height 3, moving.
ecs::Entity addCrate(Sim& sim, const geometry::MeshData& mesh) {
  Splitable sp;
  sp.density = 600.0;
  sp.minPieceVolume = 0.0;  // every cell a rigid body (no debris), so the momenta count them all
  const ecs::Entity e = testing::addSplitableBody(sim, "crate", mesh, sp, sp.density, glm::vec3(0.f, 3.f, 0.f));
  sim.physics.setVelocity(sim.world.get<RigidBody>(e).body, glm::vec3(1.f, 0.f, 0.f), glm::vec3(0.f, 0.5f, 0.f));
  return e;
}

// A one-tick shatter splitter: a 2 m box trigger around the crate.
void addShatter(Sim& sim, uint32_t cells, double outward) {
  Splitter s;
  s.kind = SplitterKind::Shatter;
  s.shatter.cells = cells;
  s.shatter.seed = 42;
  s.shatter.outwardImpulse = outward;
  s.halfExtents = glm::vec3(1.f);
  SplitWorld sw = sim.sw();
  ASSERT_NE(createSplitter(sw, "hammer", physics::ShapeDef::box(s.halfExtents), glm::vec3(0.2f, 3.f, 0.f),
                           glm::quat(1.f, 0.f, 0.f, 0.f), s),
            ecs::kNullEntity);
}

struct Shattered {
  SplitEvent event;
  testing::Momenta before, after;                 // the tick before the pieces, right after them
  std::vector<std::vector<glm::vec3>> positions;  // per piece, for determinism
  std::vector<glm::vec3> velocities, centres;     // per piece, right after the commit
  uint64_t offThread = 0;                          // split jobs computed by a worker
};

Shattered shatterCrate(uint32_t threads, uint32_t cells, double outward,
                       const geometry::MeshData& mesh = geometry::primitives::box(glm::vec3(0.5f))) {
  Sim sim;
  SplitBudgetSettings settings = sim.splits.budget().settings();
  settings.threads = threads;
  sim.splits.budget().setSettings(settings);
  PieceBudgetSettings pieces = sim.splits.pieces().settings();
  pieces.minBodyVolume = pieces.minBodyThickness = 0.0;  // every cell a body, however thin (see addCrate)
  sim.splits.pieces().setSettings(pieces);
  const ecs::Entity crate = addCrate(sim, mesh);
  (void)crate;
  Shattered out;
  sim.step();  // let the body move once
  addShatter(sim, cells, outward);
  for (int t = 0; t < 8 && out.event.pieces.empty(); ++t) {
    const testing::Momenta before = testing::momentaOf(sim);
    sim.step([&] {
      for (const SplitEvent& ev : sim.splits.lastEvents()) {
        if (ev.pieces.empty()) continue;
        out.event = ev;
        out.before = before;
        out.after = testing::momentaOf(sim);
        for (ecs::Entity piece : ev.pieces) {
          const auto state = sim.physics.bodyState(sim.world.get<RigidBody>(piece).body);
          out.velocities.push_back(state ? state->linearVelocity : glm::vec3(NAN));
          out.centres.push_back(state ? state->transform.position : glm::vec3(NAN));
          out.positions.push_back(sim.world.get<MeshRenderer>(piece).source->positions);
        }
      }
    });
    // A job in flight: leave the workers (a lower priority) a moment to take it before the commit.
    if (threads > 0 && sim.splits.jobsInFlight() > 0) std::this_thread::sleep_for(std::chrono::milliseconds(30));
  }
  out.offThread = sim.splits.jobsComputedOffTheCallingThread();
  return out;
}

TEST(Shatter, ACrateBreaksIntoCellsWithItsMassAndMomentum) {
  const Shattered s = shatterCrate(0, 16, 0.0);
  ASSERT_EQ(s.event.status, geometry::SplitStatus::Ok) << s.event.message;
  EXPECT_GE(s.event.pieces.size(), 8u);
  for (PieceKind kind : s.event.kinds) EXPECT_EQ(kind, PieceKind::Rigid);
  EXPECT_NEAR(s.event.piecesMass, 600.0, 1e-6 * 600.0);
  EXPECT_NEAR(s.after.mass, s.before.mass, 1e-3 * s.before.mass);
  // Pieces move with the parent (v + w x r): the linear momentum is kept.
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(s.after.linear[k], s.before.linear[k], 1e-2 * s.before.mass) << k;
}

// A concave source: its carried parts (a decomposition of the torus) are clipped by every cell.
TEST(Shatter, ATorusBreaksIntoCellsWithCarriedPartsAsColliders) {
  const geometry::MeshData torus = geometry::primitives::torus(0.5f, 0.2f, 48, 24);
  const double volume = geometry::computeMassProperties(torus).volume;
  const Shattered s = shatterCrate(0, 16, 0.0, torus);
  ASSERT_EQ(s.event.status, geometry::SplitStatus::Ok) << s.event.message;
  EXPECT_GE(s.event.pieces.size(), 8u);
  EXPECT_NEAR(s.event.piecesMass, 600.0 * volume, 1e-6 * 600.0 * volume);
  for (size_t k = 0; k < s.event.kinds.size(); ++k) {
    EXPECT_EQ(s.event.kinds[k], PieceKind::Rigid) << k;
    std::printf("[ shatter ] torus piece %zu: collider fit %.3f\n", k, s.event.colliderFit[k]);
    EXPECT_GT(s.event.colliderFit[k], 0.6) << k;
    EXPECT_LT(s.event.colliderFit[k], 2.0) << k;  // a curved chunk's own hull may fill its bend
  }
}

TEST(Shatter, OutwardImpulseSendsPiecesAwayFromTheImpact) {
  const Shattered calm = shatterCrate(0, 16, 0.0), blast = shatterCrate(0, 16, 3.0);
  ASSERT_EQ(blast.event.status, geometry::SplitStatus::Ok) << blast.event.message;
  // The same cells (same seed, same impact); each piece gets 3 m/s more, away from the impact.
  ASSERT_EQ(calm.event.pieces.size(), blast.event.pieces.size());
  ASSERT_GT(blast.velocities.size(), 0u);
  const glm::vec3 impact(0.2f, 3.f, 0.f);  // the splitter's position
  for (size_t k = 0; k < blast.velocities.size(); ++k) {
    const glm::vec3 added = blast.velocities[k] - calm.velocities[k];
    EXPECT_NEAR(glm::length(added), 3.f, 1e-3f) << "piece " << k;
    EXPECT_GT(glm::dot(added, blast.centres[k] - impact), 0.f) << "piece " << k << " is not sent away";
  }
}

TEST(Shatter, SamePiecesOnZeroAndTwoThreads) {
  const Shattered a = shatterCrate(0, 16, 1.0), b = shatterCrate(2, 16, 1.0);
  EXPECT_EQ(a.offThread, 0u);
  EXPECT_EQ(b.offThread, 1u) << "the shatter was computed on a worker";
  ASSERT_EQ(a.positions.size(), b.positions.size());
  ASSERT_GT(a.positions.size(), 0u);
  for (size_t k = 0; k < a.positions.size(); ++k) {
    ASSERT_EQ(a.positions[k].size(), b.positions[k].size());
    EXPECT_EQ(std::memcmp(a.positions[k].data(), b.positions[k].data(), a.positions[k].size() * sizeof(glm::vec3)), 0);
  }
}

// A piece of a shatter is shattered again (depth 2), and with maxDepth 1 its pieces are no longer
// splitable at all.
TEST(Shatter, PiecesShatterAgainUpToTheSplitablesDepth) {
  for (uint32_t maxDepth : {2u, 1u}) {
    Sim sim;
    const ecs::Entity crate = addCrate(sim, geometry::primitives::box(glm::vec3(0.5f)));
    sim.world.get<Splitable>(crate).maxDepth = maxDepth;
    addShatter(sim, 8, 0.0);
    std::vector<SplitEvent> events = sim.runUntil(6);
    ASSERT_EQ(events.size(), 1u);
    ASSERT_GE(events[0].pieces.size(), 4u);
    // The largest piece, shattered where it is now.
    ecs::Entity largest;
    double most = 0.0;
    for (ecs::Entity piece : events[0].pieces) {
      const double mass = sim.world.get<MassInfo>(piece).mass;
      if (mass > most) most = mass, largest = piece;
    }
    EXPECT_EQ(sim.world.has<Splitable>(largest), maxDepth > 1) << "maxDepth " << maxDepth;
    if (maxDepth == 1) continue;
    Splitter s;
    s.kind = SplitterKind::Shatter;
    s.shatter.cells = 8;
    s.shatter.seed = 3;
    s.halfExtents = glm::vec3(1.f);
    SplitWorld sw = sim.sw();
    const glm::vec3 at = sim.world.get<ecs::Transform>(largest).position;
    ASSERT_NE(createSplitter(sw, "second", physics::ShapeDef::box(s.halfExtents), at, glm::quat(1.f, 0.f, 0.f, 0.f), s),
              ecs::kNullEntity);
    events = sim.runUntil(12);
    size_t again = 0;
    for (const SplitEvent& ev : events) {
      if (ev.original != largest) continue;
      ++again;
      EXPECT_EQ(ev.status, geometry::SplitStatus::Ok) << ev.message;
      EXPECT_GE(ev.pieces.size(), 2u);
      EXPECT_NEAR(ev.piecesMass, most, 1e-6 * most);
    }
    EXPECT_EQ(again, 1u) << "the largest piece was not shattered again";
  }
}

}  // namespace
}  // namespace cleave::components
