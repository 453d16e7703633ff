// SPDX-License-Identifier: MIT
#include "cleave/ecs/world.h"

#include <gtest/gtest.h>

namespace cleave::ecs {
namespace {

struct Health {
  int value = 0;
};
struct Tag {};

TEST(Entity, NullEntityIsNullAndNeverAlive) {
  World world;
  EXPECT_TRUE(kNullEntity.isNull());
  EXPECT_FALSE(world.alive(kNullEntity));
  world.create();
  EXPECT_FALSE(world.alive(kNullEntity));
  EXPECT_FALSE(world.has<Health>(kNullEntity));
  EXPECT_EQ(world.tryGet<Health>(kNullEntity), nullptr);
  EXPECT_FALSE(world.destroy(kNullEntity));
}

TEST(Entity, OrdersByIndexThenGeneration) {
  EXPECT_LT((Entity{1, 5}), (Entity{2, 1}));
  EXPECT_LT((Entity{2, 1}), (Entity{2, 2}));
  EXPECT_EQ((Entity{3, 4}), (Entity{3, 4}));
  EXPECT_EQ(toString(Entity{12, 3}), "e12v3");
  EXPECT_EQ(toString(kNullEntity), "null");
}

TEST(World, CreateGivesDistinctLiveEntities) {
  World world;
  const Entity a = world.create();
  const Entity b = world.create();
  EXPECT_NE(a, b);
  EXPECT_TRUE(world.alive(a));
  EXPECT_TRUE(world.alive(b));
  EXPECT_FALSE(a.isNull());
  EXPECT_EQ(world.size(), 2u);
}

TEST(World, ReusedIdBumpsGenerationAndStaleIdIsNotAlive) {
  World world;
  const Entity first = world.create();
  ASSERT_TRUE(world.destroy(first));
  EXPECT_FALSE(world.alive(first));
  const Entity second = world.create();
  EXPECT_EQ(second.index, first.index);
  EXPECT_EQ(second.generation, first.generation + 1);
  EXPECT_TRUE(world.alive(second));
  EXPECT_FALSE(world.alive(first));
  EXPECT_FALSE(world.destroy(first));  // stale destroy must not hit the new entity
  EXPECT_TRUE(world.alive(second));
}

TEST(World, FreedSlotsAreReusedOldestFirst) {
  World world;
  const Entity a = world.create();
  const Entity b = world.create();
  const Entity c = world.create();
  world.destroy(b);
  world.destroy(a);
  world.destroy(c);
  EXPECT_EQ(world.create().index, b.index);
  EXPECT_EQ(world.create().index, a.index);
  EXPECT_EQ(world.create().index, c.index);
  EXPECT_EQ(world.create().index, 3u);
}

TEST(World, AddGetHasRemove) {
  World world;
  const Entity e = world.create();
  EXPECT_FALSE(world.has<Health>(e));
  EXPECT_EQ(world.tryGet<Health>(e), nullptr);
  world.add(e, Health{7});
  EXPECT_TRUE(world.has<Health>(e));
  EXPECT_EQ(world.get<Health>(e).value, 7);
  world.get<Health>(e).value = 9;
  ASSERT_NE(world.tryGet<Health>(e), nullptr);
  EXPECT_EQ(world.tryGet<Health>(e)->value, 9);
  EXPECT_FALSE(world.has<Tag>(e));
  EXPECT_TRUE(world.remove<Health>(e));
  EXPECT_FALSE(world.has<Health>(e));
  EXPECT_FALSE(world.remove<Health>(e));
  EXPECT_FALSE(world.remove<Tag>(e));
  EXPECT_TRUE(world.alive(e));
}

TEST(World, AddTwiceOverwrites) {
  World world;
  const Entity e = world.create();
  world.add(e, Health{1});
  world.add(e, Health{2});
  EXPECT_EQ(world.get<Health>(e).value, 2);
  EXPECT_EQ(world.count<Health>(), 1u);
}

TEST(World, RemoveKeepsOtherEntitiesComponents) {
  World world;
  std::vector<Entity> entities;
  for (int i = 0; i < 5; ++i) {
    entities.push_back(world.create());
    world.add(entities.back(), Health{i});
  }
  world.remove<Health>(entities[1]);  // swap-and-pop moves entity 4 into the hole
  for (int i = 0; i < 5; ++i) {
    if (i == 1) continue;
    EXPECT_EQ(world.get<Health>(entities[i]).value, i);
  }
}

TEST(World, DestroyRemovesAllComponentsAndReusedIdStartsEmpty) {
  World world;
  const Entity e = world.create();
  world.add(e, Health{3});
  world.add(e, Tag{});
  world.destroy(e);
  EXPECT_EQ(world.count<Health>(), 0u);
  EXPECT_EQ(world.count<Tag>(), 0u);
  EXPECT_FALSE(world.has<Health>(e));
  const Entity reused = world.create();
  ASSERT_EQ(reused.index, e.index);
  EXPECT_FALSE(world.has<Health>(reused));
  EXPECT_FALSE(world.has<Tag>(reused));
}

TEST(World, EntitiesAreAscendingByIndex) {
  World world;
  std::vector<Entity> created;
  for (int i = 0; i < 6; ++i) created.push_back(world.create());
  world.destroy(created[0]);
  world.destroy(created[3]);
  const Entity reused = world.create();  // takes slot 0 again
  const std::vector<Entity> expected{reused, created[1], created[2], created[4], created[5]};
  EXPECT_EQ(world.entities(), expected);
}

TEST(World, ConstAccessSeesComponents) {
  World world;
  const Entity e = world.create();
  world.add(e, Health{4});
  const World& view = world;
  EXPECT_EQ(view.get<Health>(e).value, 4);
  EXPECT_TRUE(view.has<Health>(e));
  EXPECT_EQ(view.tryGet<Tag>(e), nullptr);
}

}  // namespace
}  // namespace cleave::ecs
