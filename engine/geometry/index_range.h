// SPDX-License-Identifier: MIT
// Range checks of index and position arrays, written so that the compiler vectorises them: a
// comparison ORed into a flag runs about four times faster than a running maximum, which SSE2 has
// no unsigned instruction for. Internal to the geometry library.
#pragma once

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <span>

#include <glm/glm.hpp>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
// AVX2 variants where the compiler can build them and ask the processor for them (x86-64).
#if (defined(__GNUC__) || defined(__clang__)) && defined(__x86_64__)
#define CLEAVE_AVX2_VARIANTS 1
#include <immintrin.h>
#endif

namespace cleave::geometry::detail {

// On unless a test turned the AVX2 loops off (allowAvx2) to compare them with the plain ones.
inline std::atomic<bool>& avx2Allowed() {
  static std::atomic<bool> allowed{true};
  return allowed;
}
// For tests: false makes runsAvx2() answer false from then on (passes already running may see
// either), so that every AVX2 loop of the library gives way to its plain one.
inline void allowAvx2(bool allowed) { avx2Allowed().store(allowed, std::memory_order_relaxed); }

// Whether the processor runs AVX2 (asked once) and the AVX2 loops are allowed. The checks below
// then take twice the values per instruction: the same loops compiled for it, the same answers.
// So do the lanes of the classification, the cut pass (side_lanes.h, whole_blocks.h) and the
// closedness check (mesh_container.cpp).
inline bool runsAvx2() {
#ifdef CLEAVE_AVX2_VARIANTS
  static const bool yes = (__builtin_cpu_init(), __builtin_cpu_supports("avx2"));
  return yes && avx2Allowed().load(std::memory_order_relaxed);
#else
  return false;
#endif
}

namespace loops {
// SSE2 has no unsigned maximum: a comparison ORed into a flag. AVX2 has one: a running maximum.
[[gnu::always_inline]] inline bool anyAtOrAbove(const uint32_t* values, size_t count, uint32_t limit) {
  uint32_t over = 0;
  for (size_t i = 0; i < count; ++i) over |= uint32_t(values[i] >= limit);
  return over != 0;
}
[[gnu::always_inline]] inline bool copyBelow(const uint32_t* from, uint32_t* to, size_t count, uint32_t limit) {
  uint32_t over = 0;
  for (size_t i = 0; i < count; ++i) {
    over |= uint32_t(from[i] >= limit);
    to[i] = from[i];
  }
  return over == 0;
}
[[gnu::always_inline]] inline uint32_t largest(const uint32_t* values, size_t count) {
  uint32_t most = 0;
  for (size_t i = 0; i < count; ++i) most = std::max(most, values[i]);
  return most;
}
[[gnu::always_inline]] inline uint32_t copyLargest(const uint32_t* from, uint32_t* to, size_t count) {
  uint32_t most = 0;
  for (size_t i = 0; i < count; ++i) {
    most = std::max(most, from[i]);
    to[i] = from[i];
  }
  return most;
}
[[gnu::always_inline]] inline bool ascending(const uint32_t* values, size_t count) {
  uint32_t wrong = 0;
  for (size_t i = 1; i < count; ++i) wrong |= uint32_t(values[i] <= values[i - 1]);
  return wrong == 0;
}
// Differences ORed together: no flag to make per entry.
[[gnu::always_inline]] inline bool pointBack(const uint32_t* from, size_t count, const uint32_t* to) {
  uint32_t wrong = 0;
  for (size_t k = 0; k < count; ++k) wrong |= to[from[k]] ^ static_cast<uint32_t>(k);
  return wrong == 0;
}
#ifdef CLEAVE_AVX2_VARIANTS
[[gnu::target("avx2")]] inline bool anyAtOrAboveAvx2(const uint32_t* values, size_t count, uint32_t limit) {
  return count > 0 && largest(values, count) >= limit;
}
[[gnu::target("avx2")]] inline bool copyBelowAvx2(const uint32_t* from, uint32_t* to, size_t count, uint32_t limit) {
  return count == 0 || copyLargest(from, to, count) < limit;
}
[[gnu::target("avx2")]] inline bool ascendingAvx2(const uint32_t* values, size_t count) { return ascending(values, count); }
[[gnu::target("avx2")]] inline bool pointBackAvx2(const uint32_t* from, size_t count, const uint32_t* to) {
  return pointBack(from, count, to);
}
#endif
}  // namespace loops

// The dispatch, written once: loops::name##Avx2(args) where the processor runs AVX2 (x86-64
// builds only), else the plain loops::name(args).
#ifdef CLEAVE_AVX2_VARIANTS
#define CLEAVE_RANGE_LOOP(name, ...) (runsAvx2() ? loops::name##Avx2(__VA_ARGS__) : loops::name(__VA_ARGS__))
#else
#define CLEAVE_RANGE_LOOP(name, ...) loops::name(__VA_ARGS__)
#endif

// Whether some value is >= limit.
inline bool anyAtOrAbove(std::span<const uint32_t> values, uint32_t limit) {
  return CLEAVE_RANGE_LOOP(anyAtOrAbove, values.data(), values.size(), limit);
}

// Copies `from` to `to` (as many values; the arrays do not overlap); whether every value was below
// limit (all are copied either way).
inline bool copyBelow(std::span<const uint32_t> from, uint32_t* to, uint32_t limit) {
  return CLEAVE_RANGE_LOOP(copyBelow, from.data(), to, from.size(), limit);
}

// Whether the values rise strictly (true for none or one).
inline bool strictlyAscending(std::span<const uint32_t> values) {
  return CLEAVE_RANGE_LOOP(ascending, values.data(), values.size());
}

// Whether to[from[k]] == k for every k: `from` picks, for each k, an entry of `to` that names k
// back. Every from[k] must be an index into `to` (checked by the caller).
inline bool pointBack(std::span<const uint32_t> from, const uint32_t* to) {
  return CLEAVE_RANGE_LOOP(pointBack, from.data(), from.size(), to);
}
#undef CLEAVE_RANGE_LOOP

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
