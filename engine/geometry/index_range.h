// SPDX-License-Identifier: MIT
// Range checks of index and position arrays, written so that the compiler vectorises them: a
// comparison ORed into a flag runs about four times faster than a running maximum, which SSE2 has
// no unsigned instruction for. Internal to the geometry library.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <span>

#include <glm/glm.hpp>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace cleave::geometry::detail {

// Whether some value is >= limit.
inline bool anyAtOrAbove(std::span<const uint32_t> values, uint32_t limit) {
  uint32_t over = 0;
  for (uint32_t v : values) over |= uint32_t(v >= limit);
  return over != 0;
}

// Whether every coordinate is finite (exponent bits not all set: no infinity, no NaN), and the
// axis-aligned bounds of the points, meaningful only when they are (infinite, lo > hi, for none).
// One pass over the floats as one flat array, four points (twelve floats, three SSE registers) at a
// time into twelve running minima and maxima that are folded per axis at the end (the compiler does
// not vectorise this loop written plainly).
inline bool finiteBounds(std::span<const glm::vec3> points, glm::vec3& lo, glm::vec3& hi) {
  static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
  lo = glm::vec3(INFINITY);
  hi = glm::vec3(-INFINITY);
  if (points.empty()) return true;
  const unsigned char* bytes = reinterpret_cast<const unsigned char*>(points.data());
  auto word = [&](size_t k) {
    uint32_t bits;
    std::memcpy(&bits, bytes + 4 * k, sizeof bits);
    return bits;
  };
  float low[12], high[12];
  for (int k = 0; k < 12; ++k) low[k] = high[k] = std::bit_cast<float>(word(k % 3));
  uint32_t special = 0;
  const size_t words = 3 * points.size();
  size_t i = 0;
#if defined(__SSE2__)
  {
    const float* f = reinterpret_cast<const float*>(bytes);
    __m128 l[3], h[3];
    __m128i bad = _mm_setzero_si128();
    const __m128i exponent = _mm_set1_epi32(0x7f800000);
    for (int r = 0; r < 3; ++r) l[r] = h[r] = _mm_loadu_ps(low + 4 * r);
    for (; i + 12 <= words; i += 12) {
      for (int r = 0; r < 3; ++r) {
        const __m128 v = _mm_loadu_ps(f + i + 4 * r);
        l[r] = _mm_min_ps(l[r], v);
        h[r] = _mm_max_ps(h[r], v);
        const __m128i e = _mm_and_si128(_mm_castps_si128(v), exponent);
        bad = _mm_or_si128(bad, _mm_cmpeq_epi32(e, exponent));
      }
    }
    for (int r = 0; r < 3; ++r) {
      _mm_storeu_ps(low + 4 * r, l[r]);
      _mm_storeu_ps(high + 4 * r, h[r]);
    }
    special = uint32_t(_mm_movemask_epi8(bad));
  }
#endif
  for (; i < words; ++i) {
    const uint32_t bits = word(i);
    const float value = std::bit_cast<float>(bits);
    special |= uint32_t((bits & 0x7f800000u) == 0x7f800000u);
    low[i % 3] = std::min(low[i % 3], value);
    high[i % 3] = std::max(high[i % 3], value);
  }
  for (int a = 0; a < 3; ++a) {
    lo[a] = std::min(std::min(low[a], low[a + 3]), std::min(low[a + 6], low[a + 9]));
    hi[a] = std::max(std::max(high[a], high[a + 3]), std::max(high[a + 6], high[a + 9]));
  }
  return special == 0;
}

}  // namespace cleave::geometry::detail
