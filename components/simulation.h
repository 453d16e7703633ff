// SPDX-License-Identifier: MIT
// Simulation: the world's physics and splitting stepped in the phase order of engine/app/phase.h,
// one stage per phase. It serves both games (installSplitting registers its stages in an App's
// phases once), the component tests and the benchmarks (step() runs a whole tick without an App).
//
// Phases and stages: Triggers -> gather (splitter touches become requests); Split -> prepare (the
// budget picks requests, jobs start computing on workers); Commit -> commit (due jobs' pieces
// appear, in request order); PhysicsStep -> one fixed step; PhysicsSync -> transforms follow
// bodies, debris falls; Animation -> skinned meshes play, ragdolls follow their bones.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "cleave/components/resource_hooks.h"
#include "cleave/components/split_system.h"
#include "cleave/components/static_batches.h"
#include "cleave/app/app.h"
#include "cleave/ecs/world.h"
#include "cleave/physics/physics_world.h"

#include <array>
#include "cleave/render/renderer.h"

namespace cleave::components {

// The stages of one tick, in the one order every runner takes them in (Simulation::step,
// installSplitting, runSceneTick, the session benchmark), with the App phase each runs in.
enum class TickStage : uint8_t { Gather, Prepare, Commit, PhysicsStep, Sync, Settle, Animate };
struct TickStageInfo {
  TickStage stage;
  app::Phase phase;
  const char* name;  // the App system's name
};
inline constexpr std::array<TickStageInfo, 7> kTickOrder = {{
    {TickStage::Gather, app::Phase::Triggers, "split.gather"},
    {TickStage::Prepare, app::Phase::Split, "split.prepare"},
    {TickStage::Commit, app::Phase::Commit, "split.commit"},
    {TickStage::PhysicsStep, app::Phase::PhysicsStep, "physics.step"},
    {TickStage::Sync, app::Phase::PhysicsSync, "physics.sync"},
    {TickStage::Settle, app::Phase::PhysicsSync, "pieces.settle"},
    {TickStage::Animate, app::Phase::Animation, "animation"},
}};

// One stage on the bare parts (a world, its physics and renderer, a split system): what a runner
// without a Simulation calls (runSceneTick); a Simulation runs the same on its own parts.
void runTickStage(TickStage stage, SplitWorld& w, SplitSystem& splits, uint64_t tick, double dt,
                  const glm::dvec3& camera);

class Simulation {
 public:
  // `world` must outlive the simulation; the renderer may be null (no GPU meshes). While the
  // simulation lives, the world's entities own their bodies, shapes, joints, triggers and GPU
  // meshes (resource_hooks.h): destroying an entity frees them.
  explicit Simulation(ecs::World& world, SplitBudgetSettings budget = {}, render::Renderer* renderer = nullptr);

  ecs::World& world() { return world_; }
  physics::PhysicsWorld& physics() { return physics_; }
  SplitSystem& splits() { return splits_; }
  SplitWorld splitWorld() { return SplitWorld{world_, physics_, renderer_}; }
  StaticBatches& batches() { return batches_; }
  void setRenderer(render::Renderer* renderer) {
    renderer_ = renderer;
    resources_.setRenderer(renderer);
    batches_.setRenderer(renderer);
  }
  // Between the renderer's beginFrame and endFrame: every mesh of the world, frozen pieces through
  // their static batches (static_batches.h), which this updates first.
  void submitMeshes(uint64_t tick);

  void gather(uint64_t tick);                             // Triggers
  void prepare(uint64_t tick, const glm::dvec3& camera);  // Split
  void commit(uint64_t tick);                             // Commit
  void stepPhysics(double dt);                            // PhysicsStep
  void sync(double dt);                                   // PhysicsSync
  void settle(uint64_t tick, double dt);                  // PhysicsSync, after sync: the piece budget
  void animate(double dt);                                // Animation
  // One stage of the tick (kTickOrder).
  void run(TickStage stage, uint64_t tick, double dt, const glm::dvec3& camera);
  // One whole tick without an App, every stage of kTickOrder (gameplay is the caller's, before this).
  void step(uint64_t tick, double dt, const glm::dvec3& camera);

 private:
  ecs::World& world_;
  physics::PhysicsWorld physics_;
  ResourceHooks resources_;  // after physics_: the hooks go before the bodies they free
  SplitSystem splits_;
  render::Renderer* renderer_ = nullptr;
  StaticBatches batches_;  // a drawing cache of frozen pieces; its GPU meshes are its own
};

struct SplittingHooks {
  std::function<glm::dvec3()> camera;  // where split priority measures distance from
  // After the Commit phase, with the events of this tick's prepare and commit.
  std::function<void(app::TickContext&, const std::vector<SplitEvent>&)> committed;
};

// Registers the simulation's stages in the App's phases (kTickOrder), once. Systems a game registers in the same phases afterwards run after
// these. The simulation must outlive the App's runs.
void installSplitting(app::App& app, Simulation& sim, SplittingHooks hooks = {});

}  // namespace cleave::components
