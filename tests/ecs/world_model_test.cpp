// SPDX-License-Identifier: MIT
// Random create/destroy/add/remove sequences checked against a simple reference model.
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <set>
#include <vector>

#include "cleave/ecs/command_buffer.h"
#include "cleave/ecs/world.h"

namespace cleave::ecs {
namespace {

struct Value {
  uint32_t number = 0;
};
struct Flag {
  bool on = false;
};

struct Model {
  std::set<Entity> alive;
  std::vector<Entity> dead;  // every id ever destroyed
  std::map<Entity, uint32_t> values;
  std::set<Entity> flags;
};

void expectMatches(World& world, const Model& model) {
  ASSERT_EQ(world.size(), model.alive.size());
  const std::vector<Entity> listed = world.entities();
  ASSERT_EQ(std::set<Entity>(listed.begin(), listed.end()), model.alive);
  ASSERT_TRUE(std::is_sorted(listed.begin(), listed.end()));
  for (const Entity e : model.dead) {
    ASSERT_FALSE(world.alive(e));
    ASSERT_FALSE(world.has<Value>(e));
  }
  ASSERT_EQ(world.count<Value>(), model.values.size());
  for (const auto& [e, number] : model.values) ASSERT_EQ(world.get<Value>(e).number, number);
  std::map<Entity, uint32_t> viewed;
  std::set<Entity> both;
  for (auto [e, value] : world.view<Value>()) viewed[e] = value.number;
  world.view<Value, Flag>().each([&](Entity e, Value&, Flag&) { both.insert(e); });
  ASSERT_EQ(viewed, model.values);
  std::set<Entity> expectedBoth;
  for (const Entity e : model.flags)
    if (model.values.count(e)) expectedBoth.insert(e);
  ASSERT_EQ(both, expectedBoth);
}

Entity pick(const std::set<Entity>& entities, std::mt19937& rng) {
  auto it = entities.begin();
  std::advance(it, rng() % entities.size());
  return *it;
}

TEST(WorldModel, RandomOperationsMatchReferenceModel) {
  std::mt19937 rng(12345);
  World world;
  Model model;
  for (int step = 0; step < 4000; ++step) {
    const uint32_t op = rng() % 100;
    if (op < 30 || model.alive.empty()) {
      const Entity e = world.create();
      ASSERT_FALSE(model.alive.count(e));
      model.alive.insert(e);
    } else if (op < 50) {
      const Entity e = pick(model.alive, rng);
      ASSERT_TRUE(world.destroy(e));
      model.alive.erase(e);
      model.dead.push_back(e);
      model.values.erase(e);
      model.flags.erase(e);
    } else if (op < 55 && !model.dead.empty()) {
      ASSERT_FALSE(world.destroy(model.dead[rng() % model.dead.size()]));
    } else if (op < 75) {
      const Entity e = pick(model.alive, rng);
      const uint32_t number = rng();
      world.add(e, Value{number});
      model.values[e] = number;
    } else if (op < 85) {
      const Entity e = pick(model.alive, rng);
      ASSERT_EQ(world.remove<Value>(e), model.values.erase(e) == 1);
    } else if (op < 92) {
      const Entity e = pick(model.alive, rng);
      world.add(e, Flag{true});
      model.flags.insert(e);
    } else {
      // Deferred: destroy every entity whose value is odd, through a buffer during iteration.
      CommandBuffer commands(world);
      for (auto [e, value] : world.view<Value>())
        if (value.number % 2 == 1) commands.destroy(e);
      const Entity spawned = commands.create();
      commands.add(spawned, Value{2});
      world.apply(commands);
      for (auto it = model.values.begin(); it != model.values.end();) {
        if (it->second % 2 == 1) {
          model.alive.erase(it->first);
          model.dead.push_back(it->first);
          model.flags.erase(it->first);
          it = model.values.erase(it);
        } else {
          ++it;
        }
      }
      model.alive.insert(spawned);
      model.values[spawned] = 2;
    }
    if (step % 50 == 0) {
      expectMatches(world, model);
      if (::testing::Test::HasFatalFailure()) FAIL() << "at step " << step;
    }
  }
  expectMatches(world, model);
}

TEST(WorldModel, SameOperationsGiveSameIds) {
  auto run = [] {
    std::mt19937 rng(99);
    World world;
    std::vector<Entity> live;
    std::vector<Entity> log;
    for (int i = 0; i < 500; ++i) {
      if (live.empty() || rng() % 3 != 0) {
        live.push_back(world.create());
        log.push_back(live.back());
      } else {
        const size_t at = rng() % live.size();
        world.destroy(live[at]);
        live.erase(live.begin() + static_cast<std::ptrdiff_t>(at));
      }
    }
    return log;
  };
  EXPECT_EQ(run(), run());
}

}  // namespace
}  // namespace cleave::ecs
