// SPDX-License-Identifier: MIT
// Materials of a glTF model as plain data: images (decoded pixels and the file's encoded bytes),
// samplers, textures and PBR metallic-roughness materials, indexed the way glTF indexes them. The
// loader (model.h) fills them; the GLB writers (mesh_io.h, model.h) copy them into the files they
// write through a MaterialSource.
//
// Values are glTF's: colours are linear RGBA, sampler filters and wrap modes are the OpenGL enum
// values glTF uses (9728 NEAREST ... 10497 REPEAT). Every index is into the arrays of the same
// model and is -1 for none; the loader has checked them (a broken reference becomes -1 with a
// warning).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <string>
#include <vector>

namespace cleave::assets {

// An image of the file. `rgba` is decoded to RGBA8, rows top to bottom, and is empty (width 0) when
// the image could not be decoded (a warning says why). `encoded` is the image as the file stores it
// (PNG or JPEG bytes, unchanged), so a writer can embed it without encoding again; it is empty when
// the file's image could not be read at all. Both are owned by the image.
struct ModelImage {
  std::string name;  // the image's name, else its uri
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgba;     // width * height * 4 bytes
  std::string mimeType;          // "image/png", "image/jpeg" (as declared, else found from the
                                 // bytes' signature), empty when unknown
  std::vector<uint8_t> encoded;  // the file's bytes of the image
};

// How a texture is filtered and wrapped (glTF's sampler; -1 filters mean "not given").
struct ModelSampler {
  std::string name;
  int32_t magFilter = -1;  // 9728 NEAREST, 9729 LINEAR
  int32_t minFilter = -1;  // 9728, 9729, 9984 ... 9987 (the mipmap modes)
  int32_t wrapS = 10497;   // 33071 CLAMP_TO_EDGE, 33648 MIRRORED_REPEAT, 10497 REPEAT
  int32_t wrapT = 10497;
};

struct ModelTexture {
  std::string name;
  int32_t image = -1;    // index into the model's images, -1 for none
  int32_t sampler = -1;  // index into the model's samplers, -1 for glTF's default sampling
};

// A material's use of a texture.
struct ModelTextureRef {
  int32_t texture = -1;  // index into the model's textures, -1 for none
  int32_t texCoord = 0;  // the TEXCOORD_<n> set it is sampled with
};

struct ModelMaterial {
  std::string name;
  glm::vec4 baseColorFactor{1.f};  // linear RGBA
  float metallicFactor = 1.f;      // glTF's defaults
  float roughnessFactor = 1.f;
  ModelTextureRef baseColorTexture;
  ModelTextureRef normalTexture;
  float normalScale = 1.f;
  int32_t baseColorImage = -1;  // the image of baseColorTexture (index into images), -1 for none
  int32_t normalImage = -1;     // the image of normalTexture, -1 for none
  bool doubleSided = false;
};

// Views of a model's materials and of what they reference, for a writer to copy: a material id
// of a mesh indexes `materials`. The arrays are owned by the caller and must outlive the call they
// are passed to. Empty views mean "no materials to copy".
struct MaterialSource {
  std::span<const ModelMaterial> materials;
  std::span<const ModelTexture> textures;
  std::span<const ModelSampler> samplers;
  std::span<const ModelImage> images;
};

}  // namespace cleave::assets
