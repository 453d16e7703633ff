// SPDX-License-Identifier: MIT
#include <algorithm>
#include <vector>

#include <gtest/gtest.h>

#include "cleave/physics/physics_world.h"
#include "tests/physics/physics_test_helpers.h"

namespace cleave::physics {
namespace {

using testing::addBody;
using testing::addGround;
using testing::stepFor;

TriggerId addTrigger(PhysicsWorld& world, const ShapeDef& shapeDef, glm::vec3 position,
                     TriggerDef def = {}) {
  const ShapeId shape = world.createShape(shapeDef).value();
  def.shape = shape;
  def.position = position;
  const Result<TriggerId> trigger = world.createTrigger(def);
  EXPECT_TRUE(trigger.ok()) << trigger.message();
  world.destroyShape(shape);
  return trigger.value();
}

bool reported(const PhysicsWorld& world, BodyId body) {
  const auto events = world.triggerEvents();
  return std::any_of(events.begin(), events.end(), [&](const TriggerEvent& e) {
    return e.body == body && e.kind != TriggerEventKind::End;
  });
}

TEST(PhysicsTrigger, ReportsOnlyBodiesThatReallyTouchIt) {
  PhysicsWorld world;
  const BodyId ground = addGround(world);
  // The trigger hovers 5 cm above the ground: its AABB overlaps the huge static ground's AABB (and
  // detectStatic asks for static bodies), but their shapes do not touch.
  TriggerDef def;
  def.detectStatic = true;
  const TriggerId trigger = addTrigger(world, ShapeDef::box(glm::vec3(1.0f, 0.5f, 1.0f)),
                                       glm::vec3(0, 0.55f, 0), def);
  const BodyId far = addBody(world, ShapeDef::box(glm::vec3(0.25f)), 1.0f, glm::vec3(10, 0.3f, 0));
  const BodyId falling =
      addBody(world, ShapeDef::box(glm::vec3(0.25f)), 1.0f, glm::vec3(0, 3.0f, 0));
  int begins = 0;
  int firstTouchStep = -1;
  for (int step = 0; step < 180; ++step) {
    stepFor(world, 1);
    EXPECT_FALSE(reported(world, ground)) << "step " << step;
    EXPECT_FALSE(reported(world, far)) << "step " << step;
    for (const TriggerEvent& e : world.triggerEvents()) {
      EXPECT_EQ(e.trigger, trigger);
      if (e.kind == TriggerEventKind::Begin) ++begins;
    }
    const float bottom = world.bodyTransform(falling)->position.y - 0.25f;
    if (firstTouchStep < 0 && reported(world, falling)) {
      firstTouchStep = step;
      EXPECT_LE(bottom, 1.05f + 0.02f);  // reported only once it reaches the trigger's top (y=1.05)
    }
  }
  EXPECT_GE(firstTouchStep, 0);
  EXPECT_EQ(begins, 1);
  // Resting on the ground, the falling box is inside the trigger: it stays reported.
  ASSERT_EQ(world.triggerEvents().size(), 1u);
  EXPECT_EQ(world.triggerEvents()[0].body, falling);
  EXPECT_EQ(world.triggerEvents()[0].kind, TriggerEventKind::Stay);
}

TEST(PhysicsTrigger, MovingAwayGivesEndThenNothing) {
  PhysicsWorld world(WorldDef{glm::vec3(0.0f)});
  const BodyId body = addBody(world, ShapeDef::sphere(0.5f), 1.0f, glm::vec3(0.0f));
  const TriggerId trigger =
      addTrigger(world, ShapeDef::box(glm::vec3(1.0f)), glm::vec3(0.5f, 0, 0));
  stepFor(world, 1);
  ASSERT_EQ(world.triggerEvents().size(), 1u);
  EXPECT_EQ(world.triggerEvents()[0].kind, TriggerEventKind::Begin);
  EXPECT_EQ(world.triggerEvents()[0].body, body);
  stepFor(world, 1);
  ASSERT_EQ(world.triggerEvents().size(), 1u);
  EXPECT_EQ(world.triggerEvents()[0].kind, TriggerEventKind::Stay);
  EXPECT_EQ(world.bodyTransform(body)->position, glm::vec3(0.0f));  // triggers push nothing
  ASSERT_TRUE(world.setTriggerTransform(trigger, {glm::vec3(5, 0, 0), glm::quat(1, 0, 0, 0)}));
  stepFor(world, 1);
  ASSERT_EQ(world.triggerEvents().size(), 1u);
  EXPECT_EQ(world.triggerEvents()[0].kind, TriggerEventKind::End);
  stepFor(world, 1);
  EXPECT_TRUE(world.triggerEvents().empty());
}

TEST(PhysicsTrigger, StaticBodiesAreReportedOnlyWhenAskedFor) {
  PhysicsWorld world;
  const BodyId ground = addGround(world);
  // Both triggers sink 10 cm into the ground.
  const TriggerId quiet = addTrigger(world, ShapeDef::sphere(0.5f), glm::vec3(0, 0.4f, 0));
  TriggerDef def;
  def.detectStatic = true;
  const TriggerId seeing = addTrigger(world, ShapeDef::sphere(0.5f), glm::vec3(3, 0.4f, 0), def);
  stepFor(world, 1);
  ASSERT_EQ(world.triggerEvents().size(), 1u);
  EXPECT_EQ(world.triggerEvents()[0].trigger, seeing);
  EXPECT_EQ(world.triggerEvents()[0].body, ground);
  EXPECT_NE(world.triggerEvents()[0].trigger, quiet);
}

TEST(PhysicsTrigger, SeesSleepingBodies) {
  PhysicsWorld world;
  addGround(world);
  BodyDef asleep;
  asleep.startAwake = false;
  const BodyId body =
      addBody(world, ShapeDef::box(glm::vec3(0.5f)), 1.0f, glm::vec3(0, 0.5f, 0), asleep);
  addTrigger(world, ShapeDef::box(glm::vec3(0.2f)), glm::vec3(0, 1.0f, 0));
  stepFor(world, 2);
  EXPECT_FALSE(world.isAwake(body));
  EXPECT_TRUE(reported(world, body));
}

TEST(PhysicsTrigger, OneShotTriggerReportsOnceThenIsSpent) {
  PhysicsWorld world(WorldDef{glm::vec3(0.0f)});
  const BodyId body = addBody(world, ShapeDef::box(glm::vec3(0.5f)), 1.0f, glm::vec3(0.0f));
  TriggerDef def;
  def.persistent = false;
  def.userData = 7;
  const TriggerId trigger =
      addTrigger(world, ShapeDef::box(glm::vec3(0.3f)), glm::vec3(0.6f, 0, 0), def);
  EXPECT_FALSE(world.isTriggerSpent(trigger));
  stepFor(world, 1);
  ASSERT_EQ(world.triggerEvents().size(), 1u);
  EXPECT_EQ(world.triggerEvents()[0].body, body);
  EXPECT_EQ(world.triggerEvents()[0].kind, TriggerEventKind::Begin);
  EXPECT_TRUE(world.isTriggerSpent(trigger));
  EXPECT_EQ(*world.triggerUserData(trigger), 7u);
  stepFor(world, 3);
  EXPECT_TRUE(world.triggerEvents().empty());
  EXPECT_TRUE(world.destroyTrigger(trigger));
}

TEST(PhysicsTrigger, DestroyedBodyLeavesNoEvents) {
  PhysicsWorld world(WorldDef{glm::vec3(0.0f)});
  const BodyId body = addBody(world, ShapeDef::sphere(0.5f), 1.0f, glm::vec3(0.0f));
  addTrigger(world, ShapeDef::sphere(0.5f), glm::vec3(0.5f, 0, 0));
  stepFor(world, 1);
  ASSERT_EQ(world.triggerEvents().size(), 1u);
  ASSERT_TRUE(world.destroyBody(body));
  stepFor(world, 1);
  EXPECT_TRUE(world.triggerEvents().empty());
}

TEST(PhysicsTrigger, MeshShapesAndStaleShapesAreRefused) {
  PhysicsWorld world;
  const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<uint32_t> indices = {0, 1, 2};
  TriggerDef def;
  def.shape = world.createShape(ShapeDef::staticMesh(positions, indices)).value();
  EXPECT_EQ(world.createTrigger(def).code(), PhysicsStatus::UnsupportedCombination);
  world.destroyShape(def.shape);
  EXPECT_EQ(world.createTrigger(def).code(), PhysicsStatus::StaleHandle);
  def.shape = world.createShape(ShapeDef::sphere(1.0f)).value();
  def.position.x = NAN;
  EXPECT_EQ(world.createTrigger(def).code(), PhysicsStatus::InvalidArgument);
}

}  // namespace
}  // namespace cleave::physics
