// SPDX-License-Identifier: MIT
#include "cleave/components/activation_throttle.h"
#include "cleave/components/split_budget.h"

#include <map>
#include <vector>

#include <gtest/gtest.h>

namespace cleave::components {
namespace {

ecs::Entity entity(uint32_t index) { return ecs::Entity{index, 1}; }

// A queue driven by hand: positions per entity, a set of live entities, the busy ones, a cost per
// split, and the order of execution.
struct Fixture : SplitBudgetHost {
  SplitBudget budget;
  std::map<uint32_t, glm::dvec3> positions;
  std::map<uint32_t, bool> alive;
  std::map<uint32_t, bool> busy;
  std::vector<uint32_t> executed;
  double clock = 0.0;
  double msPerSplit = 0.1;  // measured main-thread time of one split
  SplitCost cost{0.1, 0.0};  // every split is estimated at 0.1 ms unless a test says otherwise (the default budget is 4 ms)

  explicit Fixture(SplitBudgetSettings s = {}) : budget(s) {}

  bool isAlive(ecs::Entity e) const override { return alive.count(e.index) && alive.at(e.index); }
  glm::dvec3 positionOf(ecs::Entity e) const override { return positions.at(e.index); }
  bool isBusy(ecs::Entity e) const override { return busy.count(e.index) && busy.at(e.index); }
  SplitCost estimate(const SplitRequest&) const override { return cost; }
  bool execute(const SplitRequest& r) override {
    executed.push_back(r.target.index);
    clock += msPerSplit;
    return true;
  }
  double nowMilliseconds() const override { return clock; }

  void add(uint32_t index, glm::dvec3 position, bool player, uint64_t tick) {
    positions[index] = position;
    alive[index] = true;
    SplitRequest r;
    r.target = entity(index);
    r.playerCaused = player;
    r.requestedTick = tick;
    budget.enqueue(r);
  }
  void run(uint64_t tick, double measuredPerSplit = 0.1) {
    msPerSplit = measuredPerSplit;
    budget.runTick(tick, glm::dvec3(0.0), *this);
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
  f.cost = SplitCost{1.0, 0.0};
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
  f.cost = SplitCost{5.0, 0.0};
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
  f.cost = SplitCost{0.1, 3.0};
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
  f.cost = SplitCost{0.1, 50.0};
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
  f.busy[1] = true;
  f.busy[3] = true;
  f.add(1, {0, 0, 0}, false, 0);
  f.add(2, {1, 0, 0}, false, 0);
  f.add(3, {2, 0, 0}, false, 0);
  f.run(1);
  EXPECT_EQ(f.executed, (std::vector<uint32_t>{2}));
  EXPECT_EQ(f.budget.stats().deferred, 2u);
  f.run(2);
  EXPECT_EQ(f.executed, (std::vector<uint32_t>{2}));  // still busy: still waiting, not dropped
  EXPECT_EQ(f.budget.queueLength(), 2u);
  f.busy[1] = false;
  f.alive[3] = false;
  f.run(3);
  EXPECT_EQ(f.executed, (std::vector<uint32_t>{2, 1}));
  EXPECT_EQ(f.budget.stats().dropped, 1u);
  EXPECT_EQ(f.budget.queueLength(), 0u);
}

TEST(ActivationThrottle, AtMostNPerTickInCreationOrder) {
  ActivationThrottle throttle;
  for (uint32_t k = 0; k < 40; ++k) throttle.queue(physics::BodyId{k, 1});
  const auto first = throttle.beginTick(16);
  const auto second = throttle.beginTick(16);
  const auto third = throttle.beginTick(16);
  ASSERT_EQ(first.size(), 16u);
  ASSERT_EQ(second.size(), 16u);
  ASSERT_EQ(third.size(), 8u);
  EXPECT_EQ(first.front(), (physics::BodyId{0, 1}));
  EXPECT_EQ(second.front(), (physics::BodyId{16, 1}));
  EXPECT_EQ(third.back(), (physics::BodyId{39, 1}));
  EXPECT_TRUE(throttle.beginTick(16).empty());
}

// Queued bodies woken at the start of a tick take its room first; new bodies start awake while room
// is left and are queued after.
TEST(ActivationThrottle, WokenBodiesAndNewOnesShareTheTicksRoom) {
  ActivationThrottle throttle;
  for (uint32_t k = 0; k < 3; ++k) throttle.queue(physics::BodyId{k, 1});
  EXPECT_EQ(throttle.beginTick(4).size(), 3u);
  EXPECT_TRUE(throttle.admitAwake(4));
  EXPECT_FALSE(throttle.admitAwake(4));
  throttle.queue(physics::BodyId{9, 1});
  EXPECT_EQ(throttle.queued(), 1u);
  EXPECT_EQ(throttle.beginTick(4).size(), 1u);  // the next tick: room again
  EXPECT_TRUE(throttle.admitAwake(4));
}

}  // namespace
}  // namespace cleave::components
