// SPDX-License-Identifier: MIT
// Dynamic render scale: the render scale a window uses on a software rasteriser, chosen from the
// time its frames take. Plain arithmetic, no GL: the app feeds it each frame's work time (ticks,
// drawing and the swap, not the wait for the next tick) and applies the scale it returns.
#pragma once

#include <array>

namespace cleave::render {

struct DynamicScaleSettings {
  float minScale = 0.35f;
  float maxScale = 0.6f;
  float startScale = 0.5f;
  double targetMs = 15.0;     // the work a frame may take: under the 16.7 ms of a 60 Hz tick
  double raiseBelow = 0.65;   // raise the scale when the median is below this share of the target
  float lowerFactor = 0.9f;   // per step down (median above the target)
  float raiseFactor = 1.05f;  // per step up
};

class DynamicRenderScale {
 public:
  static constexpr int kWindow = 15;  // frames per decision

  explicit DynamicRenderScale(const DynamicScaleSettings& settings = {});
  float scale() const { return scale_; }
  // Counts one frame's work in milliseconds; every kWindow frames compares their median with the
  // target and steps the scale (clamped to [minScale, maxScale]). True when the scale changed.
  bool addFrame(double workMs);

 private:
  DynamicScaleSettings settings_;
  float scale_;
  std::array<double, kWindow> frames_{};
  int count_ = 0;
};

}  // namespace cleave::render
