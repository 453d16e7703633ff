// SPDX-License-Identifier: MIT
// The skinned GLB writer (see model.h): a skinned mesh in bind space with its skeleton and clips as
// binary glTF 2.0 that loadModel reads back and the Khronos validator accepts.
//
// Layout. Node per joint with the joint's rest transform as translation, rotation and scale, under
// its parent joint's node; a joint whose fixed offset (non-joint nodes between two joints in the
// file it came from) is not the identity gets an extra parent node holding that offset as a matrix.
// The mesh node carries the mesh and the skin and sits at the scene root without a transform (glTF
// places a skinned mesh by its joints only). One primitive per submesh run; attributes POSITION
// (with bounds), NORMAL, TEXCOORD_0, JOINTS_0 (unsigned short) and WEIGHTS_0 (float); uint32
// indices. The skin lists the joint nodes in skeleton order with their inverse bind matrices. Each
// clip becomes one animation with a sampler and a channel per clip channel (times with their
// bounds, values as vec3 for translation and scale, xyzw quaternions for rotation; cubic spline
// keys keep their in-tangent, value, out-tangent triples).
//
// The buffer, the vertex data, the materials, the primitives and the serialisation are the GLB
// writing core (glb_builder.h) that the static writer uses too; this file adds the skin to it.
#include <cmath>
#include <utility>

#include <tiny_gltf.h>

#include "cleave/assets/glb_builder.h"
#include "cleave/assets/gltf_attributes.h"
#include "cleave/assets/mesh_reader.h"
#include "cleave/assets/model.h"

namespace cleave::assets {

namespace {

bool finiteMatrix(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      if (!std::isfinite(m[c][r])) return false;
    }
  }
  return true;
}

const char* interpolationName(anim::Interpolation interpolation) {
  switch (interpolation) {
    case anim::Interpolation::Step: return "STEP";
    case anim::Interpolation::CubicSpline: return "CUBICSPLINE";
    case anim::Interpolation::Linear: break;
  }
  return "LINEAR";
}

const char* pathName(anim::ChannelPath path) {
  switch (path) {
    case anim::ChannelPath::Translation: return "translation";
    case anim::ChannelPath::Scale: return "scale";
    case anim::ChannelPath::Rotation: break;
  }
  return "rotation";
}

// What the writer needs of its input: valid runs, a valid skeleton of 1 to 65535 joints with finite
// transforms, joints and weights for every vertex naming joints of the skeleton.
bool checkSkinnedInput(const geometry::MeshData& mesh, const anim::Skeleton& skeleton,
                       std::vector<geometry::SubMesh>& runs, std::string& reason) {
  if (!detail::glbRuns(mesh, runs, reason)) return false;
  if (skeleton.size() == 0) {
    reason = "the skeleton has no joints";
    return false;
  }
  if (skeleton.size() > 65535) {
    reason = "the skeleton has more than 65535 joints";
    return false;
  }
  if (const base::Status valid = anim::validateSkeleton(skeleton); !valid.ok()) {
    reason = valid.message;
    return false;
  }
  if (mesh.joints.size() != mesh.positions.size() || mesh.weights.size() != mesh.positions.size()) {
    reason = "the mesh has no joints and weights for every vertex";
    return false;
  }
  for (size_t v = 0; v < mesh.joints.size(); ++v) {
    for (int k = 0; k < 4; ++k) {
      if (mesh.weights[v][k] != 0.f && mesh.joints[v][k] >= skeleton.size()) {
        reason = "vertex " + std::to_string(v) + " uses joint " +
                 std::to_string(mesh.joints[v][k]) + " of a skeleton of " +
                 std::to_string(skeleton.size());
        return false;
      }
    }
  }
  for (size_t j = 0; j < skeleton.size(); ++j) {
    const anim::Joint& joint = skeleton.joints[j];
    if (!finiteMatrix(joint.inverseBind) || !finiteMatrix(joint.offset) || !finiteMatrix(joint.rest.matrix())) {
      reason = "joint " + std::to_string(j) + " has a non-finite transform";
      return false;
    }
  }
  return true;
}

// JOINTS_0 and WEIGHTS_0 as the attribute table has them. Unused influence slots are written as
// joint 0 with weight 0, which glTF allows.
void addSkinAttributes(tinygltf::Model& model, const geometry::MeshData& mesh,
                       detail::GlbAttributes& attributes) {
  const size_t n = mesh.positions.size();
  std::vector<glm::u16vec4> joints(n);
  for (size_t v = 0; v < n; ++v) {
    for (int k = 0; k < 4; ++k) joints[v][k] = mesh.weights[v][k] != 0.f ? mesh.joints[v][k] : uint16_t(0);
  }
  const detail::GltfAttribute& jointsAttribute = detail::gltfAttribute(detail::VertexField::Joints);
  const detail::GltfAttribute& weightsAttribute =
      detail::gltfAttribute(detail::VertexField::Weights);
  attributes[jointsAttribute.name] =
      detail::addData(model, joints, TINYGLTF_TARGET_ARRAY_BUFFER,
                      jointsAttribute.writtenComponentType, jointsAttribute.type);
  attributes[weightsAttribute.name] =
      detail::addData(model, mesh.weights, TINYGLTF_TARGET_ARRAY_BUFFER,
                      weightsAttribute.writtenComponentType, weightsAttribute.type);
}

// The node of joint j with its rest transform, under an offset node when its fixed offset is not
// the identity. Gives the joint's node; `top` is the offset node or the joint's node.
int addJointNode(tinygltf::Model& model, const anim::Joint& joint, int& top) {
  top = -1;
  if (joint.offset != glm::mat4(1.f)) {
    tinygltf::Node offset;
    offset.name = joint.name + "_offset";
    offset.matrix.assign(16, 0.0);
    for (int c = 0; c < 4; ++c) {
      for (int r = 0; r < 4; ++r) offset.matrix[size_t(4 * c + r)] = joint.offset[c][r];
    }
    model.nodes.push_back(offset);
    top = static_cast<int>(model.nodes.size() - 1);
  }
  tinygltf::Node node;
  node.name = joint.name;
  const glm::vec3 t = joint.rest.translation, s = joint.rest.scale;
  const glm::quat q = glm::normalize(joint.rest.rotation);
  if (t != glm::vec3(0.f)) node.translation = {t.x, t.y, t.z};
  if (q != glm::quat(1.f, 0.f, 0.f, 0.f)) node.rotation = {q.x, q.y, q.z, q.w};
  if (s != glm::vec3(1.f)) node.scale = {s.x, s.y, s.z};
  model.nodes.push_back(node);
  const int index = static_cast<int>(model.nodes.size() - 1);
  if (top >= 0)
    model.nodes[static_cast<size_t>(top)].children.push_back(index);
  else
    top = index;
  return index;
}

// Joint nodes (and offset nodes above joints with a fixed offset), then the hierarchy; gives the
// root nodes and each joint's node.
std::vector<int> addJointNodes(tinygltf::Model& model, const anim::Skeleton& skeleton,
                               std::vector<int>& jointNode) {
  const size_t jointCount = skeleton.size();
  std::vector<int> topNode(jointCount);
  jointNode.assign(jointCount, -1);
  for (size_t j = 0; j < jointCount; ++j)
    jointNode[j] = addJointNode(model, skeleton.joints[j], topNode[j]);
  std::vector<int> roots;
  for (size_t j = 0; j < jointCount; ++j) {
    const int32_t parent = skeleton.joints[j].parent;
    if (parent >= 0) {
      model.nodes[static_cast<size_t>(jointNode[static_cast<size_t>(parent)])].children.push_back(topNode[j]);
    } else {
      roots.push_back(topNode[j]);
    }
  }
  return roots;
}

void addSkin(tinygltf::Model& model, const anim::Skeleton& skeleton,
             const std::vector<int>& jointNode) {
  std::vector<glm::mat4> inverseBind(skeleton.size());
  for (size_t j = 0; j < skeleton.size(); ++j) inverseBind[j] = skeleton.joints[j].inverseBind;
  tinygltf::Skin skin;
  skin.name = "skin";
  skin.joints = jointNode;
  skin.inverseBindMatrices =
      detail::addData(model, inverseBind, 0, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_MAT4);
  model.skins.push_back(skin);
}

// A channel the writer can write: keys, a joint of the skeleton, values matching the keys, finite
// increasing times from 0 and finite values.
bool writableChannel(const anim::Channel& channel, size_t jointCount) {
  const size_t keys = channel.times.size();
  const size_t perKey = channel.interpolation == anim::Interpolation::CubicSpline ? 3 : 1;
  if (keys == 0 || channel.joint >= jointCount || channel.values.size() != keys * perKey)
    return false;
  bool valid = std::isfinite(channel.times[0]) && channel.times[0] >= 0.f;
  for (size_t k = 1; k < keys && valid; ++k) valid = channel.times[k] > channel.times[k - 1];
  for (const glm::vec4& value : channel.values)
    valid = valid && std::isfinite(glm::dot(value, value));
  return valid;
}

// The keys of a channel: times with their bounds, then values as vec3 for translation and scale,
// xyzw quaternions (normalised unless cubic) for rotation; gives the sampler.
tinygltf::AnimationSampler addSampler(tinygltf::Model& model, const anim::Channel& channel) {
  const int input =
      detail::addData(model, channel.times, 0, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR);
  model.accessors[static_cast<size_t>(input)].minValues = {channel.times.front()};
  model.accessors[static_cast<size_t>(input)].maxValues = {channel.times.back()};
  int output = -1;
  if (channel.path == anim::ChannelPath::Rotation) {
    std::vector<glm::vec4> rotations(channel.values);
    if (channel.interpolation != anim::Interpolation::CubicSpline) {
      for (glm::vec4& r : rotations) {
        const float length = glm::length(r);
        if (length > 0.f) r /= length;
      }
    }
    output =
        detail::addData(model, rotations, 0, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4);
  } else {
    std::vector<glm::vec3> vectors(channel.values.size());
    for (size_t k = 0; k < vectors.size(); ++k) vectors[k] = glm::vec3(channel.values[k]);
    output = detail::addData(model, vectors, 0, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3);
  }
  tinygltf::AnimationSampler sampler;
  sampler.input = input;
  sampler.output = output;
  sampler.interpolation = interpolationName(channel.interpolation);
  return sampler;
}

// Animations: channels that are malformed or name a joint outside the skeleton are left out, and
// a clip left without channels is not written.
void addAnimations(tinygltf::Model& model, std::span<const anim::AnimationClip> clips,
                   const std::vector<int>& jointNode) {
  for (size_t c = 0; c < clips.size(); ++c) {
    const anim::AnimationClip& clip = clips[c];
    tinygltf::Animation animation;
    animation.name = clip.name.empty() ? "clip_" + std::to_string(c) : clip.name;
    for (const anim::Channel& channel : clip.channels) {
      if (!writableChannel(channel, jointNode.size())) continue;
      animation.samplers.push_back(addSampler(model, channel));
      tinygltf::AnimationChannel target;
      target.sampler = static_cast<int>(animation.samplers.size() - 1);
      target.target_node = jointNode[channel.joint];
      target.target_path = pathName(channel.path);
      animation.channels.push_back(target);
    }
    if (!animation.channels.empty()) model.animations.push_back(animation);
  }
}

}  // namespace

MeshWriteResult writeSkinnedGlbToMemory(const geometry::MeshData& mesh,
                                        const anim::Skeleton& skeleton,
                                        std::span<const anim::AnimationClip> clips,
                                        const MeshWriteOptions& options,
                                        std::vector<uint8_t>& out) {
  MeshWriteResult result;
  std::vector<geometry::SubMesh> runs;
  std::string reason;
  if (!checkSkinnedInput(mesh, skeleton, runs, reason)) {
    result.setFailure(base::StatusCode::InvalidArgument, "skinned GLB: " + reason);
    return result;
  }
  tinygltf::Model model = detail::newGlbModel();
  // Vertex data: the core's attributes, then JOINTS_0 and WEIGHTS_0; addMesh puts the indices after
  // them and gives every primitive all of them.
  detail::GlbAttributes attributes = detail::addVertexAttributes(model, mesh, options);
  addSkinAttributes(model, mesh, attributes);
  detail::addMesh(model, mesh, runs, attributes, options, detail::GlbColors::Write);
  std::vector<int> jointNode;
  detail::addMeshScene(model, addJointNodes(model, skeleton, jointNode), 0);
  addSkin(model, skeleton, jointNode);
  addAnimations(model, clips, jointNode);
  if (!detail::serialiseGlb(model, out)) {
    result.setFailure(base::StatusCode::InvalidArgument, "skinned GLB: tinygltf could not serialise the model");
    return result;
  }
  result.code = base::StatusCode::Ok;
  return result;
}

MeshWriteResult writeSkinnedGlb(const std::string& path, const geometry::MeshData& mesh,
                                const anim::Skeleton& skeleton, std::span<const anim::AnimationClip> clips,
                                const MeshWriteOptions& options) {
  std::vector<uint8_t> bytes;
  MeshWriteResult result = writeSkinnedGlbToMemory(mesh, skeleton, clips, options, bytes);
  return detail::saveSerialised(path, std::move(result), bytes);
}

}  // namespace cleave::assets
