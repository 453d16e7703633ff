// SPDX-License-Identifier: MIT
// Data-driven scenes: a JSON file (docs/scene-format.md) describing objects, splitters, the split
// budget, gravity and a floor, turned into entities, bodies and scheduled splitters.
//
// Use (the same in the demo and in headless runs):
//
//   components::SplitSystem splits;
//   components::SceneContext ctx{world, physics, renderer /* or nullptr */, &splits, resolver};
//   components::SceneLoadResult scene = components::loadScene("assets/scenes/torus_cut.json", ctx);
//   if (!scene.ok()) { std::fprintf(stderr, "%s\n", scene.message.c_str()); return 1; }
//   components::SceneRunner runner(scene.splitters);
//   // every tick, in the Gameplay phase:   runner.update(splitWorld, tick, dt);
//   // or, without an App, one whole tick:   components::runSceneTick(splitWorld, splits, runner, tick, dt, camera);
//
// Units: metres, kilograms, seconds; angles in the file in degrees (Euler) or as a unit quaternion.
//
// Ownership: each entity created owns its body, shape, trigger and GPU mesh through the world's
// destroy hooks (resource_hooks.h; a Simulation installs them): World::destroy frees them, and so
// does the rollback of a scene that fails while being created. Without the hooks they stay in the
// PhysicsWorld and the Renderer until those go.
//
// Failure: loadScene never throws and never crashes on a bad file. The whole file is read and
// checked before anything is created, so a bad scene creates nothing; an error while creating (a mesh
// that encloses no volume) removes what was created. The error is one line
// "<file>:<line>: <field>: <reason>", where <field> is the JSON pointer of the offending value
// (e.g. /entities/2/mesh/radius) and <line> the line it starts on (for a syntax error, the line and
// column of the offending character and the last field before it).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "cleave/base/status.h"
#include "cleave/components/split_budget.h"
#include "cleave/components/split_system.h"
#include "cleave/components/splitable.h"
#include "cleave/ecs/entity.h"
#include "cleave/ecs/world.h"
#include "cleave/physics/physics_world.h"
#include "cleave/render/renderer.h"

namespace cleave::components {

// Maps a material name of the scene file ("wood", "metal", ...) to what is drawn. `cap` is true
// for the inside of an object (the cap material of its Splitable). Unknown names are the caller's
// business (e.g. a plain material); an empty resolver gives render::Material{} for every name.
using MaterialResolver = std::function<render::Material(const std::string& name, bool cap)>;

// What the loader creates things in. `renderer` may be null: meshes are then not uploaded (pure
// simulation). `splits` may be null: the budget settings of the file are then only returned.
struct SceneContext {
  ecs::World& world;
  physics::PhysicsWorld& physics;
  render::Renderer* renderer = nullptr;
  SplitSystem* splits = nullptr;
  MaterialResolver materials;
};

// One authored object as created.
struct SceneEntity {
  ecs::Entity entity;
  std::string name;
  std::string material;      // the material name of the file ("" when none was given)
  bool dynamic = false;      // has a dynamic rigid body
  bool splitable = false;
  ecs::Entity parent;        // null for roots
};

enum class SplitterSchedule : uint8_t {
  Persistent,  // exists from startTick (until endTick when given), cuts what it touches
  OneTick,     // exists only during tick fireTick: cuts what it touches in that tick's step
};

// A splitter of the scene. Persistent splitters are created at load when startTick is 0, the others
// by SceneRunner::update when their tick comes. Its position at tick t (from its creation tick c) is
// transform.position + velocity * (t - c) * dt; its rotation stays.
struct ScheduledSplitter {
  std::string name;
  SplitterSchedule schedule = SplitterSchedule::OneTick;
  glm::vec3 halfExtents{1.f, 0.02f, 1.f};  // trigger box in the splitter frame (plane = local y)
  glm::vec3 position{0.f};
  glm::quat rotation{1.f, 0.f, 0.f, 0.f};
  glm::vec3 velocity{0.f};                 // m/s, constant
  uint64_t startTick = 0;                  // Persistent: first tick it exists
  std::optional<uint64_t> endTick;         // Persistent: removed at the start of this tick
  uint64_t fireTick = 0;                   // OneTick: the tick whose physics step it cuts in
  bool playerCaused = false;
  SplitterKind kind = SplitterKind::Plane;  // "kind": "plane" (default) or "shatter"
  ShatterSpec shatter;                     // kind Shatter: cells, seed, impact point and radius, impulse
  ecs::Entity entity;                      // null until created (and after it is gone)
  bool created = false;                    // it has been created (it may be gone again)
  uint64_t createdTick = 0;
};

// A Status (message "<file>:<line>: <field>: <reason>" when !ok(); the parts are also given
// separately) with what the scene made.
struct SceneLoadResult : base::Status {
  std::string errorFile;
  int errorLine = 0;
  std::string errorField;    // JSON pointer, "" for the whole file

  std::vector<SceneEntity> entities;        // in file order, parents before children
  std::vector<ScheduledSplitter> splitters; // in file order (persistent ones created at load have entity set)
  ecs::Entity floor;                        // null when the scene has none
  glm::vec3 gravity{0.f, -9.81f, 0.f};      // applied to the physics world
  SplitBudgetSettings budget;               // applied to ctx.splits when given
  PieceBudgetSettings pieceBudget;          // applied to ctx.splits when given
  glm::vec3 cameraPosition{0.f, 2.f, 6.f};  // where the scene wants to be seen from
  glm::vec3 cameraTarget{0.f};
  uint64_t ticks = 0;                       // suggested run length (0: not given)

  // The entity of the first object with this name (null when there is none).
  ecs::Entity find(const std::string& name) const;
};

// Reads, checks and instantiates the scene in `path`. Model files are resolved relative to the
// folder of `path`. Applies gravity and (with ctx.splits) the budget settings. See the header note
// for errors.
SceneLoadResult loadScene(const std::string& path, SceneContext& ctx);

// The same from text in memory; `name` stands for the file in messages and `baseDirectory`
// resolves model paths.
SceneLoadResult loadSceneFromString(const std::string& text, const std::string& name,
                                    const std::string& baseDirectory, SceneContext& ctx);

// Drives the scheduled splitters of a scene: call update() once per tick in the Gameplay phase
// (before the Triggers phase gathers the last step's touches). It creates splitters whose tick has
// come, moves moving ones, and removes persistent ones whose end tick has come. One-tick splitters
// are removed by SplitSystem::gatherTriggerRequests after their step.
class SceneRunner {
 public:
  SceneRunner() = default;
  explicit SceneRunner(std::vector<ScheduledSplitter> splitters) : splitters_(std::move(splitters)) {}

  void update(SplitWorld& w, uint64_t tick, double dt);
  const std::vector<ScheduledSplitter>& splitters() const { return splitters_; }

 private:
  std::vector<ScheduledSplitter> splitters_;
};

// Creates the entity and trigger of a splitter now (used by the loader and the runner).
ecs::Entity createSplitterEntity(SplitWorld& w, const ScheduledSplitter& s);

// One whole headless tick: Gameplay (runner.update), then every stage of the one tick order
// (simulation.h's kTickOrder). A request gathered in tick N is executed in tick N+1.
void runSceneTick(SplitWorld& w, SplitSystem& splits, SceneRunner& runner, uint64_t tick, double dt,
                  const glm::dvec3& cameraPosition);

}  // namespace cleave::components
