// SPDX-License-Identifier: MIT
#include "cleave/components/split_budget.h"

#include <map>
#include <vector>

#include <gtest/gtest.h>

namespace cleave::components {
namespace {

ecs::Entity entity(uint32_t index) { return ecs::Entity{index, 1}; }

// A queue driven by hand: positions per entity, a set of live entities, and the order of execution.
struct Fixture {
  SplitBudget budget;
  std::map<uint32_t, glm::dvec3> positions;
  std::map<uint32_t, bool> alive;
  std::vector<uint32_t> executed;
  double clock = 0.0;

  // Every split is estimated at 0.1 ms unless a test says otherwise (the default budget is 4 ms).
  explicit Fixture(SplitBudgetSettings s = {}) : budget(s) {
    budget.setCostEstimator([](const SplitRequest&) { return SplitCost{0.1, 0.0}; });
  }

  void add(uint32_t index, glm::dvec3 position, bool player, uint64_t tick) {
    positions[index] = position;
    alive[index] = true;
    SplitRequest r;
    r.target = entity(index);
    r.playerCaused = player;
    r.requestedTick = tick;
    budget.enqueue(r);
  }
  void run(uint64_t tick, double msPerSplit = 0.1) {
    budget.runTick(
        tick, glm::dvec3(0.0), [&](ecs::Entity e) { return alive[e.index]; },
        [&](ecs::Entity e) { return positions[e.index]; },
        [&](const SplitRequest& r) {
          executed.push_back(r.target.index);
          clock += msPerSplit;
          return true;
        },
        [&] { return clock; });
  }
};

TEST(SplitBudget, PlayerFirstThenNearestThenOldest) {
  Fixture f;
  f.add(1, {5, 0, 0}, false, 0);
  f.add(2, {10, 0, 0}, true, 0);
  f.add(3, {1, 0, 0}, false, 0);
  f.add(4, {0, 1, 0}, false, 0);  // as near as 3, but later
  f.add(5, {2, 0, 0}, true, 0);
  f.run(1);
  EXPECT_EQ(f.executed, (std::vector<uint32_t>{5, 2, 3, 4, 1}));
  EXPECT_EQ(f.budget.stats().executed, 5u);
  EXPECT_EQ(f.budget.queueLength(), 0u);
}

TEST(SplitBudget, RequestsGatheredThisTickRunFromTheNextTick) {
  Fixture f;
  f.add(1, {0, 0, 0}, false, 3);
  f.run(3);
  EXPECT_TRUE(f.executed.empty());
  EXPECT_EQ(f.budget.stats().deferred, 1u);
  f.run(4);
  EXPECT_EQ(f.executed, (std::vector<uint32_t>{1}));
}

TEST(SplitBudget, StaleRequestsAreDroppedNotExecuted) {
  Fixture f;
  f.add(1, {0, 0, 0}, false, 0);
  f.add(2, {1, 0, 0}, false, 0);
  f.add(3, {2, 0, 0}, false, 0);
  f.alive[2] = false;
  f.run(1);
  EXPECT_EQ(f.executed, (std::vector<uint32_t>{1, 3}));
  EXPECT_EQ(f.budget.stats().dropped, 1u);
  EXPECT_EQ(f.budget.queueLength(), 0u);
}

TEST(SplitBudget, DeterministicBudgetStopsAfterTheSplitThatReachesIt) {
  SplitBudgetSettings s;
  s.millisecondsPerTick = 2.5;
  s.maxSplitsPerTick = 100;
  s.deterministic = true;
  Fixture f(s);
  f.budget.setCostEstimator([](const SplitRequest&) { return SplitCost{1.0, 0.0}; });
  for (uint32_t i = 1; i <= 7; ++i) f.add(i, {double(i), 0, 0}, false, 0);
  f.run(1, /*msPerSplit=*/50.0);  // measured time is ignored when deterministic
  EXPECT_EQ(f.executed.size(), 3u);
  EXPECT_DOUBLE_EQ(f.budget.stats().millisecondsCharged, 3.0);
  EXPECT_LE(f.budget.stats().millisecondsCharged, s.millisecondsPerTick + 1.0);
  EXPECT_EQ(f.budget.stats().deferred, 4u);
  f.run(2);
  f.run(3);
  EXPECT_EQ(f.executed, (std::vector<uint32_t>{1, 2, 3, 4, 5, 6, 7}));
}

TEST(SplitBudget, AtLeastOneSplitRunsEvenIfItAloneIsOverBudget) {
  SplitBudgetSettings s;
  s.millisecondsPerTick = 1.0;
  Fixture f(s);
  f.budget.setCostEstimator([](const SplitRequest&) { return SplitCost{5.0, 0.0}; });
  f.add(1, {0, 0, 0}, false, 0);
  f.add(2, {1, 0, 0}, false, 0);
  f.run(1);
  EXPECT_EQ(f.executed.size(), 1u);
  f.run(2);
  EXPECT_EQ(f.executed.size(), 2u);
}

TEST(SplitBudget, MeasuredModeChargesTheClock) {
  SplitBudgetSettings s;
  s.millisecondsPerTick = 1.0;
  s.deterministic = false;
  Fixture f(s);
  for (uint32_t i = 1; i <= 5; ++i) f.add(i, {double(i), 0, 0}, false, 0);
  f.run(1, /*msPerSplit=*/0.4);  // 0.4, 0.8, 1.2: stops after the third
  EXPECT_EQ(f.executed.size(), 3u);
  EXPECT_NEAR(f.budget.stats().millisecondsUsed, 1.2, 1e-9);
  EXPECT_NEAR(f.budget.stats().millisecondsCharged, 1.2, 1e-9);
}

TEST(SplitBudget, CountLimitPerTick) {
  SplitBudgetSettings s;
  s.maxSplitsPerTick = 2;
  s.millisecondsPerTick = 1000.0;
  Fixture f(s);
  for (uint32_t i = 1; i <= 5; ++i) f.add(i, {double(i), 0, 0}, false, 0);
  f.run(1);
  EXPECT_EQ(f.executed.size(), 2u);
  EXPECT_EQ(f.budget.stats().deferred, 3u);
}

TEST(SplitBudget, SecondRequestForTheSameTargetWaits) {
  SplitBudgetSettings s;
  s.millisecondsPerTick = 1000.0;
  Fixture f(s);
  f.add(1, {0, 0, 0}, false, 0);
  f.add(1, {0, 0, 0}, false, 0);
  f.run(1);
  EXPECT_EQ(f.executed.size(), 1u);
  f.alive[1] = false;  // the split destroyed it
  f.run(2);
  EXPECT_EQ(f.executed.size(), 1u);
  EXPECT_EQ(f.budget.stats().dropped, 1u);
}

TEST(SplitBudget, OverCapacityDropsTheLowestPriority) {
  SplitBudgetSettings s;
  s.maxQueueLength = 2;
  s.maxSplitsPerTick = 1;
  Fixture f(s);
  f.add(1, {9, 0, 0}, false, 0);
  f.add(2, {1, 0, 0}, false, 0);
  f.add(3, {5, 0, 0}, false, 0);
  f.run(1);
  EXPECT_EQ(f.budget.stats().dropped, 1u);
  f.run(2);
  f.run(3);
  EXPECT_EQ(f.executed, (std::vector<uint32_t>{2, 3}));
}

// The worker-time limit: splits whose compute is estimated at 3 ms each stop the tick after the one
// that reaches 8 ms of worker time, though the main thread has time left; the rest run next tick.
TEST(SplitBudget, WorkerTimeLimitStopsAfterTheSplitThatReachesIt) {
  SplitBudgetSettings s;
  s.millisecondsPerTick = 1000.0;
  s.maxSplitsPerTick = 100;
  s.workerMillisecondsPerTick = 8.0;
  s.deterministic = true;
  Fixture f(s);
  f.budget.setCostEstimator([](const SplitRequest&) { return SplitCost{0.1, 3.0}; });
  for (uint32_t i = 1; i <= 7; ++i) f.add(i, {double(i), 0, 0}, false, 0);
  f.run(1);
  EXPECT_EQ(f.executed, (std::vector<uint32_t>{1, 2, 3}));
  EXPECT_DOUBLE_EQ(f.budget.stats().workerMillisecondsCharged, 9.0);
  EXPECT_EQ(f.budget.stats().deferred, 4u);
  f.run(2);
  EXPECT_EQ(f.executed, (std::vector<uint32_t>{1, 2, 3, 4, 5, 6}));
  f.run(3);
  EXPECT_EQ(f.executed.size(), 7u);
  // One split alone over the worker limit still runs (and only it).
  f.budget.setCostEstimator([](const SplitRequest&) { return SplitCost{0.1, 50.0}; });
  f.add(8, {0, 0, 0}, false, 3);
  f.add(9, {1, 0, 0}, false, 3);
  f.run(4);
  EXPECT_EQ(f.executed.size(), 8u);
  EXPECT_EQ(f.executed.back(), 8u);
}

// A busy target (its split in flight) keeps its request queued while the others run; it runs once
// free, and a busy target that is gone meanwhile has its request dropped as stale.
TEST(SplitBudget, BusyTargetWaitsUntilFreeAndIsDroppedOnceGone) {
  SplitBudgetSettings s;
  s.millisecondsPerTick = 1000.0;
  Fixture f(s);
  std::map<uint32_t, bool> busy;
  f.budget.setBusyCheck([&](ecs::Entity e) { return busy[e.index]; });
  busy[1] = true;
  busy[3] = true;
  f.add(1, {0, 0, 0}, false, 0);
  f.add(2, {1, 0, 0}, false, 0);
  f.add(3, {2, 0, 0}, false, 0);
  f.run(1);
  EXPECT_EQ(f.executed, (std::vector<uint32_t>{2}));
  EXPECT_EQ(f.budget.stats().deferred, 2u);
  f.run(2);
  EXPECT_EQ(f.executed, (std::vector<uint32_t>{2}));  // still busy: still waiting, not dropped
  EXPECT_EQ(f.budget.queueLength(), 2u);
  busy[1] = false;
  f.alive[3] = false;
  f.run(3);
  EXPECT_EQ(f.executed, (std::vector<uint32_t>{2, 1}));
  EXPECT_EQ(f.budget.stats().dropped, 1u);
  EXPECT_EQ(f.budget.queueLength(), 0u);
}

TEST(SplitBudget, ActivationsAtMostNPerTickInCreationOrder) {
  SplitBudgetSettings s;
  s.maxActivationsPerTick = 16;
  SplitBudget budget(s);
  for (uint32_t k = 0; k < 40; ++k) budget.queueActivation(physics::BodyId{k, 1});
  const auto first = budget.takeActivations();
  const auto second = budget.takeActivations();
  const auto third = budget.takeActivations();
  ASSERT_EQ(first.size(), 16u);
  ASSERT_EQ(second.size(), 16u);
  ASSERT_EQ(third.size(), 8u);
  EXPECT_EQ(first.front(), (physics::BodyId{0, 1}));
  EXPECT_EQ(second.front(), (physics::BodyId{16, 1}));
  EXPECT_EQ(third.back(), (physics::BodyId{39, 1}));
  EXPECT_TRUE(budget.takeActivations().empty());
}

}  // namespace
}  // namespace cleave::components
