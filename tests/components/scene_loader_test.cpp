// SPDX-License-Identifier: MIT
#include "cleave/components/scene_loader.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include <gtest/gtest.h>

#include "cleave/assets/mesh_io.h"
#include "cleave/geometry/mass_properties.h"
#include "cleave/geometry/primitives.h"
#include "tests/components/sim_harness.h"

namespace cleave::components {
namespace {

using testing::kDt;
using testing::scenePath;
using testing::Sim;

std::filesystem::path tempDir() {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "cleave_scene_loader";
  std::filesystem::create_directories(dir / "models");
  return dir;
}

std::string write(const std::string& name, const std::string& text) {
  const std::filesystem::path p = tempDir() / name;
  std::ofstream(p) << text;
  return p.string();
}

TEST(SceneLoader, LoadsTheSpinningSphereScene) {
  Sim sim;
  ASSERT_TRUE(sim.load(scenePath("spinning_sphere.json"))) << sim.scene.message;
  const SceneLoadResult& s = sim.scene;
  ASSERT_EQ(s.entities.size(), 1u);
  EXPECT_EQ(s.entities[0].name, "sphere");
  EXPECT_EQ(s.entities[0].material, "metal");
  EXPECT_TRUE(s.entities[0].dynamic);
  EXPECT_TRUE(s.entities[0].splitable);
  EXPECT_TRUE(s.floor.isNull());
  EXPECT_EQ(sim.physics.gravity(), glm::vec3(0.f));
  EXPECT_EQ(s.ticks, 120u);
  ASSERT_EQ(s.splitters.size(), 1u);
  EXPECT_EQ(s.splitters[0].schedule, SplitterSchedule::OneTick);
  EXPECT_EQ(s.splitters[0].fireTick, 10u);
  EXPECT_TRUE(s.splitters[0].entity.isNull());  // created when its tick comes
  const ecs::Entity e = s.find("sphere");
  const auto state = sim.physics.bodyState(sim.world.get<RigidBody>(e).body);
  ASSERT_TRUE(state);
  EXPECT_EQ(state->linearVelocity, glm::vec3(2.f, 0.5f, -1.f));
  EXPECT_EQ(state->angularVelocity, glm::vec3(1.5f, 4.f, -2.f));
  const auto props = geometry::computeMassProperties(geometry::primitives::uvSphere(0.5f, 32, 16));
  EXPECT_NEAR(sim.world.get<MassInfo>(e).mass, 1000.0 * props.volume, 1e-9);
  const Splitable& sp = sim.world.get<Splitable>(e);
  EXPECT_TRUE(sp.convexHint);
  EXPECT_EQ(sp.density, 1000.0);
}

TEST(SceneLoader, AllExampleScenesLoad) {
  for (const char* name : {"spinning_sphere.json", "torus_cut.json", "u_shape.json", "fifty_cubes.json"}) {
    Sim sim;
    EXPECT_TRUE(sim.load(scenePath(name))) << sim.scene.message;
  }
}

TEST(SceneLoader, ReadsEveryKindOfField) {
  geometry::MeshData cube = geometry::primitives::box(glm::vec3(0.5f));
  ASSERT_TRUE(assets::writeObj((tempDir() / "models" / "cube.obj").string(), cube, {}).ok());
  const std::string path = write("rich.json", R"({
  // comments are allowed
  "version": 1,
  "gravity": [0, -5, 0],
  "floor": { "height": 1.0, "material": "stone floor" },
  "budget": { "milliseconds_per_tick": 3.5, "max_splits_per_tick": 4, "deterministic": false },
  "camera": { "position": [1, 2, 3], "target": [0, 1, 0] },
  "entities": [
    { "name": "statue", "material": "stone",
      "mesh": { "primitive": "box", "half_extents": [0.5, 0.5, 0.5] },
      "transform": { "position": [0, 3, 0] },
      "body": { "mass": 12 },
      "splitable": { "cap_material": "gold", "split_impulse": 0.5, "mass_mode": "keep_parent_mass",
                     "small_pieces": "remove", "min_piece_volume": 0.001, "cap_uv": "normalized_bounds",
                     "cap_atlas_rect": [0.5, 0, 0.5, 1], "max_depth": 3, "separate_islands": false },
      "children": [
        { "name": "crown", "material": "gold", "mesh": { "primitive": "sphere", "radius": 0.3 },
          "transform": { "position": [0, 0.7, 0] } }
      ] },
    { "name": "plank", "mesh": { "primitive": "box", "half_extents": [1, 0.1, 0.2] },
      "transform": { "position": [3, 1.1, 0], "rotation": { "euler_degrees": [0, 90, 0] } },
      "body": { "type": "static" } },
    { "name": "stretched", "mesh": { "primitive": "box", "half_extents": [0.5, 0.5, 0.5] },
      "transform": { "position": [-3, 2, 0], "scale": [2, 1, 0.5],
                     "rotation": { "quaternion": [1, 0, 0, 0] } },
      "body": { "density": 100, "linear_velocity": [0, 0, 1] } },
    { "name": "model", "mesh": { "file": "models/cube.obj" }, "transform": { "position": [5, 2, 0] },
      "body": { "density": 10 } },
    { "name": "shelf", "transform": { "position": [0, 1, -3] },
      "children": [ { "name": "book", "mesh": { "primitive": "box" }, "transform": { "position": [0.5, 0.2, 0] } } ] }
  ],
  "splitters": [
    { "name": "wall", "lifetime": "persistent", "half_extents": [2, 0.05, 2], "transform": { "position": [0, 5, 0] } },
    { "name": "mover", "lifetime": "persistent", "start_tick": 5, "end_tick": 9, "velocity": [6, 0, 0],
      "transform": { "position": [0, 6, 0] }, "player_caused": true },
    { "name": "swing", "fire_tick": 20 }
  ]
})");
  std::vector<std::pair<std::string, bool>> asked;
  Sim sim;
  ASSERT_TRUE(sim.load(path, [&](const std::string& name, bool cap) {
    asked.push_back({name, cap});
    render::Material m;
    m.specular = cap ? 2.f : 1.f;
    return m;
  })) << sim.scene.message;
  const SceneLoadResult& s = sim.scene;
  EXPECT_EQ(sim.physics.gravity(), glm::vec3(0.f, -5.f, 0.f));
  EXPECT_DOUBLE_EQ(sim.splits.budget().settings().millisecondsPerTick, 3.5);
  EXPECT_EQ(sim.splits.budget().settings().maxSplitsPerTick, 4u);
  EXPECT_FALSE(sim.splits.budget().settings().deterministic);
  EXPECT_EQ(s.cameraPosition, glm::vec3(1, 2, 3));
  ASSERT_FALSE(s.floor.isNull());
  EXPECT_FLOAT_EQ(sim.physics.bodyTransform(sim.world.get<RigidBody>(s.floor).body)->position.y, 0.5f);

  // The statue: the crown merged in (one body), its mass as given, its own and the cap material.
  const ecs::Entity statue = s.find("statue");
  ASSERT_TRUE(sim.world.alive(statue));
  EXPECT_TRUE(s.find("crown").isNull());
  EXPECT_NEAR(sim.world.get<MassInfo>(statue).mass, 12.0, 1e-9);
  EXPECT_NEAR(*sim.physics.bodyMass(sim.world.get<RigidBody>(statue).body), 12.f, 1e-5f);
  const MeshRenderer& mr = sim.world.get<MeshRenderer>(statue);
  ASSERT_EQ(mr.materials.size(), 3u);  // stone, gold, cap
  EXPECT_EQ(mr.materials[2].specular, 2.f);
  const Splitable& sp = sim.world.get<Splitable>(statue);
  EXPECT_EQ(sp.capMaterialId, 2u);
  EXPECT_EQ(sp.massMode, MassMode::KeepParentMass);
  EXPECT_EQ(sp.smallPieces, SmallPieceMode::Remove);
  EXPECT_EQ(sp.capUvMode, geometry::CapUvMode::NormalizedBounds);
  EXPECT_EQ(sp.capAtlasRect, glm::vec4(0.5f, 0.f, 0.5f, 1.f));
  EXPECT_EQ(sp.maxDepth, 3u);
  EXPECT_FALSE(sp.separateIslands);
  EXPECT_DOUBLE_EQ(sp.splitImpulse, 0.5);
  const std::set<std::pair<std::string, bool>> askedSet(asked.begin(), asked.end());
  EXPECT_TRUE(askedSet.count({"stone", false}));
  EXPECT_TRUE(askedSet.count({"gold", false}));
  EXPECT_TRUE(askedSet.count({"gold", true}));
  EXPECT_TRUE(askedSet.count({"stone floor", false}));

  // Static plank turned 90 degrees about y.
  const ecs::Entity plank = s.find("plank");
  const auto* plankBody = sim.world.tryGet<RigidBody>(plank);
  ASSERT_NE(plankBody, nullptr);
  EXPECT_EQ(*sim.physics.bodyMass(plankBody->body), 0.f);
  const glm::quat expected = glm::angleAxis(glm::radians(90.f), glm::vec3(0, 1, 0));
  EXPECT_NEAR(std::abs(glm::dot(sim.physics.bodyTransform(plankBody->body)->rotation, expected)), 1.f, 1e-6f);

  // Non-uniform scale: a 2 x 1 x 0.5 box of density 100.
  const ecs::Entity stretched = s.find("stretched");
  EXPECT_NEAR(sim.world.get<MassInfo>(stretched).mass, 100.0, 1e-6);
  EXPECT_EQ(*sim.physics.linearVelocity(sim.world.get<RigidBody>(stretched).body), glm::vec3(0, 0, 1));

  // A model file, resolved next to the scene.
  const ecs::Entity model = s.find("model");
  EXPECT_EQ(sim.world.get<MeshRenderer>(model).source->positions.size(), cube.positions.size());
  EXPECT_NEAR(sim.world.get<MassInfo>(model).mass, 10.0, 1e-6);

  // A group: the book follows the shelf.
  const ecs::Entity shelf = s.find("shelf"), book = s.find("book");
  EXPECT_EQ(ecs::parentOf(sim.world, book), shelf);
  EXPECT_EQ(glm::vec3(sim.world.get<ecs::WorldTransform>(book).matrix[3]), glm::vec3(0.5f, 1.2f, -3.f));

  // Splitters: the first exists now, the second from tick 5 to 8, moving.
  ASSERT_EQ(s.splitters.size(), 3u);
  EXPECT_TRUE(sim.world.alive(s.splitters[0].entity));
  EXPECT_EQ(sim.world.get<Splitter>(s.splitters[0].entity).lifetime, SplitterLifetime::Persistent);
  EXPECT_TRUE(s.splitters[1].entity.isNull());
  EXPECT_EQ(s.splitters[2].schedule, SplitterSchedule::OneTick);
  EXPECT_EQ(s.splitters[2].fireTick, 20u);
  SplitWorld w = sim.sw();
  for (uint64_t t = 0; t <= 7; ++t) sim.runner.update(w, t, kDt);
  const ecs::Entity mover = sim.runner.splitters()[1].entity;
  ASSERT_TRUE(sim.world.alive(mover));
  EXPECT_TRUE(sim.world.get<Splitter>(mover).playerCaused);
  const auto trigger = sim.physics.triggerTransform(sim.world.get<Splitter>(mover).trigger);
  ASSERT_TRUE(trigger);
  EXPECT_NEAR(trigger->position.x, 6.f * 2.f * float(kDt), 1e-6f);
  EXPECT_NEAR(sim.world.get<ecs::Transform>(mover).position.x, 6.f * 2.f * float(kDt), 1e-6f);
  sim.runner.update(w, 8, kDt);
  sim.runner.update(w, 9, kDt);
  EXPECT_FALSE(sim.world.alive(mover));
}

// A bad scene creates nothing and says where the problem is.
struct BadCase {
  SceneLoadResult result;
  size_t entitiesLeft = 0;
  uint32_t bodiesLeft = 0;
};

BadCase loadBad(const std::string& name, const std::string& text) {
  const std::string path = write(name, text);
  ecs::World world;
  physics::PhysicsWorld physics;
  ResourceHooks hooks(world, physics, nullptr);  // the rollback frees what it made through them
  SceneContext ctx{world, physics, nullptr, nullptr, {}};
  BadCase c;
  c.result = loadScene(path, ctx);
  c.entitiesLeft = world.size();
  c.bodiesLeft = physics.bodyCount();
  return c;
}

// The bundled shatter scene: a stone block broken into cells by a shatter splitter, its mass kept.
TEST(SceneLoader, ShatterSplitterBreaksTheBlockIntoCells) {
  Sim sim;
  ASSERT_TRUE(sim.load(scenePath("shatter_block.json"))) << sim.scene.message;
  ASSERT_EQ(sim.scene.splitters.size(), 1u);
  EXPECT_EQ(sim.scene.splitters[0].kind, SplitterKind::Shatter);
  EXPECT_EQ(sim.scene.splitters[0].shatter.cells, 16u);
  EXPECT_DOUBLE_EQ(sim.scene.splitters[0].shatter.outwardImpulse, 1.5);
  const std::vector<SplitEvent> events = sim.runUntil(40);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].status, geometry::SplitStatus::Ok) << events[0].message;
  EXPECT_GE(events[0].pieces.size(), 10u);
  EXPECT_NEAR(events[0].piecesMass, events[0].parentMass, 1e-6 * events[0].parentMass);
  EXPECT_NEAR(events[0].parentMass, 2400.0, 1e-6 * 2400.0);
}

TEST(SceneLoaderErrors, SyntaxErrorNamesFileLineAndField) {
  const BadCase c = loadBad("bad_syntax.json",
                            "{\n"
                            "  \"version\": 1,\n"
                            "  \"gravity\": [0, -9.81, 0]\n"
                            "  \"entities\": []\n"
                            "}\n");
  ASSERT_FALSE(c.result.ok());
  EXPECT_NE(c.result.message.find("bad_syntax.json:4:"), std::string::npos) << c.result.message;
  EXPECT_NE(c.result.message.find("gravity"), std::string::npos) << c.result.message;
  EXPECT_NE(c.result.message.find("syntax error"), std::string::npos) << c.result.message;
  EXPECT_EQ(c.result.errorLine, 4);
  EXPECT_EQ(c.entitiesLeft, 0u);
}

TEST(SceneLoaderErrors, WrongTypeNamesFileLineAndField) {
  const BadCase c = loadBad("bad_type.json", R"({
  "floor": true,
  "entities": [
    { "name": "ball",
      "mesh": { "primitive": "sphere",
                "radius": "big" },
      "body": { "density": 100 } }
  ]
})");
  ASSERT_FALSE(c.result.ok());
  EXPECT_EQ(c.result.message,
            c.result.errorFile + ":6: /entities/0/mesh/radius: expected a number, found a string");
  EXPECT_NE(c.result.message.find("bad_type.json"), std::string::npos);
  EXPECT_EQ(c.entitiesLeft, 0u);
  EXPECT_EQ(c.bodiesLeft, 0u);
}

TEST(SceneLoaderErrors, UnknownPrimitiveNamesFileLineAndField) {
  const BadCase c = loadBad("bad_primitive.json", R"({
  "entities": [
    { "name": "a", "mesh": { "primitive": "box" }, "body": {} },
    { "name": "b",
      "mesh": {
        "primitive": "cub"
      },
      "body": {} }
  ]
})");
  ASSERT_FALSE(c.result.ok());
  EXPECT_NE(c.result.message.find("bad_primitive.json:6: /entities/1/mesh/primitive: unknown primitive 'cub'"),
            std::string::npos)
      << c.result.message;
  EXPECT_EQ(c.entitiesLeft, 0u);  // the good object before it was not created either
  EXPECT_EQ(c.bodiesLeft, 0u);
}

// Each primitive with every field left out is the geometry primitive with the loader's defaults:
// its mass at the default density is 1000 kg/m^3 times that mesh's volume.
TEST(SceneLoader, EveryPrimitiveUsesItsDefaults) {
  namespace P = geometry::primitives;
  const std::pair<const char*, geometry::MeshData> cases[] = {
      {"box", P::box(glm::vec3(0.5f))},
      {"sphere", P::uvSphere(0.5f, 32, 16)},
      {"ellipsoid", P::ellipsoid(glm::vec3(0.5f, 0.35f, 0.35f), 32, 16)},
      {"cylinder", P::cylinder(0.4f, 1.f, 32)},
      {"torus", P::torus(0.5f, 0.2f, 48, 24)},
      {"capsule", P::capsule(0.3f, 0.6f, 24, 12)},
      {"comb", P::combPrism(2, 0.2f, 0.6f, 0.2f, 0.3f)},
      {"star", P::starPrism(5, 1.f, 0.4f, 0.5f)},
      {"tetrahedron", P::tetrahedron(0.5f)},
      {"hollow_sphere", P::hollowSphere(0.5f, 0.4f, 32, 16)},
  };
  for (const auto& [name, mesh] : cases) {
    SCOPED_TRACE(name);
    Sim sim;
    const std::string path =
        write(std::string("default_") + name + ".json",
              std::string(R"({"entities": [{"name": "p", "mesh": {"primitive": ")") + name +
                  R"("}, "body": {}}]})");
    ASSERT_TRUE(sim.load(path)) << sim.scene.message;
    const double volume = geometry::computeMassProperties(mesh).volume;
    ASSERT_GT(volume, 0.0);
    EXPECT_NEAR(sim.world.get<MassInfo>(sim.scene.find("p")).mass, 1000.0 * volume, 1e-9 * volume);
  }
}

TEST(SceneLoaderErrors, PrimitiveFieldsAreCheckedInOrder) {
  struct Case {
    const char* mesh;
    const char* error;  // after "<file>:3: "
  };
  const Case cases[] = {
      {R"({"primitive": "torus", "major_radius": 0.2, "minor_radius": 0.3})",
       "/entities/0/mesh/minor_radius: minor_radius must be below major_radius"},
      {R"({"primitive": "star", "inner_radius": 2})",
       "/entities/0/mesh/inner_radius: inner_radius must be below outer_radius"},
      {R"({"primitive": "hollow_sphere", "outer_radius": 0.3})",
       "/entities/0/mesh/inner_radius: inner_radius must be below outer_radius"},
      {R"({"primitive": "torus", "radius": 1})",
       "/entities/0/mesh/radius: unknown field 'radius' (expected one of: primitive, major_radius, "
       "minor_radius, segments, sides)"},
      {R"({"primitive": "sphere", "segments": 2, "radius": -1})",
       "/entities/0/mesh/radius: expected a number > 0, found -1"},
      {R"({"primitive": "sphere", "rings": 1})",
       "/entities/0/mesh/rings: expected a whole number in [2, 1024], found 1"},
      {R"({"primitive": "comb", "teeth": 257})",
       "/entities/0/mesh/teeth: expected a whole number in [1, 256], found 257"},
      {R"({"primitive": "box", "half_extents": [1, 0, 1]})",
       "/entities/0/mesh/half_extents: expected three numbers > 0"},
      {R"({"primitive": "cube"})",
       "/entities/0/mesh/primitive: unknown primitive 'cube' (expected one of: box, sphere, "
       "ellipsoid, "
       "cylinder, torus, capsule, comb, star, tetrahedron, hollow_sphere)"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.mesh);
    const BadCase bad =
        loadBad("bad_primitive_field.json",
                std::string("{\n  \"entities\": [\n    {\"name\": \"p\", \"mesh\": ") + c.mesh +
                    "}\n  ]\n}");
    ASSERT_FALSE(bad.result.ok());
    EXPECT_EQ(bad.result.message, bad.result.errorFile + ":3: " + c.error);
    EXPECT_EQ(bad.entitiesLeft, 0u);
  }
}

TEST(SceneLoaderErrors, MissingModelFileNamesFileLineAndField) {
  const BadCase c = loadBad("bad_model.json", R"({
  "entities": [
    { "name": "ghost",
      "mesh": { "file": "models/missing.obj" },
      "body": { "density": 100 } }
  ]
})");
  ASSERT_FALSE(c.result.ok());
  EXPECT_NE(c.result.message.find("bad_model.json:4: /entities/0/mesh/file: cannot load the model"),
            std::string::npos)
      << c.result.message;
  EXPECT_NE(c.result.message.find("missing.obj"), std::string::npos) << c.result.message;
  EXPECT_EQ(c.result.errorField, "/entities/0/mesh/file");
  EXPECT_EQ(c.result.errorLine, 4);
}

TEST(SceneLoaderErrors, MissingSceneFileNamesTheFile) {
  ecs::World world;
  physics::PhysicsWorld physics;
  SceneContext ctx{world, physics, nullptr, nullptr, {}};
  const std::string path = (tempDir() / "no_such_scene.json").string();
  const SceneLoadResult r = loadScene(path, ctx);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.message.find(path), std::string::npos) << r.message;
}

TEST(SceneLoaderErrors, UnknownFieldIsReportedWithTheFieldsThatExist) {
  const BadCase c = loadBad("bad_field.json", R"({
  "entities": [
    { "name": "typo", "mesh": { "primitive": "box" },
      "transform": { "positon": [0, 1, 0] } }
  ]
})");
  ASSERT_FALSE(c.result.ok());
  EXPECT_NE(c.result.message.find(":4: /entities/0/transform/positon: unknown field 'positon'"), std::string::npos)
      << c.result.message;
  EXPECT_NE(c.result.message.find("position"), std::string::npos);
}

TEST(SceneLoaderErrors, FailureWhileCreatingRemovesWhatWasCreated) {
  // A single triangle: a model without volume gets no body.
  std::ofstream(tempDir() / "models" / "flat.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const BadCase c = loadBad("bad_volume.json", R"({
  "floor": true,
  "entities": [
    { "name": "fine", "mesh": { "primitive": "box" }, "body": {} },
    { "name": "flat", "mesh": { "file": "models/flat.obj" },
      "body": {} }
  ],
  "splitters": [ { "lifetime": "persistent" } ]
})");
  ASSERT_FALSE(c.result.ok());
  EXPECT_NE(c.result.message.find("bad_volume.json:5: /entities/1: flat:"), std::string::npos) << c.result.message;
  EXPECT_EQ(c.entitiesLeft, 0u);
  EXPECT_EQ(c.bodiesLeft, 0u);
}

TEST(SceneLoaderErrors, SemanticChecks) {
  struct Case {
    const char* text;
    const char* expected;
  };
  const Case cases[] = {
      {R"({"entities": [{"mesh": {"primitive": "box"}, "splitable": true}]})", "/entities/0/splitable: a splitable object needs a 'body'"},
      {R"({"entities": [{"mesh": {"primitive": "box"}, "body": {"mass": 1, "density": 2}}]})", "/entities/0/body/mass: give 'density' or 'mass'"},
      {R"({"entities": [{"mesh": {"primitive": "torus", "major_radius": 0.1, "minor_radius": 0.2}}]})", "/entities/0/mesh/minor_radius"},
      {R"({"splitters": [{"lifetime": "one_tick"}]})", "/splitters/0: a one-tick splitter needs 'fire_tick'"},
      {R"({"splitters": [{"lifetime": "sometimes", "fire_tick": 1}]})", "/splitters/0/lifetime: unknown value 'sometimes'"},
      {R"({"gravity": [0, 1]})", "/gravity: expected an array of 3 numbers"},
      {R"({"splitters": [{"fire_tick": 1, "cells": 8}]})", "/splitters/0/cells: only a shatter splitter has 'cells'"},
      {R"({"splitters": [{"kind": "shatter", "fire_tick": 1, "cells": 0}]})", "/splitters/0/cells"},
      {R"({"splitters": [{"kind": "smash", "fire_tick": 1}]})", "/splitters/0/kind: unknown value 'smash'"},
      {R"({"entities": [{"transform": {"rotation": {"quaternion": [0, 0, 0, 0]}}}]})", "quaternion has zero length"},
      {R"({"budget": {"max_splits_per_tick": -1}})", "/budget/max_splits_per_tick"},
      {R"([1, 2])", ": /: expected an object"},
  };
  for (const Case& c : cases) {
    const BadCase r = loadBad("semantic.json", c.text);
    EXPECT_FALSE(r.result.ok()) << c.text;
    EXPECT_NE(r.result.message.find(c.expected), std::string::npos) << r.result.message;
    EXPECT_NE(r.result.message.find("semantic.json:1:"), std::string::npos) << r.result.message;
  }
}

}  // namespace
}  // namespace cleave::components
