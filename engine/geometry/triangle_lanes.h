// SPDX-License-Identifier: MIT
// Eight triangles of an index list as AVX2 lanes, for the passes that take triangles eight at a
// time (the splitter's cut pass, whole_blocks.h; the container's closedness filing, fileRows).
// Internal to the geometry library.
#pragma once

#include <cstddef>
#include <cstdint>

#include "cleave/geometry/index_range.h"  // CLEAVE_AVX2_VARIANTS

namespace cleave::geometry::detail {

#ifdef CLEAVE_AVX2_VARIANTS
// Corner 0, 1 and 2 of triangles first .. first + 7 of `indices` (three indices a triangle), lane j
// holding triangle first + j: three loads of 24 indices, blended so that each lane holds the corner
// of one triangle, then put in triangle order. Reads indices[3 first] to indices[3 first + 23].
[[gnu::target("avx2"), gnu::always_inline]] inline void triangleCornersAvx2(const uint32_t* indices, size_t first,
                                                                          __m256i& g0, __m256i& g1, __m256i& g2) {
  const __m256i* from = reinterpret_cast<const __m256i*>(indices + 3 * first);
  const __m256i l0 = _mm256_loadu_si256(from), l1 = _mm256_loadu_si256(from + 1), l2 = _mm256_loadu_si256(from + 2);
  g0 = _mm256_permutevar8x32_epi32(_mm256_blend_epi32(_mm256_blend_epi32(l0, l1, 0b10010010), l2, 0b00100100),
                                   _mm256_setr_epi32(0, 3, 6, 1, 4, 7, 2, 5));
  g1 = _mm256_permutevar8x32_epi32(_mm256_blend_epi32(_mm256_blend_epi32(l0, l1, 0b00100100), l2, 0b01001001),
                                   _mm256_setr_epi32(1, 4, 7, 2, 5, 0, 3, 6));
  g2 = _mm256_permutevar8x32_epi32(_mm256_blend_epi32(_mm256_blend_epi32(l0, l1, 0b01001001), l2, 0b10010010),
                                   _mm256_setr_epi32(2, 5, 0, 3, 6, 1, 4, 7));
}
#endif

}  // namespace cleave::geometry::detail
