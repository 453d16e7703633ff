// SPDX-License-Identifier: MIT
#include <cmath>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "cleave/physics/physics_world.h"
#include "tests/physics/physics_test_helpers.h"

namespace cleave::physics {
namespace {

using testing::addBody;
using testing::addGround;
using testing::kDt;
using testing::stepFor;

float rotationAngle(const glm::quat& q) {
  return 2.0f * std::acos(std::min(1.0f, std::abs(q.w)));
}

TEST(PhysicsWorld, BoxDroppedOnStaticBoxGroundRestsAtHalfHeight) {
  PhysicsWorld world;
  addGround(world);
  const BodyId box = addBody(world, ShapeDef::box(glm::vec3(0.5f)), 1.0f, glm::vec3(0, 3, 0));
  stepFor(world, 300);
  const BodyTransform t = *world.bodyTransform(box);
  EXPECT_NEAR(t.position.y, 0.5f, 0.005f);
  EXPECT_NEAR(t.position.x, 0.0f, 1e-4f);
  EXPECT_NEAR(t.position.z, 0.0f, 1e-4f);
  EXPECT_LT(rotationAngle(t.rotation), 1e-3f);
  EXPECT_LT(glm::length(*world.linearVelocity(box)), 0.01f);
}

TEST(PhysicsWorld, RestingBoxFallsAsleepAndWakesOnImpulse) {
  PhysicsWorld world;
  addGround(world);
  const BodyId box = addBody(world, ShapeDef::box(glm::vec3(0.5f)), 1.0f, glm::vec3(0, 0.6f, 0));
  EXPECT_TRUE(world.isAwake(box));
  stepFor(world, 600);
  EXPECT_FALSE(world.isAwake(box));
  EXPECT_TRUE(world.applyImpulse(box, glm::vec3(0, 5, 0), glm::vec3(0, 0.5f, 0)));
  EXPECT_TRUE(world.isAwake(box));
  stepFor(world, 1);
  EXPECT_GT(world.bodyTransform(box)->position.y, 0.5f);
}

TEST(PhysicsWorld, ImpulseOffCentreChangesLinearAndAngularVelocity) {
  PhysicsWorld world(WorldDef{glm::vec3(0.0f)});
  const BodyId box = addBody(world, ShapeDef::box(glm::vec3(0.5f)), 2.0f, glm::vec3(0.0f));
  ASSERT_TRUE(world.applyImpulse(box, glm::vec3(0, 0, 4), glm::vec3(1, 0, 0)));
  EXPECT_NEAR(world.linearVelocity(box)->z, 2.0f, 1e-5f);  // J / m
  // L = r x J = (1,0,0) x (0,0,4) = (0,-4,0); I = m (1^2 + 1^2) / 12 = 1/3 -> w = -12.
  EXPECT_NEAR(world.angularVelocity(box)->y, -12.0f, 1e-3f);
}

TEST(PhysicsWorld, StaticBodyHasNoMassAndRefusesVelocity) {
  PhysicsWorld world;
  const BodyId ground = addGround(world);
  EXPECT_EQ(*world.bodyMass(ground), 0.0f);
  EXPECT_FALSE(world.isAwake(ground));
  EXPECT_FALSE(world.setVelocity(ground, glm::vec3(1, 0, 0), glm::vec3(0.0f)));
  EXPECT_FALSE(world.applyImpulse(ground, glm::vec3(1, 0, 0), glm::vec3(0.0f)));
  stepFor(world, 10);
  EXPECT_EQ(world.bodyTransform(ground)->position, glm::vec3(0, -1, 0));
}

TEST(PhysicsWorld, StartsAsleepWhenAskedAndActivateWakesIt) {
  PhysicsWorld world;
  BodyDef def;
  def.startAwake = false;
  const BodyId box = addBody(world, ShapeDef::box(glm::vec3(0.5f)), 1.0f, glm::vec3(0, 5, 0), def);
  EXPECT_FALSE(world.isAwake(box));
  stepFor(world, 10);
  EXPECT_EQ(world.bodyTransform(box)->position.y, 5.0f);  // asleep in mid-air: does not fall
  EXPECT_TRUE(world.activate(box));
  stepFor(world, 10);
  EXPECT_LT(world.bodyTransform(box)->position.y, 5.0f);
}

TEST(PhysicsWorld, BodyStateReportsEverythingForTheDump) {
  PhysicsWorld world(WorldDef{glm::vec3(0.0f)});
  BodyDef def;
  def.userData = 42;
  def.linearVelocity = glm::vec3(1, 2, 3);
  def.angularVelocity = glm::vec3(0, 0.5f, 0);
  const BodyId body = addBody(world, ShapeDef::sphere(0.5f), 3.0f, glm::vec3(1, 1, 1), def);
  const BodyState state = *world.bodyState(body);
  EXPECT_EQ(state.userData, 42u);
  EXPECT_EQ(state.mass, 3.0f);
  EXPECT_TRUE(state.awake);
  EXPECT_EQ(state.transform.position, glm::vec3(1, 1, 1));
  EXPECT_EQ(state.linearVelocity, glm::vec3(1, 2, 3));
  EXPECT_EQ(state.angularVelocity, glm::vec3(0, 0.5f, 0));
  stepFor(world, 60);
  EXPECT_NEAR(world.bodyTransform(body)->position.x, 2.0f, 1e-4f);
  EXPECT_NEAR(world.bodyTransform(body)->position.z, 4.0f, 1e-4f);
}

TEST(PhysicsWorld, SetTransformTeleportsTheBody) {
  PhysicsWorld world;
  const BodyId box = addBody(world, ShapeDef::box(glm::vec3(0.5f)), 1.0f, glm::vec3(0.0f));
  const glm::quat rotation = glm::angleAxis(0.5f, glm::vec3(0, 1, 0));
  ASSERT_TRUE(world.setBodyTransform(box, {glm::vec3(3, 4, 5), rotation}));
  const BodyTransform t = *world.bodyTransform(box);
  EXPECT_EQ(t.position, glm::vec3(3, 4, 5));
  EXPECT_NEAR(std::abs(glm::dot(t.rotation, rotation)), 1.0f, 1e-6f);
  EXPECT_FALSE(world.setBodyTransform(box, {glm::vec3(NAN), rotation}));
  EXPECT_FALSE(world.setBodyTransform(box, {glm::vec3(0.0f), glm::quat(0, 0, 0, 0)}));
}

TEST(PhysicsWorld, InvalidStepIsRefusedAndMovesNothing) {
  PhysicsWorld world;
  const BodyId box = addBody(world, ShapeDef::box(glm::vec3(0.5f)), 1.0f, glm::vec3(0, 3, 0));
  EXPECT_EQ(world.step(0.0), PhysicsStatus::InvalidArgument);
  EXPECT_EQ(world.step(-kDt), PhysicsStatus::InvalidArgument);
  EXPECT_EQ(world.step(NAN), PhysicsStatus::InvalidArgument);
  EXPECT_EQ(world.step(10.0), PhysicsStatus::InvalidArgument);
  EXPECT_EQ(world.stepCount(), 0u);
  EXPECT_EQ(world.bodyTransform(box)->position.y, 3.0f);
  EXPECT_EQ(world.setGravity(glm::vec3(0, NAN, 0)), PhysicsStatus::InvalidArgument);
  EXPECT_EQ(world.gravity(), glm::vec3(0, -9.81f, 0));
}

TEST(PhysicsWorld, GravityChangeAppliesToExistingBodies) {
  PhysicsWorld world;
  const BodyId box = addBody(world, ShapeDef::box(glm::vec3(0.5f)), 1.0f, glm::vec3(0.0f));
  ASSERT_EQ(world.setGravity(glm::vec3(0, 0, 0)), PhysicsStatus::Ok);
  stepFor(world, 30);
  EXPECT_EQ(world.bodyTransform(box)->position, glm::vec3(0.0f));
}

TEST(PhysicsWorld, OneStepAdvancesExactlyDt) {
  // Symplectic Euler: v = g dt, x = v dt after one step.
  PhysicsWorld world;
  const BodyId box = addBody(world, ShapeDef::box(glm::vec3(0.5f)), 1.0f, glm::vec3(0.0f));
  stepFor(world, 1);
  const float v = -9.81f * float(kDt);
  EXPECT_NEAR(world.linearVelocity(box)->y, v, 1e-6f);
  EXPECT_NEAR(world.bodyTransform(box)->position.y, v * float(kDt), 1e-6f);
  EXPECT_EQ(world.stepCount(), 1u);
}

TEST(PhysicsWorld, ContactEventReportsRestingBoxWithWeightImpulse) {
  PhysicsWorld world;
  const BodyId ground = addGround(world);
  const BodyId box = addBody(world, ShapeDef::box(glm::vec3(0.5f)), 2.0f, glm::vec3(0, 0.55f, 0));
  stepFor(world, 120);
  ASSERT_EQ(world.contactEvents().size(), 1u);
  const ContactEvent& event = world.contactEvents()[0];
  EXPECT_EQ(event.bodyA, ground);  // lower index first
  EXPECT_EQ(event.bodyB, box);
  EXPECT_NEAR(event.normal.y, 1.0f, 1e-4f);  // from the ground towards the box
  EXPECT_NEAR(event.point.y, 0.0f, 0.01f);
  EXPECT_GE(event.pointCount, 4u);
  // The ground carries the weight: sum of impulses = m g dt.
  EXPECT_NEAR(event.impulse, 2.0f * 9.81f * float(kDt), 0.05f * 2.0f * 9.81f * float(kDt));
}

TEST(PhysicsWorld, NoContactEventsWithoutTouch) {
  PhysicsWorld world;
  addGround(world);
  addBody(world, ShapeDef::box(glm::vec3(0.5f)), 1.0f, glm::vec3(0, 3, 0));
  stepFor(world, 5);
  EXPECT_TRUE(world.contactEvents().empty());
}

// createBody checks the whole def before building anything: each bad field is refused with its
// name and the reason, and no body (or shape user) is left behind.
TEST(PhysicsWorld, CreateBodyNamesTheBadFieldAndBuildsNothing) {
  PhysicsWorld world;
  const ShapeId box = world.createShape(ShapeDef::box(glm::vec3(0.5f))).value();
  const std::vector<glm::vec3> corners = testing::boxCorners(glm::vec3(1.0f));
  const std::vector<uint32_t> square = {0, 1, 3, 0, 3, 2};
  const ShapeId mesh = world.createShape(ShapeDef::staticMesh(corners, square)).value();
  struct Case {
    const char* field;
    PhysicsStatus status;
    void (*spoil)(BodyDef&);
  };
  const Case cases[] = {
      {"BodyDef::mass", PhysicsStatus::InvalidArgument, [](BodyDef& d) { d.mass = -1.0f; }},
      {"BodyDef::kinematic", PhysicsStatus::InvalidArgument, [](BodyDef& d) { d.kinematic = true; }},
      {"BodyDef::localInertia", PhysicsStatus::InvalidArgument, [](BodyDef& d) { d.localInertia = glm::vec3(1, 0, 1); }},
      {"BodyDef::position", PhysicsStatus::InvalidArgument, [](BodyDef& d) { d.position.y = NAN; }},
      {"BodyDef::rotation", PhysicsStatus::InvalidArgument, [](BodyDef& d) { d.rotation = glm::quat(0, 0, 0, 0); }},
      {"BodyDef::linearVelocity", PhysicsStatus::InvalidArgument, [](BodyDef& d) { d.linearVelocity.x = INFINITY; }},
      {"BodyDef::angularVelocity", PhysicsStatus::InvalidArgument, [](BodyDef& d) { d.angularVelocity.z = NAN; }},
      {"BodyDef::friction", PhysicsStatus::InvalidArgument, [](BodyDef& d) { d.friction = -0.1f; }},
      {"BodyDef::restitution", PhysicsStatus::InvalidArgument, [](BodyDef& d) { d.restitution = 1.5f; }},
      {"BodyDef::linearDamping", PhysicsStatus::InvalidArgument, [](BodyDef& d) { d.linearDamping = NAN; }},
      {"BodyDef::angularDamping", PhysicsStatus::InvalidArgument, [](BodyDef& d) { d.angularDamping = -1.0f; }},
      {"BodyDef::ccdRadius", PhysicsStatus::InvalidArgument, [](BodyDef& d) { d.ccdRadius = -0.01f; }},
      {"BodyDef::sleepLinearSpeed", PhysicsStatus::InvalidArgument, [](BodyDef& d) { d.sleepLinearSpeed = NAN; }},
      {"BodyDef::sleepAngularSpeed", PhysicsStatus::InvalidArgument, [](BodyDef& d) { d.sleepAngularSpeed = -2.0f; }},
  };
  for (const Case& c : cases) {
    BodyDef def;
    def.shape = box;
    def.mass = 1.0f;
    c.spoil(def);
    const Result<BodyId> body = world.createBody(def);
    EXPECT_EQ(body.code(), c.status) << c.field;
    EXPECT_NE(body.message().find(c.field), std::string::npos) << body.message();
    EXPECT_EQ(body.message().rfind("createBody: ", 0), 0u) << body.message();
  }
  BodyDef heavyMesh;
  heavyMesh.shape = mesh;
  heavyMesh.mass = 2.0f;
  const Result<BodyId> refused = world.createBody(heavyMesh);
  EXPECT_EQ(refused.code(), PhysicsStatus::UnsupportedCombination);
  EXPECT_NE(refused.message().find("BodyDef::shape"), std::string::npos) << refused.message();
  EXPECT_EQ(world.bodyCount(), 0u);
  // Nothing holds the shapes: dropping their handles frees them.
  world.destroyShape(box);
  world.destroyShape(mesh);
  EXPECT_EQ(world.liveShapeCount(), 0u);
}

}  // namespace
}  // namespace cleave::physics
