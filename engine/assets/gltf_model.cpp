// SPDX-License-Identifier: MIT
// The glTF model loader: scene nodes, static and skinned meshes, materials with their textures,
// samplers and images (decoded, and kept as the file's bytes), skins and animations (see model.h).
// tinygltf parses the JSON and the GLB container; everything it hands over (indices of nodes,
// meshes, accessors, materials, textures, images, skins) is checked here before use, because a
// file can claim anything.
#include <stb_image.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/gtc/quaternion.hpp>
#include <initializer_list>
#include <iterator>
#include <map>
#include <optional>
#include <string_view>

#include "cleave/assets/gltf_access.h"
#include "cleave/assets/gltf_attributes.h"
#include "cleave/assets/model.h"

namespace cleave::assets {

size_t Model::triangleCount() const {
  size_t total = 0;
  for (const ModelMesh& m : meshes) total += m.mesh.triangleCount();
  return total;
}

MaterialSource Model::materialSource() const {
  return MaterialSource{materials, textures, samplers, images};
}

namespace {

using detail::AccessorView;
using detail::component;
using detail::viewAccessor;

// An image's bytes as the file stores them, caught while tinygltf hands them to decodeImage.
struct EncodedImage {
  std::string mimeType;
  std::vector<uint8_t> bytes;
};

// The declared mime type, else the one of the bytes' signature (external image files declare none).
std::string mimeTypeOf(const std::string& declared, const unsigned char* bytes, int size) {
  if (!declared.empty()) return declared;
  static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (size >= 8 && std::memcmp(bytes, kPng, 8) == 0) return "image/png";
  if (size >= 3 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff) return "image/jpeg";
  return {};
}

// Decodes embedded and external images to RGBA8 with stb_image, and keeps the encoded bytes in
// `user` (a std::vector<EncodedImage>, by image index) so that writers can embed them unchanged. A
// failure to decode leaves the pixels empty and adds a warning: a broken texture must not make the
// geometry unusable.
bool decodeImage(tinygltf::Image* image, const int index, std::string*, std::string* warn, int, int,
                 const unsigned char* bytes, int size, void* user) {
  auto* encoded = static_cast<std::vector<EncodedImage>*>(user);
  if (encoded != nullptr && index >= 0 && size > 0) {
    const size_t at = static_cast<size_t>(index);
    if (encoded->size() <= at) encoded->resize(at + 1);
    (*encoded)[at] = {mimeTypeOf(image->mimeType, bytes, size),
                      std::vector<uint8_t>(bytes, bytes + size)};
  }
  int w = 0, h = 0, channels = 0;
  unsigned char* pixels =
      size > 0 ? stbi_load_from_memory(bytes, size, &w, &h, &channels, 4) : nullptr;
  if (pixels == nullptr || w <= 0 || h <= 0) {
    if (warn) {
      *warn += "image " + std::to_string(index) + " could not be decoded (" +
               (stbi_failure_reason() ? stbi_failure_reason() : "no data") + ")\n";
    }
    if (pixels) stbi_image_free(pixels);
    image->width = image->height = 0;
    image->image.clear();
    return true;
  }
  image->width = w;
  image->height = h;
  image->component = 4;
  image->bits = 8;
  image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  image->image.assign(pixels, pixels + size_t(w) * size_t(h) * 4);
  stbi_image_free(pixels);
  return true;
}

bool finite3(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

class Loader {
 public:
  Loader(const tinygltf::Model& gltf, const std::string& name, size_t fileBytes,
         std::vector<EncodedImage> encoded)
      : gltf_(gltf), name_(name), encoded_(std::move(encoded)) {
    budget_ = (uint64_t{1} << 24) + 64 * uint64_t{fileBytes};
    for (const tinygltf::Buffer& buffer : gltf.buffers) budget_ += buffer.data.size();
  }

  bool run(ModelLoadResult& result) {
    result_ = &result;
    Model& model = result.model;
    for (const std::string& extension : gltf_.extensionsRequired) {
      if (detail::geometryNeutral(extension)) continue;
      return fail("requires the glTF extension " + extension + ", which is not supported");
    }
    if (gltf_.scenes.empty()) return fail("the file has no scene");
    const int sceneIndex = gltf_.defaultScene < 0 ? 0 : gltf_.defaultScene;
    if (static_cast<size_t>(sceneIndex) >= gltf_.scenes.size()) {
      return fail("default scene " + std::to_string(sceneIndex) + " does not exist");
    }
    if (!buildHierarchy(gltf_.scenes[static_cast<size_t>(sceneIndex)].nodes)) return false;
    readImages(model);
    readSamplers(model);
    readTextures(model);
    if (!readMaterials(model)) return false;
    if (!readSkins(model)) return false;
    for (size_t n : order_) {
      const tinygltf::Node& node = gltf_.nodes[n];
      if (node.mesh < 0) continue;
      if (static_cast<size_t>(node.mesh) >= gltf_.meshes.size()) {
        return fail("node " + std::to_string(n) + " refers to missing mesh " +
                    std::to_string(node.mesh));
      }
      if (node.skin >= 0 && static_cast<size_t>(node.skin) >= gltf_.skins.size()) {
        return fail("node " + std::to_string(n) + " refers to missing skin " +
                    std::to_string(node.skin));
      }
      ModelMesh out;
      out.skin = node.skin;
      const tinygltf::Mesh& mesh = gltf_.meshes[static_cast<size_t>(node.mesh)];
      out.name = !node.name.empty() ? node.name : mesh.name;
      const glm::dmat4 transform = node.skin >= 0 ? glm::dmat4(1.0) : global_[n];
      if (!readMesh(static_cast<size_t>(node.mesh), transform, out)) return false;
      if (!out.mesh.indices.empty()) model.meshes.push_back(std::move(out));
    }
    if (usesDefaultMaterial_) {
      ModelMaterial fallback;
      fallback.name = "default";
      model.materials.push_back(fallback);
    }
    if (model.meshes.empty()) return fail("the scene has no triangle mesh");
    if (!readAnimations(model)) return false;
    return true;
  }

 private:
  bool fail(const std::string& reason) {
    result_->setFailure(base::StatusCode::ParseError, name_ + ": " + reason);
    return false;
  }
  void warn(const std::string& text) { result_->warnings.push_back(name_ + ": " + text); }

  // Parent of every node and the scene's nodes in depth-first order with their scene transforms.
  // A node reached twice from the scene (a cycle, or a child of two parents) is an error.
  bool buildHierarchy(const std::vector<int>& roots) {
    const size_t n = gltf_.nodes.size();
    parent_.assign(n, -1);
    for (size_t i = 0; i < n; ++i) {
      for (int child : gltf_.nodes[i].children) {
        if (child < 0 || static_cast<size_t>(child) >= n) {
          return fail("node " + std::to_string(i) + " has a missing child " +
                      std::to_string(child));
        }
        if (parent_[static_cast<size_t>(child)] >= 0 || static_cast<size_t>(child) == i) {
          return fail("node " + std::to_string(child) +
                      " has two parents or is its own child (a node cycle)");
        }
        parent_[static_cast<size_t>(child)] = static_cast<int>(i);
      }
    }
    // A cycle without a root never reaches one walking up.
    for (size_t i = 0; i < n; ++i) {
      int at = static_cast<int>(i);
      size_t steps = 0;
      while (at >= 0 && steps <= n) {
        at = parent_[static_cast<size_t>(at)];
        ++steps;
      }
      if (at >= 0) return fail("node " + std::to_string(i) + " is part of a node cycle");
    }
    global_.assign(n, glm::dmat4(1.0));
    std::vector<uint8_t> visited(n, 0);
    std::vector<std::pair<int, glm::dmat4>> stack;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it)
      stack.push_back({*it, glm::dmat4(1.0)});
    while (!stack.empty()) {
      const auto [node, parentMatrix] = stack.back();
      stack.pop_back();
      if (node < 0 || static_cast<size_t>(node) >= n)
        return fail("the scene names missing node " + std::to_string(node));
      const size_t i = static_cast<size_t>(node);
      if (visited[i])
        return fail("node " + std::to_string(node) +
                    " is reached twice from the scene (a node cycle)");
      visited[i] = 1;
      global_[i] = parentMatrix * detail::localMatrix(gltf_.nodes[i]);
      order_.push_back(i);
      const auto& children = gltf_.nodes[i].children;
      for (auto it = children.rbegin(); it != children.rend(); ++it)
        stack.push_back({*it, global_[i]});
    }
    // Nodes outside the scene (joints may be) get their transform through their parent chain.
    for (size_t i = 0; i < n; ++i) {
      if (visited[i]) continue;
      glm::dmat4 m(1.0);
      for (int at = static_cast<int>(i); at >= 0; at = parent_[static_cast<size_t>(at)]) {
        m = detail::localMatrix(gltf_.nodes[static_cast<size_t>(at)]) * m;
      }
      global_[i] = m;
    }
    return true;
  }

  void readImages(Model& model) {
    for (size_t i = 0; i < gltf_.images.size(); ++i) {
      const tinygltf::Image& image = gltf_.images[i];
      ModelImage out;
      out.name = !image.name.empty() ? image.name : image.uri;
      const size_t expected =
          size_t(std::max(image.width, 0)) * size_t(std::max(image.height, 0)) * 4;
      if (image.width > 0 && image.height > 0 && image.component == 4 && image.bits == 8 &&
          image.image.size() == expected) {
        out.width = image.width;
        out.height = image.height;
        out.rgba = image.image;
      } else {
        warn("image " + std::to_string(i) + " ('" + out.name + "') has no decoded pixels");
      }
      if (i < encoded_.size()) {
        out.mimeType = std::move(encoded_[i].mimeType);
        out.encoded = std::move(encoded_[i].bytes);
      }
      model.images.push_back(std::move(out));
    }
  }

  // A sampler's filter or wrap mode: `value` when glTF allows it, else `fallback` with a warning.
  int32_t samplerMode(int value, std::initializer_list<int> allowed, int32_t fallback,
                      size_t sampler, const char* what) {
    if (value == fallback || std::find(allowed.begin(), allowed.end(), value) != allowed.end())
      return value;
    warn("sampler " + std::to_string(sampler) + " has an unknown " + what + " " +
         std::to_string(value) + "; the default is used");
    return fallback;
  }

  void readSamplers(Model& model) {
    const std::initializer_list<int> wraps = {33071, 33648, 10497};
    for (size_t i = 0; i < gltf_.samplers.size(); ++i) {
      const tinygltf::Sampler& sampler = gltf_.samplers[i];
      ModelSampler out;
      out.name = sampler.name;
      out.magFilter = samplerMode(sampler.magFilter, {9728, 9729}, -1, i, "magFilter");
      out.minFilter = samplerMode(sampler.minFilter, {9728, 9729, 9984, 9985, 9986, 9987}, -1, i,
                                  "minFilter");
      out.wrapS = samplerMode(sampler.wrapS, wraps, 10497, i, "wrapS");
      out.wrapT = samplerMode(sampler.wrapT, wraps, 10497, i, "wrapT");
      model.samplers.push_back(std::move(out));
    }
  }

  // Texture `texture`'s reference to its image or sampler: -1 for none, and for a missing one
  // (with a warning).
  int32_t textureSource(size_t texture, int index, size_t count, const char* what) {
    if (index < 0) return -1;
    if (static_cast<size_t>(index) < count) return index;
    warn("texture " + std::to_string(texture) + " names missing " + what + " " +
         std::to_string(index));
    return -1;
  }

  // Textures with their image and sampler. A texture without a source (its image given by an
  // extension) has no image.
  void readTextures(Model& model) {
    for (size_t i = 0; i < gltf_.textures.size(); ++i) {
      const tinygltf::Texture& texture = gltf_.textures[i];
      ModelTexture out;
      out.name = texture.name;
      out.image = textureSource(i, texture.source, gltf_.images.size(), "image");
      out.sampler = textureSource(i, texture.sampler, gltf_.samplers.size(), "sampler");
      model.textures.push_back(std::move(out));
    }
  }

  // Material `material`'s use of texture `index` with set `texCoord`; none (with a warning) when
  // the texture does not exist.
  ModelTextureRef textureRef(int index, int texCoord, size_t material) {
    if (index < 0) return {};
    if (static_cast<size_t>(index) >= gltf_.textures.size() || texCoord < 0) {
      warn("material " + std::to_string(material) + " names missing texture " +
           std::to_string(index) + " (set " + std::to_string(texCoord) + ")");
      return {};
    }
    return ModelTextureRef{index, texCoord};
  }

  // The factors of material `i`; false (the model fails) when one is not finite.
  bool readFactors(const tinygltf::Material& material, size_t i, ModelMaterial& out) {
    const tinygltf::PbrMetallicRoughness& pbr = material.pbrMetallicRoughness;
    const std::vector<double>& factor = pbr.baseColorFactor;
    if (factor.size() == 4) {
      out.baseColorFactor =
          glm::vec4(float(factor[0]), float(factor[1]), float(factor[2]), float(factor[3]));
    }
    out.metallicFactor = static_cast<float>(pbr.metallicFactor);
    out.roughnessFactor = static_cast<float>(pbr.roughnessFactor);
    out.normalScale = static_cast<float>(material.normalTexture.scale);
    const glm::vec4& color = out.baseColorFactor;
    for (const float value : {color.r, color.g, color.b, color.a, out.metallicFactor,
                              out.roughnessFactor, out.normalScale}) {
      if (!std::isfinite(value)) {
        return fail("material " + std::to_string(i) +
                    " has a non-finite base colour, metallic, roughness or normal scale factor");
      }
    }
    return true;
  }

  bool readMaterials(Model& model) {
    auto imageOf = [&](const ModelTextureRef& ref) {
      return ref.texture < 0 ? -1 : model.textures[static_cast<size_t>(ref.texture)].image;
    };
    for (size_t i = 0; i < gltf_.materials.size(); ++i) {
      const tinygltf::Material& material = gltf_.materials[i];
      ModelMaterial out;
      out.name = material.name.empty() ? "material_" + std::to_string(i) : material.name;
      if (!readFactors(material, i, out)) return false;
      const tinygltf::TextureInfo& base = material.pbrMetallicRoughness.baseColorTexture;
      const tinygltf::NormalTextureInfo& normal = material.normalTexture;
      out.baseColorTexture = textureRef(base.index, base.texCoord, i);
      out.normalTexture = textureRef(normal.index, normal.texCoord, i);
      out.baseColorImage = imageOf(out.baseColorTexture);
      out.normalImage = imageOf(out.normalTexture);
      out.doubleSided = material.doubleSided;
      model.materials.push_back(std::move(out));
    }
    return true;
  }

  // The joint index of each joint node of a skin; false when a node is missing or named twice.
  bool jointNodes(const tinygltf::Skin& skin, const std::string& what,
                  std::map<int, int32_t>& jointOf) {
    if (skin.joints.empty()) return fail(what + " has no joints");
    if (skin.joints.size() > 65535) return fail(what + " has too many joints");
    for (size_t j = 0; j < skin.joints.size(); ++j) {
      const int node = skin.joints[j];
      if (node < 0 || static_cast<size_t>(node) >= gltf_.nodes.size()) {
        return fail(what + " names missing joint node " + std::to_string(node));
      }
      if (!jointOf.emplace(node, static_cast<int32_t>(j)).second) {
        return fail(what + " names node " + std::to_string(node) + " twice");
      }
    }
    return true;
  }

  // The skin's inverse bind matrices (identity without them): float MAT4, one per joint, finite.
  bool inverseBindMatrices(const tinygltf::Skin& skin, const std::string& what,
                           std::vector<glm::mat4>& inverseBind) {
    inverseBind.assign(skin.joints.size(), glm::mat4(1.f));
    if (skin.inverseBindMatrices < 0) return true;
    AccessorView view;
    std::string reason;
    if (!viewAccessor(gltf_, skin.inverseBindMatrices, view, reason))
      return fail(what + ": " + reason);
    if (view.components != 16 || view.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT ||
        view.count < skin.joints.size()) {
      return fail(what + ": inverse bind matrices must be float MAT4, one per joint");
    }
    for (size_t j = 0; j < skin.joints.size(); ++j) {
      for (int c = 0; c < 16; ++c) {
        const double v = component(view, j, c);
        if (!std::isfinite(v))
          return fail(what + ": inverse bind matrix " + std::to_string(j) + " is not finite");
        inverseBind[j][c / 4][c % 4] = static_cast<float>(v);
      }
    }
    return true;
  }

  // A joint node's rest transform (translation, rotation, scale), or for a matrix node (glTF does
  // not animate those) its matrix as the fixed offset.
  bool jointRest(size_t node, anim::Joint& joint, glm::dmat4& offset) {
    const tinygltf::Node& n = gltf_.nodes[node];
    offset = glm::dmat4(1.0);
    if (n.matrix.size() == 16) {
      offset = detail::localMatrix(n);
      return true;
    }
    if (n.translation.size() == 3)
      joint.rest.translation = glm::vec3(n.translation[0], n.translation[1], n.translation[2]);
    if (n.rotation.size() == 4) {
      glm::quat q(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]),
                  float(n.rotation[2]));
      const float len = glm::length(q);
      if (!(len > 0.f) || !std::isfinite(len))
        return fail("node " + std::to_string(node) + " has an invalid rotation");
      joint.rest.rotation = q / len;
    }
    if (n.scale.size() == 3) joint.rest.scale = glm::vec3(n.scale[0], n.scale[1], n.scale[2]);
    return true;
  }

  // Joint j of a skin: its name, inverse bind, rest transform, parent joint and fixed offset.
  bool readJoint(const tinygltf::Skin& skin, size_t j, std::map<int, int32_t>& jointOf,
                 const std::string& what, anim::Joint& joint) {
    const size_t node = static_cast<size_t>(skin.joints[j]);
    const tinygltf::Node& n = gltf_.nodes[node];
    joint.name = n.name.empty() ? "joint_" + std::to_string(j) : n.name;
    glm::dmat4 offset(1.0);
    if (!jointRest(node, joint, offset)) return false;
    int at = parent_[node];
    glm::dmat4 between(1.0);
    while (at >= 0 && jointOf.find(at) == jointOf.end()) {
      between = detail::localMatrix(gltf_.nodes[static_cast<size_t>(at)]) * between;
      at = parent_[static_cast<size_t>(at)];
    }
    joint.parent = at >= 0 ? jointOf[at] : -1;
    joint.offset = glm::mat4(between * offset);
    for (int c = 0; c < 4; ++c) {
      for (int r = 0; r < 4; ++r) {
        if (!std::isfinite(joint.offset[c][r]))
          return fail(what + ": joint " + std::to_string(j) + " has a non-finite transform");
      }
    }
    return true;
  }

  // One skeleton per skin. A joint's parent is its nearest ancestor node that is a joint of the
  // same skin; non-joint nodes between them (or above a root joint) become the joint's fixed
  // offset.
  bool readSkins(Model& model) {
    for (size_t s = 0; s < gltf_.skins.size(); ++s) {
      const tinygltf::Skin& skin = gltf_.skins[s];
      const std::string what = "skin " + std::to_string(s);
      std::map<int, int32_t> jointOf;
      std::vector<glm::mat4> inverseBind;
      if (!jointNodes(skin, what, jointOf) || !inverseBindMatrices(skin, what, inverseBind))
        return false;
      ModelSkin out;
      out.name = skin.name.empty() ? what : skin.name;
      out.skeleton.joints.resize(skin.joints.size());
      for (size_t j = 0; j < skin.joints.size(); ++j) {
        out.skeleton.joints[j].inverseBind = inverseBind[j];
        if (!readJoint(skin, j, jointOf, what, out.skeleton.joints[j])) return false;
      }
      const base::Status valid = anim::validateSkeleton(out.skeleton);
      if (!valid.ok()) return fail(what + ": " + valid.message);
      model.skins.push_back(std::move(out));
    }
    return true;
  }

  // An animation sampler, decoded once for every skin's clip.
  struct Sampler {
    std::vector<float> times;
    std::vector<glm::vec4> values;  // raw, components padded with 0
    anim::Interpolation interpolation = anim::Interpolation::Linear;
    int components = 0;
  };

  bool readSampler(const tinygltf::AnimationSampler& in, const std::string& what, Sampler& out) {
    if (in.interpolation == "STEP")
      out.interpolation = anim::Interpolation::Step;
    else if (in.interpolation == "CUBICSPLINE")
      out.interpolation = anim::Interpolation::CubicSpline;
    else if (in.interpolation.empty() || in.interpolation == "LINEAR")
      out.interpolation = anim::Interpolation::Linear;
    else
      return fail(what + ": unknown interpolation " + in.interpolation);
    AccessorView input, output;
    std::string reason;
    if (!viewAccessor(gltf_, in.input, input, reason) ||
        !viewAccessor(gltf_, in.output, output, reason)) {
      return fail(what + ": " + reason);
    }
    if (input.components != 1 || input.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
      return fail(what + ": key times must be float scalars");
    }
    out.components = output.components;
    for (size_t k = 0; k < input.count; ++k) {
      const float t = static_cast<float>(component(input, k, 0));
      if (!std::isfinite(t) || (!out.times.empty() && !(t > out.times.back()))) {
        return fail(what + ": key times must be finite and increasing");
      }
      out.times.push_back(t);
    }
    if (output.components > 4) return true;
    for (size_t k = 0; k < output.count; ++k) {
      glm::vec4 v(0.f);
      for (int c = 0; c < output.components; ++c)
        v[c] = static_cast<float>(component(output, k, c));
      out.values.push_back(v);
    }
    return true;
  }

  // Channel c of an animation as a channel of `skin`'s clip; `keep` false for a channel that
  // targets no joint of the skin or morph-target weights.
  bool readChannel(const tinygltf::Animation& animation, size_t c, const tinygltf::Skin& skin,
                   const std::vector<Sampler>& samplers, const std::string& what,
                   anim::Channel& out, bool& keep) {
    keep = false;
    const tinygltf::AnimationChannel& channel = animation.channels[c];
    if (channel.sampler < 0 || static_cast<size_t>(channel.sampler) >= samplers.size()) {
      return fail(what + " channel " + std::to_string(c) + " names missing sampler " +
                  std::to_string(channel.sampler));
    }
    if (channel.target_node < 0) return true;
    const auto it = std::find(skin.joints.begin(), skin.joints.end(), channel.target_node);
    if (it == skin.joints.end()) return true;
    out.joint = static_cast<uint32_t>(it - skin.joints.begin());
    int components = 0;
    if (channel.target_path == "translation")
      out.path = anim::ChannelPath::Translation, components = 3;
    else if (channel.target_path == "rotation")
      out.path = anim::ChannelPath::Rotation, components = 4;
    else if (channel.target_path == "scale")
      out.path = anim::ChannelPath::Scale, components = 3;
    else
      return true;  // morph-target weights
    const Sampler& sampler = samplers[static_cast<size_t>(channel.sampler)];
    out.interpolation = sampler.interpolation;
    out.times = sampler.times;
    out.values = sampler.values;
    const size_t perKey = out.interpolation == anim::Interpolation::CubicSpline ? 3 : 1;
    if (sampler.components != components || out.values.size() != out.times.size() * perKey ||
        out.times.empty()) {
      return fail(what + " channel " + std::to_string(c) +
                  ": the sampler output does not match its " + channel.target_path + " keys");
    }
    if (out.path == anim::ChannelPath::Rotation &&
        out.interpolation != anim::Interpolation::CubicSpline) {
      for (glm::vec4& q : out.values) {
        const float len = glm::length(q);
        if (len > 0.f && std::isfinite(len)) q /= len;
      }
    }
    keep = true;
    return true;
  }

  bool readAnimations(Model& model) {
    for (size_t a = 0; a < gltf_.animations.size(); ++a) {
      const tinygltf::Animation& animation = gltf_.animations[a];
      const std::string what = "animation " + std::to_string(a);
      std::vector<Sampler> samplers(animation.samplers.size());
      for (size_t s = 0; s < animation.samplers.size(); ++s) {
        if (!readSampler(animation.samplers[s], what + " sampler " + std::to_string(s),
                         samplers[s]))
          return false;
      }
      for (size_t s = 0; s < model.skins.size(); ++s) {
        anim::AnimationClip clip;
        clip.name = animation.name.empty() ? what : animation.name;
        for (size_t c = 0; c < animation.channels.size(); ++c) {
          anim::Channel out;
          bool keep = false;
          if (!readChannel(animation, c, gltf_.skins[s], samplers, what, out, keep)) return false;
          if (keep) clip.channels.push_back(std::move(out));
        }
        if (clip.channels.empty()) continue;
        clip.updateDuration();
        const base::Status valid = anim::validateClip(clip, model.skins[s].skeleton.size());
        if (!valid.ok()) return fail(valid.message);
        model.skins[s].clips.push_back(std::move(clip));
      }
    }
    return true;
  }

  bool readMesh(size_t meshIndex, const glm::dmat4& transform, ModelMesh& out) {
    const tinygltf::Mesh& mesh = gltf_.meshes[meshIndex];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      if (!readPrimitive(meshIndex, p, transform, out)) return false;
    }
    geometry::MeshData& m = out.mesh;
    if (!anyUv_) m.uv0.clear();
    if (out.skin < 0) {
      m.joints.clear();
      m.weights.clear();
    }
    anyUv_ = false;
    return true;
  }

  // The accessors of a primitive's attributes, by VertexField (see gltf_attributes.h).
  struct PrimitiveViews {
    AccessorView views[5];
    bool present[5] = {};
    const AccessorView& operator[](detail::VertexField f) const { return views[size_t(f)]; }
    bool has(detail::VertexField f) const { return present[size_t(f)]; }
  };

  // Views every attribute of the table, then checks each against what it accepts.
  bool viewAttributes(const tinygltf::Primitive& primitive, const std::string& where, int skin,
                      PrimitiveViews& v) {
    using detail::VertexField;
    for (size_t a = 0; a < std::size(detail::kGltfAttributes); ++a) {
      const detail::GltfAttribute& attribute = detail::kGltfAttributes[a];
      std::string reason;
      int accessor = -1;
      if (!detail::viewAttribute(gltf_, primitive, attribute, v.views[a], accessor, reason))
        return fail(where + attribute.name + ": " + reason);
      v.present[a] = accessor >= 0;
    }
    if (!v.has(VertexField::Positions)) return fail(where + "has no POSITION attribute");
    const size_t n = v[VertexField::Positions].count;
    for (const VertexField field :
         {VertexField::Positions, VertexField::Normals, VertexField::Uv0}) {
      const detail::GltfAttribute& attribute = detail::gltfAttribute(field);
      if (v.has(field) && !detail::attributeFits(attribute, v[field], n))
        return fail(where + attribute.requirement);
    }
    if (skin < 0) return true;
    const bool hasJoints = v.has(VertexField::Joints);
    if (hasJoints != v.has(VertexField::Weights))
      return fail(where + "JOINTS_0 and WEIGHTS_0 must come together");
    if (!hasJoints) {
      warn(where + "a skinned mesh without JOINTS_0: bound to joint 0");
      return true;
    }
    for (const VertexField field : {VertexField::Joints, VertexField::Weights}) {
      const detail::GltfAttribute& attribute = detail::gltfAttribute(field);
      if (!detail::attributeFits(attribute, v[field], n))
        return fail(where + attribute.requirement);
    }
    return true;
  }

  // The joints and weights of vertex i: the weights normalised to a sum of 1, a joint without
  // weight set to 0; joint 0 with weight 1 when the vertex has no weight at all.
  bool skinVertex(const PrimitiveViews& v, size_t i, size_t jointCount, const std::string& where,
                  glm::u16vec4& j, glm::vec4& w) {
    using detail::VertexField;
    j = glm::u16vec4(0);
    w = glm::vec4(1.f, 0.f, 0.f, 0.f);
    if (!v.has(VertexField::Joints)) return true;
    double raw[4], total = 0.0;
    for (int k = 0; k < 4; ++k) {
      raw[k] = component(v[VertexField::Weights], i, k);
      if (!std::isfinite(raw[k]) || raw[k] < 0.0) raw[k] = 0.0;
      const double joint = component(v[VertexField::Joints], i, k);
      if (raw[k] > 0.0 && joint >= static_cast<double>(jointCount)) {
        return fail(where + "vertex " + std::to_string(i) + " uses joint " +
                    std::to_string(uint64_t(joint)) + " of a skin with " +
                    std::to_string(jointCount) + " joints");
      }
      j[k] = raw[k] > 0.0 ? static_cast<uint16_t>(joint) : 0;
      total += raw[k];
    }
    if (total > 0.0) {
      for (int k = 0; k < 4; ++k) w[k] = static_cast<float>(raw[k] / total);
    } else {
      j = glm::u16vec4(0);
    }
    return true;
  }

  // Appends the primitive's vertices to out.mesh: positions by `transform`, normals by its normal
  // matrix (zero when absent or degenerate), uv0 (zero when absent), joints and weights when
  // skinned.
  bool appendVertices(const PrimitiveViews& v, const glm::dmat4& transform,
                      const std::string& where, ModelMesh& out) {
    using detail::VertexField;
    geometry::MeshData& m = out.mesh;
    const size_t n = v[VertexField::Positions].count;
    const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(transform)));
    const size_t jointCount =
        out.skin >= 0 ? gltf_.skins[static_cast<size_t>(out.skin)].joints.size() : 0;
    const AccessorView &positions = v[VertexField::Positions], &normals = v[VertexField::Normals],
                       &uvs = v[VertexField::Uv0];
    for (size_t i = 0; i < n; ++i) {
      const glm::dvec3 local(component(positions, i, 0), component(positions, i, 1),
                             component(positions, i, 2));
      const glm::dvec3 p = glm::dvec3(transform * glm::dvec4(local, 1.0));
      if (!finite3(local) || !finite3(p)) {
        return fail(where + "vertex " + std::to_string(i) + " has a non-finite position");
      }
      m.positions.emplace_back(p);
      glm::vec3 normal(0.f);
      if (v.has(VertexField::Normals)) {
        const glm::dvec3 t =
            normalMatrix * glm::dvec3(component(normals, i, 0), component(normals, i, 1),
                                      component(normals, i, 2));
        const double len = glm::length(t);
        if (len > 0.0 && std::isfinite(len)) normal = glm::vec3(t / len);
      }
      m.normals.push_back(normal);
      m.uv0.push_back(v.has(VertexField::Uv0)
                          ? glm::vec2(component(uvs, i, 0), component(uvs, i, 1))
                          : glm::vec2(0.f));
      if (out.skin < 0) continue;
      glm::u16vec4 j;
      glm::vec4 w;
      if (!skinVertex(v, i, jointCount, where, j, w)) return false;
      m.joints.push_back(j);
      m.weights.push_back(w);
    }
    return true;
  }

  // Missing (or degenerate) normals: area-weighted smooth normals of the primitive's triangles
  // (indices from firstIndex, vertices from base).
  static void fillMissingNormals(geometry::MeshData& m, size_t base, size_t firstIndex,
                                 bool hasNormal) {
    const size_t n = m.positions.size() - base;
    bool needNormals = !hasNormal;
    for (size_t i = base; i < m.positions.size() && !needNormals; ++i)
      needNormals = m.normals[i] == glm::vec3(0.f);
    if (!needNormals) return;
    std::vector<glm::dvec3> sum(n, glm::dvec3(0.0));
    for (size_t t = firstIndex; t < m.indices.size(); t += 3) {
      const glm::dvec3 a(m.positions[m.indices[t]]), b(m.positions[m.indices[t + 1]]),
          c(m.positions[m.indices[t + 2]]);
      const glm::dvec3 face = glm::cross(b - a, c - a);
      for (int k = 0; k < 3; ++k) sum[m.indices[t + k] - base] += face;
    }
    for (size_t i = 0; i < n; ++i) {
      if (hasNormal && m.normals[base + i] != glm::vec3(0.f)) continue;
      const double len = glm::length(sum[i]);
      m.normals[base + i] =
          len > 0.0 && std::isfinite(len) ? glm::vec3(sum[i] / len) : glm::vec3(0.f, 1.f, 0.f);
    }
  }

  // The triangles of a primitive of n vertices (its indices or 0..n-1, by its mode).
  bool primitiveTriangles(const tinygltf::Primitive& primitive, int mode, size_t n,
                          const std::string& where, std::vector<uint32_t>& triangles) {
    std::vector<uint32_t> corners;
    detail::CornerFailure failure;
    if (!detail::primitiveCorners(gltf_, primitive, n, corners, failure)) {
      switch (failure.kind) {
        case detail::CornerFailure::View:
          return fail(where + "indices: " + failure.reason);
        case detail::CornerFailure::Type:
          return fail(where + "indices must be unsigned byte, short or int scalars");
        case detail::CornerFailure::Range:
          return fail(where + "index " + std::to_string(failure.index) + " at position " +
                      std::to_string(failure.position) + " is out of range (" + std::to_string(n) +
                      " vertices)");
        case detail::CornerFailure::TooManyVertices:
          return fail(where + "too many vertices");
      }
    }
    if (!detail::trianglesOfPrimitive(mode, corners, triangles))
      warn(where + "index count not a multiple of 3; the last partial triangle is ignored");
    return true;
  }

  // The material id of a primitive: its material, or the default material after the file's.
  bool primitiveMaterial(const tinygltf::Primitive& primitive, const std::string& where,
                         uint32_t& materialId) {
    if (primitive.material < 0) {
      materialId = static_cast<uint32_t>(gltf_.materials.size());
      usesDefaultMaterial_ = true;
      return true;
    }
    if (static_cast<size_t>(primitive.material) >= gltf_.materials.size()) {
      return fail(where + "material " + std::to_string(primitive.material) + " does not exist");
    }
    materialId = static_cast<uint32_t>(primitive.material);
    return true;
  }

  bool readPrimitive(size_t meshIndex, size_t primitiveIndex, const glm::dmat4& transform,
                     ModelMesh& out) {
    const tinygltf::Primitive& primitive = gltf_.meshes[meshIndex].primitives[primitiveIndex];
    const std::string where =
        "mesh " + std::to_string(meshIndex) + " primitive " + std::to_string(primitiveIndex) + ": ";
    if (detail::usesDraco(primitive)) {
      return fail(where + "uses KHR_draco_mesh_compression, which is not supported");
    }
    int mode = 0;
    if (!detail::triangleMode(primitive, mode)) {
      warn(where + "mode " + std::to_string(mode) + " (points or lines) skipped");
      return true;
    }
    PrimitiveViews views;
    if (!viewAttributes(primitive, where, out.skin, views)) return false;
    const size_t n = views[detail::VertexField::Positions].count;
    std::vector<uint32_t> triangles;
    if (!primitiveTriangles(primitive, mode, n, where, triangles)) return false;
    if (triangles.empty()) return true;
    const uint64_t elements = uint64_t{n} + triangles.size();
    if (elements > budget_)
      return fail("the scene instantiates more geometry than the file size allows");
    budget_ -= elements;

    geometry::MeshData& m = out.mesh;
    const size_t base = m.positions.size();
    if (base + n > UINT32_MAX) return fail("too many vertices");
    if (!appendVertices(views, transform, where, out)) return false;
    const bool hasNormal = views.has(detail::VertexField::Normals);
    anyUv_ = anyUv_ || views.has(detail::VertexField::Uv0);

    uint32_t materialId = 0;
    if (!primitiveMaterial(primitive, where, materialId)) return false;
    const size_t firstIndex = m.indices.size();
    m.submeshes.push_back(geometry::SubMesh{static_cast<uint32_t>(firstIndex), 0, materialId});
    const bool mirrored = glm::determinant(glm::dmat3(transform)) < 0.0;
    detail::appendTriangles(triangles, base, mirrored, m.indices);
    m.submeshes.back().indexCount = static_cast<uint32_t>(m.indices.size() - firstIndex);
    fillMissingNormals(m, base, firstIndex, hasNormal);
    return true;
  }

  const tinygltf::Model& gltf_;
  const std::string& name_;
  std::vector<EncodedImage> encoded_;  // by image index, moved into Model::images
  ModelLoadResult* result_ = nullptr;
  uint64_t budget_ = 0;
  std::vector<int> parent_;
  std::vector<glm::dmat4> global_;
  std::vector<size_t> order_;
  bool usesDefaultMaterial_ = false;
  bool anyUv_ = false;
};

ModelLoadResult failed(const std::string& name, const std::string& reason,
                       std::vector<std::string> warnings = {}) {
  ModelLoadResult result;
  result.setFailure(base::StatusCode::ParseError, name + ": " + reason);
  result.warnings = std::move(warnings);
  return result;
}

// The names in the JSON's "extensionsRequired" array, found by a plain text scan. This runs before
// tinygltf because a file with, say, Draco-compressed primitives is usually rejected by tinygltf
// for a consequence (accessors without buffer views) rather than for the cause.
std::vector<std::string> requiredExtensions(std::string_view json) {
  std::vector<std::string> names;
  const size_t key = json.find("\"extensionsRequired\"");
  if (key == std::string_view::npos) return names;
  const size_t open = json.find('[', key);
  const size_t close = open == std::string_view::npos ? open : json.find(']', open);
  if (close == std::string_view::npos) return names;
  size_t at = open;
  while (true) {
    const size_t begin = json.find('"', at + 1);
    if (begin == std::string_view::npos || begin > close) break;
    const size_t end = json.find('"', begin + 1);
    if (end == std::string_view::npos || end > close) break;
    names.emplace_back(json.substr(begin + 1, end - begin - 1));
    at = end;
  }
  return names;
}

ModelLoadResult readModel(std::span<const uint8_t> bytes, const std::string& name,
                          const std::optional<std::string>& baseDir) {
  if (bytes.size() > UINT32_MAX) return failed(name, "file too large for glTF");
  if (bytes.empty()) return failed(name, "the file is empty");
  const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  std::string_view json(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  if (binary) {
    uint32_t length = 0;
    if (bytes.size() >= 20) std::memcpy(&length, bytes.data() + 12, 4);
    json = bytes.size() >= 20 ? json.substr(20, std::min<size_t>(length, bytes.size() - 20))
                              : std::string_view();
  }
  for (const std::string& extension : requiredExtensions(json)) {
    if (!detail::geometryNeutral(extension)) {
      return failed(name, "requires the glTF extension " + extension + ", which is not supported");
    }
  }
  tinygltf::Model gltf;
  std::vector<EncodedImage> encoded;
  detail::GltfParse parse =
      detail::parseGltf(bytes, name, binary, baseDir, decodeImage, &encoded, gltf);
  if (!parse.ok()) return failed(name, parse.message, std::move(parse.warnings));
  std::vector<std::string> warnings = std::move(parse.warnings);
  ModelLoadResult result;
  result.warnings = std::move(warnings);
  Loader reader(gltf, name, bytes.size(), std::move(encoded));
  if (!reader.run(result)) {
    ModelLoadResult failure;
    failure.setFailure(result.code, std::move(result.message));
    failure.warnings = std::move(result.warnings);
    return failure;
  }
  result.code = base::StatusCode::Ok;
  return result;
}

}  // namespace

ModelLoadResult loadModel(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    return failed(path, "is a directory, not a glTF file");
  std::ifstream file(path, std::ios::binary);
  if (!file) return failed(path, "cannot open the file");
  file.seekg(0, std::ios::end);
  const std::streamoff size = file.tellg();
  if (size < 0) return failed(path, "cannot read the file");
  if (static_cast<uint64_t>(size) > UINT32_MAX) return failed(path, "file too large for glTF");
  std::vector<uint8_t> bytes(static_cast<size_t>(size));
  file.seekg(0);
  if (size > 0 && !file.read(reinterpret_cast<char*>(bytes.data()), size))
    return failed(path, "cannot read the file");
  std::string baseDir = std::filesystem::path(path).parent_path().string();
  if (baseDir.empty()) baseDir = ".";
  return readModel(bytes, path, baseDir);
}

ModelLoadResult readModelFromMemory(std::span<const uint8_t> bytes, const std::string& name) {
  return readModel(bytes, name, std::nullopt);
}

}  // namespace cleave::assets
