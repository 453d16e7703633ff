// SPDX-License-Identifier: MIT
// A headless simulation for the component tests: a World, a PhysicsWorld and a SplitSystem without
// renderer (a components::Simulation), stepped tick by tick in the App's phase order
// (engine/app/phase.h): Gameplay (scene splitters) -> Triggers (gather the last step's touches) ->
// Split (activations, budgeted prepares) -> Commit (due jobs) -> PhysicsStep -> PhysicsSync
// (transforms, debris) -> Animation.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "cleave/components/scene_components.h"
#include "cleave/components/scene_loader.h"
#include "cleave/components/simulation.h"
#include "cleave/components/skinned.h"
#include "cleave/components/split_system.h"
#include "cleave/ecs/hierarchy.h"
#include "cleave/ecs/world.h"
#include "cleave/physics/physics_world.h"

namespace cleave::components::testing {

inline constexpr double kDt = 1.0 / 60.0;

inline std::string scenePath(const std::string& name) {
  return std::string(CLEAVE_SOURCE_DIR) + "/assets/scenes/" + name;
}

struct Sim {
  ecs::World world;
  Simulation simulation{world};
  physics::PhysicsWorld& physics = simulation.physics();
  SplitSystem& splits = simulation.splits();
  SceneRunner runner;
  SceneLoadResult scene;
  uint64_t tick = 0;
  glm::dvec3 camera{0.0, 2.0, 6.0};

  SplitWorld sw() { return SplitWorld{world, physics, nullptr}; }

  bool load(const std::string& path, MaterialResolver materials = {}) {
    SceneContext ctx{world, physics, nullptr, &splits, std::move(materials)};
    scene = loadScene(path, ctx);
    runner = SceneRunner(scene.splitters);
    camera = glm::dvec3(scene.cameraPosition);
    return scene.ok();
  }

  // Queues a cut of `target` by the world plane {x : dot(normal, x) = offset}, requested this tick.
  void requestCut(ecs::Entity target, const glm::dvec3& normal, double offset) {
    SplitRequest r;
    r.target = target;
    r.planeNormal = normal;
    r.planeOffset = offset;
    r.requestedTick = tick;
    splits.request(r);
  }

  // One tick. `afterSplit` runs between the Split and the PhysicsStep phases (the state right after
  // the pieces appeared); `afterStep` after the physics step, before the sync.
  void step(const std::function<void()>& afterSplit = {}, const std::function<void()>& afterStep = {}) {
    SplitWorld w = sw();
    runner.update(w, tick, kDt);
    simulation.gather(tick);
    simulation.prepare(tick, camera);
    simulation.commit(tick);
    if (afterSplit) afterSplit();
    simulation.stepPhysics(kDt);
    if (afterStep) afterStep();
    simulation.sync(kDt);
    simulation.animate(kDt);
    ++tick;
  }

  // Runs until `tick` == until (exclusive), collecting every split event.
  std::vector<SplitEvent> runUntil(uint64_t until) {
    std::vector<SplitEvent> events;
    while (tick < until) {
      step();
      for (const SplitEvent& ev : splits.lastEvents()) events.push_back(ev);
    }
    return events;
  }

  // Entities with a dynamic body.
  std::vector<ecs::Entity> dynamicBodies() {
    std::vector<ecs::Entity> out;
    for (ecs::Entity e : world.entities()) {
      const auto* rb = world.tryGet<RigidBody>(e);
      if (!rb) continue;
      const auto m = physics.bodyMass(rb->body);
      if (m && *m > 0.f) out.push_back(e);
    }
    return out;
  }
};

// An entity named `name` drawing `mesh` (an outside and a cap material), with `splitable` and a
// dynamic body of `density` at `position` (its collider parts kept in the split system's cache).
inline ecs::Entity addSplitableBody(Sim& sim, const std::string& name, const geometry::MeshData& mesh,
                                    const Splitable& splitable, double density, const glm::vec3& position) {
  const ecs::Entity e = sim.world.create();
  ecs::Transform t;
  t.position = position;
  sim.world.add<ecs::Transform>(e, t);
  sim.world.add<ecs::WorldTransform>(e, ecs::WorldTransform{ecs::localMatrix(t)});
  sim.world.add<ecs::Name>(e, ecs::Name{name});
  MeshRenderer mr;
  mr.source = std::make_shared<geometry::MeshData>(mesh);
  mr.materials = {render::Material{}, render::Material{}};
  sim.world.add<MeshRenderer>(e, mr);
  sim.world.add<Splitable>(e, splitable);
  SplitWorld sw = sim.sw();
  EXPECT_EQ(makeDynamicBody(sw, e, density, ColliderMode::Auto, &sim.splits).message, "");
  return e;
}

// Total mass, linear momentum, centre of mass and angular momentum about it, in double precision
// from the bodies the solver integrates: L = sum R diag(I) R^T w + m (x - c) x v.
struct Momenta {
  double mass = 0.0;
  glm::dvec3 linear{0.0};
  glm::dvec3 centre{0.0};
  glm::dvec3 angular{0.0};
  size_t bodies = 0;
};

inline Momenta momentaOf(Sim& sim) {
  Momenta m;
  struct B {
    double mass;
    glm::dvec3 x, v, w, inertia;
    glm::dquat q;
  };
  std::vector<B> bodies;
  for (ecs::Entity e : sim.dynamicBodies()) {
    const auto& rb = sim.world.get<RigidBody>(e);
    const auto state = sim.physics.bodyState(rb.body);
    const auto inertia = sim.physics.bodyLocalInertia(rb.body);
    if (!state || !inertia) continue;
    bodies.push_back(B{double(state->mass), glm::dvec3(state->transform.position), glm::dvec3(state->linearVelocity),
                       glm::dvec3(state->angularVelocity), glm::dvec3(*inertia),
                       glm::dquat(state->transform.rotation)});
  }
  for (const B& b : bodies) {
    m.mass += b.mass;
    m.linear += b.mass * b.v;
    m.centre += b.mass * b.x;
  }
  if (m.mass > 0.0) m.centre /= m.mass;
  for (const B& b : bodies) {
    const glm::dmat3 r = glm::mat3_cast(b.q);
    glm::dmat3 diag(0.0);
    diag[0][0] = b.inertia.x;
    diag[1][1] = b.inertia.y;
    diag[2][2] = b.inertia.z;
    const glm::dmat3 world = r * diag * glm::transpose(r);
    m.angular += world * b.w + b.mass * glm::cross(b.x - m.centre, b.v);
  }
  m.bodies = bodies.size();
  return m;
}

inline double relativeError(double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-300); }
inline double relativeError(const glm::dvec3& a, const glm::dvec3& b) {
  return glm::length(a - b) / std::max(glm::length(b), 1e-300);
}

// What a target whose split is in flight holds before a change made to it by gameplay, and the
// check that the commit then refused: one event naming `reason`, no piece made, the target alive
// with the same body and mass, the world's entity count unchanged.
struct InFlightTarget {
  ecs::Entity target;
  physics::BodyId body;
  double mass = 0.0;
  size_t entities = 0;
};

inline InFlightTarget inFlightTarget(Sim& sim, ecs::Entity target) {
  return {target, sim.world.get<RigidBody>(target).body, sim.world.get<MassInfo>(target).mass,
          sim.world.entities().size()};
}

inline void expectRefusedAtCommit(Sim& sim, const InFlightTarget& before, const std::vector<SplitEvent>& events,
                                  const std::string& reason) {
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].status, geometry::SplitStatus::InvalidInput);
  EXPECT_NE(events[0].message.find(reason), std::string::npos) << events[0].message;
  EXPECT_TRUE(events[0].pieces.empty());
  EXPECT_EQ(sim.splits.totalPiecesCreated(), 0u);
  ASSERT_TRUE(sim.world.alive(before.target));
  EXPECT_EQ(sim.world.entities().size(), before.entities);
  EXPECT_EQ(sim.world.get<RigidBody>(before.target).body, before.body);
  EXPECT_DOUBLE_EQ(sim.world.get<MassInfo>(before.target).mass, before.mass);
}

}  // namespace cleave::components::testing
