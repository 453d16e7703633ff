// SPDX-License-Identifier: MIT
#include <gtest/gtest.h>

#include "cleave/physics/physics_world.h"
#include "tests/physics/physics_test_helpers.h"

namespace cleave::physics {
namespace {

using testing::addBody;
using testing::addGround;

TEST(PhysicsRaycast, HitsTheClosestBodyWithPointNormalAndFraction) {
  PhysicsWorld world;
  const BodyId ground = addGround(world);
  const BodyId box = addBody(world, ShapeDef::box(glm::vec3(0.5f)), 1.0f, glm::vec3(0, 0.5f, 0));
  const std::optional<RayHit> hit = world.raycast(glm::vec3(0.1f, 5, 0), glm::vec3(0.1f, -5, 0));
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->body, box);
  EXPECT_NEAR(hit->point.y, 1.0f, 1e-4f);
  EXPECT_NEAR(hit->point.x, 0.1f, 1e-4f);
  EXPECT_NEAR(hit->normal.y, 1.0f, 1e-4f);
  EXPECT_NEAR(hit->fraction, 0.4f, 1e-4f);

  const std::optional<RayHit> side = world.raycast(glm::vec3(5, 0.5f, 0), glm::vec3(-5, 0.5f, 0));
  ASSERT_TRUE(side.has_value());
  EXPECT_EQ(side->body, box);
  EXPECT_NEAR(side->point.x, 0.5f, 1e-4f);
  EXPECT_NEAR(side->normal.x, 1.0f, 1e-4f);

  const std::optional<RayHit> floor = world.raycast(glm::vec3(3, 5, 0), glm::vec3(3, -5, 0));
  ASSERT_TRUE(floor.has_value());
  EXPECT_EQ(floor->body, ground);
  EXPECT_NEAR(floor->point.y, 0.0f, 1e-4f);
}

TEST(PhysicsRaycast, MissesReturnNothing) {
  PhysicsWorld world;
  addGround(world);
  EXPECT_FALSE(world.raycast(glm::vec3(0, 5, 0), glm::vec3(0, 10, 0)).has_value());
  EXPECT_FALSE(world.raycast(glm::vec3(0, 5, 0), glm::vec3(0, 1, 0)).has_value());  // too short
  EXPECT_FALSE(world.raycast(glm::vec3(1), glm::vec3(1)).has_value());
  EXPECT_FALSE(world.raycast(glm::vec3(NAN), glm::vec3(0)).has_value());
}

TEST(PhysicsRaycast, IgnoresTriggers) {
  PhysicsWorld world;
  const BodyId ground = addGround(world);
  TriggerDef def;
  def.shape = world.createShape(ShapeDef::box(glm::vec3(1.0f))).value();
  def.position = glm::vec3(0, 2, 0);
  ASSERT_TRUE(world.createTrigger(def).ok());
  const std::optional<RayHit> hit = world.raycast(glm::vec3(0, 5, 0), glm::vec3(0, -5, 0));
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->body, ground);
}

TEST(PhysicsRaycast, HitsConcaveMeshInsideItsNotch) {
  PhysicsWorld world;
  const testing::LShape l = testing::makeLShape();
  const BodyId body =
      addBody(world, ShapeDef::concaveMesh(l.positions, l.indices), 0.0f, glm::vec3(0.0f));
  // Straight down into the notch: the hit is the notch floor (local y = 0.5 - centre), not the
  // top of the tall leg.
  const float x = 0.75f - testing::kLShapeCentre;
  const std::optional<RayHit> hit = world.raycast(glm::vec3(x, 3, 0), glm::vec3(x, -3, 0));
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->body, body);
  EXPECT_NEAR(hit->point.y, 0.5f - testing::kLShapeCentre, 1e-4f);
  EXPECT_NEAR(hit->normal.y, 1.0f, 1e-4f);
}

}  // namespace
}  // namespace cleave::physics
