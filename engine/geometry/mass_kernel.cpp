// SPDX-License-Identifier: MIT
// The tetrahedron sums of mass_properties.cpp in eight lanes (see mass_kernel.h for why every
// kernel gives the same bits). One body, written once over a lane type: `double` for the scalar
// loop, an eight-double GCC vector for the others; the compiler lowers the vector to four SSE2, two
// AVX2 or one AVX-512 register per value according to the target of the function it is inlined in.
#include "cleave/geometry/mass_kernel.h"

#include <atomic>

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
    // Built from braced lists (element stores would go through memory and stall the loads).
    Lane8 x[3], y[3], z[3];
    const int corner[3] = {0, second, third};
    for (int c = 0; c < 3; ++c) {
      const int o = corner[c];
      const glm::dvec3 &q0 = p[tri[o]], &q1 = p[tri[3 + o]], &q2 = p[tri[6 + o]], &q3 = p[tri[9 + o]],
                       &q4 = p[tri[12 + o]], &q5 = p[tri[15 + o]], &q6 = p[tri[18 + o]], &q7 = p[tri[21 + o]];
      x[c] = Lane8{q0.x, q1.x, q2.x, q3.x, q4.x, q5.x, q6.x, q7.x} - rx;
      y[c] = Lane8{q0.y, q1.y, q2.y, q3.y, q4.y, q5.y, q6.y, q7.y} - ry;
      z[c] = Lane8{q0.z, q1.z, q2.z, q3.z, q4.z, q5.z, q6.z, q7.z} - rz;
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
