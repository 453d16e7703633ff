// SPDX-License-Identifier: MIT
// The glTF model loader: a crafted skinned and animated file read exactly, crafted broken files
// that must fail with a reason naming the file, the real characters of the shared models folder
// (skipped when absent) and the glTF files of Debian's assimp-testmodels (skipped when absent).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>

#include "cleave/assets/model.h"
#include "cleave/geometry/mesh_splitter.h"
#include "cleave/geometry/primitives.h"
#include "tests/assets/asset_test_files.h"

namespace cleave::assets {
namespace {

using test::TempDir;

std::string base64(const std::vector<uint8_t>& bytes) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const uint32_t b0 = bytes[i], b1 = i + 1 < bytes.size() ? bytes[i + 1] : 0,
                   b2 = i + 2 < bytes.size() ? bytes[i + 2] : 0;
    const uint32_t triple = (b0 << 16) | (b1 << 8) | b2;
    out += kAlphabet[(triple >> 18) & 63];
    out += kAlphabet[(triple >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(triple >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kAlphabet[triple & 63] : '=';
  }
  return out;
}

template <typename T>
void put(std::vector<uint8_t>& buffer, T value) {
  uint8_t raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  buffer.insert(buffer.end(), raw, raw + sizeof(T));
}

// What to break in the crafted file.
struct Craft {
  bool indices = false;  // add an index accessor (unsigned byte)
  uint8_t badIndex = 0;  // > 0: this value replaces the last index
  bool nanPosition = false;
  bool missingBuffer = false;    // a buffer view names buffer 3
  bool externalMissing = false;  // the buffer is an external file that does not exist
  bool cycle = false;            // joint node 2 lists node 1 as its child
  bool noScene = false;
  bool draco = false;
  uint8_t jointValue = 1;  // joint of the upper vertices
  std::string interpolation = "STEP";
};

// A skinned quad (two triangles, no indices, no normals) on two joints: bone0 at the origin and
// bone1 one metre up, the upper vertices bound to bone1. Joints are unsigned bytes and weights
// normalised unsigned bytes. One animation turns bone1 by 90 degrees about z at t = 1.
std::string craftedGltf(const Craft& craft) {
  std::vector<uint8_t> b;
  const float quad[6][3] = {{0, 0, 0}, {1, 0, 0}, {1, 2, 0}, {0, 0, 0}, {1, 2, 0}, {0, 2, 0}};
  for (int v = 0; v < 6; ++v)
    for (int c = 0; c < 3; ++c)
      put(b, craft.nanPosition && v == 2 && c == 1 ? std::numeric_limits<float>::quiet_NaN()
                                                   : quad[v][c]);
  for (int v = 0; v < 6; ++v) {  // joints at 72
    const bool upper = quad[v][1] > 1.f;
    put<uint8_t>(b, upper ? craft.jointValue : 0);
    put<uint8_t>(b, 0);
    put<uint8_t>(b, 0);
    put<uint8_t>(b, 0);
  }
  for (int v = 0; v < 6; ++v) {  // weights at 96: 255 = 1.0
    put<uint8_t>(b, 255);
    put<uint8_t>(b, 0);
    put<uint8_t>(b, 0);
    put<uint8_t>(b, 0);
  }
  for (int j = 0; j < 2; ++j) {  // inverse bind matrices at 120
    for (int c = 0; c < 16; ++c) {
      float v = (c % 5 == 0) ? 1.f : 0.f;
      if (j == 1 && c == 13) v = -1.f;  // translation y -1
      put(b, v);
    }
  }
  put(b, 0.f);  // key times at 248
  put(b, 1.f);
  const float s = std::sqrt(0.5f);
  const float keys[2][4] = {{0, 0, 0, 1}, {0, 0, s, s}};
  if (craft.interpolation == "CUBICSPLINE") {  // rotations at 256: in-tangent, value, out-tangent
    for (const auto& key : keys) {
      for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 4; ++c) put(b, k == 1 ? key[c] : 0.f);
    }
  } else {
    for (const auto& key : keys)
      for (int c = 0; c < 4; ++c) put(b, key[c]);
  }
  const size_t rotationsBytes = b.size() - 256;
  const size_t indicesOffset = b.size();
  for (uint8_t i = 0; i < 6; ++i) put<uint8_t>(b, i == 5 && craft.badIndex ? craft.badIndex : i);
  while (b.size() % 4) b.push_back(0);

  const std::string uri =
      craft.externalMissing ? "missing.bin" : "data:application/octet-stream;base64," + base64(b);
  const std::string buffer = craft.missingBuffer ? "3" : "0";
  std::string json = R"({"asset":{"version":"2.0"},)";
  if (craft.draco) {
    json +=
        R"("extensionsUsed":["KHR_draco_mesh_compression"],"extensionsRequired":["KHR_draco_mesh_compression"],)";
  }
  if (!craft.noScene) json += R"("scene":0,"scenes":[{"nodes":[0,1]}],)";
  json += R"("nodes":[{"name":"body","mesh":0,"skin":0},{"name":"bone0","children":[2]},)";
  json += craft.cycle ? R"({"name":"bone1","translation":[0,1,0],"children":[1]}],)"
                      : R"({"name":"bone1","translation":[0,1,0]}],)";
  json += R"("skins":[{"joints":[1,2],"inverseBindMatrices":3}],)";
  json +=
      R"("meshes":[{"name":"quad","primitives":[{"attributes":{"POSITION":0,"JOINTS_0":1,"WEIGHTS_0":2})";
  if (craft.indices) json += R"(,"indices":6)";
  json += R"(,"material":0}]}],)";
  json +=
      R"("materials":[{"name":"paint","pbrMetallicRoughness":{"baseColorFactor":[0.5,0.25,1,1]}}],)";
  json += R"("animations":[{"name":"bend","samplers":[{"input":4,"output":5,"interpolation":")" +
          craft.interpolation +
          R"("}],"channels":[{"sampler":0,"target":{"node":2,"path":"rotation"}}]}],)";
  json += R"("accessors":[)";
  json +=
      R"({"bufferView":0,"componentType":5126,"count":6,"type":"VEC3","min":[0,0,0],"max":[1,2,0]},)";
  json += R"({"bufferView":1,"componentType":5121,"count":6,"type":"VEC4"},)";
  json += R"({"bufferView":2,"componentType":5121,"normalized":true,"count":6,"type":"VEC4"},)";
  json += R"({"bufferView":3,"componentType":5126,"count":2,"type":"MAT4"},)";
  json += R"({"bufferView":4,"componentType":5126,"count":2,"type":"SCALAR","min":[0],"max":[1]},)";
  json += R"({"bufferView":5,"componentType":5126,"count":)" +
          std::to_string(craft.interpolation == "CUBICSPLINE" ? 6 : 2) + R"(,"type":"VEC4"},)";
  json += R"({"bufferView":6,"componentType":5121,"count":6,"type":"SCALAR"}],)";
  auto view = [&](size_t offset, size_t length) {
    return R"({"buffer":)" + buffer + R"(,"byteOffset":)" + std::to_string(offset) +
           R"(,"byteLength":)" + std::to_string(length) + "}";
  };
  json += R"("bufferViews":[)" + view(0, 72) + "," + view(72, 24) + "," + view(96, 24) + "," +
          view(120, 128) + "," + view(248, 8) + "," + view(256, rotationsBytes) + "," +
          view(indicesOffset, 6) + "],";
  json +=
      R"("buffers":[{"byteLength":)" + std::to_string(b.size()) + R"(,"uri":")" + uri + R"("}]})";
  return json;
}

ModelLoadResult loadCrafted(const Craft& craft, const TempDir& dir,
                            const std::string& name = "crafted.gltf") {
  return loadModel(dir.write(name, craftedGltf(craft)));
}

TEST(GltfModel, ReadsACraftedSkinnedAnimatedFileExactly) {
  TempDir dir;
  const ModelLoadResult result = loadCrafted({}, dir);
  ASSERT_TRUE(result.ok()) << result.message;
  const Model& model = result.model;
  ASSERT_EQ(model.meshes.size(), 1u);
  const ModelMesh& mesh = model.meshes[0];
  EXPECT_EQ(mesh.name, "body");
  EXPECT_EQ(mesh.skin, 0);
  EXPECT_EQ(mesh.mesh.triangleCount(), 2u);  // no indices: a triangle list
  ASSERT_EQ(mesh.mesh.normals.size(), 6u);   // no normals: computed
  for (const glm::vec3& n : mesh.mesh.normals) EXPECT_NEAR(n.z, 1.f, 1e-6f);
  EXPECT_EQ(mesh.mesh.joints[2], glm::u16vec4(1, 0, 0, 0));  // unsigned byte joints
  EXPECT_EQ(mesh.mesh.weights[2], glm::vec4(1, 0, 0, 0));    // normalised byte weights
  ASSERT_EQ(model.materials.size(), 1u);
  EXPECT_EQ(model.materials[0].baseColorFactor, glm::vec4(0.5f, 0.25f, 1.f, 1.f));
  ASSERT_EQ(model.skins.size(), 1u);
  const anim::Skeleton& skeleton = model.skins[0].skeleton;
  ASSERT_EQ(skeleton.size(), 2u);
  EXPECT_EQ(skeleton.joints[1].name, "bone1");
  EXPECT_EQ(skeleton.joints[1].parent, 0);
  EXPECT_EQ(skeleton.joints[1].rest.translation, glm::vec3(0, 1, 0));
  ASSERT_EQ(model.skins[0].clips.size(), 1u);
  const anim::AnimationClip& clip = model.skins[0].clips[0];
  EXPECT_EQ(clip.name, "bend");
  EXPECT_FLOAT_EQ(clip.duration, 1.f);
  // At t = 1 bone1 turns 90 degrees about z around (0, 1): the top corner (1, 2) goes to (-1, 2).
  anim::Pose pose;
  anim::sampleClip(skeleton, clip, 1.f, false, pose);
  std::vector<glm::mat4> joints;
  anim::poseToJointMatrices(skeleton, pose, joints);
  const glm::vec3 moved(joints[1] * glm::vec4(1, 2, 0, 1));
  EXPECT_NEAR(moved.x, -1.f, 1e-5f);
  EXPECT_NEAR(moved.y, 1.f + 1.f, 1e-5f);
  // STEP holds the first key until t = 1.
  anim::sampleClip(skeleton, clip, 0.99f, false, pose);
  EXPECT_FLOAT_EQ(pose[1].rotation.w, 1.f);
}

TEST(GltfModel, ReadsCubicSplineChannelsAndIndices) {
  TempDir dir;
  Craft craft;
  craft.interpolation = "CUBICSPLINE";
  craft.indices = true;
  const ModelLoadResult result = loadCrafted(craft, dir);
  ASSERT_TRUE(result.ok()) << result.message;
  const anim::Channel& channel = result.model.skins[0].clips[0].channels[0];
  EXPECT_EQ(channel.interpolation, anim::Interpolation::CubicSpline);
  EXPECT_EQ(channel.values.size(), 6u);
  EXPECT_EQ(result.model.meshes[0].mesh.indices, std::vector<uint32_t>({0, 1, 2, 3, 4, 5}));
}

void expectFailure(const ModelLoadResult& result, const std::string& file,
                   const std::string& reason) {
  EXPECT_FALSE(result.ok());
  EXPECT_TRUE(result.model.meshes.empty());
  EXPECT_EQ(result.message.rfind(file, 0), 0u) << "the error names the file: " << result.message;
  EXPECT_NE(result.message.find(reason), std::string::npos) << result.message;
}

TEST(GltfModel, BrokenFilesFailWithAReasonNamingTheFile) {
  TempDir dir;
  struct Case {
    const char* name;
    Craft craft;
    const char* reason;
  };
  std::vector<Case> cases;
  {
    Craft c;
    c.indices = true;
    c.badIndex = 40;
    cases.push_back({"index.gltf", c, "index 40 at position 5 is out of range (6 vertices)"});
  }
  {
    Craft c;
    c.nanPosition = true;
    cases.push_back({"nan.gltf", c, "vertex 2 has a non-finite position"});
  }
  {
    Craft c;
    c.missingBuffer = true;
    cases.push_back({"buffer.gltf", c, "buffer"});
  }
  {
    Craft c;
    c.externalMissing = true;
    cases.push_back({"external.gltf", c, "missing.bin"});
  }
  {
    Craft c;
    c.cycle = true;
    cases.push_back({"cycle.gltf", c, "cycle"});
  }
  {
    Craft c;
    c.noScene = true;
    cases.push_back({"noscene.gltf", c, "no scene"});
  }
  {
    Craft c;
    c.draco = true;
    cases.push_back({"draco.gltf", c, "KHR_draco_mesh_compression, which is not supported"});
  }
  {
    Craft c;
    c.jointValue = 7;
    cases.push_back({"joint.gltf", c, "uses joint 7 of a skin with 2 joints"});
  }
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string path = dir.file(c.name);
    expectFailure(loadCrafted(c.craft, dir, c.name), path, c.reason);
  }
  expectFailure(loadModel(dir.file("absent.glb")), dir.file("absent.glb"), "cannot open");
  const std::string garbage = "glTF\x02\0\0\0garbage";
  expectFailure(readModelFromMemory(
                    std::span(reinterpret_cast<const uint8_t*>(garbage.data()), garbage.size()),
                    "garbage.glb"),
                "garbage.glb", "");
  // Every prefix of a valid file fails cleanly or loads; none crashes.
  const std::string valid = craftedGltf({});
  for (size_t cut = 0; cut < valid.size(); cut += 97) {
    const ModelLoadResult r = readModelFromMemory(
        std::span(reinterpret_cast<const uint8_t*>(valid.data()), cut), "prefix");
    EXPECT_FALSE(r.ok());
  }
}

std::filesystem::path modelsFolder() {
  if (const char* env = std::getenv("CLEAVE_MODELS_DIR")) return env;
  return std::filesystem::path(CLEAVE_SOURCE_DIR).parent_path() / "shared" / "models";
}

// Poses every clip of every skin at a few times, checks the joint matrices, and cuts the skinned
// meshes in one pose (with caps when the mesh is closed, hollow otherwise).
void exercise(const Model& model) {
  for (const ModelMesh& mesh : model.meshes) {
    if (mesh.skin < 0) continue;
    const ModelSkin& skin = model.skins[size_t(mesh.skin)];
    anim::Pose pose;
    std::vector<glm::mat4> joints;
    if (skin.clips.empty()) {
      anim::restPose(skin.skeleton, pose);
    } else {
      for (const anim::AnimationClip& clip : skin.clips) {
        for (float t : {0.f, 0.37f, 1.1f}) {
          anim::sampleClip(skin.skeleton, clip, t, true, pose);
          anim::poseToJointMatrices(skin.skeleton, pose, joints);
          for (const glm::mat4& m : joints)
            for (int c = 0; c < 4; ++c)
              for (int r = 0; r < 4; ++r) ASSERT_TRUE(std::isfinite(m[c][r]));
        }
      }
    }
    anim::poseToJointMatrices(skin.skeleton, pose, joints);
    geometry::MeshContainer container;
    ASSERT_EQ(container.setMesh(mesh.mesh).message, "");
    ASSERT_EQ(container.setSkinningPose(joints, glm::mat4(1.f)).message, "");
    glm::dvec3 lo(1e30), hi(-1e30);
    for (const glm::dvec3& p : container.cutPositions()) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    geometry::SplitOptions options;
    options.cap = container.closed();
    geometry::SplitResult result;
    const geometry::Plane plane{{0.1, 1.0, 0.05},
                                glm::dot(glm::dvec3(0.1, 1.0, 0.05), 0.5 * (lo + hi))};
    const geometry::SplitStatus status =
        geometry::makeConcaveSplitter()->split(container, plane, options, result);
    EXPECT_EQ(status, geometry::SplitStatus::Ok) << mesh.name << ": " << result.message;
    for (const geometry::SplitPiece& piece : result.pieces) EXPECT_FALSE(piece.joints.empty());
  }
}

TEST(GltfModel, SharedCharactersLoadPoseAndCut) {
  const std::filesystem::path folder = modelsFolder();
  if (!std::filesystem::is_directory(folder)) GTEST_SKIP() << "no models folder at " << folder;
  struct Expected {
    size_t triangles, joints, clips;
    bool closed;
  };
  const std::map<std::string, Expected> expected = {{"greenman.glb", {356, 12, 4, true}},
                                                    {"robot.glb", {3238, 43, 14, false}},
                                                    {"Fox.glb", {576, 24, 3, true}},
                                                    {"SimpleSkin.gltf", {8, 2, 1, false}}};
  size_t loaded = 0;
  for (const auto& [file, want] : expected) {
    const std::filesystem::path path = folder / file;
    if (!std::filesystem::exists(path)) continue;
    SCOPED_TRACE(file);
    const ModelLoadResult result = loadModel(path.string());
    ASSERT_TRUE(result.ok()) << result.message;
    ++loaded;
    const Model& model = result.model;
    EXPECT_EQ(model.triangleCount(), want.triangles);
    ASSERT_EQ(model.skins.size(), 1u);
    EXPECT_EQ(model.skins[0].skeleton.size(), want.joints);
    EXPECT_EQ(model.skins[0].clips.size(), want.clips);
    // Closed or open, as the container finds the skinned meshes taken together.
    geometry::MeshData skinned;
    for (const ModelMesh& mesh : model.meshes) {
      if (mesh.skin < 0) continue;
      skinned = skinned.positions.empty() ? mesh.mesh : geometry::primitives::merge(skinned, mesh.mesh);
    }
    geometry::MeshContainer container;
    ASSERT_EQ(container.setMesh(skinned).code, geometry::SplitStatus::Ok);
    EXPECT_EQ(container.closed(), want.closed);
    for (const ModelMesh& mesh : model.meshes) {
      EXPECT_EQ(mesh.mesh.normals.size(), mesh.mesh.vertexCount());
      for (const glm::vec3& n : mesh.mesh.normals) ASSERT_NEAR(glm::length(n), 1.f, 1e-3f);
      for (const geometry::SubMesh& run : mesh.mesh.submeshes)
        EXPECT_LT(run.materialId, model.materials.size());
      if (mesh.skin >= 0) {
        for (const glm::vec4& w : mesh.mesh.weights) ASSERT_NEAR(w.x + w.y + w.z + w.w, 1.f, 1e-5f);
      }
    }
    for (const ModelMaterial& material : model.materials) {
      if (material.baseColorImage < 0) continue;
      const ModelImage& image = model.images[size_t(material.baseColorImage)];
      EXPECT_GT(image.width, 0) << "base colour texture decoded";
      EXPECT_EQ(image.rgba.size(), size_t(image.width) * size_t(image.height) * 4);
    }
    exercise(model);
  }
  if (loaded == 0) GTEST_SKIP() << "none of the four characters is in " << folder;
}

TEST(GltfModel, AssimpTestModelsLoadOrFailCleanly) {
  const std::filesystem::path root = "/usr/share/assimp/models/glTF2";
  if (!std::filesystem::is_directory(root)) GTEST_SKIP() << "assimp-testmodels is not installed";
  size_t files = 0, ok = 0;
  std::map<std::string, std::string> errors;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".gltf" && ext != ".glb") continue;
    ++files;
    const std::string path = entry.path().string();
    const ModelLoadResult result = loadModel(path);
    if (result.ok()) {
      ++ok;
      EXPECT_GT(result.model.triangleCount(), 0u) << path;
      exercise(result.model);
    } else {
      EXPECT_EQ(result.message.rfind(path + ": ", 0), 0u) << result.message;
      errors[entry.path().lexically_relative(root).string()] = result.message;
    }
  }
  ASSERT_GT(files, 0u);
  EXPECT_GT(ok, files / 2) << "most of the corpus is valid";
  std::printf("assimp glTF2 corpus: %zu of %zu files loaded; refused:\n", ok, files);
  for (const auto& [file, error] : errors) std::printf("  %s\n", error.c_str());
  // The deliberately broken ones fail for the right reason.
  const std::map<std::string, std::string> reasons = {
      {"IndexOutOfRange/IndexOutOfRange.gltf", "out of range"},
      {"IndexOutOfRange/AllIndicesOutOfRange.gltf", "out of range"},
      {"RecursiveNodes/RecursiveNodes.gltf", "cycle"},
      {"TestNoRootNode/NoScene.gltf", "no scene"},
      {"draco/2CylinderEngine.gltf", "KHR_draco_mesh_compression"},
      {"MissingBin/BoxTextured.gltf", "BoxTextured0.bin"},
      {"BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "non-finite"},
  };
  for (const auto& [file, reason] : reasons) {
    if (!std::filesystem::exists(root / file)) continue;
    SCOPED_TRACE(file);
    ASSERT_TRUE(errors.count(file)) << "loaded although broken";
    EXPECT_NE(errors[file].find(reason), std::string::npos) << errors[file];
  }
  // A valid skinned sample loads with its skin.
  if (std::filesystem::exists(root / "simple_skin/simple_skin.gltf")) {
    const ModelLoadResult skin = loadModel((root / "simple_skin/simple_skin.gltf").string());
    ASSERT_TRUE(skin.ok()) << skin.message;
    EXPECT_EQ(skin.model.skins.size(), 1u);
  }
  if (std::filesystem::exists(root / "BoxTextured-glTF-Binary/BoxTextured.glb")) {
    const ModelLoadResult box =
        loadModel((root / "BoxTextured-glTF-Binary/BoxTextured.glb").string());
    ASSERT_TRUE(box.ok()) << box.message;
    ASSERT_FALSE(box.model.materials.empty());
    ASSERT_GE(box.model.materials[0].baseColorImage, 0);
    EXPECT_GT(box.model.images[size_t(box.model.materials[0].baseColorImage)].width, 0);
  }
}

}  // namespace
}  // namespace cleave::assets
