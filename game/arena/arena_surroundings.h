// SPDX-License-Identifier: MIT
// What lies outside the arena's wall, so that no view from inside (the menu's low view, the follow
// view at the wall) shows the empty sky below the horizon: tiered stone stands (the cavea) rising
// behind the wall with a tall outer wall, a crowd of spectators on the tiers, and dry turf out to
// the fog.
//
// Units: metres, y up, the arena's centre at the origin. The meshes are for drawing only (no
// collider, never cut): closed, wound counter-clockwise seen from outside, with normals and uv0.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "cleave/assets/procedural_textures.h"
#include "cleave/geometry/mesh_data.h"

namespace cleave::arena {

// The stands: `tiers` steps of `tierDepth` by `tierRise` from `innerRadius` (just behind the wall)
// and `firstTierHeight` up, then the outer wall `outerWallHeight` above the top tier.
struct StandsLayout {
  float innerRadius = 12.9f;      // m, the outer face of the arena wall
  float firstTierHeight = 2.6f;   // m: the wall's merlons stand above the front row
  float tierDepth = 0.85f;        // m
  float tierRise = 0.5f;          // m
  int tiers = 8;
  float outerWallHeight = 2.2f;   // m above the top tier
  float outerWallThickness = 0.6f;
  uint32_t segments = 128;        // around the ring

  float outerRadius() const { return innerRadius + tierDepth * float(tiers); }
  float topHeight() const { return firstTierHeight + tierRise * float(tiers - 1); }
};

// The solid swept once around the y axis by the closed polygon `section` of (radius, height)
// points, counter-clockwise in the (radius, height) plane (radii >= 0). Each edge of the polygon
// becomes a band of `segments` quads with its own flat normal, so steps keep their sharp edges.
// uv0: u along the circle and v along the edge, both in metres times `uvPerMetre`.
geometry::MeshData sweepAround(const std::vector<glm::vec2>& section, uint32_t segments, float uvPerMetre);

// The stands as one mesh: submesh 0 the stone of the treads and the outer wall, 2 the risers (a
// darker stone), so two materials tell the steps apart from above.
geometry::MeshData standsMesh(const StandsLayout& layout);

// Spectators sitting on the treads, facing the sand: a body and a head box each, about two seats in
// three taken (chosen by `seed`). Submeshes 0..3 are the tunic colours, 4 the skin.
geometry::MeshData crowdMesh(const StandsLayout& layout, uint32_t seed);
inline constexpr uint32_t kCrowdColours = 4;

// Flat ground around the arena: a ring from `innerRadius` to `outerRadius`, its top at y = `top`
// (below the sand so the arena floor covers it), planar uv at `uvPerMetre`.
geometry::MeshData groundRing(float innerRadius, float outerRadius, float top, float uvPerMetre);

// Dry turf: yellow-green grass with patches of bare earth, tileable.
assets::Image makeTurfTexture(int size, uint32_t seed);

}  // namespace cleave::arena
