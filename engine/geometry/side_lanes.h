// SPDX-License-Identifier: MIT
// The splitter's classification of position ids by the cut plane, four at a time where the
// processor runs AVX2. Internal to the geometry library.
//
// An id's side is that of its representative vertex p: +1 when its distance to the plane,
// (n.x p.x + n.y p.y) + n.z p.z - offset in double (glm::dot's order; the library is built without
// fused multiply-adds), is above the tolerance, -1 when it is below minus the tolerance, else 0.
// Here four ids at a time gather their representatives' coordinates and take the same operations
// in the same order: the same sides as Splitter::classify's scalar loop.
#pragma once

#include <cstdint>
#include <cstring>

#include <glm/glm.hpp>

#include "cleave/geometry/index_range.h"  // CLEAVE_AVX2_VARIANTS

namespace cleave::geometry::detail {

#ifdef CLEAVE_AVX2_VARIANTS
// sides[id] for the ids from begin in groups of four below end, the representative of id being
// vertex reps[id] of the cut positions: `source` floats or, when it is null, `moved` doubles.
// Returns the first id not done (the caller's scalar loop takes the last fewer than four). With
// `ahead` (a big mesh), the representatives `ahead` ids on are asked for early. Vertex indices
// below 2^29 (gathered at three times the index).
[[gnu::target("avx2")]] inline uint32_t classifyAvx2(const glm::vec3* source, const glm::dvec3* moved, const uint32_t* reps,
                                                 uint32_t begin, uint32_t end, const glm::dvec3& normal,
                                                 double offset, double tolerance, uint32_t ahead, int8_t* sides) {
  const __m256d nx = _mm256_set1_pd(normal.x), ny = _mm256_set1_pd(normal.y), nz = _mm256_set1_pd(normal.z);
  const __m256d off = _mm256_set1_pd(offset), above = _mm256_set1_pd(tolerance), below = _mm256_set1_pd(-tolerance);
  uint32_t id = begin;
  for (; id + 4 <= end; id += 4) {
    if (ahead != 0 && id + ahead < end) {
      if (source) __builtin_prefetch(source + reps[id + ahead]);
      else __builtin_prefetch(moved + reps[id + ahead]);
    }
    const __m128i rep = _mm_loadu_si128(reinterpret_cast<const __m128i*>(reps + id));
    const __m128i at = _mm_add_epi32(_mm_add_epi32(rep, rep), rep);
    __m256d x, y, z;
    if (source) {
      const float* base = &source[0].x;
      x = _mm256_cvtps_pd(_mm_i32gather_ps(base, at, 4));
      y = _mm256_cvtps_pd(_mm_i32gather_ps(base + 1, at, 4));
      z = _mm256_cvtps_pd(_mm_i32gather_ps(base + 2, at, 4));
    } else {
      // The masked gathers: the plain ones read an uninitialised source register (a warning in GCC 12).
      const double* base = &moved[0].x;
      const __m256d zero = _mm256_setzero_pd(), all = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
      x = _mm256_mask_i32gather_pd(zero, base, at, all, 8);
      y = _mm256_mask_i32gather_pd(zero, base + 1, at, all, 8);
      z = _mm256_mask_i32gather_pd(zero, base + 2, at, all, 8);
    }
    const __m256d d = _mm256_sub_pd(
        _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(nx, x), _mm256_mul_pd(ny, y)), _mm256_mul_pd(nz, z)), off);
    // Per lane +1, -1 or 0 as a 64-bit lane, then the low byte of each to four bytes.
    const __m256i up = _mm256_castpd_si256(_mm256_cmp_pd(d, above, _CMP_GT_OQ));
    const __m256i down = _mm256_castpd_si256(_mm256_cmp_pd(d, below, _CMP_LT_OQ));
    const __m256i side = _mm256_sub_epi64(down, up);  // all ones (-1) below, 1 above, 0 on
    const __m256i bytes = _mm256_shuffle_epi8(side, _mm256_setr_epi8(0, 8, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1,
                                                                        -1, -1, -1, 0, 8, -1, -1, -1, -1, -1, -1, -1,
                                                                        -1, -1, -1, -1, -1, -1, -1));
    const uint32_t low = static_cast<uint32_t>(_mm_cvtsi128_si32(_mm256_castsi256_si128(bytes))) & 0xffffu;
    const uint32_t high = static_cast<uint32_t>(_mm_cvtsi128_si32(_mm256_extracti128_si256(bytes, 1))) & 0xffffu;
    const uint32_t four = low | high << 16;
    std::memcpy(sides + id, &four, sizeof four);
  }
  return id;
}
#endif

}  // namespace cleave::geometry::detail
