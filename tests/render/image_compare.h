// SPDX-License-Identifier: MIT
// Golden-image comparison for headless render tests: tolerance = largest allowed per-channel
// difference plus the share of pixels allowed to exceed it. On failure the actual image and a diff
// image are written next to the golden so a person can look at them.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "cleave/render/renderer.h"

namespace cleave::testing {

struct ImageTolerance {
  int maxChannelDifference = 8;   // a pixel differs when any channel differs by more than this
  double maxDifferingShare = 0.002;  // share of differing pixels allowed
};

struct ImageComparison {
  bool ok = false;
  std::string message;
  double differingShare = 1.0;
  int largestDifference = 255;
};

// The tolerance of every golden image test. Measured: the software renderer (Mesa llvmpipe)
// draws each golden frame of the replays, the arena and the fixed scene again with 0 differing
// pixels, and two renders of one scene are identical (RenderGolden.ToleranceSeesAShiftedLight...
// checks both). One level of rounding on 0.05% of the pixels is what is allowed; a light turned by
// a few degrees, a missing shadow or a removed piece each fail (the same test shows it).
inline constexpr ImageTolerance kGoldenTolerance{1, 0.0005};

// The frame just drawn, as RGBA rows top to bottom, expected to be width x height (a test failure
// otherwise, and an image of that size all the same, so callers can index it).
inline std::vector<uint8_t> readFrame(render::Renderer& renderer, int width, int height) {
  std::vector<uint8_t> rgba;
  int w = 0, h = 0;
  renderer.readPixels(rgba, w, h);
  EXPECT_EQ(w, width);
  EXPECT_EQ(h, height);
  rgba.resize(size_t(width) * size_t(height) * 4, 0);
  return rgba;
}

// Blanks the pixels of [x0, x1) x [y0, y1) (clipped to the image): text that shows wall-clock
// figures, which no two runs share.
inline void maskRect(std::vector<uint8_t>& rgba, int width, int height, int x0, int y0, int x1, int y1) {
  for (int y = std::max(0, y0); y < std::min(height, y1); ++y)
    for (int x = std::max(0, x0); x < std::min(width, x1); ++x)
      for (int c = 0; c < 4; ++c) rgba[(size_t(y) * width + x) * 4 + c] = 0;
}

// The share of pixels of `a` and `b` (RGBA rows, same size) whose colour channels differ by more
// than the tolerance's level, and the largest difference; `diff`, when given, gets an image of it.
inline ImageComparison compareImages(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, int width,
                                     int height, const ImageTolerance& tolerance,
                                     std::vector<uint8_t>* diff = nullptr) {
  ImageComparison result;
  if (diff) diff->assign(a.size(), 255);
  size_t differing = 0;
  int largest = 0;
  for (size_t p = 0; p < size_t(width) * size_t(height); ++p) {
    int worst = 0;
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(int(a[p * 4 + c]) - int(b[p * 4 + c])));
    largest = std::max(largest, worst);
    const bool differs = worst > tolerance.maxChannelDifference;
    differing += differs ? 1 : 0;
    if (diff) {
      const uint8_t v = uint8_t(std::min(255, worst * 4));
      (*diff)[p * 4 + 0] = differs ? 255 : v;
      (*diff)[p * 4 + 1] = differs ? 0 : v;
      (*diff)[p * 4 + 2] = differs ? 0 : v;
    }
  }
  result.largestDifference = largest;
  result.differingShare = double(differing) / double(size_t(width) * size_t(height));
  result.ok = result.differingShare <= tolerance.maxDifferingShare;
  return result;
}

// Compares `rgba` (rows top to bottom) with the PNG at goldenPath. When the environment variable
// CLEAVE_UPDATE_GOLDENS=1 is set, the golden is (re)written instead and the comparison passes.
inline ImageComparison compareWithGolden(const std::string& goldenPath, int width, int height,
                                         const std::vector<uint8_t>& rgba,
                                         const ImageTolerance& tolerance) {
  ImageComparison result;
  const char* update = std::getenv("CLEAVE_UPDATE_GOLDENS");
  if (update && std::string(update) == "1") {
    std::filesystem::create_directories(std::filesystem::path(goldenPath).parent_path());
    const base::Status written = render::writePng(goldenPath, width, height, rgba);
    result.ok = written.ok();
    result.message = result.ok ? "golden updated: " + goldenPath : written.message;
    return result;
  }
  int gw = 0, gh = 0;
  std::vector<uint8_t> golden;
  const std::string stem = std::filesystem::path(goldenPath).stem().string();
  const std::filesystem::path outDir = std::filesystem::path(CLEAVE_BINARY_DIR) / "test-images";
  std::filesystem::create_directories(outDir);
  const std::string actualPath = (outDir / (stem + ".actual.png")).string();
  const std::string diffPath = (outDir / (stem + ".diff.png")).string();
  if (const base::Status read = render::readPng(goldenPath, gw, gh, golden); !read.ok()) {
    render::writePng(actualPath, width, height, rgba);
    result.message = "cannot read golden " + read.message + "; actual written to " + actualPath;
    return result;
  }
  if (gw != width || gh != height) {
    render::writePng(actualPath, width, height, rgba);
    result.message = "golden is " + std::to_string(gw) + "x" + std::to_string(gh) + ", frame is " +
                     std::to_string(width) + "x" + std::to_string(height);
    return result;
  }
  std::vector<uint8_t> diff;
  result = compareImages(rgba, golden, width, height, tolerance, &diff);
  const int largest = result.largestDifference;
  if (!result.ok) {
    render::writePng(actualPath, width, height, rgba);
    render::writePng(diffPath, width, height, diff);
    result.message = std::to_string(result.differingShare * 100.0) + "% of pixels differ by more than " +
                     std::to_string(tolerance.maxChannelDifference) + " (largest " +
                     std::to_string(largest) + "); see " + actualPath + " and " + diffPath;
  }
  return result;
}

}  // namespace cleave::testing
