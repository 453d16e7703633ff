// SPDX-License-Identifier: MIT
// The loop that sums a surface's signed tetrahedra (mass_properties.cpp), in the widest vector
// registers the CPU has. Internal to the geometry library; tests pick a kernel to compare them.
//
// Every kernel computes the same bits: triangle i is summed into lane i % 8 of eight running sums,
// each lane with the operations of the scalar formula in its order (no fused multiply-add: the
// library is built with -ffp-contract=off), and the lanes are added 0 + 1 + ... + 7 at the end. The
// vector width only decides how many lanes one instruction holds (SSE2 two, AVX2 four, AVX-512
// eight), so a replay gives the same masses on any x86-64 machine and in the scalar build.
#pragma once

#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "cleave/geometry/mass_properties.h"

namespace cleave::geometry::detail {

enum class MassKernel : uint8_t {
  Best,     // the widest this CPU runs (the default)
  Sse2,     // two lanes per instruction; the scalar loop where SSE2 is absent or CLEAVE_MASS_SCALAR
  Avx2,     // four
  Avx512,   // eight
};

// Whether this build and this CPU can run `kernel` (Best always).
bool massKernelRuns(MassKernel kernel);

// Makes every later integration in the process use `kernel` (falls back to Best when it cannot run).
// For tests and benchmarks that compare the kernels; not thread-safe against running integrations.
void useMassKernel(MassKernel kernel);

// The sums over the triangles `indices` (corners p[indices[3t..3t+2]], relative to ref; with flip
// the second and third corner swapped) of det = a . (b x c) and of det times the first and second
// moment terms (see mass_properties.cpp).
struct MomentSums {
  double sixV = 0.0, fx = 0.0, fy = 0.0, fz = 0.0;
  double xx = 0.0, yy = 0.0, zz = 0.0, xy = 0.0, yz = 0.0, zx = 0.0;
};
MomentSums sumMoments(std::span<const glm::dvec3> p, std::span<const uint32_t> indices, const glm::dvec3& ref,
                      bool flip);

// integrateClosedSurface(positions, indices, flipWinding, true) without its index check, for a
// surface the caller has just written: a whole number of triangles, every index in range and every
// position referenced (a splitter's piece), whose bounds [lo, hi] the caller worked out on the way.
MassProperties integrateWrittenSurface(std::span<const glm::dvec3> positions, std::span<const uint32_t> indices,
                                       bool flipWinding, const glm::dvec3& lo, const glm::dvec3& hi);

}  // namespace cleave::geometry::detail
