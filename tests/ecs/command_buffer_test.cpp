// SPDX-License-Identifier: MIT
#include "cleave/ecs/command_buffer.h"

#include <gtest/gtest.h>

#include "cleave/ecs/hierarchy.h"
#include "cleave/ecs/world.h"

namespace cleave::ecs {
namespace {

struct Health {
  int value = 0;
};
struct Marker {
  int value = 0;
};

TEST(CommandBuffer, DestroyDuringIterationIsAppliedAfter) {
  World world;
  std::vector<Entity> entities;
  for (int i = 0; i < 10; ++i) {
    entities.push_back(world.create());
    world.add(entities.back(), Health{i % 3 == 0 ? 0 : 5});
  }
  CommandBuffer commands(world);
  int visited = 0;
  for (auto [entity, health] : world.view<Health>()) {
    ++visited;
    if (health.value <= 0) commands.destroy(entity);
    EXPECT_TRUE(world.alive(entity));  // nothing happens before apply
  }
  EXPECT_EQ(visited, 10);
  EXPECT_EQ(world.size(), 10u);
  const ApplyResult result = world.apply(commands);
  EXPECT_EQ(result.applied, 4u);
  EXPECT_EQ(result.skipped, 0u);
  EXPECT_TRUE(commands.empty());
  EXPECT_EQ(world.size(), 6u);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(world.alive(entities[i]), i % 3 != 0) << i;
  EXPECT_EQ(world.count<Health>(), 6u);
}

TEST(CommandBuffer, CreateAndAddInOneBuffer) {
  World world;
  const Entity existing = world.create();
  CommandBuffer commands(world);
  const Entity created = commands.create();
  EXPECT_FALSE(created.isNull());
  EXPECT_NE(created, existing);
  EXPECT_FALSE(world.alive(created));  // reserved, not alive yet
  commands.add(created, Health{42});
  commands.add(created, Marker{1});
  commands.add(existing, Marker{2});
  const ApplyResult result = world.apply(commands);
  EXPECT_EQ(result.applied, 4u);
  EXPECT_TRUE(world.alive(created));
  EXPECT_EQ(world.get<Health>(created).value, 42);
  EXPECT_EQ(world.get<Marker>(created).value, 1);
  EXPECT_EQ(world.get<Marker>(existing).value, 2);
}

TEST(CommandBuffer, ReservedIdCanBeStoredInComponentsBeforeApply) {
  World world;
  const Entity root = world.create();
  CommandBuffer commands(world);
  const Entity child = commands.create();
  commands.add(child, Parent{root});
  commands.add(root, Children{{child}});
  world.apply(commands);
  EXPECT_EQ(parentOf(world, child), root);
  EXPECT_EQ(destroyRecursive(world, root), 2u);
}

TEST(CommandBuffer, CommandsOnDeadEntitiesAreSkipped) {
  World world;
  const Entity e = world.create();
  CommandBuffer commands(world);
  commands.destroy(e);
  commands.destroy(e);          // destroyed twice
  commands.add(e, Health{1});   // after its destroy
  commands.remove<Health>(e);
  const ApplyResult result = world.apply(commands);
  EXPECT_EQ(result.applied, 1u);
  EXPECT_EQ(result.skipped, 3u);
  EXPECT_EQ(world.count<Health>(), 0u);
  EXPECT_EQ(world.size(), 0u);
}

TEST(CommandBuffer, RemoveIsApplied) {
  World world;
  const Entity e = world.create();
  world.add(e, Health{1});
  CommandBuffer commands(world);
  world.view<Health>().each([&](Entity entity, Health&) { commands.remove<Health>(entity); });
  world.apply(commands);
  EXPECT_FALSE(world.has<Health>(e));
  EXPECT_TRUE(world.alive(e));
}

TEST(CommandBuffer, DroppedBufferReturnsReservedIds) {
  World world;
  Entity reserved;
  {
    CommandBuffer commands(world);
    reserved = commands.create();
  }
  EXPECT_FALSE(world.alive(reserved));
  const Entity next = world.create();
  EXPECT_EQ(next.index, reserved.index);
  EXPECT_NE(next.generation, reserved.generation);
  EXPECT_EQ(world.size(), 1u);
}

TEST(CommandBuffer, AppliesInRecordingOrder) {
  World world;
  const Entity e = world.create();
  CommandBuffer commands(world);
  commands.add(e, Marker{1});
  commands.add(e, Marker{2});
  commands.remove<Marker>(e);
  commands.add(e, Marker{3});
  world.apply(commands);
  EXPECT_EQ(world.get<Marker>(e).value, 3);
}

}  // namespace
}  // namespace cleave::ecs
