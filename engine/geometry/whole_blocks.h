// SPDX-License-Identifier: MIT
// The splitter's cut pass over the source triangles, eight at a time where the processor runs AVX2.
// Internal to the geometry library.
//
// Most triangles of a cut lie on one side of the plane with at most one corner on it, and the pass
// only files them into that side's list. One by one, each corner costs lookups that wait on each
// other (vertex, then its position id, then the id's side). Here the sides are first spread to the
// vertices (vertexSidesAvx2), then eight triangles at a time gather the sides of their corners and,
// when all eight are such whole triangles, are written to their lists (wholeBlocksAvx2). A block
// with a crossing triangle or one with two corners on the plane is left to the scalar loop, which
// writes the same bytes as the blocks would: the output does not depend on the processor.
//
// Side bytes are read four at a time: every array of sides passed here must have kSidePadding
// readable bytes past its last entry. Gather offsets are signed 32-bit: vertex indices and position
// ids must be below 2^31 (wholeBlocksRun checks the counts).
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <utility>

#include "cleave/geometry/index_range.h"  // CLEAVE_AVX2_VARIANTS, runsAvx2
#include "cleave/geometry/triangle_lanes.h"

namespace cleave::geometry::detail {

constexpr size_t kSidePadding = 3;

// Whether the blocks below run here, for a mesh of `vertices` vertices and `ids` position ids (a
// test turns them off with allowAvx2, index_range.h).
inline bool wholeBlocksRun(size_t vertices, size_t ids) {
  return runsAvx2() && vertices < 0x80000000u && ids < 0x80000000u;
}

// For tests: the blocks of eight taken so far in this process (wholeBlocksAvx2), so that a test can
// tell that its splits went through them.
inline std::atomic<uint64_t>& wholeBlocksTaken() {
  static std::atomic<uint64_t> taken{0};
  return taken;
}

#ifdef CLEAVE_AVX2_VARIANTS
// out[v] = sides[ids[v]] for the vertices v in [begin, end). Writes only that range (threads may
// fill other ranges of `out` at once).
[[gnu::target("avx2")]] inline void vertexSidesAvx2(const uint32_t* ids, const int8_t* sides, uint32_t begin,
                                                    uint32_t end, int8_t* out) {
  // Byte 0 of each 32-bit lane to the low four bytes of each half, then the halves side by side.
  const __m256i lowBytes = _mm256_setr_epi8(0, 4, 8, 12, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1,  //
                                            0, 4, 8, 12, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1);
  const __m256i halves = _mm256_setr_epi32(0, 4, 1, 1, 1, 1, 1, 1);
  uint32_t v = begin;
  for (; v + 8 <= end; v += 8) {
    const __m256i id = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(ids + v));
    const __m256i words = _mm256_i32gather_epi32(reinterpret_cast<const int*>(sides), id, 1);
    const __m256i bytes = _mm256_permutevar8x32_epi32(_mm256_shuffle_epi8(words, lowBytes), halves);
    _mm_storel_epi64(reinterpret_cast<__m128i*>(out + v), _mm256_castsi256_si128(bytes));
  }
  for (; v < end; ++v) out[v] = sides[ids[v]];
}

// The sides (+1, -1, 0) of eight vertices, from their bytes.
[[gnu::target("avx2"), gnu::always_inline]] inline __m256i sidesOfAvx2(const int8_t* vertexSides, __m256i vertices) {
  const __m256i words = _mm256_i32gather_epi32(reinterpret_cast<const int*>(vertexSides), vertices, 1);
  return _mm256_srai_epi32(_mm256_slli_epi32(words, 24), 24);
}

// The whole triangles of [lo, hi) eight at a time, forwards from lo (each to at[side]++) or, with
// kBackwards, last triangle first down from hi (each to --at[side]), as the scalar loop files them:
// a row {corner 0, corner 1, corner 2, source triangle} in cut-space winding (corners 1 and 2
// swapped when `mirrored`), side 0 above the plane (no corner below, at most one on it), side 1
// below (the same mirrored). A triangle with two corners on the plane (the scalar loop marks it as
// reached by the plane) or corners on both sides is another triangle.
// Stops before the first block of eight that holds another triangle, or where fewer than eight are
// left. Returns the triangle it stopped at: the first not taken forwards, one past the last not
// taken backwards. `Row` is the lists' 16-byte row type.
template <bool kBackwards, class Row>
[[gnu::target("avx2")]] uint32_t wholeBlocksAvx2(const uint32_t* indices, const int8_t* vertexSides, bool mirrored,
                                                 uint32_t lo, uint32_t hi, Row* const (&lists)[2], uint32_t (&at)[2]) {
  static_assert(sizeof(Row) == 16);
  const __m256i lanes = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  const uint32_t loAtStart = lo, hiAtStart = hi;
  // Forwards the next row of each side; backwards one past it.
  Row* nextAbove = lists[0] + at[0];
  Row* nextBelow = lists[1] + at[1];
  while (hi - lo >= 8) {
    const uint32_t first = kBackwards ? hi - 8 : lo;
    __m256i g0, g1, g2;
    triangleCornersAvx2(indices, first, g0, g1, g2);
    const __m256i sum = _mm256_add_epi32(
        _mm256_add_epi32(sidesOfAvx2(vertexSides, g0), sidesOfAvx2(vertexSides, g1)),
        sidesOfAvx2(vertexSides, g2));
    // Sides are -1, 0 or +1: a sum of 2 or 3 is no corner below and at most one on the plane, a
    // whole triangle above that is not in the plane; -2 or -3 the same below.
    const __m256i up = _mm256_cmpgt_epi32(sum, _mm256_set1_epi32(1));
    const __m256i down = _mm256_cmpgt_epi32(_mm256_set1_epi32(-1), sum);
    if (_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_or_si256(up, down))) != 0xff) break;
    if (mirrored) std::swap(g1, g2);
    // The rows of triangles j and j + 4 in the two halves of rows[j].
    const __m256i t = _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(first)), lanes);
    const __m256i a = _mm256_unpacklo_epi32(g0, g1), b = _mm256_unpackhi_epi32(g0, g1);
    const __m256i c = _mm256_unpacklo_epi32(g2, t), d = _mm256_unpackhi_epi32(g2, t);
    const __m256i rows[4] = {_mm256_unpacklo_epi64(a, c), _mm256_unpackhi_epi64(a, c), _mm256_unpacklo_epi64(b, d),
                             _mm256_unpackhi_epi64(b, d)};
    const uint32_t above = static_cast<uint32_t>(_mm256_movemask_ps(_mm256_castsi256_ps(up)));
    for (int k = 0; k < 8; ++k) {
      const int j = kBackwards ? 7 - k : k;
      const bool isAbove = ((above >> j) & 1u) != 0;
      const __m128i row = j < 4 ? _mm256_castsi256_si128(rows[j]) : _mm256_extracti128_si256(rows[j - 4], 1);
      if (kBackwards) nextAbove -= isAbove, nextBelow -= !isAbove;
      Row* const to = isAbove ? nextAbove : nextBelow;
      if (!kBackwards) nextAbove += isAbove, nextBelow += !isAbove;
      _mm_storeu_si128(reinterpret_cast<__m128i*>(to), row);
    }
    if (kBackwards) hi -= 8;
    else lo += 8;
  }
  wholeBlocksTaken().fetch_add((kBackwards ? hiAtStart - hi : lo - loAtStart) / 8, std::memory_order_relaxed);
  at[0] = static_cast<uint32_t>(nextAbove - lists[0]);
  at[1] = static_cast<uint32_t>(nextBelow - lists[1]);
  return kBackwards ? hi : lo;
}
#endif

}  // namespace cleave::geometry::detail
