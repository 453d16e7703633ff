// SPDX-License-Identifier: MIT
// The scene of the engine examples: a headless App with splitting installed, a floor, one wooden
// crate (a splittable rigid body) and a one-tick splitter (a thin blade) through the crate at a
// tick of the run. Each example adds what it shows on top.
#pragma once

#include <cstdio>
#include <functional>
#include <memory>
#include <string>

#include <cleave/components/scene_components.h>
#include <cleave/components/simulation.h>
#include <cleave/components/split_system.h>
#include <cleave/components/splitable_object.h>
#include <cleave/app/app.h>
#include <cleave/ecs/hierarchy.h>
#include <cleave/geometry/primitives.h>

namespace examples {

using namespace cleave;

struct CrateScene {
  app::App app;
  std::unique_ptr<components::Simulation> sim;
  ecs::Entity crate;

  using Committed = std::function<void(app::TickContext&, const std::vector<components::SplitEvent>&)>;

  // Starts a headless App for `ticks` ticks, `committed` called after each tick's commit; false
  // with a reason printed when it cannot.
  bool start(int ticks, Committed committed) {
    components::SplittingHooks hooks;
    hooks.committed = std::move(committed);
    app::AppOptions options;
    options.headless = true;
    options.ticks = ticks;
    if (const base::Status started = app.init(options, "example"); !started.ok()) return fail(started.message);
    sim = std::make_unique<components::Simulation>(app.world(), components::SplitBudgetSettings{}, &app.renderer());
    components::installSplitting(app, *sim, std::move(hooks));
    return addFloor() && addCrate();
  }

  // A one-tick splitter: a 2 m x 2 m blade whose plane is its local +Y axis, through the crate.
  void addBladeAt(uint64_t tick, const glm::vec3& position, const glm::quat& rotation) {
    app.addSystem(app::Phase::Gameplay, "example.blade", [this, tick, position, rotation](app::TickContext& c) {
      if (c.tick != tick) return;
      components::Splitter blade;
      blade.lifetime = components::SplitterLifetime::OneTick;
      components::SplitWorld sw = sim->splitWorld();
      components::createSplitter(sw, "blade", physics::ShapeDef::box(blade.halfExtents), position, rotation, blade);
    });
  }

  static bool fail(const std::string& why) {
    std::fprintf(stderr, "example: %s\n", why.c_str());
    return false;
  }

 private:
  bool addFloor() {
    auto shape = sim->physics().createShape(physics::ShapeDef::box(glm::vec3(10.f, 0.5f, 10.f)));
    if (!shape.ok()) return fail(shape.message());
    physics::BodyDef def;
    def.shape = shape.value();
    def.position = glm::vec3(0.f, -0.5f, 0.f);  // its top at y = 0
    return sim->physics().createBody(def).ok() || fail("no floor body");
  }

  // A 1 m wooden crate (600 kg/m^3) resting on the floor, centre at y = 0.5.
  bool addCrate() {
    components::SplitableObject object;
    object.name = "crate";
    object.transform.position = glm::vec3(0.f, 0.5f, 0.f);
    object.mesh = std::make_shared<geometry::MeshData>(geometry::primitives::box(glm::vec3(0.5f)));
    object.materials = {render::Material{}, render::Material{}};  // outside, cap
    object.splitable.density = 600.0;
    object.splitable.capMaterialId = 1;
    components::SplitWorld sw = sim->splitWorld();
    crate = components::createSplitableObject(sw, object);
    const base::Status made =
        components::makeDynamicBody(sw, crate, object.splitable.density, object.splitable.collider, &sim->splits());
    if (!made.ok()) return fail(made.message);
    return true;
  }
};

}  // namespace examples
