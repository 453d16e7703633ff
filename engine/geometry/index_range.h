// SPDX-License-Identifier: MIT
// Range checks of index arrays, written so that the compiler vectorises them: a comparison ORed
// into a flag runs about four times faster than a running maximum, which SSE2 has no unsigned
// instruction for. Internal to the geometry library.
#pragma once

#include <cstdint>
#include <span>

namespace cleave::geometry::detail {

// Whether some value is >= limit.
inline bool anyAtOrAbove(std::span<const uint32_t> values, uint32_t limit) {
  uint32_t over = 0;
  for (uint32_t v : values) over |= uint32_t(v >= limit);
  return over != 0;
}

}  // namespace cleave::geometry::detail
