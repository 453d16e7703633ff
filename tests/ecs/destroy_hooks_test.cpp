// SPDX-License-Identifier: MIT
// Destroy hooks (World::onDestroy): when they run (remove, destroy, clear, a command buffer's
// playback; not on overwrite, not when the World is dropped), in which order, with which value,
// and what a hook may do (destroy its own or another entity, remove another component).
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "cleave/ecs/command_buffer.h"
#include "cleave/ecs/hierarchy.h"
#include "cleave/ecs/world.h"

namespace cleave::ecs {
namespace {

struct Body {
  int id = 0;
};
struct Mesh {
  int id = 0;
};
struct Label {
  std::string text;
};

TEST(DestroyHooks, RemoveRunsTheHookOnceWithTheLastValueNoLongerStored) {
  World world;
  const Entity e = world.create();
  world.add(e, Body{7});
  std::vector<int> freed;
  bool storedDuringHook = true;
  world.onDestroy<Body>([&](World& w, Entity who, Body& body) {
    EXPECT_EQ(who, e);
    storedDuringHook = w.has<Body>(who);
    freed.push_back(body.id);
  });
  EXPECT_TRUE(world.remove<Body>(e));
  EXPECT_FALSE(world.remove<Body>(e));  // nothing left: no second call
  EXPECT_EQ(freed, std::vector<int>{7});
  EXPECT_FALSE(storedDuringHook);
  EXPECT_TRUE(world.alive(e));
}

TEST(DestroyHooks, OverwritingAComponentRunsNoHook) {
  World world;
  const Entity e = world.create();
  int calls = 0;
  world.onDestroy<Body>([&](World&, Entity, Body&) { ++calls; });
  world.add(e, Body{1});
  world.add(e, Body{2});
  EXPECT_EQ(calls, 0);
  world.destroy(e);
  EXPECT_EQ(calls, 1);
}

TEST(DestroyHooks, DestroyRunsTypesInTheOrderOfTheirFirstHookAndHooksOfATypeInRegistrationOrder) {
  World world;
  std::vector<std::string> log;
  // Mesh gets its first hook before Body: Mesh's hooks run first, whatever the add order.
  world.onDestroy<Mesh>([&](World& w, Entity e, Mesh& m) {
    // Body's hooks have not run yet: the entity is alive and still has its Body and its Label.
    EXPECT_TRUE(w.alive(e));
    EXPECT_TRUE(w.has<Body>(e));
    EXPECT_TRUE(w.has<Label>(e));
    log.push_back("mesh1:" + std::to_string(m.id));
  });
  world.onDestroy<Body>([&](World& w, Entity e, Body& b) {
    EXPECT_FALSE(w.has<Mesh>(e));
    log.push_back("body:" + std::to_string(b.id));
  });
  world.onDestroy<Mesh>([&](World&, Entity, Mesh& m) { log.push_back("mesh2:" + std::to_string(m.id)); });
  const Entity e = world.create();
  world.add(e, Body{1});
  world.add(e, Label{"crate"});
  world.add(e, Mesh{2});
  const Entity plain = world.create();
  world.add(plain, Label{"no hooked component"});
  EXPECT_TRUE(world.destroy(e));
  EXPECT_EQ(log, (std::vector<std::string>{"mesh1:2", "mesh2:2", "body:1"}));
  EXPECT_FALSE(world.alive(e));
  EXPECT_EQ(world.count<Body>() + world.count<Mesh>(), 0u);
  EXPECT_EQ(world.count<Label>(), 1u);
  log.clear();
  EXPECT_TRUE(world.destroy(plain));
  EXPECT_TRUE(log.empty());
}

TEST(DestroyHooks, AHookMayDestroyAnotherEntityButNotItsOwnTwice) {
  World world;
  const Entity a = world.create();
  const Entity b = world.create();
  world.add(a, Body{1});
  world.add(b, Body{2});
  std::vector<int> freed;
  std::vector<bool> ownDestroy;
  world.onDestroy<Body>([&](World& w, Entity e, Body& body) {
    freed.push_back(body.id);
    ownDestroy.push_back(w.destroy(e));       // already being destroyed: refused
    if (body.id == 1) {
      EXPECT_TRUE(w.destroy(b));  // nested: b's hook runs now
    }
  });
  EXPECT_TRUE(world.destroy(a));
  EXPECT_EQ(freed, (std::vector<int>{1, 2}));
  EXPECT_EQ(ownDestroy, (std::vector<bool>{false, false}));
  EXPECT_FALSE(world.alive(a));
  EXPECT_FALSE(world.alive(b));
  EXPECT_EQ(world.size(), 0u);
  // Both slots are free again and reused in the order they were freed (b inside a's destroy).
  EXPECT_EQ(world.create().index, b.index);
  EXPECT_EQ(world.create().index, a.index);
}

TEST(DestroyHooks, AHookRemovingAnotherComponentOfItsEntityRunsThatHookOnce) {
  World world;
  int meshCalls = 0;
  world.onDestroy<Body>([&](World& w, Entity e, Body&) { EXPECT_TRUE(w.remove<Mesh>(e)); });
  world.onDestroy<Mesh>([&](World&, Entity, Mesh&) { ++meshCalls; });
  const Entity e = world.create();
  world.add(e, Body{1});
  world.add(e, Mesh{1});
  world.destroy(e);
  EXPECT_EQ(meshCalls, 1);
}

TEST(DestroyHooks, ComponentsAHookAddsToItsDyingEntityGoWithIt) {
  World world;
  world.onDestroy<Body>([&](World& w, Entity e, Body&) { w.add(e, Mesh{9}); });
  const Entity e = world.create();
  world.add(e, Body{1});
  world.destroy(e);
  EXPECT_EQ(world.count<Mesh>(), 0u);
}

TEST(DestroyHooks, CommandBufferDestroysAndRemovesRunHooksAtPlaybackOnly) {
  World world;
  std::vector<int> freed;
  world.onDestroy<Body>([&](World&, Entity, Body& b) { freed.push_back(b.id); });
  const Entity a = world.create();
  const Entity b = world.create();
  world.add(a, Body{1});
  world.add(b, Body{2});
  CommandBuffer commands(world);
  for (auto [e, body] : world.view<Body>()) {
    if (body.id == 1) commands.destroy(e);
    if (body.id == 2) commands.remove<Body>(e);
  }
  commands.destroy(a);  // twice: skipped, no second hook
  EXPECT_TRUE(freed.empty());
  const ApplyResult applied = world.apply(commands);
  EXPECT_EQ(applied.applied, 2u);
  EXPECT_EQ(applied.skipped, 1u);
  EXPECT_EQ(freed, (std::vector<int>{1, 2}));
  EXPECT_TRUE(world.alive(b));
}

TEST(DestroyHooks, DestroyRecursiveRunsTheHooksOfTheWholeSubtree) {
  World world;
  std::vector<int> freed;
  world.onDestroy<Mesh>([&](World&, Entity, Mesh& m) { freed.push_back(m.id); });
  const Entity root = world.create();
  const Entity child = world.create();
  const Entity grandchild = world.create();
  world.add(root, Mesh{1});
  world.add(child, Mesh{2});
  world.add(grandchild, Mesh{3});
  setParent(world, child, root);
  setParent(world, grandchild, child);
  CommandBuffer commands(world);
  commands.destroyRecursive(root);
  world.apply(commands);
  EXPECT_EQ(freed, (std::vector<int>{1, 2, 3}));  // pre-order
  EXPECT_EQ(world.size(), 0u);
}

TEST(DestroyHooks, ClearRunsEveryHookIncludingThoseOfEntitiesHooksCreate) {
  World world;
  std::vector<int> freed;
  world.onDestroy<Body>([&](World& w, Entity, Body& b) {
    freed.push_back(b.id);
    if (b.id == 2) w.add(w.create(), Body{20});  // made while clearing: cleared too
  });
  for (int id = 1; id <= 3; ++id) world.add(world.create(), Body{id});
  world.add(world.create(), Label{"no body"});
  EXPECT_EQ(world.clear(), 5u);
  EXPECT_EQ(freed, (std::vector<int>{1, 2, 3, 20}));
  EXPECT_EQ(world.size(), 0u);
  EXPECT_EQ(world.count<Body>(), 0u);
}

TEST(DestroyHooks, DroppingTheWorldRunsNoHookAndReleasesTheHooks) {
  auto calls = std::make_shared<int>(0);
  {
    World world;
    world.onDestroy<Body>([calls](World&, Entity, Body&) { ++*calls; });
    EXPECT_EQ(calls.use_count(), 2);
    world.add(world.create(), Body{1});
  }
  EXPECT_EQ(*calls, 0);
  EXPECT_EQ(calls.use_count(), 1);
}

TEST(DestroyHooks, RemovedHookNoLongerRunsAndItsTypeLosesItsPlace) {
  World world;
  std::vector<std::string> log;
  const HookId body = world.onDestroy<Body>([&](World&, Entity, Body&) { log.push_back("body"); });
  world.onDestroy<Mesh>([&](World&, Entity, Mesh&) { log.push_back("mesh"); });
  EXPECT_NE(body, 0u);
  EXPECT_TRUE(world.removeHook(body));
  EXPECT_FALSE(world.removeHook(body));
  EXPECT_FALSE(world.removeHook(0));
  world.onDestroy<Body>([&](World&, Entity, Body&) { log.push_back("body again"); });  // now after Mesh
  const Entity e = world.create();
  world.add(e, Body{1});
  world.add(e, Mesh{1});
  world.destroy(e);
  EXPECT_EQ(log, (std::vector<std::string>{"mesh", "body again"}));
  EXPECT_EQ(world.onDestroy<Body>(std::function<void(World&, Entity, Body&)>{}), 0u);
}

TEST(DestroyHooks, RegisteringAHookInsideAHookIsAPreconditionViolation) {
  World world;
  HookId inner = 99;
  world.onDestroy<Body>([&](World& w, Entity, Body&) {
    inner = w.onDestroy<Mesh>([](World&, Entity, Mesh&) {});
  });
  const Entity e = world.create();
  world.add(e, Body{1});
  // Debug builds stop at the assert; release builds refuse the hook (id 0).
  EXPECT_DEBUG_DEATH(world.destroy(e), "outside hooks");
#ifdef NDEBUG
  EXPECT_EQ(inner, 0u);
  EXPECT_FALSE(world.alive(e));
#endif
}

}  // namespace
}  // namespace cleave::ecs
