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
#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include <tiny_gltf.h>

#include "engine/assets/mesh_reader.h"
#include "engine/assets/model.h"

namespace cleave::assets {

namespace {

template <typename T>
size_t appendBlock(std::vector<unsigned char>& buffer, const T* values, size_t count) {
  while (buffer.size() % 4 != 0) buffer.push_back(0);  // glTF wants 4-byte aligned accessors
  const size_t offset = buffer.size();
  buffer.resize(offset + count * sizeof(T));
  if (count > 0) std::memcpy(buffer.data() + offset, values, count * sizeof(T));
  return offset;
}

// A buffer view of its own and an accessor over all of it. `target` 0 leaves the view without a
// target (inverse bind matrices, animation data).
int addData(tinygltf::Model& model, size_t offset, size_t length, int target, int componentType, int type,
            size_t count) {
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = offset;
  view.byteLength = length;
  view.target = target;
  model.bufferViews.push_back(view);
  tinygltf::Accessor accessor;
  accessor.bufferView = static_cast<int>(model.bufferViews.size() - 1);
  accessor.byteOffset = 0;
  accessor.componentType = componentType;
  accessor.type = type;
  accessor.count = count;
  model.accessors.push_back(accessor);
  return static_cast<int>(model.accessors.size() - 1);
}

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

}  // namespace

MeshWriteResult writeSkinnedGlbToMemory(const geometry::MeshData& mesh, const anim::Skeleton& skeleton,
                                        std::span<const anim::AnimationClip> clips,
                                        const MeshWriteOptions& options, std::vector<uint8_t>& out) {
  MeshWriteResult result;
  auto fail = [&](const std::string& reason) {
    result.error = "skinned GLB: " + reason;
    return result;
  };
  std::vector<geometry::SubMesh> runs;
  std::string reason;
  if (!detail::writableRuns(mesh, runs, reason)) return fail(reason);
  if (mesh.indices.empty()) return fail("the mesh has no triangles");
  if (skeleton.size() == 0) return fail("the skeleton has no joints");
  if (skeleton.size() > 65535) return fail("the skeleton has more than 65535 joints");
  if (!anim::validateSkeleton(skeleton, &reason)) return fail(reason);
  if (mesh.joints.size() != mesh.positions.size() || mesh.weights.size() != mesh.positions.size()) {
    return fail("the mesh has no joints and weights for every vertex");
  }
  for (size_t v = 0; v < mesh.joints.size(); ++v) {
    for (int k = 0; k < 4; ++k) {
      if (mesh.weights[v][k] != 0.f && mesh.joints[v][k] >= skeleton.size()) {
        return fail("vertex " + std::to_string(v) + " uses joint " + std::to_string(mesh.joints[v][k]) +
                    " of a skeleton of " + std::to_string(skeleton.size()));
      }
    }
  }
  for (size_t j = 0; j < skeleton.size(); ++j) {
    const anim::Joint& joint = skeleton.joints[j];
    if (!finiteMatrix(joint.inverseBind) || !finiteMatrix(joint.offset) || !finiteMatrix(joint.rest.matrix())) {
      return fail("joint " + std::to_string(j) + " has a non-finite transform");
    }
  }

  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "Cleave";
  model.buffers.emplace_back();
  std::vector<unsigned char>& data = model.buffers[0].data;

  // Vertex data.
  const size_t n = mesh.positions.size();
  const int positionAccessor =
      addData(model, appendBlock(data, mesh.positions.data(), n), n * sizeof(glm::vec3),
              TINYGLTF_TARGET_ARRAY_BUFFER, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n);
  glm::vec3 lo = mesh.positions[0], hi = mesh.positions[0];
  for (const glm::vec3& p : mesh.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  model.accessors[static_cast<size_t>(positionAccessor)].minValues = {lo.x, lo.y, lo.z};
  model.accessors[static_cast<size_t>(positionAccessor)].maxValues = {hi.x, hi.y, hi.z};
  int normalAccessor = -1;
  if (options.writeNormals && mesh.normals.size() == n) {
    normalAccessor = addData(model, appendBlock(data, mesh.normals.data(), n), n * sizeof(glm::vec3),
                             TINYGLTF_TARGET_ARRAY_BUFFER, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, n);
  }
  int uvAccessor = -1;
  if (options.writeUvs && mesh.uv0.size() == n) {
    uvAccessor = addData(model, appendBlock(data, mesh.uv0.data(), n), n * sizeof(glm::vec2),
                         TINYGLTF_TARGET_ARRAY_BUFFER, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, n);
  }
  // Unused influence slots are written as joint 0 with weight 0, which glTF allows.
  std::vector<glm::u16vec4> joints(n);
  for (size_t v = 0; v < n; ++v) {
    for (int k = 0; k < 4; ++k) joints[v][k] = mesh.weights[v][k] != 0.f ? mesh.joints[v][k] : uint16_t(0);
  }
  const int jointAccessor =
      addData(model, appendBlock(data, joints.data(), n), n * sizeof(glm::u16vec4), TINYGLTF_TARGET_ARRAY_BUFFER,
              TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC4, n);
  const int weightAccessor =
      addData(model, appendBlock(data, mesh.weights.data(), n), n * sizeof(glm::vec4), TINYGLTF_TARGET_ARRAY_BUFFER,
              TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, n);
  tinygltf::BufferView indexView;
  indexView.buffer = 0;
  indexView.byteOffset = appendBlock(data, mesh.indices.data(), mesh.indices.size());
  indexView.byteLength = mesh.indices.size() * sizeof(uint32_t);
  indexView.target = TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER;
  model.bufferViews.push_back(indexView);
  const int indexViewId = static_cast<int>(model.bufferViews.size() - 1);

  // Materials and primitives.
  tinygltf::Mesh gltfMesh;
  gltfMesh.name = "mesh";
  std::vector<uint32_t> materialIds;  // glTF material index -> our material id, in order of first use
  for (const geometry::SubMesh& run : runs) {
    if (run.indexCount == 0) continue;
    int material = -1;
    for (size_t i = 0; i < materialIds.size(); ++i) {
      if (materialIds[i] == run.materialId) material = static_cast<int>(i);
    }
    if (material < 0) {
      materialIds.push_back(run.materialId);
      tinygltf::Material gltfMaterial;
      gltfMaterial.name = materialName(options, run.materialId);
      if (run.materialId < options.materialColors.size()) {
        const glm::vec4 c = glm::clamp(options.materialColors[run.materialId], glm::vec4(0.f), glm::vec4(1.f));
        gltfMaterial.pbrMetallicRoughness.baseColorFactor = {c.r, c.g, c.b, c.a};
      }
      model.materials.push_back(gltfMaterial);
      material = static_cast<int>(model.materials.size() - 1);
    }
    tinygltf::Primitive primitive;
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    primitive.material = material;
    primitive.attributes["POSITION"] = positionAccessor;
    if (normalAccessor >= 0) primitive.attributes["NORMAL"] = normalAccessor;
    if (uvAccessor >= 0) primitive.attributes["TEXCOORD_0"] = uvAccessor;
    primitive.attributes["JOINTS_0"] = jointAccessor;
    primitive.attributes["WEIGHTS_0"] = weightAccessor;
    tinygltf::Accessor indices;
    indices.bufferView = indexViewId;
    indices.byteOffset = size_t{run.firstIndex} * sizeof(uint32_t);
    indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    indices.type = TINYGLTF_TYPE_SCALAR;
    indices.count = run.indexCount;
    model.accessors.push_back(indices);
    primitive.indices = static_cast<int>(model.accessors.size() - 1);
    gltfMesh.primitives.push_back(primitive);
  }
  model.meshes.push_back(gltfMesh);

  // Joint nodes (and offset nodes above joints with a fixed offset), then the hierarchy.
  const size_t jointCount = skeleton.size();
  std::vector<int> jointNode(jointCount), topNode(jointCount);
  for (size_t j = 0; j < jointCount; ++j) {
    const anim::Joint& joint = skeleton.joints[j];
    if (joint.offset != glm::mat4(1.f)) {
      tinygltf::Node offset;
      offset.name = joint.name + "_offset";
      offset.matrix.assign(16, 0.0);
      for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) offset.matrix[size_t(4 * c + r)] = joint.offset[c][r];
      }
      model.nodes.push_back(offset);
      topNode[j] = static_cast<int>(model.nodes.size() - 1);
    } else {
      topNode[j] = -1;
    }
    tinygltf::Node node;
    node.name = joint.name;
    const glm::vec3 t = joint.rest.translation, s = joint.rest.scale;
    const glm::quat q = glm::normalize(joint.rest.rotation);
    if (t != glm::vec3(0.f)) node.translation = {t.x, t.y, t.z};
    if (q != glm::quat(1.f, 0.f, 0.f, 0.f)) node.rotation = {q.x, q.y, q.z, q.w};
    if (s != glm::vec3(1.f)) node.scale = {s.x, s.y, s.z};
    model.nodes.push_back(node);
    jointNode[j] = static_cast<int>(model.nodes.size() - 1);
    if (topNode[j] >= 0) {
      model.nodes[static_cast<size_t>(topNode[j])].children.push_back(jointNode[j]);
    } else {
      topNode[j] = jointNode[j];
    }
  }
  tinygltf::Scene scene;
  for (size_t j = 0; j < jointCount; ++j) {
    const int32_t parent = skeleton.joints[j].parent;
    if (parent >= 0) {
      model.nodes[static_cast<size_t>(jointNode[static_cast<size_t>(parent)])].children.push_back(topNode[j]);
    } else {
      scene.nodes.push_back(topNode[j]);
    }
  }
  tinygltf::Node meshNode;
  meshNode.name = "piece";
  meshNode.mesh = 0;
  meshNode.skin = 0;
  model.nodes.push_back(meshNode);
  scene.nodes.push_back(static_cast<int>(model.nodes.size() - 1));
  model.scenes.push_back(scene);
  model.defaultScene = 0;

  // The skin.
  std::vector<glm::mat4> inverseBind(jointCount);
  for (size_t j = 0; j < jointCount; ++j) inverseBind[j] = skeleton.joints[j].inverseBind;
  tinygltf::Skin skin;
  skin.name = "skin";
  skin.joints = jointNode;
  skin.inverseBindMatrices =
      addData(model, appendBlock(data, inverseBind.data(), jointCount), jointCount * sizeof(glm::mat4), 0,
              TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_MAT4, jointCount);
  model.skins.push_back(skin);

  // Animations: channels that are malformed or name a joint outside the skeleton are left out, and
  // a clip left without channels is not written.
  for (size_t c = 0; c < clips.size(); ++c) {
    const anim::AnimationClip& clip = clips[c];
    tinygltf::Animation animation;
    animation.name = clip.name.empty() ? "clip_" + std::to_string(c) : clip.name;
    for (const anim::Channel& channel : clip.channels) {
      const size_t keys = channel.times.size();
      const size_t perKey = channel.interpolation == anim::Interpolation::CubicSpline ? 3 : 1;
      if (keys == 0 || channel.joint >= jointCount || channel.values.size() != keys * perKey) continue;
      bool valid = std::isfinite(channel.times[0]) && channel.times[0] >= 0.f;
      for (size_t k = 1; k < keys && valid; ++k) valid = channel.times[k] > channel.times[k - 1];
      for (const glm::vec4& value : channel.values) valid = valid && std::isfinite(glm::dot(value, value));
      if (!valid) continue;
      const int input = addData(model, appendBlock(data, channel.times.data(), keys), keys * sizeof(float), 0,
                                TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, keys);
      model.accessors[static_cast<size_t>(input)].minValues = {channel.times.front()};
      model.accessors[static_cast<size_t>(input)].maxValues = {channel.times.back()};
      int output = -1;
      const size_t values = channel.values.size();
      if (channel.path == anim::ChannelPath::Rotation) {
        std::vector<glm::vec4> rotations(channel.values);
        if (channel.interpolation != anim::Interpolation::CubicSpline) {
          for (glm::vec4& r : rotations) {
            const float length = glm::length(r);
            if (length > 0.f) r /= length;
          }
        }
        output = addData(model, appendBlock(data, rotations.data(), values), values * sizeof(glm::vec4), 0,
                         TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, values);
      } else {
        std::vector<glm::vec3> vectors(values);
        for (size_t k = 0; k < values; ++k) vectors[k] = glm::vec3(channel.values[k]);
        output = addData(model, appendBlock(data, vectors.data(), values), values * sizeof(glm::vec3), 0,
                         TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, values);
      }
      tinygltf::AnimationSampler sampler;
      sampler.input = input;
      sampler.output = output;
      sampler.interpolation = interpolationName(channel.interpolation);
      animation.samplers.push_back(sampler);
      tinygltf::AnimationChannel target;
      target.sampler = static_cast<int>(animation.samplers.size() - 1);
      target.target_node = jointNode[channel.joint];
      target.target_path = pathName(channel.path);
      animation.channels.push_back(target);
    }
    if (!animation.channels.empty()) model.animations.push_back(animation);
  }
  data.resize((data.size() + 3) / 4 * 4, 0);

  std::ostringstream stream;
  tinygltf::TinyGLTF writer;
  bool written = false;
  try {
    written = writer.WriteGltfSceneToStream(&model, stream, false, true);
  } catch (...) {
    written = false;
  }
  if (!written) return fail("tinygltf could not serialise the model");
  const std::string bytes = stream.str();
  out.assign(bytes.begin(), bytes.end());
  result.ok = true;
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
