// SPDX-License-Identifier: MIT
// The skinned GLB writer and `cleave-split --pose`: a skinned mesh with its skeleton and clips
// written as GLB reads back through loadModel with the same joints, clips, triangles and skin, and
// poses the same; pieces cut in a pose keep their skin and animations; the Khronos validator (when
// node and the npm package gltf-validator are there: ./cleave test installs it into <build>/npm)
// reports no error for them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>


#include <nlohmann/json.hpp>

#include "cleave/anim/animation_clip.h"
#include "cleave/anim/skeleton.h"
#include "cleave/assets/model.h"
#include "cleave/assets/procedural_character.h"
#include "cleave/geometry/mesh_splitter.h"
#include "tests/assets/asset_test_files.h"
#include "tests/assets/tool_runner.h"

namespace cleave::assets {
namespace {

using test::quote;
using test::runCommand;
using test::splitTool;
using test::TempDir;

const ProceduralCharacter& character() {
  static const ProceduralCharacter c = makeProceduralCharacter();
  return c;
}

MeshWriteOptions characterOptions() {
  MeshWriteOptions options;
  options.capMaterialId = 1;
  options.materialNames = {"skin", "cap", "shirt", "trousers", "shoes"};
  options.materialColors = character().materialColors;
  return options;
}

std::vector<anim::AnimationClip> characterClips() { return {character().idle, character().walk}; }

std::span<const uint8_t> bytesOf(const std::vector<uint8_t>& v) { return {v.data(), v.size()}; }

// Cut-space positions of `mesh` posed by `clip` at `time` on `skeleton`.
std::vector<glm::dvec3> posed(const geometry::MeshData& mesh, const anim::Skeleton& skeleton,
                              const anim::AnimationClip& clip, float time) {
  anim::Pose pose;
  anim::sampleClip(skeleton, clip, time, true, pose);
  std::vector<glm::mat4> joints;
  anim::poseToJointMatrices(skeleton, pose, joints);
  geometry::MeshContainer container;
  if (container.setMesh(mesh).code != geometry::SplitStatus::Ok) return {};
  if (container.setSkinningPose(joints, glm::mat4(1.f)).code != geometry::SplitStatus::Ok) return {};
  return {container.cutPositions().begin(), container.cutPositions().end()};
}

TEST(SkinnedGlbWriter, RoundTripKeepsJointsClipsTrianglesAndThePose) {
  const ProceduralCharacter& c = character();
  std::vector<uint8_t> bytes;
  const std::vector<anim::AnimationClip> clips = characterClips();
  const MeshWriteResult written = writeSkinnedGlbToMemory(c.mesh, c.skeleton, clips, characterOptions(), bytes);
  ASSERT_TRUE(written.ok()) << written.message;
  const ModelLoadResult loaded = readModelFromMemory(bytesOf(bytes), "character.glb");
  ASSERT_TRUE(loaded.ok()) << loaded.message;
  const Model& model = loaded.model;
  ASSERT_EQ(model.meshes.size(), 1u);
  ASSERT_EQ(model.skins.size(), 1u);
  const ModelMesh& mesh = model.meshes[0];
  EXPECT_EQ(mesh.skin, 0);
  EXPECT_EQ(mesh.mesh.triangleCount(), c.mesh.triangleCount());
  EXPECT_EQ(mesh.mesh.submeshes.size(), c.mesh.submeshes.size());
  // The loader gives each primitive its own copy of the shared vertices: compare corner by corner.
  ASSERT_EQ(mesh.mesh.indices.size(), c.mesh.indices.size());
  ASSERT_EQ(mesh.mesh.joints.size(), mesh.mesh.positions.size());
  for (size_t k = 0; k < c.mesh.indices.size(); ++k) {
    const uint32_t a = mesh.mesh.indices[k], b = c.mesh.indices[k];
    ASSERT_EQ(mesh.mesh.positions[a], c.mesh.positions[b]) << "corner " << k;
    for (int j = 0; j < 4; ++j) {
      if (c.mesh.weights[b][j] == 0.f) continue;
      ASSERT_EQ(mesh.mesh.joints[a][j], c.mesh.joints[b][j]) << "corner " << k;
      ASSERT_NEAR(mesh.mesh.weights[a][j], c.mesh.weights[b][j], 1e-6f) << "corner " << k;
    }
  }
  const ModelSkin& skin = model.skins[0];
  ASSERT_EQ(skin.skeleton.size(), c.skeleton.size());
  for (size_t j = 0; j < c.skeleton.size(); ++j) {
    EXPECT_EQ(skin.skeleton.joints[j].name, c.skeleton.joints[j].name);
    EXPECT_EQ(skin.skeleton.joints[j].parent, c.skeleton.joints[j].parent);
  }
  ASSERT_EQ(skin.clips.size(), 2u);
  EXPECT_EQ(skin.clips[0].name, "idle");
  EXPECT_EQ(skin.clips[1].name, "walk");
  EXPECT_NEAR(skin.clips[1].duration, c.walk.duration, 1e-6f);
  // The same pose from the file as from the character: the skin, hierarchy and keys all survived.
  for (float time : {0.f, 0.3f, 0.71f}) {
    const std::vector<glm::dvec3> expected = posed(c.mesh, c.skeleton, c.walk, time);
    const std::vector<glm::dvec3> actual = posed(mesh.mesh, skin.skeleton, skin.clips[1], time);
    ASSERT_EQ(actual.size(), mesh.mesh.positions.size());
    ASSERT_FALSE(expected.empty());
    double worst = 0.0;
    for (size_t k = 0; k < c.mesh.indices.size(); ++k) {
      worst = std::max(worst, glm::length(actual[mesh.mesh.indices[k]] - expected[c.mesh.indices[k]]));
    }
    EXPECT_LT(worst, 1e-4) << "walk at " << time << " s";
  }
}

TEST(SkinnedGlbWriter, JointOffsetsBecomeNodesAndComeBack) {
  // A two-joint chain whose child sits under a fixed offset (a non-joint node in a source file).
  geometry::MeshData mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  mesh.indices = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  mesh.joints.assign(4, glm::u16vec4(0));
  mesh.weights.assign(4, glm::vec4(1, 0, 0, 0));
  mesh.joints[3] = glm::u16vec4(1, 0, 0, 0);
  anim::Skeleton skeleton;
  skeleton.joints.resize(2);
  skeleton.joints[0].name = "root";
  skeleton.joints[1].name = "tip";
  skeleton.joints[1].parent = 0;
  skeleton.joints[1].offset = glm::mat4(1.f);
  skeleton.joints[1].offset[3] = glm::vec4(0.f, 0.5f, 0.f, 1.f);
  skeleton.joints[1].rest.translation = glm::vec3(0.f, 0.f, 0.25f);
  anim::Pose rest;
  anim::restPose(skeleton, rest);
  anim::setBindPose(skeleton, rest);
  std::vector<uint8_t> bytes;
  const MeshWriteResult written = writeSkinnedGlbToMemory(mesh, skeleton, {}, MeshWriteOptions{}, bytes);
  ASSERT_TRUE(written.ok()) << written.message;
  const ModelLoadResult loaded = readModelFromMemory(bytesOf(bytes), "chain.glb");
  ASSERT_TRUE(loaded.ok()) << loaded.message;
  ASSERT_EQ(loaded.model.skins.size(), 1u);
  const anim::Skeleton& back = loaded.model.skins[0].skeleton;
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back.joints[1].parent, 0);
  std::vector<glm::mat4> before, after;
  anim::Pose pose;
  anim::restPose(skeleton, pose);
  anim::localToGlobal(skeleton, pose, before);
  anim::restPose(back, pose);
  anim::localToGlobal(back, pose, after);
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(after[1][c][r], before[1][c][r], 1e-6f);
  }
  EXPECT_TRUE(loaded.model.skins[0].clips.empty());
}

TEST(SkinnedGlbWriter, RejectsMeshesWithoutSkinOrWithJointsOutsideTheSkeleton) {
  const ProceduralCharacter& c = character();
  std::vector<uint8_t> bytes;
  geometry::MeshData noSkin = c.mesh;
  noSkin.joints.clear();
  noSkin.weights.clear();
  MeshWriteResult result = writeSkinnedGlbToMemory(noSkin, c.skeleton, {}, MeshWriteOptions{}, bytes);
  EXPECT_FALSE(result.ok());
  EXPECT_NE(result.message.find("joints and weights"), std::string::npos) << result.message;
  geometry::MeshData outside = c.mesh;
  outside.joints[5] = glm::u16vec4(uint16_t(c.skeleton.size()), 0, 0, 0);
  outside.weights[5] = glm::vec4(1, 0, 0, 0);
  result = writeSkinnedGlbToMemory(outside, c.skeleton, {}, MeshWriteOptions{}, bytes);
  EXPECT_FALSE(result.ok());
  EXPECT_NE(result.message.find("vertex 5"), std::string::npos) << result.message;
  result = writeSkinnedGlbToMemory(c.mesh, anim::Skeleton{}, {}, MeshWriteOptions{}, bytes);
  EXPECT_FALSE(result.ok());
}

TEST(SkinnedGlbWriter, PiecesCutInAPoseKeepTheirSkinAndClips) {
  const ProceduralCharacter& c = character();
  anim::Pose pose;
  anim::sampleClip(c.skeleton, c.walk, 0.3f, true, pose);
  std::vector<glm::mat4> joints;
  anim::poseToJointMatrices(c.skeleton, pose, joints);
  geometry::MeshContainer container;
  ASSERT_EQ(container.setMesh(c.mesh).code, geometry::SplitStatus::Ok);
  ASSERT_EQ(container.setSkinningPose(joints, glm::mat4(1.f)).code, geometry::SplitStatus::Ok);
  auto splitter = geometry::makeConcaveSplitter();
  geometry::SplitResult result;
  ASSERT_EQ(splitter->split(container, geometry::Plane{{0.2, 1, 0.1}, 1.0}, geometry::SplitOptions{}, result),
            geometry::SplitStatus::Ok)
      << result.message;
  ASSERT_GE(result.pieces.size(), 2u);
  const std::vector<anim::AnimationClip> clips = characterClips();
  for (const geometry::SplitPiece& piece : result.pieces) {
    std::vector<uint8_t> bytes;
    const MeshWriteResult written = writeSkinnedGlbToMemory(piece.mesh, c.skeleton, clips, characterOptions(), bytes);
    ASSERT_TRUE(written.ok()) << written.message;
    const ModelLoadResult loaded = readModelFromMemory(bytesOf(bytes), "piece.glb");
    ASSERT_TRUE(loaded.ok()) << loaded.message;
    ASSERT_EQ(loaded.model.meshes.size(), 1u);
    EXPECT_EQ(loaded.model.meshes[0].mesh.triangleCount(), piece.mesh.triangleCount());
    ASSERT_EQ(loaded.model.skins.size(), 1u);
    EXPECT_EQ(loaded.model.skins[0].skeleton.size(), c.skeleton.size());
    EXPECT_EQ(loaded.model.skins[0].clips.size(), 2u);
    // The cap keeps its own material run.
    bool hasCap = false;
    for (const geometry::SubMesh& run : piece.mesh.submeshes) hasCap = hasCap || run.materialId == 1;
    EXPECT_TRUE(hasCap);
  }
}

// ---- The command-line tool and the validator ----

std::string writeCharacterGlb(const TempDir& dir) {
  const ProceduralCharacter& c = character();
  const std::string path = dir.file("character.glb");
  const std::vector<anim::AnimationClip> clips = characterClips();
  const MeshWriteResult written = writeSkinnedGlb(path, c.mesh, c.skeleton, clips, characterOptions());
  EXPECT_TRUE(written.ok()) << written.message;
  return path;
}

// The generated character cut in a pose into skinned GLB pieces by cleave-split; its JSON report.
nlohmann::json cutCharacterInAPose(TempDir& dir, const std::string& input) {
  std::string output;
  const int status = runCommand(quote(splitTool()) + ' ' + quote(input) + " --pose walk:0.3 --plane 0.2 1 0.1 1.0 --out " +
                             quote(dir.file("pieces")) + " --format glb --json",
                         output);
  EXPECT_EQ(status, 0) << output;
  const nlohmann::json report = nlohmann::json::parse(output, nullptr, false);
  EXPECT_FALSE(report.is_discarded()) << output;
  return report;
}

TEST(CleaveSplitTool, PoseCutsASkinnedGlbIntoSkinnedAnimatedPieces) {
  if (!std::filesystem::exists(splitTool())) GTEST_SKIP() << "cleave-split not built";
  TempDir dir;
  const std::string input = writeCharacterGlb(dir);
  const nlohmann::json report = cutCharacterInAPose(dir, input);
  ASSERT_FALSE(report.is_discarded());
  EXPECT_EQ(report["status"], "Ok");
  EXPECT_EQ(report["pose"]["clip"], "walk");
  EXPECT_EQ(report["pose"]["joints"], character().skeleton.size());
  ASSERT_GE(report["pieces"].size(), 2u);
  ASSERT_EQ(report["files"].size(), report["pieces"].size());
  double volume = 0.0;
  for (size_t k = 0; k < report["pieces"].size(); ++k) {
    const nlohmann::json& piece = report["pieces"][k];
    EXPECT_TRUE(piece["closed"].get<bool>());
    EXPECT_GT(piece["joints_used"].get<int>(), 0);
    volume += piece["volume"].get<double>();
    const ModelLoadResult loaded = loadModel(report["files"][k].get<std::string>());
    ASSERT_TRUE(loaded.ok()) << loaded.message;
    ASSERT_EQ(loaded.model.meshes.size(), 1u);
    EXPECT_EQ(loaded.model.meshes[0].skin, 0);
    EXPECT_EQ(loaded.model.meshes[0].mesh.triangleCount(), piece["triangles"].get<size_t>());
    ASSERT_EQ(loaded.model.skins.size(), 1u);
    EXPECT_EQ(loaded.model.skins[0].skeleton.size(), character().skeleton.size());
    EXPECT_EQ(loaded.model.skins[0].clips.size(), 2u);
  }
  // The input volume is that of the posed character, and the pieces share it out.
  EXPECT_NEAR(volume / report["input"]["volume"].get<double>(), 1.0, 1e-6);

  // A clip by index gives the same cut.
  std::string byIndex;
  ASSERT_EQ(runCommand(quote(splitTool()) + ' ' + quote(input) + " --pose 1:0.3 --plane 0.2 1 0.1 1.0 --json", byIndex), 0);
  const nlohmann::json indexReport = nlohmann::json::parse(byIndex, nullptr, false);
  EXPECT_EQ(indexReport["pose"]["clip"], "walk");
  EXPECT_EQ(indexReport["pieces"].size(), report["pieces"].size());
}

// The same pieces through the Khronos glTF validator (its own test, so that the checks above count
// as passed where the validator is not installed).
TEST(CleaveSplitTool, PosedSkinnedPiecesPassTheKhronosValidator) {
  if (!std::filesystem::exists(splitTool())) GTEST_SKIP() << "cleave-split not built";
  std::string why;
  const std::string validator = test::gltfValidatorDir(why);
  if (validator.empty()) GTEST_SKIP() << why;
  TempDir dir;
  const std::string input = writeCharacterGlb(dir);
  const nlohmann::json report = cutCharacterInAPose(dir, input);
  ASSERT_FALSE(report.is_discarded());
  ASSERT_GE(report["files"].size(), 2u);
  std::vector<std::string> files = {input};
  for (const auto& file : report["files"]) files.push_back(file.get<std::string>());
  std::string validation;
  const int valid = test::validateGltf(validator, files, validation);
  EXPECT_EQ(valid, 0) << validation;
  size_t lines = 0;
  for (size_t at = validation.find('\n'); at != std::string::npos; at = validation.find('\n', at + 1)) ++lines;
  EXPECT_EQ(lines, report["files"].size() + 1) << validation;
  EXPECT_EQ(validation.find("\"errors\":0"), validation.find("\"errors\":")) << validation;
  EXPECT_EQ(validation.find("\"errors\":1"), std::string::npos) << validation;
}

TEST(CleaveSplitTool, PoseErrorsNameTheProblem) {
  if (!std::filesystem::exists(splitTool())) GTEST_SKIP() << "cleave-split not built";
  TempDir dir;
  const std::string input = writeCharacterGlb(dir);
  std::string output;
  // An unknown clip: data error, one line naming the file and the clips there are.
  EXPECT_EQ(runCommand(quote(splitTool()) + ' ' + quote(input) + " --pose run:1 --plane 0 1 0 1 2>&1", output), 1);
  EXPECT_NE(output.find("no clip 'run'"), std::string::npos) << output;
  EXPECT_NE(output.find("'walk'"), std::string::npos) << output;
  EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
  // A model without a skinned mesh.
  const std::string cube = dir.write("cube.obj", test::cubeObj());
  EXPECT_EQ(runCommand(quote(splitTool()) + ' ' + quote(cube) + " --pose walk:1 --plane 0 1 0 0.5 2>&1", output), 1);
  EXPECT_NE(output.find("cube.obj"), std::string::npos) << output;
  // Bad syntax: usage error.
  EXPECT_EQ(runCommand(quote(splitTool()) + ' ' + quote(input) + " --pose walk --plane 0 1 0 1 2>&1", output), 2);
  EXPECT_NE(output.find("CLIP:SECONDS"), std::string::npos) << output;
  EXPECT_EQ(runCommand(quote(splitTool()) + ' ' + quote(input) + " --pose walk:abc --plane 0 1 0 1 2>&1", output), 2);
}

}  // namespace
}  // namespace cleave::assets
