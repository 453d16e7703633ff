// SPDX-License-Identifier: MIT
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

// A scene with every kind of shape, stacking, a trigger and a mid-run impulse and destroy.
struct Scene {
  PhysicsWorld world;
  std::vector<BodyId> bodies;
  std::vector<TriggerEvent> allTriggerEvents;
  size_t contactEventCount = 0;

  Scene() {
    bodies.push_back(addGround(world));
    for (int i = 0; i < 4; ++i) {  // a stack of boxes
      BodyDef def;
      def.angularVelocity = glm::vec3(0.0f, 0.1f * float(i), 0.0f);
      bodies.push_back(addBody(world, ShapeDef::box(glm::vec3(0.5f)), 1.0f,
                               glm::vec3(0.05f * float(i), 0.5f + 1.05f * float(i), 0.0f), def));
    }
    bodies.push_back(addBody(world, ShapeDef::sphere(0.4f), 2.0f, glm::vec3(3, 4, 0)));
    bodies.push_back(addBody(world, ShapeDef::capsule(0.3f, 0.5f), 1.5f, glm::vec3(-3, 2, 0)));
    bodies.push_back(addBody(world, ShapeDef::convexHull(testing::boxCorners(glm::vec3(0.01f))),
                             0.008f, glm::vec3(1, 0.5f, 2)));
    const testing::LShape l = testing::makeLShape();
    BodyDef tilted;
    tilted.rotation = glm::angleAxis(0.3f, glm::normalize(glm::vec3(1, 0, 1)));
    bodies.push_back(addBody(world, ShapeDef::concaveMesh(l.positions, l.indices), 3.0f,
                             glm::vec3(0, 2, 3), tilted));
    std::vector<ConvexPart> parts(2);
    parts[0].points = testing::boxCorners(glm::vec3(0.2f));
    parts[0].position = glm::vec3(-0.5f, 0, 0);
    parts[1].points = testing::boxCorners(glm::vec3(0.2f));
    parts[1].position = glm::vec3(0.5f, 0, 0);
    BodyDef inertia;
    inertia.localInertia = glm::vec3(0.05f, 0.3f, 0.3f);
    bodies.push_back(addBody(world, ShapeDef::compound(parts), 2.0f, glm::vec3(0, 3, -3), inertia));
    const ShapeId triggerShape = world.createShape(ShapeDef::box(glm::vec3(2, 0.5f, 2))).value();
    TriggerDef trigger;
    trigger.shape = triggerShape;
    trigger.position = glm::vec3(0, 1.0f, 0);
    world.createTrigger(trigger);
    world.destroyShape(triggerShape);
  }

  void run(int steps) {
    for (int i = 0; i < steps; ++i) {
      if (i == 100) world.applyImpulse(bodies[5], glm::vec3(-3, 2, 0), glm::vec3(3, 4.2f, 0.1f));
      if (i == 200) world.destroyBody(bodies[2]);
      if (i == 201) bodies[2] = addBody(world, ShapeDef::sphere(0.2f), 1.0f, glm::vec3(0, 5, 0));
      ASSERT_EQ(world.step(kDt), PhysicsStatus::Ok);
      for (const TriggerEvent& e : world.triggerEvents()) allTriggerEvents.push_back(e);
      contactEventCount += world.contactEvents().size();
    }
  }
};

TEST(PhysicsDeterminism, TwoWorldsGiveBitIdenticalStatesAfter600Steps) {
  Scene a;
  Scene b;
  a.run(600);
  b.run(600);
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (size_t i = 0; i < a.bodies.size(); ++i) {
    const BodyState sa = *a.world.bodyState(a.bodies[i]);
    const BodyState sb = *b.world.bodyState(b.bodies[i]);
    EXPECT_EQ(std::memcmp(&sa.transform, &sb.transform, sizeof(BodyTransform)), 0) << "body " << i;
    EXPECT_EQ(std::memcmp(&sa.linearVelocity, &sb.linearVelocity, sizeof(glm::vec3)), 0);
    EXPECT_EQ(std::memcmp(&sa.angularVelocity, &sb.angularVelocity, sizeof(glm::vec3)), 0);
  }
  EXPECT_EQ(a.world.stateHash(), b.world.stateHash());
  EXPECT_EQ(a.contactEventCount, b.contactEventCount);
  ASSERT_EQ(a.allTriggerEvents.size(), b.allTriggerEvents.size());
  for (size_t i = 0; i < a.allTriggerEvents.size(); ++i) {
    EXPECT_EQ(a.allTriggerEvents[i].trigger, b.allTriggerEvents[i].trigger);
    EXPECT_EQ(a.allTriggerEvents[i].body, b.allTriggerEvents[i].body);
    EXPECT_EQ(a.allTriggerEvents[i].kind, b.allTriggerEvents[i].kind);
  }
  EXPECT_FALSE(a.allTriggerEvents.empty());  // the scene does exercise the trigger
}

TEST(PhysicsDeterminism, HashIsStableAcrossRunsAndTracksTheState) {
  Scene a;
  const uint64_t initial = a.world.stateHash();
  EXPECT_EQ(initial, a.world.stateHash());  // a pure function of the state
  a.run(300);
  const uint64_t later = a.world.stateHash();
  EXPECT_NE(initial, later);
  Scene b;
  EXPECT_EQ(b.world.stateHash(), initial);
  b.run(300);
  EXPECT_EQ(b.world.stateHash(), later);
  b.run(1);
  EXPECT_NE(b.world.stateHash(), later);
}

TEST(PhysicsDeterminism, EventsAreSortedByHandle) {
  Scene scene;
  for (int i = 0; i < 200; ++i) {
    ASSERT_EQ(scene.world.step(kDt), PhysicsStatus::Ok);
    const auto contacts = scene.world.contactEvents();
    for (size_t k = 0; k < contacts.size(); ++k) {
      EXPECT_LT(contacts[k].bodyA.index, contacts[k].bodyB.index);
      if (k > 0) {
        EXPECT_LT(std::pair(contacts[k - 1].bodyA, contacts[k - 1].bodyB),
                  std::pair(contacts[k].bodyA, contacts[k].bodyB));
      }
    }
    const auto triggers = scene.world.triggerEvents();
    for (size_t k = 1; k < triggers.size(); ++k) {
      EXPECT_LT(std::pair(triggers[k - 1].trigger, triggers[k - 1].body),
                std::pair(triggers[k].trigger, triggers[k].body));
    }
  }
}

}  // namespace
}  // namespace cleave::physics
