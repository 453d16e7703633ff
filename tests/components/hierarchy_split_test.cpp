// SPDX-License-Identifier: MIT
// One Splitable on a parent cuts the meshes of its children together and copies the hierarchy to
// each side: a box body with a sphere "head" and a rotated, offset box "arm" as child entities.
#include <gtest/gtest.h>

#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "cleave/components/scene_components.h"
#include "cleave/components/splitable.h"
#include "cleave/components/split_system.h"
#include "cleave/ecs/hierarchy.h"
#include "cleave/geometry/mass_properties.h"
#include "cleave/geometry/primitives.h"
#include "tests/components/sim_harness.h"

namespace cleave::components::testing {
namespace {

struct Figure {
  ecs::Entity root, head, arm;
  double volume = 0.0;  // of the three meshes in the world
};

// Volume enclosed by the meshes drawn by an entity and its children, merged in world space (a
// piece's caps live in the parent's mesh and close the children's open cut edges).
double drawnVolume(ecs::World& world, ecs::Entity e) {
  ecs::updateWorldTransforms(world);
  geometry::MeshData drawn;
  std::vector<ecs::Entity> stack{e};
  while (!stack.empty()) {
    const ecs::Entity x = stack.back();
    stack.pop_back();
    const auto* mr = world.tryGet<MeshRenderer>(x);
    const auto* wt = world.tryGet<ecs::WorldTransform>(x);
    if (mr && mr->source && wt) {
      geometry::MeshData part = *mr->source;
      geometry::primitives::transform(part, wt->matrix * mr->meshOffset);
      drawn = drawn.positions.empty() ? std::move(part) : geometry::primitives::merge(drawn, part);
    }
    if (const auto* children = world.tryGet<ecs::Children>(x))
      for (ecs::Entity c : children->entities)
        if (world.alive(c)) stack.push_back(c);
  }
  const geometry::MassProperties props = geometry::computeMassProperties(drawn);
  EXPECT_TRUE(props.closed) << "the drawn surface of a piece must be closed";
  return props.volume;
}

Figure makeFigure(Sim& sim) {
  ecs::World& world = sim.world;
  Figure f;
  auto addMesh = [&](ecs::Entity e, geometry::MeshData mesh, const char* name, const ecs::Transform& t) {
    world.add<ecs::Name>(e, ecs::Name{name});
    world.add<ecs::Transform>(e, t);
    MeshRenderer mr;
    mr.source = std::make_shared<geometry::MeshData>(std::move(mesh));
    mr.materials = {render::Material{}};
    world.add<MeshRenderer>(e, std::move(mr));
  };
  f.root = world.create();
  ecs::Transform rootT;
  rootT.position = glm::vec3(0.f, 1.f, 0.f);
  addMesh(f.root, geometry::primitives::box(glm::vec3(0.3f, 0.4f, 0.2f)), "body", rootT);
  f.head = world.create();
  ecs::Transform headT;
  headT.position = glm::vec3(0.f, 0.6f, 0.f);
  addMesh(f.head, geometry::primitives::uvSphere(0.18f, 24, 12), "head", headT);
  f.arm = world.create();
  ecs::Transform armT;
  armT.position = glm::vec3(0.45f, 0.1f, 0.f);
  armT.rotation = glm::angleAxis(0.3f, glm::vec3(0.f, 0.f, 1.f));
  addMesh(f.arm, geometry::primitives::box(glm::vec3(0.08f, 0.35f, 0.08f)), "arm", armT);
  EXPECT_TRUE(ecs::setParent(world, f.head, f.root).ok());
  EXPECT_TRUE(ecs::setParent(world, f.arm, f.root).ok());
  f.volume = drawnVolume(world, f.root);

  Splitable sp;
  sp.density = 1000.0;
  world.add<Splitable>(f.root, sp);
  SplitWorld w = sim.sw();
  EXPECT_EQ(makeDynamicBody(w, f.root, sp.density, ColliderMode::ConvexHull).message, "");
  return f;
}

TEST(HierarchySplit, BodyOfTheWholeSubtreeKeepsChildrenInPlace) {
  Sim sim;
  const Figure f = makeFigure(sim);
  const MassInfo& info = sim.world.get<MassInfo>(f.root);
  // The body's mass covers the body, the head and the arm (disjoint meshes).
  EXPECT_NEAR(info.volume, f.volume, 1e-6 * f.volume);
  EXPECT_NEAR(info.mass, 1000.0 * f.volume, 1e-6 * info.mass);
  // Moving the entity to the centre of mass did not move anything drawn.
  EXPECT_NEAR(drawnVolume(sim.world, f.root), f.volume, 1e-6 * f.volume);
  ecs::updateWorldTransforms(sim.world);
  const glm::vec3 headCentre(sim.world.get<ecs::WorldTransform>(f.head).matrix *
                             sim.world.get<MeshRenderer>(f.head).meshOffset * glm::vec4(0.f, 0.f, 0.f, 1.f));
  EXPECT_NEAR(glm::distance(headCentre, glm::vec3(0.f, 1.6f, 0.f)), 0.f, 1e-5f);
}

// A part of the figure changes while its cut computes on a worker (gameplay swaps the head's mesh,
// or takes the arm off): the commit refuses, and the figure stays whole with its parts, body, mass and
// motion; nothing is made.
TEST(HierarchySplit, APartChangedBeforeTheCommitLeavesTheFigureWhole) {
  for (const char* change : {"head swapped", "arm removed"}) {
    SCOPED_TRACE(change);
    Sim sim;
    SplitBudgetSettings settings = sim.splits.budget().settings();
    settings.threads = 1;
    settings.commitDelayTicks = 2;
    sim.splits.budget().setSettings(settings);
    const Figure f = makeFigure(sim);
    const physics::BodyId body = sim.world.get<RigidBody>(f.root).body;
    sim.requestCut(f.root, glm::dvec3(1.0, 0.0, 0.0), 0.05);
    while (sim.splits.jobsInFlight() == 0 && sim.tick < 10) sim.step();
    ASSERT_EQ(sim.splits.jobsInFlight(), 1u);
    if (std::string(change) == "head swapped") {
      sim.world.get<MeshRenderer>(f.head).source =
          std::make_shared<geometry::MeshData>(geometry::primitives::uvSphere(0.1f, 12, 6));
    } else {
      sim.world.destroy(f.arm);
    }
    const auto before = sim.physics.bodyState(body);
    ASSERT_TRUE(before);
    const InFlightTarget held = inFlightTarget(sim, f.root);
    expectRefusedAtCommit(sim, held, sim.runUntil(sim.tick + 4), "a part of the target changed");
    EXPECT_TRUE(sim.world.alive(f.head));
    EXPECT_EQ(ecs::parentOf(sim.world, f.head), f.root);
    // Still falling as one body: the refusal changed nothing of its motion.
    const auto after = sim.physics.bodyState(body);
    ASSERT_TRUE(after);
    EXPECT_LT(after->transform.position.y, before->transform.position.y);
  }
}

TEST(HierarchySplit, ParentAndChildrenAreCutTogetherAndCopiedToEachSide) {
  Sim sim;
  const Figure f = makeFigure(sim);
  const double mass = sim.world.get<MassInfo>(f.root).mass;
  // A vertical plane through the body, the head and the arm's root (x = 0.3 crosses the tilted arm).
  SplitRequest request;
  request.target = f.root;
  request.planeNormal = glm::dvec3(1.0, 0.0, 0.0);
  request.planeOffset = 0.05;
  SplitWorld w = sim.sw();
  const SplitEvent ev = sim.splits.splitNow(w, f.root, request, 0);
  ASSERT_EQ(ev.status, geometry::SplitStatus::Ok) << ev.message;
  ASSERT_EQ(ev.pieces.size(), 2u);
  EXPECT_NEAR(ev.piecesMass, mass, 1e-6 * mass);
  EXPECT_FALSE(sim.world.alive(f.root));
  EXPECT_FALSE(sim.world.alive(f.head));
  EXPECT_FALSE(sim.world.alive(f.arm));

  double volume = 0.0;
  int heads = 0, arms = 0;
  for (ecs::Entity piece : ev.pieces) {
    ASSERT_TRUE(sim.world.alive(piece));
    ASSERT_TRUE(sim.world.has<RigidBody>(piece));
    const auto* children = sim.world.tryGet<ecs::Children>(piece);
    ASSERT_NE(children, nullptr);
    for (ecs::Entity c : children->entities) {
      ASSERT_TRUE(sim.world.alive(c));
      EXPECT_EQ(ecs::parentOf(sim.world, c), piece);
      const std::string name = sim.world.get<ecs::Name>(c).value;
      heads += name.rfind("head/", 0) == 0;
      arms += name.rfind("arm/", 0) == 0;
      EXPECT_FALSE(sim.world.has<RigidBody>(c)) << "children ride on the piece's body";
    }
    volume += drawnVolume(sim.world, piece);
    // The piece's collider-bearing mass matches what it draws (body + its children).
    EXPECT_NEAR(sim.world.get<MassInfo>(piece).volume, drawnVolume(sim.world, piece), 1e-5 * f.volume);
  }
  EXPECT_EQ(heads, 2) << "the head is cut, one half on each side";
  EXPECT_EQ(arms, 1) << "the arm lies on one side of the plane";
  // Everything drawn after the cut is what was drawn before (the caps close each side).
  EXPECT_NEAR(volume, f.volume, 1e-5 * f.volume);

  // The pieces fall as rigid bodies with their children attached.
  sim.runUntil(120);
  for (ecs::Entity piece : ev.pieces) {
    const auto* children = sim.world.tryGet<ecs::Children>(piece);
    ASSERT_NE(children, nullptr);
    for (ecs::Entity c : children->entities) EXPECT_EQ(ecs::parentOf(sim.world, c), piece);
  }
}

// A hierarchy of more parts and higher material ids than a tag in the material id could hold (the
// parts are told apart by provenance): 80 cubes, each of its own material 100 + k, on a bar.
TEST(HierarchySplit, ManyPartsWithHighMaterialIdsAreCutAndKeepTheirMaterials) {
  Sim sim;
  ecs::World& world = sim.world;
  const ecs::Entity root = world.create();
  world.add<ecs::Transform>(root, ecs::Transform{});
  MeshRenderer bar;
  bar.source = std::make_shared<geometry::MeshData>(geometry::primitives::box(glm::vec3(0.9f, 0.05f, 0.05f)));
  bar.materials = {render::Material{}};
  world.add<MeshRenderer>(root, std::move(bar));
  constexpr uint32_t kCubes = 80;
  for (uint32_t k = 0; k < kCubes; ++k) {
    const ecs::Entity cube = world.create();
    world.add<ecs::Name>(cube, ecs::Name{"cube" + std::to_string(k)});
    ecs::Transform t;
    t.position = glm::vec3(-0.79f + 0.02f * float(k), 0.f, 0.1f);
    world.add<ecs::Transform>(cube, t);
    geometry::MeshData mesh = geometry::primitives::box(glm::vec3(0.008f));
    mesh.submeshes = {{0, uint32_t(mesh.indices.size()), 100 + k}};
    MeshRenderer mr;
    mr.source = std::make_shared<geometry::MeshData>(std::move(mesh));
    world.add<MeshRenderer>(cube, std::move(mr));
    ASSERT_TRUE(ecs::setParent(world, cube, root).ok());
  }
  const double volume = drawnVolume(world, root);
  Splitable sp;
  world.add<Splitable>(root, sp);
  SplitWorld w = sim.sw();
  ASSERT_EQ(makeDynamicBody(w, root, sp.density, ColliderMode::ConvexHull).message, "");
  SplitRequest request;
  request.target = root;
  request.planeNormal = glm::dvec3(0.0, 1.0, 0.0);
  request.planeOffset = 0.001;
  const SplitEvent ev = sim.splits.splitNow(w, root, request, 0);
  ASSERT_EQ(ev.status, geometry::SplitStatus::Ok) << ev.message;
  ASSERT_EQ(ev.pieces.size(), 2u);
  double after = 0.0;
  for (ecs::Entity piece : ev.pieces) {
    const auto* children = world.tryGet<ecs::Children>(piece);
    ASSERT_NE(children, nullptr);
    EXPECT_EQ(children->entities.size(), kCubes) << "every cube is cut: half of it on each side";
    for (ecs::Entity c : children->entities) {
      const std::string name = world.get<ecs::Name>(c).value;
      const uint32_t k = uint32_t(std::stoul(name.substr(4, name.find('/') - 4)));
      for (const geometry::SubMesh& run : world.get<MeshRenderer>(c).source->submeshes) {
        EXPECT_TRUE(run.materialId == 100 + k || run.materialId == sp.capMaterialId) << name << " " << run.materialId;
      }
    }
    after += drawnVolume(world, piece);
  }
  EXPECT_NEAR(after, volume, 1e-5 * volume);
}

}  // namespace
}  // namespace cleave::components::testing
