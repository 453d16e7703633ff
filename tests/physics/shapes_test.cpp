// SPDX-License-Identifier: MIT
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "cleave/physics/physics_world.h"
#include "tests/physics/physics_test_helpers.h"

namespace cleave::physics {
namespace {

using testing::addBody;
using testing::addGround;
using testing::boxCorners;
using testing::stepFor;

// Angle between the body's up axis and the world's: 0 when the body sits flat (any yaw).
float tilt(const glm::quat& q) {
  return std::acos(std::min(1.0f, (q * glm::vec3(0, 1, 0)).y));
}

TEST(PhysicsShapes, SmallHullPieceRestsWithinOneMillimetreOfTheGround) {
  // A 2 cm cube as a split piece: Bullet's default 4 cm margin would float it 4 cm high.
  PhysicsWorld world;
  addGround(world);
  const ShapeId shape =
      world.createShape(ShapeDef::convexHull(boxCorners(glm::vec3(0.01f)))).value();
  EXPECT_LE(*world.shapeMargin(shape), 0.1f * 0.02f + 1e-6f);
  EXPECT_GT(*world.shapeMargin(shape), 0.0f);
  EXPECT_EQ(*world.hullVertexCount(shape), 8u);
  BodyDef def;
  def.shape = shape;
  def.mass = 0.008f;
  def.position = glm::vec3(0, 0.05f, 0);
  const BodyId piece = world.createBody(def).value();
  stepFor(world, 180);
  const BodyTransform t = *world.bodyTransform(piece);
  EXPECT_NEAR(t.position.y - 0.01f, 0.0f, 0.001f);
  EXPECT_LT(tilt(t.rotation), 0.01f);
}

TEST(PhysicsShapes, LargeHullGetsTheCappedMarginAndKeepsItsSize) {
  PhysicsWorld world;
  addGround(world);
  const ShapeId shape =
      world.createShape(ShapeDef::convexHull(boxCorners(glm::vec3(0.5f)))).value();
  EXPECT_FLOAT_EQ(*world.shapeMargin(shape), kMaxConvexMargin);
  BodyDef def;
  def.shape = shape;
  def.mass = 1.0f;
  def.position = glm::vec3(0, 1.0f, 0);
  const BodyId box = world.createBody(def).value();
  stepFor(world, 180);
  EXPECT_NEAR(world.bodyTransform(box)->position.y, 0.5f, 0.002f);
}

TEST(PhysicsShapes, HullIgnoresInteriorPointsAndReducesManyVertices) {
  PhysicsWorld world;
  std::vector<glm::vec3> points = boxCorners(glm::vec3(0.5f));
  points.push_back(glm::vec3(0.1f, 0.2f, -0.3f));  // interior
  points.push_back(glm::vec3(0.0f));
  const ShapeId box = world.createShape(ShapeDef::convexHull(points)).value();
  EXPECT_EQ(*world.hullVertexCount(box), 8u);

  std::vector<glm::vec3> sphere;  // 400 points on a unit sphere (Fibonacci lattice)
  for (int i = 0; i < 400; ++i) {
    const float z = 1.0f - 2.0f * (float(i) + 0.5f) / 400.0f;
    const float r = std::sqrt(1.0f - z * z);
    const float phi = 2.39996323f * float(i);
    sphere.push_back(glm::vec3(r * std::cos(phi), r * std::sin(phi), z));
  }
  ShapeDef def = ShapeDef::convexHull(sphere);
  def.maxHullVertices = 32;
  const ShapeId reduced = world.createShape(def).value();
  EXPECT_LE(*world.hullVertexCount(reduced), 32u);
  EXPECT_GE(*world.hullVertexCount(reduced), 20u);
}

TEST(PhysicsShapes, InvalidHullsAreRefusedWithAReason) {
  PhysicsWorld world;
  const std::vector<glm::vec3> flat = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {1, 0, 1}, {0.5f, 0, 0.5f}};
  Result<ShapeId> result = world.createShape(ShapeDef::convexHull(flat));
  EXPECT_EQ(result.code(), PhysicsStatus::DegenerateShape);
  EXPECT_NE(result.message().find("coplanar"), std::string::npos) << result.message();

  const std::vector<glm::vec3> three = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_EQ(world.createShape(ShapeDef::convexHull(three)).code(),
            PhysicsStatus::InvalidArgument);

  std::vector<glm::vec3> nan = boxCorners(glm::vec3(1.0f));
  nan[3].y = NAN;
  result = world.createShape(ShapeDef::convexHull(nan));
  EXPECT_EQ(result.code(), PhysicsStatus::InvalidArgument);
  EXPECT_NE(result.message().find("point 3"), std::string::npos) << result.message();

  ShapeDef tooFew = ShapeDef::convexHull(boxCorners(glm::vec3(1.0f)));
  tooFew.maxHullVertices = 3;
  EXPECT_EQ(world.createShape(tooFew).code(), PhysicsStatus::InvalidArgument);
  EXPECT_EQ(world.liveShapeCount(), 0u);
}

TEST(PhysicsShapes, InvalidPrimitivesAndMeshesAreRefused) {
  PhysicsWorld world;
  EXPECT_EQ(world.createShape(ShapeDef::box(glm::vec3(1, -1, 1))).code(),
            PhysicsStatus::InvalidArgument);
  EXPECT_EQ(world.createShape(ShapeDef::sphere(0.0f)).code(), PhysicsStatus::InvalidArgument);
  EXPECT_EQ(world.createShape(ShapeDef::sphere(INFINITY)).code(), PhysicsStatus::InvalidArgument);
  EXPECT_EQ(world.createShape(ShapeDef::capsule(0.5f, -1.0f)).code(),
            PhysicsStatus::InvalidArgument);
  const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<uint32_t> outOfRange = {0, 1, 3};
  const Result<ShapeId> result = world.createShape(ShapeDef::concaveMesh(positions, outOfRange));
  EXPECT_EQ(result.code(), PhysicsStatus::InvalidArgument);
  EXPECT_NE(result.message().find("out of range"), std::string::npos) << result.message();
  const std::vector<uint32_t> notTriangles = {0, 1};
  EXPECT_EQ(world.createShape(ShapeDef::staticMesh(positions, notTriangles)).code(),
            PhysicsStatus::InvalidArgument);
  const std::vector<uint32_t> degenerate = {0, 1, 1};
  EXPECT_EQ(world.createShape(ShapeDef::staticMesh(positions, degenerate)).code(),
            PhysicsStatus::DegenerateShape);
  EXPECT_EQ(world.createShape(ShapeDef::compound({})).code(), PhysicsStatus::InvalidArgument);
  EXPECT_EQ(world.liveShapeCount(), 0u);
}

TEST(PhysicsShapes, InvalidBodyDefsAreRefused) {
  PhysicsWorld world;
  const ShapeId box = world.createShape(ShapeDef::box(glm::vec3(0.5f))).value();
  const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<uint32_t> indices = {0, 1, 2};
  const ShapeId mesh = world.createShape(ShapeDef::staticMesh(positions, indices)).value();
  auto status = [&](auto edit) {
    BodyDef def;
    def.shape = box;
    def.mass = 1.0f;
    edit(def);
    return world.createBody(def).code();
  };
  EXPECT_EQ(status([](BodyDef& d) { d.mass = -1.0f; }), PhysicsStatus::InvalidArgument);
  EXPECT_EQ(status([](BodyDef& d) { d.position.x = NAN; }), PhysicsStatus::InvalidArgument);
  EXPECT_EQ(status([](BodyDef& d) { d.rotation = glm::quat(0, 0, 0, 0); }),
            PhysicsStatus::InvalidArgument);
  EXPECT_EQ(status([](BodyDef& d) { d.angularVelocity.z = INFINITY; }),
            PhysicsStatus::InvalidArgument);
  EXPECT_EQ(status([](BodyDef& d) { d.restitution = 2.0f; }), PhysicsStatus::InvalidArgument);
  EXPECT_EQ(status([](BodyDef& d) { d.friction = -0.1f; }), PhysicsStatus::InvalidArgument);
  EXPECT_EQ(status([](BodyDef& d) { d.localInertia = glm::vec3(1, 0, 1); }),
            PhysicsStatus::InvalidArgument);
  EXPECT_EQ(status([](BodyDef& d) {
              d.mass = 0.0f;
              d.localInertia = glm::vec3(1.0f);
            }),
            PhysicsStatus::InvalidArgument);
  EXPECT_EQ(status([&](BodyDef& d) { d.shape = mesh; }), PhysicsStatus::UnsupportedCombination);
  EXPECT_EQ(status([&](BodyDef& d) {
              d.shape = mesh;
              d.mass = 0.0f;
            }),
            PhysicsStatus::Ok);
  EXPECT_EQ(status([](BodyDef& d) { d.rotation = glm::quat(2, 0, 0, 0); }), PhysicsStatus::Ok);
  EXPECT_EQ(world.bodyCount(), 2u);
}

TEST(PhysicsShapes, InertiaOverrideIsAppliedAndKeepsAngularMomentum) {
  // A sphere collider with the inertia of a thin rod along x: if the override were ignored, the
  // (isotropic) sphere would spin with constant omega and the rod's angular momentum
  // L = R I R^T omega would swing around as the body turns.
  PhysicsWorld world(WorldDef{glm::vec3(0.0f)});
  const glm::vec3 inertia(0.002f, 0.25f, 0.25f);
  BodyDef def;
  def.localInertia = inertia;
  def.angularVelocity = glm::vec3(1.0f, 0.5f, 0.0f);
  def.allowSleep = false;
  const BodyId rod = addBody(world, ShapeDef::sphere(0.1f), 1.0f, glm::vec3(0.0f), def);
  const glm::vec3 used = *world.bodyLocalInertia(rod);
  EXPECT_NEAR(used.x, inertia.x, 1e-6f);
  EXPECT_NEAR(used.y, inertia.y, 1e-5f);
  EXPECT_NEAR(used.z, inertia.z, 1e-5f);
  auto momentum = [&] {
    const glm::mat3 r = glm::mat3_cast(world.bodyTransform(rod)->rotation);
    const glm::mat3 i = r * glm::mat3(glm::vec3(inertia.x, 0, 0), glm::vec3(0, inertia.y, 0),
                                      glm::vec3(0, 0, inertia.z)) *
                        glm::transpose(r);
    return i * *world.angularVelocity(rod);
  };
  const glm::vec3 l0 = momentum();
  float worst = 0.0f;
  for (int i = 0; i < 30; ++i) {
    stepFor(world, 1);
    worst = std::max(worst, glm::length(momentum() - l0) / glm::length(l0));
  }
  // Bullet's implicit gyroscopic integration drifts about 0.5% here; ignoring the override gives
  // about 50%.
  EXPECT_LT(worst, 0.01f);
}

TEST(PhysicsShapes, ConcaveGImpactLShapeRestsOnTheGround) {
  PhysicsWorld world;
  addGround(world);
  const testing::LShape l = testing::makeLShape();
  const BodyId body = addBody(world, ShapeDef::concaveMesh(l.positions, l.indices), 3.0f,
                              glm::vec3(0, 1.5f, 0));
  stepFor(world, 300);
  const BodyTransform t = *world.bodyTransform(body);
  // GImpact keeps its triangle margin outside the surface.
  EXPECT_NEAR(t.position.y, testing::kLShapeCentre + kConcaveMeshMargin, 0.001f);
  EXPECT_LT(tilt(t.rotation), 0.01f);
  EXPECT_LT(glm::length(*world.linearVelocity(body)), 0.01f);
}

TEST(PhysicsShapes, ConcaveLShapeHoldsABoxInItsNotch) {
  // The notch of the L is only reachable through its concavity: a convex hull would fill it.
  PhysicsWorld world;
  addGround(world);
  const testing::LShape l = testing::makeLShape();
  addBody(world, ShapeDef::concaveMesh(l.positions, l.indices), 0.0f,
          glm::vec3(0, testing::kLShapeCentre, 0));
  // The notch floor is at y = 0.5, spanning x in [0.5, 1] of the outline.
  const float notchX = 0.75f - testing::kLShapeCentre;
  const BodyId box =
      addBody(world, ShapeDef::box(glm::vec3(0.1f)), 0.5f, glm::vec3(notchX, 1.5f, 0.0f));
  stepFor(world, 240);
  EXPECT_NEAR(world.bodyTransform(box)->position.y, 0.6f + kConcaveMeshMargin, 0.001f);
}

TEST(PhysicsShapes, CompoundDumbbellRestsOnBothParts) {
  PhysicsWorld world;
  addGround(world);
  std::vector<ConvexPart> parts(2);
  parts[0].points = boxCorners(glm::vec3(0.2f));
  parts[0].position = glm::vec3(-0.5f, 0, 0);
  parts[1].points = boxCorners(glm::vec3(0.2f));
  parts[1].position = glm::vec3(0.5f, 0, 0);
  parts[1].rotation = glm::angleAxis(glm::radians(45.0f), glm::vec3(0, 1, 0));
  const BodyId body = addBody(world, ShapeDef::compound(parts), 2.0f, glm::vec3(0, 1, 0));
  stepFor(world, 300);
  const BodyTransform t = *world.bodyTransform(body);
  EXPECT_NEAR(t.position.y, 0.2f, 0.003f);
  EXPECT_LT(tilt(t.rotation), 0.01f);
  // Exactly one contact event for the pair, merged over both child manifolds.
  ASSERT_EQ(world.contactEvents().size(), 1u);
  EXPECT_GE(world.contactEvents()[0].pointCount, 8u);
}

TEST(PhysicsShapes, CompoundPartErrorsNameThePart) {
  PhysicsWorld world;
  std::vector<ConvexPart> parts(2);
  parts[0].points = boxCorners(glm::vec3(0.2f));
  parts[1].points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  const Result<ShapeId> result = world.createShape(ShapeDef::compound(parts));
  EXPECT_EQ(result.code(), PhysicsStatus::DegenerateShape);
  EXPECT_NE(result.message().find("part 1"), std::string::npos) << result.message();
}

TEST(PhysicsShapes, BoxRestsOnStaticTriangleMesh) {
  PhysicsWorld world;
  addGround(world, /*mesh=*/true);
  const BodyId box = addBody(world, ShapeDef::box(glm::vec3(0.5f)), 1.0f, glm::vec3(0, 2, 0));
  stepFor(world, 240);
  EXPECT_NEAR(world.bodyTransform(box)->position.y, 0.5f, 0.005f);
}

TEST(PhysicsShapes, SphereAndLyingCapsuleRestAtTheirRadius) {
  PhysicsWorld world;
  addGround(world);
  const BodyId sphere = addBody(world, ShapeDef::sphere(0.3f), 1.0f, glm::vec3(0, 1, 0));
  BodyDef lying;
  lying.rotation = glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 0, 1));
  const BodyId capsule =
      addBody(world, ShapeDef::capsule(0.25f, 0.5f), 1.0f, glm::vec3(3, 1, 0), lying);
  stepFor(world, 240);
  EXPECT_NEAR(world.bodyTransform(sphere)->position.y, 0.3f, 0.005f);
  EXPECT_NEAR(world.bodyTransform(capsule)->position.y, 0.25f, 0.005f);
}

}  // namespace
}  // namespace cleave::physics
