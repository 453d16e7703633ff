// SPDX-License-Identifier: MIT
// The golden tolerance (image_compare.h, kGoldenTolerance) against what it must tell apart: a scene
// drawn twice gives the same pixels (what the software renderer varies by: nothing), and the same
// scene with its light turned by 3 degrees, without shadows, or without one of its pieces each
// fails the comparison. A tolerance loose enough to pass a broken renderer fails this test.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

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

struct Variant {
  float lightTurnDegrees = 0.f;
  bool shadows = true;
  bool withPiece = true;
};

class Scene {
 public:
  bool init(std::string& why) {
    if (!testing::startHeadless(context_, renderer_, why)) return false;
    floor_ = renderer_.uploadMesh(geometry::primitives::box(glm::vec3(20.f, 0.5f, 20.f))).valueOr({});
    cube_ = renderer_.uploadMesh(geometry::primitives::box(glm::vec3(0.5f))).valueOr({});
    sphere_ = renderer_.uploadMesh(geometry::primitives::uvSphere(0.55f, 32, 16)).valueOr({});
    const geometry::SplitResult split = geometry::splitMesh(geometry::primitives::box(glm::vec3(0.5f)), glm::mat4(1.f),
                                                            geometry::Plane{{1.0, 1.0, 0.3}, 0.1}, {});
    if (split.status != geometry::SplitStatus::Ok) return why = split.message, false;
    piece_ = renderer_.uploadMesh(split.pieces.back().mesh).valueOr({});
    return floor_.valid() && cube_.valid() && sphere_.valid() && piece_.valid();
  }

  std::vector<uint8_t> draw(const Variant& v) {
    Material floor;
    floor.shading = Shading::Checker;
    floor.baseColor = glm::vec4(0.62f, 0.62f, 0.6f, 1.f);
    floor.checkerColor = glm::vec4(0.16f, 0.17f, 0.19f, 1.f);
    Material red, metal;
    red.baseColor = glm::vec4(0.8f, 0.3f, 0.2f, 1.f);
    metal.baseColor = glm::vec4(0.85f, 0.86f, 0.9f, 1.f);
    metal.reflectivity = 0.6f;
    const std::vector<Material> pieceMaterials = {red, metal};
    Camera camera;
    camera.position = glm::vec3(0.f, 2.2f, 5.5f);
    camera.view = glm::lookAt(camera.position, glm::vec3(0.f, 0.4f, 0.f), glm::vec3(0, 1, 0));
    Lighting lighting;
    lighting.sunDirection = glm::vec3(glm::rotate(glm::mat4(1.f), glm::radians(v.lightTurnDegrees), glm::vec3(0, 1, 0)) *
                                      glm::vec4(lighting.sunDirection, 0.f));
    lighting.shadows = v.shadows;
    lighting.shadowRadius = 6.f;
    renderer_.beginFrame(kWidth, kHeight, camera, lighting);
    renderer_.submit(floor_, glm::translate(glm::mat4(1.f), glm::vec3(0.f, -0.5f, 0.f)),
                     std::span<const Material>(&floor, 1));
    renderer_.submit(cube_, glm::translate(glm::mat4(1.f), glm::vec3(-1.6f, 0.5f, 0.f)),
                     std::span<const Material>(&red, 1));
    renderer_.submit(sphere_, glm::translate(glm::mat4(1.f), glm::vec3(0.f, 0.55f, 0.5f)),
                     std::span<const Material>(&metal, 1));
    if (v.withPiece) {
      renderer_.submit(piece_, glm::translate(glm::mat4(1.f), glm::vec3(1.6f, 0.5f, -0.3f)), pieceMaterials);
    }
    renderer_.endFrame();
    return testing::readFrame(renderer_, kWidth, kHeight);
  }

 private:
  std::unique_ptr<HeadlessGlContext> context_;
  Renderer renderer_;
  MeshHandle floor_, cube_, sphere_, piece_;
};

TEST(RenderGolden, ToleranceSeesAShiftedLightAMissingShadowAndARemovedPiece) {
  Scene scene;
  std::string why;
  if (!scene.init(why)) GTEST_SKIP() << "no headless OpenGL context: " << why;
  const std::vector<uint8_t> reference = scene.draw({});
  const testing::ImageComparison again =
      testing::compareImages(scene.draw({}), reference, kWidth, kHeight, testing::kGoldenTolerance);
  EXPECT_TRUE(again.ok);
  EXPECT_EQ(again.largestDifference, 0) << "two renders of one scene differ";
  const std::pair<const char*, Variant> broken[] = {
      {"light turned by 3 degrees", {3.f, true, true}},
      {"no shadows", {0.f, false, true}},
      {"a piece removed", {0.f, true, false}},
  };
  for (const auto& [what, variant] : broken) {
    const testing::ImageComparison c =
        testing::compareImages(scene.draw(variant), reference, kWidth, kHeight, testing::kGoldenTolerance);
    std::printf("[ golden  ] %s: %.3f%% of the pixels differ (largest %d)\n", what, 100.0 * c.differingShare,
                c.largestDifference);
    EXPECT_FALSE(c.ok) << what << " passes the golden tolerance";
  }
  // And the loose tolerance the goldens had before (24 levels on 1% of the pixels) passed a render
  // brightened by 24 levels everywhere: the golden one does not.
  std::vector<uint8_t> brighter = reference;
  for (size_t k = 0; k < brighter.size(); ++k)
    if (k % 4 != 3) brighter[k] = uint8_t(std::min(255, brighter[k] + 24));
  const testing::ImageTolerance loose{24, 0.01};
  EXPECT_TRUE(testing::compareImages(brighter, reference, kWidth, kHeight, loose).ok);
  EXPECT_FALSE(testing::compareImages(brighter, reference, kWidth, kHeight, testing::kGoldenTolerance).ok);
}

}  // namespace
}  // namespace cleave::render
