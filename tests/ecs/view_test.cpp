// SPDX-License-Identifier: MIT
#include "cleave/ecs/view.h"

#include <gtest/gtest.h>

#include <vector>

#include "cleave/ecs/world.h"

namespace cleave::ecs {
namespace {

struct A {
  int value = 0;
};
struct B {
  float value = 0.0f;
};
struct C {
  int value = 0;
};

std::vector<Entity> collect(View<A, B>&& view) {
  std::vector<Entity> result;
  for (auto [entity, a, b] : view) result.push_back(entity);
  return result;
}

TEST(View, TwoTypesIncludeExactlyEntitiesWithBoth) {
  World world;
  const Entity onlyA = world.create();
  const Entity both1 = world.create();
  const Entity onlyB = world.create();
  const Entity both2 = world.create();
  const Entity none = world.create();
  (void)none;
  world.add(onlyA, A{1});
  world.add(both1, A{2});
  world.add(both1, B{2.5f});
  world.add(onlyB, B{3.5f});
  world.add(both2, B{4.5f});
  world.add(both2, A{4});
  const std::vector<Entity> expected{both1, both2};
  EXPECT_EQ(collect(world.view<A, B>()), expected);
}

TEST(View, ThreeTypesIncludeExactlyEntitiesWithAll) {
  World world;
  std::vector<Entity> entities;
  for (int i = 0; i < 16; ++i) {
    const Entity e = world.create();
    entities.push_back(e);
    if (i & 1) world.add(e, A{i});
    if (i & 2) world.add(e, B{static_cast<float>(i)});
    if (i & 4) world.add(e, C{i});
  }
  std::vector<Entity> seen;
  world.view<A, B, C>().each([&](Entity e, A& a, B& b, C& c) {
    EXPECT_EQ(a.value, c.value);
    EXPECT_EQ(static_cast<float>(a.value), b.value);
    seen.push_back(e);
  });
  const std::vector<Entity> expected{entities[7], entities[15]};
  EXPECT_EQ(seen, expected);
}

TEST(View, IteratesDenseOrderOfSmallestPool) {
  World world;
  std::vector<Entity> e;
  for (int i = 0; i < 5; ++i) e.push_back(world.create());
  for (int i = 0; i < 5; ++i) world.add(e[i], A{i});
  // B is the smaller pool; it was filled in the order 3, 0, 4.
  world.add(e[3], B{});
  world.add(e[0], B{});
  world.add(e[4], B{});
  const std::vector<Entity> expected{e[3], e[0], e[4]};
  EXPECT_EQ(collect(world.view<A, B>()), expected);
  // Removing the first B moves the last one (e[4]) into its place.
  world.remove<B>(e[3]);
  const std::vector<Entity> afterRemove{e[4], e[0]};
  EXPECT_EQ(collect(world.view<A, B>()), afterRemove);
}

TEST(View, StructuredBindingsGiveWritableReferences) {
  World world;
  const Entity e = world.create();
  world.add(e, A{1});
  world.add(e, B{1.0f});
  for (auto [entity, a, b] : world.view<A, B>()) {
    a.value = 10;
    b.value = 20.0f;
  }
  EXPECT_EQ(world.get<A>(e).value, 10);
  EXPECT_EQ(world.get<B>(e).value, 20.0f);
}

TEST(View, EmptyWhenATypeHasNoPool) {
  World world;
  const Entity e = world.create();
  world.add(e, A{1});
  int count = 0;
  world.view<A, C>().each([&](Entity, A&, C&) { ++count; });
  EXPECT_EQ(count, 0);
  EXPECT_EQ((world.view<A, C>().sizeHint()), 0u);
}

TEST(View, LocksStructuralChangesWhileAlive) {
  World world;
  EXPECT_TRUE(world.structuralChangesAllowed());
  {
    auto view = world.view<A>();
    EXPECT_FALSE(world.structuralChangesAllowed());
  }
  EXPECT_TRUE(world.structuralChangesAllowed());
}

TEST(View, StructuralChangeDuringIterationIsAPreconditionViolation) {
  World world;
  const Entity e = world.create();
  world.add(e, A{1});
  // Debug builds stop at the assert; release builds leave the World unchanged.
  EXPECT_DEBUG_DEATH(
      {
        for (auto [entity, a] : world.view<A>()) world.add(entity, B{2.0f});
      },
      "structural change");
  EXPECT_FALSE(world.has<B>(e));
  EXPECT_EQ(world.count<A>(), 1u);
}

}  // namespace
}  // namespace cleave::ecs
