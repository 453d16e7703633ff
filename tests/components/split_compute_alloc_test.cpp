// SPDX-License-Identifier: MIT
// Allocation counting over the split system's compute stage: a warm scratch cutting a mesh whose
// weld and collider parts are known allocates for what it hands to commit (a mesh, a weld, hulls
// per piece) and nothing per triangle: a sphere with 16 times the triangles of another costs the same
// count, up to a vector's geometric growth. Global operator new is replaced in this test binary
// (tests/support/counting_allocator.h).
#include <gtest/gtest.h>

#include <cstdio>

#include "cleave/components/split_compute.h"
#include "cleave/geometry/collider_parts.h"
#include "cleave/geometry/primitives.h"
#include "tests/support/counting_allocator.h"

namespace cleave::components {
namespace {

// Allocations of one computeSplit of a sphere (segments x rings) with a warm scratch.
size_t computeAllocations(uint32_t segments, uint32_t rings) {
  auto job = std::make_shared<SplitJob>();
  job->mesh = std::make_shared<geometry::MeshData>(geometry::primitives::uvSphere(0.5f, segments, rings));
  geometry::MeshContainer container;
  EXPECT_EQ(container.setMesh(*job->mesh).code, geometry::SplitStatus::Ok);
  auto weld = std::make_shared<geometry::MeshWeld>();
  container.copyWeld(*weld);
  job->weld = weld;
  auto splitter = geometry::makeConcaveSplitter();
  job->parts = std::make_shared<const geometry::ColliderPartSet>(geometry::decomposeConvex(*job->mesh, *splitter));
  job->plane = geometry::Plane{{0.2, 1.0, 0.1}, 0.05};
  job->parent.mass = 10.0;
  SplitComputeScratch scratch;
  SplitOutcome out;
  for (int warm = 0; warm < 2; ++warm) computeSplit(*job, scratch, out);
  EXPECT_EQ(out.status, geometry::SplitStatus::Ok) << out.message;
  out = SplitOutcome{};
  cleave::testing::gAllocations = 0;
  cleave::testing::gCountAllocations = true;
  computeSplit(*job, scratch, out);
  cleave::testing::gCountAllocations = false;
  EXPECT_EQ(out.status, geometry::SplitStatus::Ok) << out.message;
  EXPECT_EQ(out.pieces.size(), 2u);
  return cleave::testing::gAllocations.load();
}

TEST(SplitComputeAllocations, DoNotGrowWithTheMesh) {
  const size_t small = computeAllocations(32, 17);
  const size_t large = computeAllocations(128, 65);
  std::printf("[ allocs  ] compute stage: %zu allocations for a 1k-triangle sphere, %zu for a 16k one\n", small,
              large);
  EXPECT_GT(small, 0u) << "the counter sees nothing: the outputs of a split are allocated";
  // A vector that grows geometrically may grow once or twice more for 16 times the triangles;
  // anything per triangle would be thousands more.
  EXPECT_LE(large, small + 4);
}

}  // namespace
}  // namespace cleave::components
