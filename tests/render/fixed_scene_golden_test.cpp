// SPDX-License-Identifier: MIT
// A fixed scene rendered headless and compared with a committed golden PNG: checker floor, sky,
// shadows, a textured lit cube, a reflective sphere, a debug-normals torus and a split cube whose
// cap uses a solid checker. Tolerance: per-channel difference and share of differing pixels; on
// failure the actual and diff images are written next to the golden (CLEAVE_UPDATE_GOLDENS=1
// rewrites it). Also checks that GPU resources are freed and handles go stale.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "cleave/assets/procedural_textures.h"
#include "cleave/geometry/mesh_splitter.h"
#include "cleave/geometry/primitives.h"
#include "cleave/render/gl_context.h"
#include "cleave/render/renderer.h"
#include "tests/render/headless_gl.h"
#include "tests/render/image_compare.h"

namespace cleave::render {
namespace {

constexpr int kWidth = 480;
constexpr int kHeight = 270;

struct FixedScene {
  std::unique_ptr<HeadlessGlContext> context;
  Renderer renderer;

  bool init(std::string& why) {
    return testing::startHeadless(context, renderer, why);
  }
};

TEST(RenderGolden, FixedSceneMatchesTheCommittedImage) {
  FixedScene scene;
  std::string why;
  if (!scene.init(why)) GTEST_SKIP() << "no headless OpenGL context: " << why;
  Renderer& r = scene.renderer;

  const assets::Image wood = assets::makeTexture(assets::TextureKind::Wood, 128, 7);
  const TextureHandle woodTexture = r.createTexture(wood.width, wood.height, wood.rgba).valueOr({});
  ASSERT_TRUE(woodTexture.valid());

  const MeshHandle floor = r.uploadMesh(geometry::primitives::box(glm::vec3(20.f, 0.5f, 20.f))).valueOr({});
  const MeshHandle cube = r.uploadMesh(geometry::primitives::box(glm::vec3(0.5f))).valueOr({});
  const MeshHandle sphere = r.uploadMesh(geometry::primitives::uvSphere(0.55f, 32, 16)).valueOr({});
  const MeshHandle torus = r.uploadMesh(geometry::primitives::torus(0.45f, 0.18f, 40, 20)).valueOr({});

  // One half of a cube cut diagonally: its cap (material 1) shows the solid checker.
  geometry::MeshContainer container;
  ASSERT_EQ(container.setMesh(geometry::primitives::box(glm::vec3(0.5f))).code, geometry::SplitStatus::Ok);
  geometry::SplitResult split;
  const geometry::Plane plane{glm::normalize(glm::dvec3(1.0, 1.0, 0.3)), 0.1};
  ASSERT_EQ(geometry::makeConvexSplitter()->split(container, plane, {}, split), geometry::SplitStatus::Ok);
  ASSERT_EQ(split.pieces.size(), 2u);
  const MeshHandle half = r.uploadMesh(split.pieces[0].side < 0 ? split.pieces[0].mesh : split.pieces[1].mesh).valueOr({});
  for (MeshHandle h : {floor, cube, sphere, torus, half}) ASSERT_TRUE(h.valid());

  Material floorMaterial;
  floorMaterial.shading = Shading::Checker;
  floorMaterial.baseColor = glm::vec4(0.62f, 0.62f, 0.6f, 1.f);
  floorMaterial.checkerColor = glm::vec4(0.16f, 0.17f, 0.19f, 1.f);
  Material woodMaterial;
  woodMaterial.albedo = woodTexture;
  Material metal;
  metal.baseColor = glm::vec4(0.85f, 0.86f, 0.9f, 1.f);
  metal.reflectivity = 0.6f;
  metal.specular = 1.2f;
  metal.shininess = 90.f;
  Material normals;
  normals.shading = Shading::DebugNormals;
  Material outside;
  outside.baseColor = glm::vec4(0.8f, 0.3f, 0.2f, 1.f);
  Material cap;
  cap.shading = Shading::CheckerCube;
  cap.checkerScale = 6.f;
  const std::vector<Material> halfMaterials = {outside, cap};

  Camera camera;
  camera.position = glm::vec3(0.f, 2.2f, 5.5f);
  camera.view = glm::lookAt(camera.position, glm::vec3(0.f, 0.4f, 0.f), glm::vec3(0, 1, 0));
  Lighting lighting;
  lighting.shadowCenter = glm::vec3(0.f);
  lighting.shadowRadius = 6.f;
  r.beginFrame(kWidth, kHeight, camera, lighting);
  r.submit(floor, glm::translate(glm::mat4(1.f), glm::vec3(0.f, -0.5f, 0.f)),
           std::span<const Material>(&floorMaterial, 1));
  r.submit(cube, glm::rotate(glm::translate(glm::mat4(1.f), glm::vec3(-2.f, 0.5f, 0.f)), 0.5f, glm::vec3(0, 1, 0)),
           std::span<const Material>(&woodMaterial, 1));
  r.submit(sphere, glm::translate(glm::mat4(1.f), glm::vec3(-0.6f, 0.55f, 0.6f)), std::span<const Material>(&metal, 1));
  r.submit(torus, glm::translate(glm::mat4(1.f), glm::vec3(0.8f, 0.18f, 0.8f)), std::span<const Material>(&normals, 1));
  r.submit(half, glm::translate(glm::mat4(1.f), glm::vec3(2.0f, 0.5f, -0.3f)), halfMaterials);
  r.endFrame();

  const std::vector<uint8_t> rgba = testing::readFrame(r, kWidth, kHeight);
  const int width = kWidth, height = kHeight;

  // Not blank: the sky (top rows) is bluish and the floor (bottom rows) has two checker tones.
  const auto pixel = [&](int x, int y) { return &rgba[(size_t(y) * width + x) * 4]; };
  EXPECT_GT(pixel(kWidth / 2, 2)[2], pixel(kWidth / 2, 2)[0]) << "the sky is not blue";
  int darkest = 255, brightest = 0;
  for (int x = 0; x < kWidth; ++x) {
    const int v = pixel(x, kHeight - 3)[1];
    darkest = std::min(darkest, v);
    brightest = std::max(brightest, v);
  }
  EXPECT_GT(brightest - darkest, 60) << "the floor shows no checker";

  const testing::ImageTolerance tolerance = testing::kGoldenTolerance;
  const std::string golden = std::string(CLEAVE_SOURCE_DIR) + "/tests/render/goldens/fixed_scene.png";
  const testing::ImageComparison comparison = testing::compareWithGolden(golden, width, height, rgba, tolerance);
  EXPECT_TRUE(comparison.ok) << comparison.message;

  // Freed resources: the handles go stale and drawing them is a no-op, not a crash.
  const uint32_t meshesBefore = r.liveMeshCount();
  const uint32_t texturesBefore = r.liveTextureCount();
  EXPECT_TRUE(r.isValid(torus));
  r.destroyMesh(torus);
  r.destroyTexture(woodTexture);
  EXPECT_FALSE(r.isValid(torus));
  EXPECT_FALSE(r.isValid(woodTexture));
  EXPECT_EQ(r.liveMeshCount() + 1, meshesBefore);
  EXPECT_EQ(r.liveTextureCount() + 1, texturesBefore);
  // A new mesh may reuse the slot but never the generation: the old handle stays stale.
  const MeshHandle again = r.uploadMesh(geometry::primitives::box(glm::vec3(0.1f))).valueOr({});
  EXPECT_TRUE(r.isValid(again));
  EXPECT_FALSE(r.isValid(torus));
  r.beginFrame(kWidth, kHeight, camera, lighting);
  r.submit(torus, glm::mat4(1.f), std::span<const Material>(&normals, 1));
  r.endFrame();
}

}  // namespace
}  // namespace cleave::render
