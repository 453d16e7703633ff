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

void Simulation::gather(uint64_t tick) {
  SplitWorld w = splitWorld();
  splits_.gatherTriggerRequests(w, tick);
}

void Simulation::prepare(uint64_t tick, const glm::dvec3& camera) {
  SplitWorld w = splitWorld();
  splits_.prepareSplits(w, tick, camera);
}

void Simulation::commit(uint64_t tick) {
  SplitWorld w = splitWorld();
  splits_.commitSplits(w, tick);
}

void Simulation::stepPhysics(double dt) { physics_.step(dt); }

void Simulation::sync(double dt) {
  SplitWorld w = splitWorld();
  syncTransformsFromBodies(w);
  updateDebris(w, float(dt));
}

void Simulation::settle(uint64_t tick, double dt) {
  SplitWorld w = splitWorld();
  splits_.settlePieces(w, tick, dt);
}

void Simulation::animate(double dt) {
  SplitWorld w = splitWorld();
  updateAnimations(w, float(dt));
}

void Simulation::step(uint64_t tick, double dt, const glm::dvec3& camera) {
  gather(tick);
  prepare(tick, camera);
  commit(tick);
  stepPhysics(dt);
  sync(dt);
  settle(tick, dt);
  animate(dt);
}

void installSplitting(app::App& app, Simulation& sim, SplittingHooks hooks) {
  sim.setRenderer(&app.renderer());
  std::function<glm::dvec3()> camera = hooks.camera;
  if (!camera) camera = [] { return glm::dvec3(0.0); };
  app.addSystem(app::Phase::Triggers, "split.gather", [&sim](app::TickContext& c) { sim.gather(c.tick); });
  app.addSystem(app::Phase::Split, "split.prepare",
                [&sim, camera](app::TickContext& c) { sim.prepare(c.tick, camera()); });
  app.addSystem(app::Phase::Commit, "split.commit", [&sim, committed = hooks.committed](app::TickContext& c) {
    sim.commit(c.tick);
    if (committed) committed(c, sim.splits().lastEvents());
  });
  app.addSystem(app::Phase::PhysicsStep, "physics.step", [&sim](app::TickContext& c) { sim.stepPhysics(c.dt); });
  app.addSystem(app::Phase::PhysicsSync, "physics.sync", [&sim](app::TickContext& c) {
    sim.sync(c.dt);
    sim.settle(c.tick, c.dt);
  });
  app.addSystem(app::Phase::Animation, "animation", [&sim](app::TickContext& c) { sim.animate(c.dt); });
}

}  // namespace cleave::components
