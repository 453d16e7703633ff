// SPDX-License-Identifier: MIT
#include "cleave/components/split_budget.h"

#include <algorithm>
#include <thread>

namespace cleave::components {

uint32_t defaultSplitThreads() {
  const unsigned hardware = std::thread::hardware_concurrency();
  return hardware > 1 ? uint32_t(hardware - 1) : 0u;
}

void SplitBudget::enqueue(SplitRequest request) {
  request.sequence = nextSequence_++;
  queue_.push_back(request);
}

void SplitBudget::clear() {
  queue_.clear();
  stats_ = {};
}

void SplitBudget::runTick(uint64_t currentTick, const glm::dvec3& cameraPosition, SplitBudgetHost& host) {
  stats_.executed = 0;
  stats_.deferred = 0;
  stats_.dropped = 0;
  stats_.failed = 0;
  stats_.millisecondsUsed = 0.0;
  stats_.millisecondsCharged = 0.0;
  stats_.workerMillisecondsCharged = 0.0;

  // Stale requests (the entity is gone, e.g. already split or destroyed by gameplay) are dropped.
  const size_t before = queue_.size();
  std::erase_if(queue_, [&](const SplitRequest& r) { return !host.isAlive(r.target); });
  stats_.dropped += uint32_t(before - queue_.size());

  // Priority: player-caused first, then nearer to the camera, then older.
  struct Keyed {
    bool player;
    double distance;
    uint64_t sequence;
    size_t index;
  };
  std::vector<Keyed> order;
  order.reserve(queue_.size());
  for (size_t i = 0; i < queue_.size(); ++i) {
    const SplitRequest& r = queue_[i];
    order.push_back({r.playerCaused, glm::length(host.positionOf(r.target) - cameraPosition), r.sequence, i});
  }
  std::sort(order.begin(), order.end(), [](const Keyed& a, const Keyed& b) {
    if (a.player != b.player) return a.player;
    if (a.distance != b.distance) return a.distance < b.distance;
    return a.sequence < b.sequence;
  });

  // Over capacity: the lowest-priority requests go.
  if (order.size() > settings_.maxQueueLength) {
    stats_.dropped += uint32_t(order.size() - settings_.maxQueueLength);
    order.resize(settings_.maxQueueLength);
  }

  std::vector<bool> done(queue_.size(), false);
  std::vector<bool> keep(queue_.size(), false);
  for (const Keyed& k : order) keep[k.index] = true;
  std::vector<ecs::Entity> splitThisTick;
  for (const Keyed& k : order) {
    const SplitRequest& r = queue_[k.index];
    if (r.requestedTick >= currentTick) continue;  // gathered this tick: runs from the next one
    if (stats_.executed >= settings_.maxSplitsPerTick) break;
    if (stats_.executed > 0 && (stats_.millisecondsCharged >= settings_.millisecondsPerTick ||
                                stats_.workerMillisecondsCharged >= settings_.workerMillisecondsPerTick))
      break;
    // A second request for a target split this tick waits; next tick its target is gone and the
    // request is dropped as stale (the pieces are new entities).
    if (std::find(splitThisTick.begin(), splitThisTick.end(), r.target) != splitThisTick.end()) continue;
    if (host.isBusy(r.target)) continue;  // its split is in flight: it waits
    const SplitCost estimate = host.estimate(r);
    const double start = host.nowMilliseconds();
    const bool ok = host.execute(r);
    const double spent = host.nowMilliseconds() - start;
    stats_.millisecondsUsed += spent;
    stats_.workerMillisecondsCharged += std::max(0.0, estimate.worker);
    if (settings_.deterministic) {
      stats_.millisecondsCharged += std::max(0.0, estimate.main);
      stats_.maxChargeMilliseconds = std::max(stats_.maxChargeMilliseconds, estimate.main);
    } else {
      stats_.millisecondsCharged += spent;
    }
    stats_.lastSplitMilliseconds = spent;
    stats_.maxSplitMilliseconds = std::max(stats_.maxSplitMilliseconds, spent);
    stats_.executed++;
    stats_.totalExecuted++;
    if (!ok) stats_.failed++;
    done[k.index] = true;
    splitThisTick.push_back(r.target);
  }

  std::vector<SplitRequest> remaining;
  remaining.reserve(queue_.size());
  for (size_t i = 0; i < queue_.size(); ++i)
    if (keep[i] && !done[i]) remaining.push_back(queue_[i]);
  queue_.swap(remaining);
  stats_.deferred = uint32_t(queue_.size());
  stats_.queueLength = uint32_t(queue_.size());
}

}  // namespace cleave::components
