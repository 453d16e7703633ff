// Golden-image comparison for headless render tests: tolerance = largest allowed per-channel
// difference plus the share of pixels allowed to exceed it. On failure the actual image and a diff
// image are written next to the golden so a person can look at them.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/render/renderer.h"

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

// Compares `rgba` (rows top to bottom) with the PNG at goldenPath. When the environment variable
// CLEAVE_UPDATE_GOLDENS=1 is set, the golden is (re)written instead and the comparison passes.
inline ImageComparison compareWithGolden(const std::string& goldenPath, int width, int height,
                                         const std::vector<uint8_t>& rgba,
                                         const ImageTolerance& tolerance) {
  ImageComparison result;
  const char* update = std::getenv("CLEAVE_UPDATE_GOLDENS");
  if (update && std::string(update) == "1") {
    std::filesystem::create_directories(std::filesystem::path(goldenPath).parent_path());
    std::string error;
    result.ok = render::writePng(goldenPath, width, height, rgba, &error);
    result.message = result.ok ? "golden updated: " + goldenPath : error;
    return result;
  }
  int gw = 0, gh = 0;
  std::vector<uint8_t> golden;
  std::string error;
  const std::string stem = std::filesystem::path(goldenPath).stem().string();
  const std::filesystem::path outDir = std::filesystem::path(CLEAVE_BINARY_DIR) / "test-images";
  std::filesystem::create_directories(outDir);
  const std::string actualPath = (outDir / (stem + ".actual.png")).string();
  const std::string diffPath = (outDir / (stem + ".diff.png")).string();
  if (!render::readPng(goldenPath, gw, gh, golden, &error)) {
    render::writePng(actualPath, width, height, rgba);
    result.message = "cannot read golden " + error + "; actual written to " + actualPath;
    return result;
  }
  if (gw != width || gh != height) {
    render::writePng(actualPath, width, height, rgba);
    result.message = "golden is " + std::to_string(gw) + "x" + std::to_string(gh) + ", frame is " +
                     std::to_string(width) + "x" + std::to_string(height);
    return result;
  }
  std::vector<uint8_t> diff(rgba.size(), 255);
  size_t differing = 0;
  int largest = 0;
  for (size_t p = 0; p < size_t(width) * size_t(height); ++p) {
    int worst = 0;
    for (int c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(int(rgba[p * 4 + c]) - int(golden[p * 4 + c])));
    largest = std::max(largest, worst);
    const bool differs = worst > tolerance.maxChannelDifference;
    differing += differs ? 1 : 0;
    const uint8_t v = uint8_t(std::min(255, worst * 4));
    diff[p * 4 + 0] = differs ? 255 : v;
    diff[p * 4 + 1] = differs ? 0 : v;
    diff[p * 4 + 2] = differs ? 0 : v;
  }
  result.largestDifference = largest;
  result.differingShare = double(differing) / double(size_t(width) * size_t(height));
  result.ok = result.differingShare <= tolerance.maxDifferingShare;
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
