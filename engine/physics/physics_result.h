// SPDX-License-Identifier: MIT
// Status results of the physics layer: an error code plus a reason a person can act on.
//
// No call of the physics layer throws or crashes on bad input; data-dependent failures come back as
// a PhysicsStatus or a Result<T> (the shared shape of <cleave/base/status.h> with the physics codes:
// code() and message()), and handle-taking queries return false or nullopt for stale handles.
#pragma once

#include <cstdint>

#include "cleave/base/status.h"

namespace cleave::physics {

enum class PhysicsStatus : uint8_t {
  Ok = 0,
  InvalidArgument,         // NaN/Inf, negative size or mass, index out of range, empty arrays, ...
  StaleHandle,             // the handle is null, was destroyed, or belongs to a reused slot
  DegenerateShape,         // points are (nearly) coplanar/colinear, the mesh has no usable triangle
  UnsupportedCombination,  // e.g. a static triangle mesh on a dynamic body, a mesh as a trigger
};
const char* toString(PhysicsStatus status);

// A value or the reason there is none. T must be default-constructible (handles are).
template <class T>
using Result = base::Expected<T, PhysicsStatus>;

}  // namespace cleave::physics
