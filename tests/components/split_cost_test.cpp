// SPDX-License-Identifier: MIT
// The split cost model (split_cost.h): estimates grow with what the split does, and commits wait
// for long computes and for the splits prepared before them.
#include "cleave/components/split_cost.h"

#include <gtest/gtest.h>

#include "cleave/geometry/collider_parts.h"
#include "cleave/geometry/mesh_splitter.h"
#include "cleave/geometry/primitives.h"

namespace cleave::components {
namespace {

TEST(SplitCost, KnownPartsSpareTheDecompositionAndShattersScaleWithTheirCells) {
  const SplitBudgetSettings s;
  SplitCostInputs cut;
  cut.triangles = 2000;
  const SplitCost first = estimateSplitCost(s, cut);  // parts unknown: decomposed in the compute
  auto splitter = geometry::makeConcaveSplitter();
  const geometry::ColliderPartSet parts = geometry::decomposeConvex(geometry::primitives::box(glm::vec3(0.5f)), *splitter);
  ASSERT_FALSE(parts.empty());
  SplitCostInputs known = cut;
  known.parts = &parts;
  const SplitCost again = estimateSplitCost(s, known);
  EXPECT_LT(again.worker, first.worker);
  EXPECT_NEAR(first.worker - (s.estimatedWorkerMilliseconds + s.estimatedWorkerMillisecondsPerTriangle * 2000),
              s.estimatedDecomposeMillisecondsPerTriangle * 2000, 1e-12);
  SplitCostInputs shatter = known;
  shatter.shatterCells = 16;
  const SplitCost cells = estimateSplitCost(s, shatter);
  EXPECT_DOUBLE_EQ(cells.main, 8.0 * again.main);
  EXPECT_DOUBLE_EQ(cells.worker, 24.0 * again.worker);
  SplitCostInputs ragdoll = cut;
  ragdoll.skinned = ragdoll.ragdoll = true;
  EXPECT_GT(estimateSplitCost(s, ragdoll).worker, s.estimatedRagdollWorkerMillisecondsPerTriangle * 2000);
}

TEST(SplitCost, ALongComputeCommitsLaterButNeverBeforeAnEarlierSplit) {
  SplitBudgetSettings s;
  s.commitDelayTicks = 1;
  s.workerMillisecondsPerCommitTick = 16.0;
  s.maxExtraCommitTicks = 3;
  EXPECT_EQ(commitTickFor(s, 100, 2.0, 0), 101u);
  EXPECT_EQ(commitTickFor(s, 100, 16.0, 0), 101u);
  EXPECT_EQ(commitTickFor(s, 100, 40.0, 0), 103u);   // three ticks' worth: two more
  EXPECT_EQ(commitTickFor(s, 100, 500.0, 0), 104u);  // at most three more
  EXPECT_EQ(commitTickFor(s, 100, 2.0, 103), 103u);  // behind a split prepared before it
}

}  // namespace
}  // namespace cleave::components
