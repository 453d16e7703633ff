// SPDX-License-Identifier: MIT
// A skinned humanoid made in code, so demos and tests need no outside files: a closed mesh of about
// 4,000 triangles with a 17-joint skeleton and two looping clips, "idle" and "walk".
//
// The body is the zero set of a signed distance field (capsules and spheres joined with a smooth
// minimum), meshed by surface nets (Gibson 1998): one vertex per grid cell that the surface
// crosses, one quad per grid edge it crosses, each quad split along its shorter diagonal. The
// result is one closed, consistently wound surface (every edge shared by exactly two triangles in
// opposite directions, vertices unique per position), so the split core can cut it anywhere with
// caps.
//
// Units: metres, y up, the character faces +z, its feet on y = 0, about 1.8 m tall. Winding:
// counter-clockwise seen from outside. Bind pose = rest pose (an A-pose with the arms 30 degrees
// out). Skin: at most 4 joints per vertex, weights sorted largest first, summing to 1, empty slots
// joint 0 weight 0. Materials (submesh ids): 0 skin, 2 shirt, 3 trousers, 4 shoes; id 1 is left
// free for cut caps (geometry::SplitOptions::capMaterialId). Deterministic: the same options give
// the same bytes.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "cleave/anim/animation_clip.h"
#include "cleave/anim/skeleton.h"
#include "cleave/geometry/mesh_data.h"

namespace cleave::assets {

struct CharacterOptions {
  float cellSize = 0.0365f;  // surface-nets grid step in metres; smaller gives more triangles
};

struct ProceduralCharacter {
  geometry::MeshData mesh;   // bind space, with normals, joints, weights and submeshes
  anim::Skeleton skeleton;   // joint names: hips, spine, chest, neck, head,
                             // {left,right}_{upper_arm,forearm,hand,thigh,shin,foot}
  anim::AnimationClip idle;  // 2 s loop: breathing, a slight sway
  anim::AnimationClip walk;  // 1 s loop: one stride of each leg, in place
  std::vector<glm::vec4>
      materialColors;  // linear RGBA by material id (index 1: a suggested cap colour)
};

ProceduralCharacter makeProceduralCharacter(const CharacterOptions& options = {});

// The convex multi-part variant of the same character (the thesis's figure of convex parts
// animated as one): one box per bone in the bind pose, each rigidly bound to its joint (weight 1),
// shortened at both ends so no two parts touch. It uses the character's skeleton and clips, so it
// animates with the same Animator; every part is closed and convex. Materials as the character's.
geometry::MeshData makeCharacterParts(const ProceduralCharacter& character);

}  // namespace cleave::assets
