// SPDX-License-Identifier: MIT
#include "cleave/components/simulation.h"

#include "cleave/components/skinned.h"

namespace cleave::components {

Simulation::Simulation(ecs::World& world, SplitBudgetSettings budget, render::Renderer* renderer)
    : world_(world), resources_(world, physics_, renderer), splits_(budget), renderer_(renderer) {
  batches_.setRenderer(renderer);
}

void Simulation::submitMeshes(uint64_t tick) {
  batches_.update(world_, tick);
  SplitWorld w = splitWorld();
  components::submitMeshes(w, &batches_);
}

void runTickStage(TickStage stage, SplitWorld& w, SplitSystem& splits, uint64_t tick, double dt,
                  const glm::dvec3& camera) {
  switch (stage) {
    case TickStage::Gather: splits.gatherTriggerRequests(w, tick); break;
    case TickStage::Prepare: splits.prepareSplits(w, tick, camera); break;
    case TickStage::Commit: splits.commitSplits(w, tick); break;
    case TickStage::PhysicsStep: w.physics.step(dt); break;
    case TickStage::Sync:
      syncTransformsFromBodies(w);
      updateDebris(w, float(dt));
      break;
    case TickStage::Settle: splits.settlePieces(w, tick, dt); break;
    case TickStage::Animate: updateAnimations(w, float(dt)); break;
  }
}

void Simulation::run(TickStage stage, uint64_t tick, double dt, const glm::dvec3& camera) {
  SplitWorld w = splitWorld();
  runTickStage(stage, w, splits_, tick, dt, camera);
}

void Simulation::gather(uint64_t tick) { run(TickStage::Gather, tick, 0.0, glm::dvec3(0.0)); }
void Simulation::prepare(uint64_t tick, const glm::dvec3& camera) { run(TickStage::Prepare, tick, 0.0, camera); }
void Simulation::commit(uint64_t tick) { run(TickStage::Commit, tick, 0.0, glm::dvec3(0.0)); }
void Simulation::stepPhysics(double dt) { run(TickStage::PhysicsStep, 0, dt, glm::dvec3(0.0)); }
void Simulation::sync(double dt) { run(TickStage::Sync, 0, dt, glm::dvec3(0.0)); }
void Simulation::settle(uint64_t tick, double dt) { run(TickStage::Settle, tick, dt, glm::dvec3(0.0)); }
void Simulation::animate(double dt) { run(TickStage::Animate, 0, dt, glm::dvec3(0.0)); }

void Simulation::step(uint64_t tick, double dt, const glm::dvec3& camera) {
  for (const TickStageInfo& s : kTickOrder) run(s.stage, tick, dt, camera);
}

void installSplitting(app::App& app, Simulation& sim, SplittingHooks hooks) {
  sim.setRenderer(&app.renderer());
  std::function<glm::dvec3()> camera = hooks.camera;
  if (!camera) camera = [] { return glm::dvec3(0.0); };
  for (const TickStageInfo& s : kTickOrder) {
    const TickStage stage = s.stage;
    app.addSystem(s.phase, s.name, [&sim, stage, camera, committed = hooks.committed](app::TickContext& c) {
      sim.run(stage, c.tick, c.dt, stage == TickStage::Prepare ? camera() : glm::dvec3(0.0));
      if (stage == TickStage::Commit && committed) committed(c, sim.splits().lastEvents());
    });
  }
}

}  // namespace cleave::components
