// SplitBudget: the resource manager the thesis left as future work. Split requests wait in a
// priority queue; each tick the split system takes them in order while the tick's time and count
// budgets last, and the rest wait for later ticks. Requests whose entity is gone are dropped.
// Newly created bodies are activated at most `maxActivationsPerTick` per tick so a burst of pieces
// does not wake the whole solver at once.
//
// Priority: player-caused requests first, then by distance to the camera (near first), then by
// arrival order (older first). The order is total and deterministic.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "engine/ecs/entity.h"

namespace cleave::components {

struct SplitRequest {
  ecs::Entity target;                 // the entity carrying the Splitable
  glm::dvec3 planeNormal{0, 1, 0};    // world-space plane {x : dot(n, x) = offset}
  double planeOffset = 0.0;
  ecs::Entity splitter;               // who asked (may be null)
  bool playerCaused = false;
  uint64_t requestedTick = 0;         // the tick the request was gathered in (executed from N+1)
  uint64_t sequence = 0;              // arrival order, filled by the budget
};

struct SplitBudgetSettings {
  double millisecondsPerTick = 4.0;   // split work allowed per tick (at least one split always runs)
  uint32_t maxSplitsPerTick = 8;
  uint32_t maxActivationsPerTick = 16;
  uint32_t maxQueueLength = 1024;     // beyond this the lowest-priority requests are dropped
  // Deterministic scheduling: each split is charged its estimated cost (from the cost estimator,
  // e.g. triangles x a per-triangle cost) instead of the measured time, so the same input splits in
  // the same ticks on every run and machine (replays stay exact). The measured time is still
  // reported in the stats. False: charge the measured wall time (adapts to the machine, but the
  // schedule, and so the simulation, depends on timing).
  bool deterministic = true;
  // The split system's estimate of one split: a fixed part plus a part per triangle of the target
  // (collider building dominates; measured on the demo objects).
  double estimatedMillisecondsPerSplit = 0.3;
  double estimatedMillisecondsPerTriangle = 0.004;
};

struct SplitBudgetStats {
  uint32_t executed = 0;      // splits done this tick
  uint32_t deferred = 0;      // requests left waiting at the end of this tick
  uint32_t dropped = 0;       // stale or over-capacity requests dropped this tick
  uint32_t failed = 0;        // splits that failed this tick (original kept)
  double millisecondsUsed = 0.0;      // measured split time this tick
  double millisecondsCharged = 0.0;   // what the budget counted (the estimate when deterministic)
  double lastSplitMilliseconds = 0.0;
  double maxSplitMilliseconds = 0.0;  // over the whole run
  uint32_t queueLength = 0;
  uint32_t pendingActivations = 0;
  uint64_t totalExecuted = 0;
};

class SplitBudget {
 public:
  explicit SplitBudget(SplitBudgetSettings settings = {}) : settings_(settings) {}

  const SplitBudgetSettings& settings() const { return settings_; }
  void setSettings(const SplitBudgetSettings& settings) { settings_ = settings; }

  // Queues a request. A second request for the same target in the same tick is kept too (both
  // planes cut; the second one applies to the pieces that no longer exist and is dropped then).
  void enqueue(SplitRequest request);

  // Runs one tick's worth of requests gathered before `currentTick`. `isAlive` tells whether a
  // target still exists; `cameraPosition` and `positionOf` order non-player requests by distance;
  // `execute` performs one split and returns false if it failed. `nowMilliseconds` is a clock.
  void runTick(uint64_t currentTick, const glm::dvec3& cameraPosition,
               const std::function<bool(ecs::Entity)>& isAlive,
               const std::function<glm::dvec3(ecs::Entity)>& positionOf,
               const std::function<bool(const SplitRequest&)>& execute,
               const std::function<double()>& nowMilliseconds);

  // Estimated milliseconds of one request, used when settings().deterministic is true. Without an
  // estimator every split is charged millisecondsPerTick (one split per tick).
  void setCostEstimator(std::function<double(const SplitRequest&)> estimator) {
    estimator_ = std::move(estimator);
  }

  // Bodies created by splits wait here and are activated by takeActivations, a few per tick.
  void queueActivation(uint64_t bodyKey) { activations_.push_back(bodyKey); }
  // Returns up to maxActivationsPerTick keys in creation order and removes them from the queue.
  std::vector<uint64_t> takeActivations();

  const SplitBudgetStats& stats() const { return stats_; }
  size_t queueLength() const { return queue_.size(); }
  void clear();

 private:
  SplitBudgetSettings settings_;
  SplitBudgetStats stats_;
  std::vector<SplitRequest> queue_;
  std::vector<uint64_t> activations_;
  uint64_t nextSequence_ = 0;
  std::function<double(const SplitRequest&)> estimator_;
  double chargedMilliseconds_ = 0.0;
};

}  // namespace cleave::components
