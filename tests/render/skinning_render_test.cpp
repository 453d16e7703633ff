// SPDX-License-Identifier: MIT
// GPU skinning against the CPU: the generated character in a walking pose rendered with
// submitSkinned must look like the same pose skinned on the CPU and drawn statically; a skinned cut
// piece, rendered in the same pose, must cover exactly its half of the uncut character.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>

#include "cleave/anim/animation_clip.h"
#include "cleave/assets/procedural_character.h"
#include "cleave/geometry/mesh_splitter.h"
#include "cleave/render/gl_context.h"
#include "cleave/render/renderer.h"
#include "tests/render/headless_gl.h"

namespace cleave::render {
namespace {

constexpr int kWidth = 160, kHeight = 200;
constexpr float kEyeHeight =
    1.0f;  // a horizontal plane at this height projects onto the middle row

struct Scene {
  std::unique_ptr<HeadlessGlContext> context;
  Renderer renderer;
  assets::ProceduralCharacter character = assets::makeProceduralCharacter();
  std::vector<Material> materials;
  std::vector<glm::mat4> joints;
  glm::mat4 model{1.f};

  bool init(std::string& why) {
    if (!testing::startHeadless(context, renderer, why)) return false;
    for (const glm::vec4& color : character.materialColors) {
      Material m;
      m.baseColor = color;
      materials.push_back(m);
    }
    anim::Pose pose;
    anim::sampleClip(character.skeleton, character.walk, 0.3f, true, pose);
    anim::poseToJointMatrices(character.skeleton, pose, joints);
    model = glm::rotate(glm::mat4(1.f), glm::radians(35.f), glm::vec3(0, 1, 0));
    return true;
  }

  // Draws the listed meshes (skinned with `joints` when `skinned`) and reads the frame back.
  std::vector<uint8_t> render(const std::vector<MeshHandle>& meshes, bool skinned, bool shadows) {
    Camera camera;
    camera.position = glm::vec3(0.f, kEyeHeight, 2.4f);
    camera.view = glm::lookAt(camera.position, glm::vec3(0.f, kEyeHeight, 0.f), glm::vec3(0, 1, 0));
    Lighting lighting;
    lighting.shadows = shadows;
    lighting.shadowCenter = glm::vec3(0.f, 1.f, 0.f);
    lighting.shadowRadius = 2.f;
    renderer.beginFrame(kWidth, kHeight, camera, lighting);
    for (MeshHandle mesh : meshes) {
      if (skinned)
        renderer.submitSkinned(mesh, model, joints, materials);
      else
        renderer.submit(mesh, model, materials);
    }
    renderer.endFrame();
    std::vector<uint8_t> rgba;
    int w = 0, h = 0;
    renderer.readPixels(rgba, w, h);
    return rgba;
  }
};

// Largest channel difference of pixel p.
int difference(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, size_t p) {
  int worst = 0;
  for (int c = 0; c < 3; ++c)
    worst = std::max(worst, std::abs(int(a[p * 4 + c]) - int(b[p * 4 + c])));
  return worst;
}

// Share of pixels in rows [rowBegin, rowEnd) differing by more than `tolerance`.
double differingShare(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, int rowBegin,
                      int rowEnd, int tolerance = 8) {
  size_t differing = 0, total = 0;
  for (int y = std::max(rowBegin, 0); y < std::min(rowEnd, kHeight); ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const size_t p = size_t(y) * kWidth + size_t(x);
      differing += difference(a, b, p) > tolerance ? 1 : 0;
      ++total;
    }
  }
  return total ? double(differing) / double(total) : 0.0;
}

void save(const std::string& name, const std::vector<uint8_t>& rgba) {
  const std::filesystem::path dir = std::filesystem::path(CLEAVE_BINARY_DIR) / "test-images";
  std::filesystem::create_directories(dir);
  writePng((dir / name).string(), kWidth, kHeight, rgba);
}

// The pose skinned on the CPU exactly as the shader does it, as a static mesh.
geometry::MeshData skinOnCpu(const geometry::MeshData& mesh, std::span<const glm::mat4> joints) {
  geometry::MeshData out = mesh;
  out.joints.clear();
  out.weights.clear();
  for (size_t v = 0; v < mesh.vertexCount(); ++v) {
    glm::mat4 blend(0.f);
    float total = 0.f;
    for (int k = 0; k < 4; ++k) {
      blend += mesh.weights[v][k] * joints[mesh.joints[v][k]];
      total += mesh.weights[v][k];
    }
    blend /= total;
    out.positions[v] = glm::vec3(blend * glm::vec4(mesh.positions[v], 1.f));
    out.normals[v] = glm::normalize(glm::mat3(blend) * mesh.normals[v]);
  }
  return out;
}

TEST(SkinnedRendering, GpuPoseMatchesCpuPose) {
  Scene scene;
  std::string why;
  if (!scene.init(why)) GTEST_SKIP() << "no headless GL: " << why;
  const base::Expected<MeshHandle> skinned = scene.renderer.uploadMesh(scene.character.mesh);
  ASSERT_TRUE(skinned.ok()) << skinned.message();
  const base::Expected<MeshHandle> cpu = scene.renderer.uploadMesh(skinOnCpu(scene.character.mesh, scene.joints));
  ASSERT_TRUE(cpu.ok()) << cpu.message();
  const MeshHandle bind = scene.renderer.uploadMesh(scene.character.mesh).valueOr({});
  const std::vector<uint8_t> gpuFrame = scene.render({*skinned}, true, true);
  const std::vector<uint8_t> cpuFrame = scene.render({*cpu}, false, true);
  const std::vector<uint8_t> bindFrame =
      scene.render({bind}, false, true);  // submit() ignores the skin
  const std::vector<uint8_t> empty = scene.render({}, false, true);
  save("skinning_gpu.png", gpuFrame);
  save("skinning_cpu.png", cpuFrame);
  // The character fills a good part of the frame, and the pose really moved it.
  EXPECT_GT(differingShare(gpuFrame, empty, 0, kHeight), 0.08);
  EXPECT_GT(differingShare(gpuFrame, bindFrame, 0, kHeight), 0.02);
  // GPU and CPU skinning agree up to rounding along silhouettes.
  EXPECT_LT(differingShare(gpuFrame, cpuFrame, 0, kHeight, 12), 0.004);
}

TEST(SkinnedRendering, CutPiecesInThePoseCoverTheirHalfOfTheCharacter) {
  Scene scene;
  std::string why;
  if (!scene.init(why)) GTEST_SKIP() << "no headless GL: " << why;
  geometry::MeshContainer container;
  ASSERT_EQ(container.setMesh(scene.character.mesh).message, "");
  ASSERT_EQ(container.setSkinningPose(scene.joints, scene.model).message, "");
  geometry::SplitResult result;
  const geometry::Plane plane{{0.0, 1.0, 0.0},
                              kEyeHeight};  // seen edge-on: the seam is the middle row
  ASSERT_EQ(
      geometry::makeConcaveSplitter()->split(container, plane, geometry::SplitOptions{}, result),
      geometry::SplitStatus::Ok)
      << result.message;
  std::vector<MeshHandle> above, all;
  for (const geometry::SplitPiece& piece : result.pieces) {
    const base::Expected<MeshHandle> handle = scene.renderer.uploadMesh(piece.mesh);
    ASSERT_TRUE(handle.ok()) << handle.message();
    all.push_back(*handle);
    if (piece.side > 0) above.push_back(*handle);
  }
  ASSERT_FALSE(above.empty());
  const MeshHandle whole = scene.renderer.uploadMesh(scene.character.mesh).valueOr({});
  const std::vector<uint8_t> uncut = scene.render({whole}, true, false);
  const std::vector<uint8_t> upper = scene.render(above, true, false);
  const std::vector<uint8_t> pieces = scene.render(all, true, false);
  const std::vector<uint8_t> empty = scene.render({}, true, false);
  save("skinned_cut_uncut.png", uncut);
  save("skinned_cut_upper.png", upper);
  save("skinned_cut_pieces.png", pieces);
  constexpr int kSeam = kHeight / 2, kMargin = 4;
  // The upper pieces look like the upper half of the uncut character, and leave the lower half
  // empty.
  EXPECT_LT(differingShare(upper, uncut, 0, kSeam - kMargin), 0.002);
  EXPECT_LT(differingShare(upper, empty, kSeam + kMargin, kHeight), 0.002);
  EXPECT_GT(differingShare(uncut, empty, kSeam + kMargin, kHeight),
            0.05);  // there was a lower half
  EXPECT_GT(differingShare(upper, empty, 0, kSeam - kMargin), 0.05);
  // All pieces together differ from the uncut character only along the seam.
  EXPECT_LT(differingShare(pieces, uncut, 0, kSeam - kMargin), 0.002);
  EXPECT_LT(differingShare(pieces, uncut, kSeam + kMargin, kHeight), 0.002);
}

}  // namespace
}  // namespace cleave::render
