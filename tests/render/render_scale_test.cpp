// SPDX-License-Identifier: MIT
// The render scale (Renderer::setRenderScale): the 3D scene drawn at a fraction of the frame and
// stretched over it, the HUD at the frame's full resolution. Checked against the same scene at scale
// 1: the frame keeps its size, the HUD's pixels are the same bit for bit, the scene is the same
// picture (small differences along edges only) and yet not the same pixels (it really was drawn
// smaller); the shadow map shrinks with the scale.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "cleave/geometry/primitives.h"
#include "cleave/render/dynamic_scale.h"
#include "cleave/render/gl_context.h"
#include "cleave/render/renderer.h"
#include "tests/render/headless_gl.h"
#include "tests/render/image_compare.h"

namespace cleave::render {
namespace {

constexpr int kWidth = 480;
constexpr int kHeight = 270;
const glm::vec4 kHudRect(10.f, 10.f, 200.f, 40.f);  // x, y, w, h in pixels (top-left origin)

class ScaledScene {
 public:
  bool init(std::string& why) {
    if (!testing::startHeadless(context_, renderer_, why)) return false;
    floor_ = renderer_.uploadMesh(geometry::primitives::box(glm::vec3(20.f, 0.5f, 20.f))).valueOr({});
    sphere_ = renderer_.uploadMesh(geometry::primitives::uvSphere(0.8f, 48, 24)).valueOr({});
    return floor_.valid() && sphere_.valid();
  }

  Renderer& renderer() { return renderer_; }

  std::vector<uint8_t> draw(float scale, bool withSphere = true) {
    renderer_.setRenderScale(scale);
    Material floor;
    floor.shading = Shading::Checker;
    floor.baseColor = glm::vec4(0.62f, 0.62f, 0.6f, 1.f);
    Material red;
    red.baseColor = glm::vec4(0.8f, 0.3f, 0.2f, 1.f);
    Camera camera;
    camera.position = glm::vec3(0.f, 2.f, 5.f);
    camera.view = glm::lookAt(camera.position, glm::vec3(0.f, 0.5f, 0.f), glm::vec3(0, 1, 0));
    Lighting lighting;
    lighting.shadowRadius = 6.f;
    renderer_.beginFrame(kWidth, kHeight, camera, lighting);
    renderer_.submit(floor_, glm::translate(glm::mat4(1.f), glm::vec3(0.f, -0.5f, 0.f)),
                     std::span<const Material>(&floor, 1));
    if (withSphere) {
      renderer_.submit(sphere_, glm::translate(glm::mat4(1.f), glm::vec3(0.f, 0.8f, 0.f)),
                       std::span<const Material>(&red, 1));
    }
    // An opaque HUD box with text: drawn after the scene, at full resolution.
    renderer_.submitOverlayRect(kHudRect, glm::vec4(0.05f, 0.05f, 0.1f, 1.f));
    renderer_.submitText("HUD 0123456789", {18.f, 20.f}, 2.f, glm::vec4(1.f));
    renderer_.endFrame();
    return testing::readFrame(renderer_, kWidth, kHeight);
  }

 private:
  std::unique_ptr<HeadlessGlContext> context_;
  Renderer renderer_;
  MeshHandle floor_, sphere_;
};

bool insideHud(int x, int y) {
  return x >= int(kHudRect.x) && x < int(kHudRect.x + kHudRect.z) && y >= int(kHudRect.y) &&
         y < int(kHudRect.y + kHudRect.w);
}

constexpr int kBlock = 15;  // block averages: what a viewer sees, without the pixel-level edges

struct Difference {
  int hudPixelsDiffering = 0;
  double largestBlockDifference = 0.0;  // of kBlock x kBlock block means, per channel, 0..255
  double sceneShareDiffering = 0.0;     // share of scene pixels with any channel differing
};

double largestBlockDifference(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  double largest = 0.0;
  for (int by = 0; by + kBlock <= kHeight; by += kBlock) {
    for (int bx = 0; bx + kBlock <= kWidth; bx += kBlock) {
      for (int c = 0; c < 3; ++c) {
        double sum = 0.0;
        for (int y = by; y < by + kBlock; ++y)
          for (int x = bx; x < bx + kBlock; ++x) {
            const size_t p = (size_t(y) * kWidth + size_t(x)) * 4 + size_t(c);
            sum += double(a[p]) - double(b[p]);
          }
        largest = std::max(largest, std::abs(sum) / (kBlock * kBlock));
      }
    }
  }
  return largest;
}

Difference compare(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  Difference d;
  int scenePixels = 0, sceneDiffering = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const size_t p = (size_t(y) * kWidth + size_t(x)) * 4;
      int largest = 0;
      for (int c = 0; c < 3; ++c)
        largest = std::max(largest, std::abs(int(a[p + size_t(c)]) - int(b[p + size_t(c)])));
      if (insideHud(x, y)) {
        d.hudPixelsDiffering += largest > 0 ? 1 : 0;
      } else {
        ++scenePixels;
        sceneDiffering += largest > 0 ? 1 : 0;
      }
    }
  }
  d.largestBlockDifference = largestBlockDifference(a, b);
  d.sceneShareDiffering = double(sceneDiffering) / scenePixels;
  return d;
}

TEST(RenderScale, HalfScaleKeepsTheFrameSizeAndASharpHudAndDrawsTheSameScene) {
  ScaledScene scene;
  std::string why;
  if (!scene.init(why)) GTEST_SKIP() << "no headless OpenGL context: " << why;
  const std::vector<uint8_t> full = scene.draw(1.f);
  EXPECT_EQ(scene.renderer().shadowMapSize(), 1024);
  const std::vector<uint8_t> half = scene.draw(0.5f);
  EXPECT_FLOAT_EQ(scene.renderer().renderScale(), 0.5f);
  EXPECT_EQ(scene.renderer().shadowMapSize(), 512);
  std::vector<uint8_t> pixels;
  int w = 0, h = 0;
  scene.renderer().readPixels(pixels, w, h);
  EXPECT_EQ(w, kWidth);
  EXPECT_EQ(h, kHeight);

  const Difference d = compare(half, full);
  // The comparison sees a real change of the scene at the same scale: the sphere removed.
  const Difference gone = compare(scene.draw(0.5f, false), half);
  std::printf("[ scale   ] 0.5 against 1: largest block difference %.1f levels, %.1f%% of the scene's pixels "
              "differ, HUD pixels differing %d; the sphere removed: %.1f levels\n", d.largestBlockDifference,
              100.0 * d.sceneShareDiffering, d.hudPixelsDiffering, gone.largestBlockDifference);
  EXPECT_EQ(d.hudPixelsDiffering, 0) << "the HUD is not drawn at full resolution";
  EXPECT_GT(d.sceneShareDiffering, 0.02) << "the scene was not drawn at the lower scale";
  EXPECT_LT(d.largestBlockDifference, 12.0) << "the upscaled scene is not the same picture";
  EXPECT_GT(gone.largestBlockDifference, 40.0);

  // Back to 1: the same pixels as the first frame.
  EXPECT_EQ(compare(scene.draw(1.f), full).sceneShareDiffering, 0.0);
  EXPECT_EQ(scene.renderer().shadowMapSize(), 1024);
}

TEST(RenderScale, IsClampedAndShrinksTheShadowMapToAFloor) {
  ScaledScene scene;
  std::string why;
  if (!scene.init(why)) GTEST_SKIP() << "no headless OpenGL context: " << why;
  Renderer& r = scene.renderer();
  r.setRenderScale(0.1f);
  EXPECT_FLOAT_EQ(r.renderScale(), Renderer::kMinRenderScale);
  EXPECT_EQ(r.shadowMapSize(), 256);
  r.setRenderScale(2.f);
  EXPECT_FLOAT_EQ(r.renderScale(), 1.f);
  r.setRenderScale(NAN);
  EXPECT_FLOAT_EQ(r.renderScale(), 1.f);
  r.setRenderScale(0.75f);
  EXPECT_EQ(r.shadowMapSize(), 1024);
  r.setRenderScale(0.35f);
  EXPECT_EQ(r.shadowMapSize(), 512);
  // A frame at the smallest scale still draws (the scene target is at least one pixel).
  const std::vector<uint8_t> tiny = scene.draw(0.25f);
  EXPECT_EQ(tiny.size(), size_t(kWidth) * kHeight * 4);
}

TEST(RenderScale, SoftwareRasterisersAreRecognisedByTheirGlRendererString) {
  EXPECT_TRUE(Renderer::isSoftwareRasterizer("llvmpipe (LLVM 15.0.6, 256 bits)"));
  EXPECT_TRUE(Renderer::isSoftwareRasterizer("softpipe"));
  EXPECT_TRUE(Renderer::isSoftwareRasterizer("Mesa OffScreen swrast"));
  EXPECT_TRUE(Renderer::isSoftwareRasterizer("Microsoft Basic Render Driver (Software)"));
  EXPECT_FALSE(Renderer::isSoftwareRasterizer("Mesa Intel(R) UHD Graphics 620 (KBL GT2)"));
  EXPECT_FALSE(Renderer::isSoftwareRasterizer("NVIDIA GeForce RTX 3060/PCIe/SSE2"));
  EXPECT_FALSE(Renderer::isSoftwareRasterizer("AMD Radeon RX 6600 (radeonsi, navi23, LLVM 15.0.6)"));
  EXPECT_FALSE(Renderer::isSoftwareRasterizer(""));
}


TEST(DynamicRenderScale, StepsDownWhenFramesRunLongAndUpWhenTheyAreShortWithinItsBounds) {
  DynamicRenderScale dynamic;
  EXPECT_FLOAT_EQ(dynamic.scale(), 0.5f);
  // Slow frames (25 ms of work against a 15 ms target): down by 10% a window, to the floor.
  int changes = 0;
  for (int k = 0; k < DynamicRenderScale::kWindow * 20; ++k) changes += dynamic.addFrame(25.0) ? 1 : 0;
  EXPECT_FLOAT_EQ(dynamic.scale(), 0.35f);
  EXPECT_EQ(changes, 4);  // 0.45, 0.405, 0.3645, then the floor
  // A window of frames in the band (between 65% and 100% of the target) keeps the scale.
  for (int k = 0; k < DynamicRenderScale::kWindow; ++k) EXPECT_FALSE(dynamic.addFrame(12.0));
  EXPECT_FLOAT_EQ(dynamic.scale(), 0.35f);
  // One slow frame in a window of fast ones does not move the median.
  for (int k = 0; k < DynamicRenderScale::kWindow; ++k) dynamic.addFrame(k == 3 ? 80.0 : 5.0);
  EXPECT_GT(dynamic.scale(), 0.35f);
  // Fast frames: up to the ceiling and no further.
  for (int k = 0; k < DynamicRenderScale::kWindow * 40; ++k) dynamic.addFrame(5.0);
  EXPECT_FLOAT_EQ(dynamic.scale(), 0.6f);
  // Not a number is not a frame.
  EXPECT_FALSE(dynamic.addFrame(NAN));
}

}  // namespace
}  // namespace cleave::render
