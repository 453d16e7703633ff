// SPDX-License-Identifier: MIT
// View culling (frustum.h and the renderer's passes): a sphere is out only when it lies wholly
// behind one of the six planes; a mesh outside the camera's view costs no draw call and the frame
// is the same as without it; a mesh outside the view but inside the light's still casts its shadow.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "cleave/geometry/primitives.h"
#include "cleave/render/frustum.h"
#include "tests/render/headless_gl.h"
#include "tests/render/image_compare.h"

namespace cleave::render {
namespace {

// A camera at the origin looking down -z, 90 degrees vertically, square, near 1, far 100.
glm::mat4 squareView() { return glm::perspective(glm::radians(90.f), 1.f, 1.f, 100.f); }

TEST(Frustum, ASphereIsOutOnlyWhenWhollyBehindOnePlane) {
  const Frustum f = Frustum::fromMatrix(squareView());
  EXPECT_TRUE(f.touchesSphere(glm::vec3(0, 0, -10), 1.f));    // straight ahead
  EXPECT_FALSE(f.touchesSphere(glm::vec3(0, 0, 10), 1.f));    // behind the camera
  EXPECT_FALSE(f.touchesSphere(glm::vec3(0, 0, -102), 1.f));  // past the far plane
  EXPECT_TRUE(f.touchesSphere(glm::vec3(0, 0, -100.5f), 1.f));  // across it
  // The side planes run at 45 degrees: at depth 10 the edge is at x = 10; the distance of a centre
  // at x = 10 + a to that plane is a / sqrt(2).
  EXPECT_TRUE(f.touchesSphere(glm::vec3(11.f, 0, -10), 1.f));   // 0.71 out, radius 1: touches
  EXPECT_FALSE(f.touchesSphere(glm::vec3(11.5f, 0, -10), 1.f)); // 1.06 out
  EXPECT_FALSE(f.touchesSphere(glm::vec3(0, -11.5f, -10), 1.f));
  EXPECT_TRUE(f.touchesSphere(glm::vec3(0, 0, -0.5f), 0.6f));   // across the near plane
}

TEST(Frustum, AModelsScaleGrowsTheSphereByItsLargestAxis) {
  const glm::mat4 model = glm::scale(glm::translate(glm::mat4(1.f), glm::vec3(1, 2, 3)), glm::vec3(2.f, -3.f, 0.5f));
  const auto [centre, radius] = worldSphere(model, glm::vec3(1, 0, 0), 2.f);
  EXPECT_EQ(centre, glm::vec3(3, 2, 3));
  EXPECT_FLOAT_EQ(radius, 6.f);
}

class CulledScene : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string why;
    if (!testing::startHeadless(context_, renderer_, why)) GTEST_SKIP() << "no headless GL: " << why;
    floor_ = renderer_.uploadMesh(geometry::primitives::box(glm::vec3(20.f, 0.5f, 20.f))).valueOr({});
    box_ = renderer_.uploadMesh(geometry::primitives::box(glm::vec3(0.5f))).valueOr({});
  }

  // The floor and a box in front of the camera, and `extra` boxes at the given places.
  std::vector<uint8_t> draw(const std::vector<glm::vec3>& extra, uint32_t& drawCalls) {
    Material floor;
    floor.shading = Shading::Checker;
    floor.castsShadow = false;
    Material red;
    red.baseColor = glm::vec4(0.8f, 0.3f, 0.2f, 1.f);
    Camera camera;
    camera.position = glm::vec3(0.f, 2.f, 5.f);
    camera.view = glm::lookAt(camera.position, glm::vec3(0.f, 0.5f, 0.f), glm::vec3(0, 1, 0));
    Lighting lighting;
    lighting.shadowRadius = 12.f;
    renderer_.beginFrame(kWidth, kHeight, camera, lighting);
    renderer_.submit(floor_, glm::translate(glm::mat4(1.f), glm::vec3(0.f, -0.5f, 0.f)), std::span<const Material>(&floor, 1), true);
    renderer_.submit(box_, glm::translate(glm::mat4(1.f), glm::vec3(0.f, 0.5f, 0.f)), std::span<const Material>(&red, 1), true);
    for (const glm::vec3& at : extra)
      renderer_.submit(box_, glm::translate(glm::mat4(1.f), at), std::span<const Material>(&red, 1), true);
    drawCalls = renderer_.endFrame().drawCalls;
    return testing::readFrame(renderer_, kWidth, kHeight);
  }

  static constexpr int kWidth = 320, kHeight = 180;
  std::unique_ptr<HeadlessGlContext> context_;
  Renderer renderer_;
  MeshHandle floor_, box_;
};

TEST_F(CulledScene, BoxesBehindTheCameraCostNoDrawAndChangeNothing) {
  uint32_t alone = 0, withHidden = 0;
  const std::vector<uint8_t> a = draw({}, alone);
  // Behind the camera and far outside the light's square (so no shadow of theirs can fall in view).
  const std::vector<uint8_t> b = draw({glm::vec3(0.f, 0.5f, 40.f), glm::vec3(3.f, 0.5f, 45.f)}, withHidden);
  EXPECT_EQ(alone, 2u);
  EXPECT_EQ(withHidden, 2u);
  const testing::ImageComparison same = testing::compareImages(a, b, kWidth, kHeight, {0, 0.0});
  EXPECT_TRUE(same.ok) << same.differingShare;
}

TEST_F(CulledScene, ABoxOutOfViewStillCastsItsShadowIntoIt) {
  uint32_t alone = 0, withCaster = 0;
  const std::vector<uint8_t> a = draw({}, alone);
  // Above the camera, out of its view, between the sun and the floor in view.
  const std::vector<uint8_t> b = draw({glm::vec3(0.f, 9.f, 1.f)}, withCaster);
  EXPECT_EQ(withCaster, alone);  // not drawn in view
  const testing::ImageComparison same = testing::compareImages(a, b, kWidth, kHeight, {8, 0.0});
  EXPECT_FALSE(same.ok) << "its shadow should darken the floor";
}

}  // namespace
}  // namespace cleave::render
