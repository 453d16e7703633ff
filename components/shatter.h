// SPDX-License-Identifier: MIT
// Shatter: what a split request carries to break its target into cells instead of cutting it by a
// plane (a Splitter of kind Shatter makes such requests; the compute stage runs geometry::fracture).
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

namespace cleave::components {

// A shatter instead of a cut: the target broken into Voronoi cells (geometry::fracture) of `cells`
// seeds from a seeded generator in its bounds, denser within `impactRadius` of `impactPoint`; each
// piece moves with the parent (v + w x r) plus `outwardImpulse` m/s away from the impact point.
struct ShatterSpec {
  uint32_t cells = 16;
  uint64_t seed = 0;
  glm::dvec3 impactPoint{0.0};  // world (a Splitter's requests: its position, unless impactGiven)
  bool impactGiven = false;     // a Splitter keeps impactPoint as given instead of its position
  double impactRadius = 0.0;    // metres; 0: seeds evenly in the bounds
  double outwardImpulse = 0.0;  // m/s
};

}  // namespace cleave::components
