// SPDX-License-Identifier: MIT
// The split cost model (split_cost.h).
#include "cleave/components/split_cost.h"

#include <algorithm>
#include <cmath>

namespace cleave::components {

SplitCost estimateSplitCost(const SplitBudgetSettings& s, const SplitCostInputs& in) {
  SplitCost cost;
  const double triangles = in.triangles;
  double once = 0.0;  // worker time a shatter spends once, not per cell: the decomposition
  cost.worker = s.estimatedWorkerMilliseconds + s.estimatedWorkerMillisecondsPerTriangle * triangles;
  if (in.ragdoll) {
    cost.main = s.estimatedRagdollMainMilliseconds + s.estimatedSkinnedMainMillisecondsPerTriangle * triangles;
    cost.worker += s.estimatedRagdollWorkerMillisecondsPerTriangle * triangles;
  } else if (in.skinned) {
    cost.main = s.estimatedSkinnedMainMilliseconds + s.estimatedSkinnedMainMillisecondsPerTriangle * triangles;
    once = s.estimatedDecomposeMillisecondsPerTriangle * triangles;
  } else {
    const double partCount = in.parts ? double(in.parts->size()) : 1.0;
    cost.main = s.estimatedMainMilliseconds + s.estimatedMainMillisecondsPerPart * partCount +
                s.estimatedMainMillisecondsPerTriangle * triangles;
    if (in.parts) {
      cost.worker += s.estimatedWorkerMillisecondsPerPartWork * geometry::partsWork(*in.parts);
    } else {
      once = s.estimatedDecomposeMillisecondsPerTriangle * triangles;
    }
  }
  if (in.shatterCells > 0) {
    // About a piece per cell (a split makes two) and a few plane cuts per cell on shrinking parts.
    const double cells = double(in.shatterCells);
    cost.main *= 0.5 * cells;
    cost.worker *= 1.5 * cells;
  }
  cost.worker += once;
  return cost;
}

uint64_t commitTickFor(const SplitBudgetSettings& s, uint64_t preparedTick, double workerMilliseconds,
                       uint64_t latestPendingCommit) {
  uint64_t extra = 0;
  if (s.workerMillisecondsPerCommitTick > 0.0 && workerMilliseconds > s.workerMillisecondsPerCommitTick)
    extra = uint64_t(std::ceil(workerMilliseconds / s.workerMillisecondsPerCommitTick)) - 1;
  const uint64_t at = preparedTick + s.commitDelayTicks + std::min<uint64_t>(extra, s.maxExtraCommitTicks);
  return std::max(at, latestPendingCommit);
}

}  // namespace cleave::components
