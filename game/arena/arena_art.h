// SPDX-License-Identifier: MIT
// The arena's art, all made in code: textures (flagstones, terracotta, lettered metal), materials,
// and meshes (the lathe-turned urn, the multi-part gladiator, the round floor, the wall ring).
//
// Units: metres, y up; every mesh is closed and wound counter-clockwise seen from outside, with
// normals, tangents and uv0, so the split core can cut and cap it. Textures are RGBA8, rows top to
// bottom, tileable, deterministic for a given size and seed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cleave/assets/procedural_textures.h"
#include "cleave/geometry/mesh_data.h"
#include "cleave/render/renderer.h"

namespace cleave::arena {

// Sandstone flagstones in a running bond, 4 x 4 stones per tile, with dark grout.
assets::Image makeFlagstoneTexture(int size, uint32_t seed);
// Fired clay with a painted black band and meander, for the urns (u around, v up).
assets::Image makeTerracottaTexture(int size, uint32_t seed);
// Brushed metal plate with a riveted border and `word` engraved in the middle (at most 5 of the
// letters A Q R S T U I; others are left blank), for the menu cubes.
assets::Image makeLetteredMetalTexture(int size, const std::string& word, uint32_t seed);

// A solid of revolution around y: `profile` holds (radius, height) points from the bottom up (radii
// > 0, heights increasing); the bottom and top are closed by flat discs. uv: u around, v up.
geometry::MeshData lathe(const std::vector<glm::vec2>& profile, uint32_t segments);
// The urn: a lathe-turned amphora about 1.35 m tall standing on y = 0.
geometry::MeshData urnMesh();
// Sets uv0 of every vertex to (x, z) * uvPerMetre (planar mapping from above, for floors).
void planarUv(geometry::MeshData& mesh, float uvPerMetre);
// Marks all triangles of `mesh` as one submesh of material `materialId`.
void setMaterial(geometry::MeshData& mesh, uint32_t materialId);

// The multi-part gladiator, standing on y = 0 and facing +z: legs, torso, head and arms as separate
// convex parts a few centimetres apart (each part convex, so every island a cut leaves is convex
// too). Submesh ids: 0 armour (torso), 2 skin (head, arms), 3 cloth (legs); 1 is left to caps.
geometry::MeshData gladiatorMesh();

// Materials of the arena, created once on the renderer.
struct ArenaMaterials {
  render::Material floor, wall, wallTrim, pillar, gate;
  render::Material stands, standsRiser, turf;         // outside the wall (arena_surroundings.h)
  std::vector<render::Material> crowd;               // by crowdMesh's submesh id
  render::Material crate, crateCap, urn, urnCap;
  render::Material armour, skin, cloth, flesh;       // enemies; flesh is their cap (an energy burn)
  render::Material startCube, quitCube, metalCap;
  render::Material disc, blade, bladeCore;
  std::vector<render::Material> player;              // by the character's submesh id
  std::vector<render::Material> skinnedEnemy;        // the same ids, restyled; id 1 (caps) is flesh
  std::vector<render::TextureHandle> textures;       // owned; destroyed with the renderer
};
ArenaMaterials createArenaMaterials(render::Renderer& renderer, const std::vector<glm::vec4>& characterColors);

}  // namespace cleave::arena
