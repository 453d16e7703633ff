// SPDX-License-Identifier: MIT
#include "cleave/ecs/hierarchy.h"

#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>

#include "cleave/ecs/command_buffer.h"

namespace cleave::ecs {
namespace {

glm::vec3 transformPoint(const glm::mat4& m, glm::vec3 p) {
  return glm::vec3(m * glm::vec4(p, 1.0f));
}

void expectNear(glm::vec3 actual, glm::vec3 expected, float tolerance = 1e-5f) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

Entity makeNode(World& world, Transform transform) {
  const Entity e = world.create();
  world.add(e, transform);
  return e;
}

TEST(Hierarchy, LocalMatrixAppliesScaleThenRotationThenTranslation) {
  Transform t;
  t.position = {1.0f, 2.0f, 3.0f};
  t.rotation = glm::angleAxis(glm::half_pi<float>(), glm::vec3(0, 0, 1));
  t.scale = {2.0f, 2.0f, 2.0f};
  // (1,0,0) -> scale (2,0,0) -> rotate 90 deg about z (0,2,0) -> translate (1,4,3)
  expectNear(transformPoint(localMatrix(t), {1, 0, 0}), {1, 4, 3});
}

TEST(Hierarchy, TranslationChainAddsUp) {
  World world;
  const Entity a = makeNode(world, Transform{{1, 0, 0}, {1, 0, 0, 0}, {1, 1, 1}});
  const Entity b = makeNode(world, Transform{{0, 2, 0}, {1, 0, 0, 0}, {1, 1, 1}});
  const Entity c = makeNode(world, Transform{{0, 0, 3}, {1, 0, 0, 0}, {1, 1, 1}});
  ASSERT_TRUE(setParent(world, b, a).ok());
  ASSERT_TRUE(setParent(world, c, b).ok());
  ASSERT_TRUE(updateWorldTransforms(world).ok());
  expectNear(transformPoint(world.get<WorldTransform>(c).matrix, {0, 0, 0}), {1, 2, 3});
  expectNear(transformPoint(world.get<WorldTransform>(b).matrix, {0, 0, 0}), {1, 2, 0});
}

TEST(Hierarchy, RotationAndScaleOfParentApplyToChildOffset) {
  World world;
  Transform parentLocal;
  parentLocal.position = {10, 0, 0};
  parentLocal.rotation = glm::angleAxis(glm::half_pi<float>(), glm::vec3(0, 1, 0));
  parentLocal.scale = {3, 3, 3};
  const Entity parent = makeNode(world, parentLocal);
  const Entity child = makeNode(world, Transform{{1, 0, 0}, {1, 0, 0, 0}, {1, 1, 1}});
  ASSERT_TRUE(setParent(world, child, parent).ok());
  ASSERT_TRUE(updateWorldTransforms(world).ok());
  // Child origin: (1,0,0) scaled to (3,0,0), rotated 90 deg about y to (0,0,-3), moved by (10,0,0).
  expectNear(transformPoint(world.get<WorldTransform>(child).matrix, {0, 0, 0}), {10, 0, -3});
}

TEST(Hierarchy, ChildCreatedBeforeParentIsStillComputedParentFirst) {
  World world;
  const Entity child = makeNode(world, Transform{{0, 1, 0}, {1, 0, 0, 0}, {1, 1, 1}});
  const Entity parent = makeNode(world, Transform{{5, 0, 0}, {1, 0, 0, 0}, {2, 2, 2}});
  ASSERT_TRUE(setParent(world, child, parent).ok());
  ASSERT_TRUE(updateWorldTransforms(world).ok());
  expectNear(transformPoint(world.get<WorldTransform>(child).matrix, {0, 0, 0}), {5, 2, 0});
}

TEST(Hierarchy, ReparentingMovesChildAndUpdatesChildrenLists) {
  World world;
  const Entity a = makeNode(world, Transform{{1, 0, 0}, {1, 0, 0, 0}, {1, 1, 1}});
  const Entity b = makeNode(world, Transform{{0, 0, 7}, {1, 0, 0, 0}, {1, 1, 1}});
  const Entity child = makeNode(world, Transform{{0, 1, 0}, {1, 0, 0, 0}, {1, 1, 1}});
  ASSERT_TRUE(setParent(world, child, a).ok());
  ASSERT_TRUE(setParent(world, child, b).ok());
  EXPECT_TRUE(world.get<Children>(a).entities.empty());
  EXPECT_EQ(world.get<Children>(b).entities, std::vector<Entity>{child});
  EXPECT_EQ(parentOf(world, child), b);
  ASSERT_TRUE(updateWorldTransforms(world).ok());
  expectNear(transformPoint(world.get<WorldTransform>(child).matrix, {0, 0, 0}), {0, 1, 7});

  ASSERT_TRUE(setParent(world, child, kNullEntity).ok());
  EXPECT_FALSE(world.has<Parent>(child));
  EXPECT_TRUE(world.get<Children>(b).entities.empty());
  ASSERT_TRUE(updateWorldTransforms(world).ok());
  expectNear(transformPoint(world.get<WorldTransform>(child).matrix, {0, 0, 0}), {0, 1, 0});
}

TEST(Hierarchy, SetParentRejectsCyclesSelfAndDeadEntities) {
  World world;
  const Entity a = world.create();
  const Entity b = world.create();
  const Entity c = world.create();
  ASSERT_TRUE(setParent(world, b, a).ok());
  ASSERT_TRUE(setParent(world, c, b).ok());
  const HierarchyStatus cycle = setParent(world, a, c);
  EXPECT_FALSE(cycle.ok());
  EXPECT_NE(cycle.message.find("cycle"), std::string::npos) << cycle.message;
  EXPECT_FALSE(world.has<Parent>(a));
  EXPECT_FALSE(setParent(world, a, a).ok());
  const Entity dead = world.create();
  world.destroy(dead);
  EXPECT_FALSE(setParent(world, a, dead).ok());
  EXPECT_FALSE(setParent(world, dead, a).ok());
}

TEST(Hierarchy, CycleMadeByDirectEditsIsReportedAndTreatedAsRoot) {
  World world;
  const Entity a = makeNode(world, Transform{{1, 0, 0}, {1, 0, 0, 0}, {1, 1, 1}});
  const Entity b = makeNode(world, Transform{{0, 1, 0}, {1, 0, 0, 0}, {1, 1, 1}});
  world.add(a, Parent{b});
  world.add(b, Parent{a});
  const HierarchyStatus status = updateWorldTransforms(world);
  EXPECT_FALSE(status.ok());
  EXPECT_NE(status.message.find("cycle"), std::string::npos) << status.message;
  // Walk from a (lowest index): a -> b -> a; b is reached last and becomes the root.
  expectNear(transformPoint(world.get<WorldTransform>(b).matrix, {0, 0, 0}), {0, 1, 0});
  expectNear(transformPoint(world.get<WorldTransform>(a).matrix, {0, 0, 0}), {1, 1, 0});
}

TEST(Hierarchy, DestroyRecursiveRemovesSubtreeOnly) {
  World world;
  const Entity root = world.create();
  const Entity keep = world.create();
  const Entity child1 = world.create();
  const Entity child2 = world.create();
  const Entity grandchild = world.create();
  ASSERT_TRUE(setParent(world, keep, root).ok());
  ASSERT_TRUE(setParent(world, child1, keep).ok());
  ASSERT_TRUE(setParent(world, child2, keep).ok());
  ASSERT_TRUE(setParent(world, grandchild, child2).ok());
  EXPECT_EQ(destroyRecursive(world, keep), 4u);
  EXPECT_TRUE(world.alive(root));
  EXPECT_FALSE(world.alive(keep));
  EXPECT_FALSE(world.alive(child1));
  EXPECT_FALSE(world.alive(child2));
  EXPECT_FALSE(world.alive(grandchild));
  EXPECT_TRUE(world.get<Children>(root).entities.empty());
  EXPECT_EQ(destroyRecursive(world, keep), 0u);
  EXPECT_EQ(world.size(), 1u);
}

TEST(Hierarchy, DestroyRecursiveThroughCommandBuffer) {
  World world;
  const Entity root = world.create();
  const Entity child = world.create();
  ASSERT_TRUE(setParent(world, child, root).ok());
  world.add(root, Name{"root"});
  CommandBuffer commands(world);
  world.view<Name>().each([&](Entity e, Name&) { commands.destroyRecursive(e); });
  EXPECT_TRUE(world.alive(child));
  world.apply(commands);
  EXPECT_EQ(world.size(), 0u);
}

TEST(Hierarchy, PlainDestroyOfParentLeavesChildAsRoot) {
  World world;
  const Entity parent = makeNode(world, Transform{{4, 0, 0}, {1, 0, 0, 0}, {1, 1, 1}});
  const Entity child = makeNode(world, Transform{{0, 1, 0}, {1, 0, 0, 0}, {1, 1, 1}});
  ASSERT_TRUE(setParent(world, child, parent).ok());
  world.destroy(parent);
  EXPECT_EQ(parentOf(world, child), kNullEntity);
  ASSERT_TRUE(updateWorldTransforms(world).ok());
  expectNear(transformPoint(world.get<WorldTransform>(child).matrix, {0, 0, 0}), {0, 1, 0});
}

}  // namespace
}  // namespace cleave::ecs
