// SPDX-License-Identifier: MIT
// When a pass asks the memory for what it reads a few dozen entries ahead (__builtin_prefetch).
// Internal to the geometry library.
//
// A pass that reads through an index (positions by vertex, a weld cell by position, corners by
// triangle) waits on each read once its arrays outgrow the caches: the reads come from memory one
// behind the other. From kFarCount entries on (2^18: 3 MB of float positions, a 2 MB weld table)
// the passes below ask ahead; under it every read is a cache hit and asking only costs
// instructions. Measured on the 1M-triangle sphere, against the same pass without: the
// classification (mesh_splitter.cpp: 2.8 -> 1 ms), the weld's table (mesh_container.cpp: a tenth
// of the set-up), the closedness filing's corners (mesh_container.cpp: about 2 ms of 45), the
// closedness check's rows, read in order after a scattered filing (1.5-2 ms of about 33). The cut
// pass, the piece gathers and the mass sums gained nothing and do not ask.
#pragma once

#include <cstddef>

namespace cleave::geometry::detail {

inline constexpr size_t kFarCount = size_t(1) << 18;

}  // namespace cleave::geometry::detail
