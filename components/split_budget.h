// SPDX-License-Identifier: MIT
// SplitBudget: the resource manager the thesis left as future work. Split requests wait in a
// priority queue; each tick the split system takes them in order while the tick's time and count
// budgets last, and the rest wait for later ticks. Requests whose entity is gone are dropped. What
// the budget needs of the world (is a target alive, where is it, is its split in flight, what will
// its split cost, do it, what time is it) it asks through one SplitBudgetHost per tick.
// (Newly created bodies are woken a few per tick by the ActivationThrottle, activation_throttle.h.)
//
// Priority: player-caused requests first, then by distance to the camera (near first), then by
// arrival order (older first). The order is total and deterministic.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "cleave/components/shatter.h"
#include "cleave/ecs/entity.h"

namespace cleave::components {

struct SplitRequest {
  ecs::Entity target;                 // the entity carrying the Splitable
  glm::dvec3 planeNormal{0, 1, 0};    // world-space plane {x : dot(n, x) = offset}
  double planeOffset = 0.0;
  ecs::Entity splitter;               // who asked (may be null)
  bool playerCaused = false;
  uint64_t requestedTick = 0;         // the tick the request was gathered in (executed from N+1)
  uint64_t sequence = 0;              // arrival order, filled by the budget
  bool shatter = false;               // break into cells (shatterSpec) instead of cutting by the plane
  ShatterSpec shatterSpec;
};

// Worker threads by default: the hardware threads but one (the main thread's), at least 0.
uint32_t defaultSplitThreads();

// The estimated cost of one split per stage, in milliseconds: main thread (prepare + commit) and
// worker (compute).
struct SplitCost {
  double main = 0.0;
  double worker = 0.0;
};

struct SplitBudgetSettings {
  double millisecondsPerTick = 4.0;   // main-thread split work allowed per tick (at least one split runs)
  double workerMillisecondsPerTick = 8.0;   // compute work started per tick, summed over workers
  uint32_t maxSplitsPerTick = 8;
  uint32_t maxActivationsPerTick = 16;
  uint32_t maxQueueLength = 1024;     // beyond this the lowest-priority requests are dropped
  // Deterministic scheduling: each split is charged its estimated cost (from the cost estimator)
  // instead of the measured time, so the same input splits in the same ticks on every run, machine
  // and thread count (replays stay exact). The measured times are still reported in the stats.
  // False: charge the measured main-thread time (adapts to the machine, but the schedule, and so the
  // simulation, depends on timing).
  bool deterministic = true;
  // Worker threads for the compute stage (0: computed inline on the main thread). The results, and
  // so the replays, are the same for any number.
  uint32_t threads = defaultSplitThreads();
  // A split prepared in tick T commits in tick T + commitDelayTicks, whatever the threads did: the
  // main thread waits for a late job. 0 commits in the tick it was prepared.
  uint32_t commitDelayTicks = 1;
  // A split whose compute is estimated at more than one tick's worth (workerMillisecondsPerCommitTick,
  // a worker's share of a 60 Hz tick) commits later by as many ticks as the estimate needs, at most
  // maxExtraCommitTicks more, so that the main thread does not stand waiting for it (a hammer on a
  // skinned warrior: about 50 ms of ragdoll planning). A job never commits before one prepared
  // earlier (commit order is request order). From the estimate only: the same ticks on any threads.
  double workerMillisecondsPerCommitTick = 16.0;
  uint32_t maxExtraCommitTicks = 3;
  // The split system's estimates, per stage and piece kind, fitted to the demo objects (each within
  // 2x of the measured medians; docs/performance.md lists both). Main thread, rigid pieces: a fixed
  // part, per collider part (shapes built at commit) and per triangle (GPU upload); skinned pieces
  // on a rigid body, and ragdoll pieces (bones and joints), a fixed cost each plus their upload per
  // triangle (skinned vertices are larger). Worker: a fixed part,
  // per triangle, per unit of collider-part work (geometry::partsWork: clipping and shrinking), and
  // per triangle again when the collider parts are decomposed in the cut (a mesh's first cut, and
  // skinned pieces on a rigid body, whose posed pieces are decomposed every cut).
  double estimatedMainMilliseconds = 0.006;
  double estimatedMainMillisecondsPerPart = 0.006;
  double estimatedMainMillisecondsPerTriangle = 0.00002;
  double estimatedSkinnedMainMilliseconds = 0.02;
  double estimatedRagdollMainMilliseconds = 0.03;
  double estimatedSkinnedMainMillisecondsPerTriangle = 0.000018;
  double estimatedWorkerMilliseconds = 0.01;
  double estimatedWorkerMillisecondsPerTriangle = 0.00012;
  double estimatedWorkerMillisecondsPerPartWork = 0.00004;
  double estimatedDecomposeMillisecondsPerTriangle = 0.004;
  double estimatedRagdollWorkerMillisecondsPerTriangle = 0.0006;  // planning each piece's bones
};

// What the budget asks of the world it schedules, for one tick (SplitBudget::runTick).
class SplitBudgetHost {
 public:
  virtual ~SplitBudgetHost() = default;
  // The target still exists (a request for a target that does not is dropped as stale).
  virtual bool isAlive(ecs::Entity target) const = 0;
  // Where the target is (non-player requests run nearest to the camera first).
  virtual glm::dvec3 positionOf(ecs::Entity target) const = 0;
  // Its split is in flight: the request waits, queued, until it is free (or gone).
  virtual bool isBusy(ecs::Entity target) const = 0;
  // The estimated cost of the split per stage (charged on the main thread when deterministic, on the
  // workers always).
  virtual SplitCost estimate(const SplitRequest& request) const = 0;
  // Performs the split (its main-thread part); false when it failed.
  virtual bool execute(const SplitRequest& request) = 0;
  // A clock in milliseconds, for the measured main-thread time.
  virtual double nowMilliseconds() const = 0;
};

struct SplitBudgetStats {
  uint32_t executed = 0;      // splits done this tick
  uint32_t deferred = 0;      // requests left waiting at the end of this tick
  uint32_t dropped = 0;       // stale or over-capacity requests dropped this tick
  uint32_t failed = 0;        // splits that failed this tick, at prepare or commit (original kept)
  double millisecondsUsed = 0.0;      // measured main-thread prepare time this tick
  double millisecondsCharged = 0.0;   // main-thread time the budget counted (the estimate when deterministic)
  double workerMillisecondsCharged = 0.0;  // compute time the budget counted (estimates)
  double lastSplitMilliseconds = 0.0;
  double maxSplitMilliseconds = 0.0;  // over the whole run
  double maxChargeMilliseconds = 0.0; // the largest main-thread charge of one split, whole run
  uint32_t queueLength = 0;
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

  // Runs one tick's worth of requests gathered before `currentTick`, asking `host` what it needs;
  // `cameraPosition` orders non-player requests by distance.
  void runTick(uint64_t currentTick, const glm::dvec3& cameraPosition, SplitBudgetHost& host);

  // A split that was executed (prepared) but failed later, at commit: counted in this tick's stats.
  void recordFailure() { stats_.failed++; }

  const SplitBudgetStats& stats() const { return stats_; }
  size_t queueLength() const { return queue_.size(); }
  void clear();

 private:
  SplitBudgetSettings settings_;
  SplitBudgetStats stats_;
  std::vector<SplitRequest> queue_;
  uint64_t nextSequence_ = 0;
};

}  // namespace cleave::components
