// SPDX-License-Identifier: MIT
// Models: glTF 2.0 scenes with static and skinned meshes, materials with their textures (decoded,
// and as the file's encoded bytes), skins and animations, as plain data (no tinygltf type leaks
// out of engine/assets).
//
// What is read. The default scene (else scene 0) and every node under it. A node with a mesh and no
// skin becomes a static ModelMesh whose vertices are baked into scene space (the node hierarchy is
// flattened). A node with a mesh and a skin becomes a skinned ModelMesh in bind space, as stored in
// the file; glTF places skinned meshes by their joints only, so its node transform is not applied.
// All triangle primitives of a mesh are merged into one MeshData with one submesh per primitive
// (materialId = index into Model::materials); points and lines are skipped with a warning.
// Attributes: POSITION (float), NORMAL (computed, area-weighted smooth, when missing), TEXCOORD_0
// (float or normalised integers), JOINTS_0 (unsigned byte or short) and WEIGHTS_0 (float or
// normalised unsigned byte or short; renormalised to sum 1). No indices means a plain triangle
// list. Animations: translation, rotation and scale channels, step, linear and cubic spline. Each
// glTF animation becomes one clip per skin whose joints it moves (morph-target weights are
// skipped). Materials (material.h): base colour factor and texture, metallic and roughness
// factors, normal texture with its scale, doubleSided; textures with their samplers and images,
// each image decoded with stb_image and kept as the file's bytes with its mime type. Other
// material properties and texture extensions (KHR_texture_transform, ...) are not read.
//
// Units: those of the file (the engine reads them as metres). Winding: counter-clockwise seen from
// outside; a mirroring node transform of a static mesh flips the triangles back.
//
// Failure: no function throws and no input crashes; on failure `ok` is false, the model is empty
// and `error` is one line "<file>: <reason>": an index out of range, a non-finite position, a
// missing buffer, a node cycle, no scene, a required extension that is not supported (named, for
// example KHR_draco_mesh_compression), joints outside their skin, a file without a triangle.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <string>
#include <vector>

#include "cleave/base/status.h"
#include "cleave/anim/animation_clip.h"
#include "cleave/anim/skeleton.h"
#include "cleave/assets/material.h"
#include "cleave/assets/mesh_io.h"
#include "cleave/geometry/mesh_data.h"

namespace cleave::assets {

struct ModelMesh {
  std::string name;         // the node's name, else the mesh's
  geometry::MeshData mesh;  // static: scene space; skinned: bind space with joints and weights
  int32_t skin = -1;        // index into Model::skins for a skinned mesh, -1 for a static one
};

struct ModelSkin {
  std::string name;
  anim::Skeleton skeleton;  // joint j is the skin's j-th joint (JOINTS_0 values index it)
  std::vector<anim::AnimationClip>
      clips;  // the file's animations that move this skin, in file order
};

struct Model {
  std::vector<ModelMesh> meshes;
  std::vector<ModelMaterial> materials;  // the file's, then "default" when a primitive has none
  std::vector<ModelTexture> textures;    // the file's, in file order (see material.h)
  std::vector<ModelSampler> samplers;
  std::vector<ModelImage> images;
  std::vector<ModelSkin> skins;

  size_t triangleCount() const;
  // Views of the materials, textures, samplers and images, for MeshWriteOptions::materials; they
  // point into this model.
  MaterialSource materialSource() const;
};

// A Status (code, and a message of one line naming the file and the reason; empty when ok) with
// the model.
struct ModelLoadResult : base::Status {
  Model model;
  std::vector<std::string> warnings;  // non-fatal remarks, each naming the file
};

// Loads a .gltf (external or embedded buffers and images, looked up beside the file) or a .glb.
// The kind is chosen by content (the GLB magic), not by the extension.
ModelLoadResult loadModel(const std::string& path);

// The same from bytes in memory; `name` is used in messages only. Only data: URIs and GLB chunks
// can be read (there is no folder to look in).
ModelLoadResult readModelFromMemory(std::span<const uint8_t> bytes, const std::string& name);

// Writes a skinned mesh (bind space, joints and weights indexing `skeleton`) with its skeleton and
// clips as binary glTF 2.0 that loadModel reads back as one skinned ModelMesh with one skin and
// these clips: a node per joint (rest transform as translation, rotation, scale; a joint's fixed
// offset as an extra parent node), the skin (joints in skeleton order, inverse bind matrices), one
// animation per clip, one primitive per submesh run (materials named as in MeshWriteOptions, copied
// from MeshWriteOptions::materials when it has them, else with MeshWriteOptions::materialColors as
// base colours), POSITION with bounds, NORMAL, TEXCOORD_0,
// JOINTS_0 (unsigned short) and WEIGHTS_0. Every joint of the skeleton is written, also those the
// mesh does not use, so the clips keep driving the whole hierarchy. Malformed clip channels are
// left out. Failure (invalid mesh or skeleton, a weight on a joint outside the skeleton) gives
// ok = false and a one-line error.
MeshWriteResult writeSkinnedGlbToMemory(const geometry::MeshData& mesh, const anim::Skeleton& skeleton,
                                        std::span<const anim::AnimationClip> clips,
                                        const MeshWriteOptions& options, std::vector<uint8_t>& out);
MeshWriteResult writeSkinnedGlb(const std::string& path, const geometry::MeshData& mesh,
                                const anim::Skeleton& skeleton, std::span<const anim::AnimationClip> clips,
                                const MeshWriteOptions& options);

}  // namespace cleave::assets
