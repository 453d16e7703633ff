// SPDX-License-Identifier: MIT
// The material part of the GLB writing core (glb_builder.h): source materials copied into a GLB
// with the textures, samplers and images they use. An image is embedded as the bytes the source
// file stored, not decoded and encoded again (that would change the bytes, lose the encoder's
// choices and cost time). glTF 2.0 without extensions allows PNG and JPEG images only, so an image
// of another kind is not embedded and the textures that use it are left out.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <system_error>

#include "cleave/assets/glb_builder.h"

namespace cleave::assets::detail {

namespace {

constexpr int kUnseen = -2;

bool embeddable(const ModelImage& image) {
  return !image.encoded.empty() &&
         (image.mimeType == "image/png" || image.mimeType == "image/jpeg");
}

// A float as the double of its shortest decimal form, so that a file's 0.58, read into a float, is
// written as 0.58 again and not as the float widened (0.57999998...). A non-finite value is 1.
double decimal(float value) {
  if (!std::isfinite(value)) return 1.0;
  char text[32];
  const std::to_chars_result written = std::to_chars(text, text + sizeof text, value);
  double out = 1.0;
  if (written.ec == std::errc()) std::from_chars(text, written.ptr, out);
  return out;
}

// A factor glTF bounds to [0, 1] (base colour, metallic, roughness).
double unitFactor(float value) {
  return decimal(std::isfinite(value) ? std::clamp(value, 0.f, 1.f) : 1.f);
}

// The written index of source item `index` (-1 for none or out of range): `write(index)` makes it
// on first use (-1 when it cannot be written) and `written` remembers it.
template <class Write>
int writeOnce(std::vector<int>& written, int32_t index, Write write) {
  if (index < 0 || static_cast<size_t>(index) >= written.size()) return -1;
  int& slot = written[static_cast<size_t>(index)];
  if (slot == kUnseen) slot = write(static_cast<size_t>(index));
  return slot;
}

}  // namespace

GlbMaterialCopy::GlbMaterialCopy(tinygltf::Model& model, const MaterialSource& source, int uvSets)
    : model_(model),
      source_(source),
      uvSets_(uvSets),
      textures_(source.textures.size(), kUnseen),
      samplers_(source.samplers.size(), kUnseen),
      images_(source.images.size(), kUnseen) {}

bool GlbMaterialCopy::copy(uint32_t id, tinygltf::Material& out) {
  if (id >= source_.materials.size()) return false;
  const ModelMaterial& material = source_.materials[id];
  tinygltf::PbrMetallicRoughness& pbr = out.pbrMetallicRoughness;
  const glm::vec4& color = material.baseColorFactor;
  pbr.baseColorFactor = {unitFactor(color.r), unitFactor(color.g), unitFactor(color.b),
                         unitFactor(color.a)};
  pbr.metallicFactor = unitFactor(material.metallicFactor);
  pbr.roughnessFactor = unitFactor(material.roughnessFactor);
  out.doubleSided = material.doubleSided;
  if (const int base = texture(material.baseColorTexture); base >= 0) {
    pbr.baseColorTexture.index = base;
    pbr.baseColorTexture.texCoord = material.baseColorTexture.texCoord;
  }
  if (const int normal = texture(material.normalTexture); normal >= 0) {
    out.normalTexture.index = normal;
    out.normalTexture.texCoord = material.normalTexture.texCoord;
    out.normalTexture.scale = decimal(material.normalScale);
  }
  return true;
}

int GlbMaterialCopy::texture(const ModelTextureRef& ref) {
  if (ref.texCoord < 0 || ref.texCoord >= uvSets_) return -1;
  return writeOnce(textures_, ref.texture, [&](size_t i) {
    const ModelTexture& texture = source_.textures[i];
    const int image = this->image(texture.image);
    if (image < 0) return -1;
    tinygltf::Texture out;
    out.name = texture.name;
    out.source = image;
    out.sampler = sampler(texture.sampler);
    model_.textures.push_back(out);
    return static_cast<int>(model_.textures.size() - 1);
  });
}

int GlbMaterialCopy::sampler(int32_t index) {
  return writeOnce(samplers_, index, [&](size_t i) {
    const ModelSampler& sampler = source_.samplers[i];
    tinygltf::Sampler out;
    out.name = sampler.name;
    out.magFilter = sampler.magFilter;
    out.minFilter = sampler.minFilter;
    out.wrapS = sampler.wrapS;
    out.wrapT = sampler.wrapT;
    model_.samplers.push_back(out);
    return static_cast<int>(model_.samplers.size() - 1);
  });
}

int GlbMaterialCopy::image(int32_t index) {
  return writeOnce(images_, index, [&](size_t i) {
    const ModelImage& image = source_.images[i];
    if (!embeddable(image)) return -1;
    const size_t length = image.encoded.size();
    tinygltf::Image out;
    out.name = image.name;
    out.mimeType = image.mimeType;
    out.bufferView =
        addView(model_, appendToBuffer(model_, image.encoded.data(), length), length, 0);
    model_.images.push_back(out);
    return static_cast<int>(model_.images.size() - 1);
  });
}

}  // namespace cleave::assets::detail
