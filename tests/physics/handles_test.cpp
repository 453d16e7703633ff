// SPDX-License-Identifier: MIT
#include <gtest/gtest.h>

#include "cleave/physics/physics_world.h"
#include "tests/physics/physics_test_helpers.h"

namespace cleave::physics {
namespace {

using testing::addBody;
using testing::addGround;
using testing::stepFor;

TEST(PhysicsHandles, NullHandlesAreInvalidEverywhere) {
  PhysicsWorld world;
  EXPECT_TRUE(BodyId{}.isNull());
  EXPECT_FALSE(world.isValid(BodyId{}));
  EXPECT_FALSE(world.isValid(ShapeId{}));
  EXPECT_FALSE(world.isValid(TriggerId{}));
  EXPECT_FALSE(world.destroyBody(BodyId{}));
  EXPECT_FALSE(world.bodyTransform(BodyId{}).has_value());
  BodyDef def;  // shape left null
  const Result<BodyId> body = world.createBody(def);
  EXPECT_EQ(body.code(), PhysicsStatus::StaleHandle);
  EXPECT_FALSE(body.message().empty());
}

TEST(PhysicsHandles, DestroyedBodyIsStaleAndItsSlotReuseGetsANewGeneration) {
  PhysicsWorld world;
  const BodyId first = addBody(world, ShapeDef::box(glm::vec3(0.5f)), 1.0f, glm::vec3(0.0f));
  ASSERT_TRUE(world.isValid(first));
  ASSERT_TRUE(world.destroyBody(first));
  EXPECT_FALSE(world.isValid(first));
  EXPECT_FALSE(world.destroyBody(first));
  EXPECT_FALSE(world.bodyTransform(first).has_value());
  EXPECT_FALSE(world.bodyState(first).has_value());
  EXPECT_FALSE(world.bodyMass(first).has_value());
  EXPECT_FALSE(world.setVelocity(first, glm::vec3(1.0f), glm::vec3(0.0f)));
  EXPECT_FALSE(world.applyImpulse(first, glm::vec3(1.0f), glm::vec3(0.0f)));
  EXPECT_FALSE(world.activate(first));
  EXPECT_FALSE(world.isAwake(first));
  EXPECT_EQ(world.bodyCount(), 0u);

  const BodyId second = addBody(world, ShapeDef::sphere(0.5f), 1.0f, glm::vec3(0.0f));
  EXPECT_EQ(second.index, first.index);
  EXPECT_NE(second.generation, first.generation);
  EXPECT_TRUE(world.isValid(second));
  EXPECT_FALSE(world.isValid(first));
  EXPECT_FALSE(world.destroyBody(first));
  EXPECT_TRUE(world.isValid(second));  // the stale destroy did not touch the new body
}

TEST(PhysicsHandles, DestroyedTriggerIsStaleAfterSlotReuse) {
  PhysicsWorld world;
  const ShapeId shape = world.createShape(ShapeDef::sphere(1.0f)).value();
  TriggerDef def;
  def.shape = shape;
  const TriggerId first = world.createTrigger(def).value();
  ASSERT_TRUE(world.destroyTrigger(first));
  EXPECT_FALSE(world.isValid(first));
  EXPECT_FALSE(world.setTriggerTransform(first, {}));
  const TriggerId second = world.createTrigger(def).value();
  EXPECT_EQ(second.index, first.index);
  EXPECT_NE(second.generation, first.generation);
  EXPECT_FALSE(world.destroyTrigger(first));
  EXPECT_TRUE(world.isValid(second));
}

TEST(PhysicsHandles, ShapeOutlivesItsHandleWhileBodiesUseIt) {
  PhysicsWorld world;
  const ShapeId shape = world.createShape(ShapeDef::box(glm::vec3(0.5f))).value();
  BodyDef def;
  def.shape = shape;
  def.mass = 1.0f;
  const BodyId a = world.createBody(def).value();
  const BodyId b = world.createBody(def).value();
  ASSERT_TRUE(world.destroyShape(shape));
  EXPECT_FALSE(world.isValid(shape));
  EXPECT_FALSE(world.destroyShape(shape));
  EXPECT_EQ(world.liveShapeCount(), 1u);  // still used by a and b
  EXPECT_EQ(world.createBody(def).code(), PhysicsStatus::StaleHandle);
  stepFor(world, 10);  // the bodies still collide and fall with the shared shape
  EXPECT_TRUE(world.destroyBody(a));
  EXPECT_EQ(world.liveShapeCount(), 1u);
  EXPECT_TRUE(world.destroyBody(b));
  EXPECT_EQ(world.liveShapeCount(), 0u);
}

TEST(PhysicsHandles, ShapeHandleOutlivesItsBodies) {
  PhysicsWorld world;
  const ShapeId shape = world.createShape(ShapeDef::sphere(0.5f)).value();
  BodyDef def;
  def.shape = shape;
  def.mass = 1.0f;
  const BodyId body = world.createBody(def).value();
  ASSERT_TRUE(world.destroyBody(body));
  EXPECT_TRUE(world.isValid(shape));
  EXPECT_EQ(world.liveShapeCount(), 1u);
  EXPECT_TRUE(world.createBody(def).ok());
}

TEST(PhysicsHandles, CreatingAndDestroyingEverythingLeavesNothingAlive) {
  PhysicsWorld world;
  addGround(world);
  std::vector<BodyId> bodies;
  std::vector<TriggerId> triggers;
  const testing::LShape l = testing::makeLShape();
  for (int round = 0; round < 3; ++round) {
    for (int i = 0; i < 5; ++i) {
      const glm::vec3 at(float(i) * 2.0f, 1.0f + float(round), 0.0f);
      bodies.push_back(addBody(world, ShapeDef::box(glm::vec3(0.3f)), 1.0f, at));
      bodies.push_back(addBody(world, ShapeDef::convexHull(testing::boxCorners(glm::vec3(0.2f))),
                               1.0f, at + glm::vec3(0, 0, 2)));
      bodies.push_back(addBody(world, ShapeDef::concaveMesh(l.positions, l.indices), 1.0f,
                               at + glm::vec3(0, 0, 4)));
      const ShapeId triggerShape = world.createShape(ShapeDef::box(glm::vec3(1.0f))).value();
      TriggerDef def;
      def.shape = triggerShape;
      def.position = at;
      triggers.push_back(world.createTrigger(def).value());
      world.destroyShape(triggerShape);
    }
    stepFor(world, 20);
    // Destroy in an order different from creation.
    for (size_t i = 0; i < bodies.size(); i += 2) EXPECT_TRUE(world.destroyBody(bodies[i]));
    for (TriggerId t : triggers) EXPECT_TRUE(world.destroyTrigger(t));
    for (size_t i = 1; i < bodies.size(); i += 2) EXPECT_TRUE(world.destroyBody(bodies[i]));
    bodies.clear();
    triggers.clear();
    stepFor(world, 2);
    EXPECT_EQ(world.bodyCount(), 1u);       // the ground
    EXPECT_EQ(world.liveShapeCount(), 1u);  // the ground's shape
  }
}

TEST(PhysicsHandles, WorldDestroyedWithLiveObjectsFreesThem) {
  // Run under ASan (CLEAVE_SANITIZE=ON) to check that nothing leaks.
  PhysicsWorld world;
  addGround(world);
  addBody(world, ShapeDef::box(glm::vec3(0.5f)), 1.0f, glm::vec3(0, 1, 0));
  const ShapeId kept = world.createShape(ShapeDef::sphere(1.0f)).value();
  TriggerDef def;
  def.shape = kept;
  ASSERT_TRUE(world.createTrigger(def).ok());
  stepFor(world, 5);
  EXPECT_EQ(world.liveShapeCount(), 3u);
}

}  // namespace
}  // namespace cleave::physics
