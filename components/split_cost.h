// SPDX-License-Identifier: MIT
// The split cost model: what a split is estimated to cost per stage, from plain facts about its
// target, with the calibrated per-stage constants of SplitBudgetSettings (fitted to the demo objects,
// docs/performance.md), and the tick its commit is due in. Pure functions: the same inputs give the
// same estimates on every machine and thread count, which is what keeps a deterministic budget's
// schedule (and so every replay) exact.
#pragma once

#include <cstdint>

#include "cleave/components/split_budget.h"
#include "cleave/geometry/collider_parts.h"

namespace cleave::components {

// What the cost of one split depends on.
struct SplitCostInputs {
  double triangles = 0.0;   // of the target's mesh
  bool skinned = false;     // cut in its pose
  bool ragdoll = false;     // skinned pieces become ragdolls (bones planned on the worker)
  // The target's collider parts when known (clipped, not decomposed again); null: decomposed in the
  // compute, once.
  const geometry::ColliderPartSet* parts = nullptr;
  uint32_t shatterCells = 0;  // 0: a plane cut
};

// Main-thread (prepare + commit) and worker (compute) milliseconds.
SplitCost estimateSplitCost(const SplitBudgetSettings& settings, const SplitCostInputs& inputs);

// The tick a split prepared in `preparedTick` commits in: commitDelayTicks later, and later again
// by the ticks its estimated compute needs (workerMillisecondsPerCommitTick each, at most
// maxExtraCommitTicks more), never before `latestPendingCommit` (commit order is request order).
uint64_t commitTickFor(const SplitBudgetSettings& settings, uint64_t preparedTick, double workerMilliseconds,
                       uint64_t latestPendingCommit);

}  // namespace cleave::components
