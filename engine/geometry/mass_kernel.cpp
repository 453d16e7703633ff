// SPDX-License-Identifier: MIT
// The tetrahedron sums of mass_properties.cpp in eight lanes (see mass_kernel.h for why every
// kernel gives the same bits). One body, written once over a lane type: `double` for the scalar
// loop, an eight-double GCC vector for the others; the compiler lowers the vector to four SSE2, two
// AVX2 or one AVX-512 register per value according to the target of the function it is inlined in.
#include "cleave/geometry/mass_kernel.h"

#include <atomic>
#include <cstring>

#if (defined(__GNUC__) || defined(__clang__)) && defined(__x86_64__) && !defined(CLEAVE_MASS_SCALAR)
#define CLEAVE_MASS_VECTOR 1
#include <immintrin.h>
#endif

namespace cleave::geometry::detail {
namespace {

constexpr int kLanes = 8;

#ifdef CLEAVE_MASS_VECTOR
typedef double Lane8 __attribute__((vector_size(8 * sizeof(double))));
#endif

// The ten running sums of one lane (L = double) or of eight (L = Lane8).
template <class L>
struct Sums {
  L sixV{}, fx{}, fy{}, fz{}, xx{}, yy{}, zz{}, xy{}, yz{}, zx{};
};

// Adds the tetrahedron (ref, a, b, c), corners already relative to ref, in the scalar formula's
// order of operations: det = a . (b x c) as glm computes it, s = (a + b) + c, and each second
// moment term ((a a + b b) + c c) + s s.
template <class L>
[[gnu::always_inline]] inline void addTetrahedron(Sums<L>& s, const L& ax, const L& ay, const L& az, const L& bx,
                                                  const L& by, const L& bz, const L& cx, const L& cy, const L& cz) {
  const L kx = by * cz - cy * bz;
  const L ky = bz * cx - cz * bx;
  const L kz = bx * cy - cx * by;
  const L det = (ax * kx + ay * ky) + az * kz;
  const L sx = (ax + bx) + cx, sy = (ay + by) + cy, sz = (az + bz) + cz;
  s.sixV += det;
  s.fx += det * sx;
  s.fy += det * sy;
  s.fz += det * sz;
  s.xx += det * (((ax * ax + bx * bx) + cx * cx) + sx * sx);
  s.yy += det * (((ay * ay + by * by) + cy * cy) + sy * sy);
  s.zz += det * (((az * az + bz * bz) + cz * cz) + sz * sz);
  s.xy += det * (((ax * ay + bx * by) + cx * cy) + sx * sy);
  s.yz += det * (((ay * az + by * bz) + cy * cz) + sy * sz);
  s.zx += det * (((az * ax + bz * bx) + cz * cx) + sz * sx);
}

// Triangle t into scalar lane sums `lane`.
[[gnu::always_inline]] inline void addTriangle(Sums<double>& lane, std::span<const glm::dvec3> p, const uint32_t* tri,
                                               const glm::dvec3& ref, int second, int third) {
  const glm::dvec3 a = p[tri[0]] - ref, b = p[tri[second]] - ref, c = p[tri[third]] - ref;
  addTetrahedron<double>(lane, a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z);
}

// Lane 0 + lane 1 + ... + lane 7 of every sum. Inlined, so that the AVX kernels clear the upper
// register state only after it (a call into SSE code with that state dirty runs slowed).
[[gnu::always_inline]] inline MomentSums total(const Sums<double> (&lanes)[kLanes]) {
  MomentSums out;
  for (const Sums<double>& l : lanes) {
    out.sixV += l.sixV;
    out.fx += l.fx;
    out.fy += l.fy;
    out.fz += l.fz;
    out.xx += l.xx;
    out.yy += l.yy;
    out.zz += l.zz;
    out.xy += l.xy;
    out.yz += l.yz;
    out.zx += l.zx;
  }
  return out;
}

// The triangles from `first` on, one by one into lane t % 8.
[[gnu::always_inline]] inline void addTail(Sums<double> (&lanes)[kLanes], std::span<const glm::dvec3> p,
                                           std::span<const uint32_t> indices, size_t first, const glm::dvec3& ref,
                                           bool flip) {
  const int second = flip ? 2 : 1, third = flip ? 1 : 2;
  const size_t count = indices.size() / 3;
  for (size_t t = first; t < count; ++t) addTriangle(lanes[t % kLanes], p, &indices[3 * t], ref, second, third);
}

#ifdef CLEAVE_MASS_VECTOR
typedef double Lane2 __attribute__((vector_size(2 * sizeof(double))));
typedef double Lane4 __attribute__((vector_size(4 * sizeof(double))));

// Points p[tri[o]], p[tri[3 + o]], ..., p[tri[21 + o]] read two doubles each from `at` (0: x and y,
// 1: y and z) and laid out as eight pairs in order, the first four in `low` and the last four in
// `high`.
[[gnu::always_inline]] inline void loadPairs(const glm::dvec3* p, const uint32_t* tri, int o, int at, Lane8& low,
                                             Lane8& high) {
  Lane2 pair[kLanes];
  for (int j = 0; j < kLanes; ++j) std::memcpy(&pair[j], &p[tri[3 * j + o]][at], sizeof(Lane2));
  const Lane4 p01 = __builtin_shufflevector(pair[0], pair[1], 0, 1, 2, 3);
  const Lane4 p23 = __builtin_shufflevector(pair[2], pair[3], 0, 1, 2, 3);
  const Lane4 p45 = __builtin_shufflevector(pair[4], pair[5], 0, 1, 2, 3);
  const Lane4 p67 = __builtin_shufflevector(pair[6], pair[7], 0, 1, 2, 3);
  low = __builtin_shufflevector(p01, p23, 0, 1, 2, 3, 4, 5, 6, 7);
  high = __builtin_shufflevector(p45, p67, 0, 1, 2, 3, 4, 5, 6, 7);
}

// One corner (offset o: 0, second or third) of the eight triangles at tri as lanes x, y and z: each
// point read as (x, y) and as (y, z), the pairs transposed by two-source shuffles (x and y from the
// first pairs' even and odd places, z from the second pairs' odd places). Built from scalars each
// lane took about as many shuffles again, and the shuffles bound the kernel; the values are the same.
[[gnu::always_inline]] inline void cornerLanes(const glm::dvec3* p, const uint32_t* tri, int o, Lane8& x, Lane8& y,
                                               Lane8& z) {
  static_assert(sizeof(glm::dvec3) == 3 * sizeof(double));
  Lane8 xyLow, xyHigh, yzLow, yzHigh;
  loadPairs(p, tri, o, 0, xyLow, xyHigh);
  loadPairs(p, tri, o, 1, yzLow, yzHigh);
  x = __builtin_shufflevector(xyLow, xyHigh, 0, 2, 4, 6, 8, 10, 12, 14);
  y = __builtin_shufflevector(xyLow, xyHigh, 1, 3, 5, 7, 9, 11, 13, 15);
  z = __builtin_shufflevector(yzLow, yzHigh, 1, 3, 5, 7, 9, 11, 13, 15);
}

// Eight triangles at a time, triangle 8 k + j in lane j; the rest by the scalar tail.
[[gnu::always_inline]] inline MomentSums sumLanes(std::span<const glm::dvec3> p, std::span<const uint32_t> indices,
                                                  const glm::dvec3& ref, bool flip) {
  const int second = flip ? 2 : 1, third = flip ? 1 : 2;
  const size_t blocks = indices.size() / 3 / kLanes;
  const Lane8 rx = {ref.x, ref.x, ref.x, ref.x, ref.x, ref.x, ref.x, ref.x};
  const Lane8 ry = {ref.y, ref.y, ref.y, ref.y, ref.y, ref.y, ref.y, ref.y};
  const Lane8 rz = {ref.z, ref.z, ref.z, ref.z, ref.z, ref.z, ref.z, ref.z};
  Sums<Lane8> s;
  const uint32_t* tri = indices.data();
  for (size_t k = 0; k < blocks; ++k, tri += 3 * kLanes) {
    Lane8 x[3], y[3], z[3];
    const int corner[3] = {0, second, third};
    for (int c = 0; c < 3; ++c) {
      cornerLanes(p.data(), tri, corner[c], x[c], y[c], z[c]);
      x[c] -= rx;
      y[c] -= ry;
      z[c] -= rz;
    }
    addTetrahedron<Lane8>(s, x[0], y[0], z[0], x[1], y[1], z[1], x[2], y[2], z[2]);
  }
  Sums<double> lanes[kLanes];
  for (int j = 0; j < kLanes; ++j) {
    lanes[j] = {s.sixV[j], s.fx[j], s.fy[j], s.fz[j], s.xx[j], s.yy[j], s.zz[j], s.xy[j], s.yz[j], s.zx[j]};
  }
  addTail(lanes, p, indices, blocks * kLanes, ref, flip);
  return total(lanes);
}

MomentSums sumSse2(std::span<const glm::dvec3> p, std::span<const uint32_t> indices, const glm::dvec3& ref,
                   bool flip) {
  return sumLanes(p, indices, ref, flip);
}

// Both clear the upper halves of the vector registers on the way out: the compiler does not here,
// and SSE code running after them with the upper state dirty was slowed to half its speed.
[[gnu::target("avx2")]] MomentSums sumAvx2(std::span<const glm::dvec3> p, std::span<const uint32_t> indices,
                                           const glm::dvec3& ref, bool flip) {
  const MomentSums sums = sumLanes(p, indices, ref, flip);
  _mm256_zeroupper();
  return sums;
}

[[gnu::target("avx512f")]] MomentSums sumAvx512(std::span<const glm::dvec3> p, std::span<const uint32_t> indices,
                                                const glm::dvec3& ref, bool flip) {
  const MomentSums sums = sumLanes(p, indices, ref, flip);
  _mm256_zeroupper();
  return sums;
}
#else
MomentSums sumScalar(std::span<const glm::dvec3> p, std::span<const uint32_t> indices, const glm::dvec3& ref,
                     bool flip) {
  Sums<double> lanes[kLanes];
  addTail(lanes, p, indices, 0, ref, flip);
  return total(lanes);
}
#endif

std::atomic<MassKernel> chosen{MassKernel::Best};

MassKernel best() {
#ifdef CLEAVE_MASS_VECTOR
  static const MassKernel widest = (__builtin_cpu_init(), __builtin_cpu_supports("avx512f") ? MassKernel::Avx512
                                   : __builtin_cpu_supports("avx2")  ? MassKernel::Avx2
                                                                     : MassKernel::Sse2);
  return widest;
#else
  return MassKernel::Sse2;
#endif
}

}  // namespace

bool massKernelRuns(MassKernel kernel) {
  switch (kernel) {
    case MassKernel::Best:
    case MassKernel::Sse2:
      return true;
    case MassKernel::Avx2:
      return best() == MassKernel::Avx2 || best() == MassKernel::Avx512;
    case MassKernel::Avx512:
      return best() == MassKernel::Avx512;
  }
  return false;
}

void useMassKernel(MassKernel kernel) { chosen.store(massKernelRuns(kernel) ? kernel : MassKernel::Best); }

MomentSums sumMoments(std::span<const glm::dvec3> p, std::span<const uint32_t> indices, const glm::dvec3& ref,
                      bool flip) {
  MassKernel kernel = chosen.load(std::memory_order_relaxed);
  if (kernel == MassKernel::Best) kernel = best();
#ifdef CLEAVE_MASS_VECTOR
  switch (kernel) {
    case MassKernel::Avx512:
      return sumAvx512(p, indices, ref, flip);
    case MassKernel::Avx2:
      return sumAvx2(p, indices, ref, flip);
    default:
      return sumSse2(p, indices, ref, flip);
  }
#else
  (void)kernel;
  return sumScalar(p, indices, ref, flip);
#endif
}

}  // namespace cleave::geometry::detail
