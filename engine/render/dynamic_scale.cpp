// SPDX-License-Identifier: MIT
#include "cleave/render/dynamic_scale.h"

#include <algorithm>
#include <cmath>

namespace cleave::render {

DynamicRenderScale::DynamicRenderScale(const DynamicScaleSettings& settings)
    : settings_(settings), scale_(std::clamp(settings.startScale, settings.minScale, settings.maxScale)) {}

bool DynamicRenderScale::addFrame(double workMs) {
  if (!std::isfinite(workMs)) return false;
  frames_[size_t(count_++)] = workMs;
  if (count_ < kWindow) return false;
  count_ = 0;
  std::array<double, kWindow> sorted = frames_;
  std::nth_element(sorted.begin(), sorted.begin() + kWindow / 2, sorted.end());
  const double median = sorted[kWindow / 2];
  float next = scale_;
  if (median > settings_.targetMs) {
    next = std::max(settings_.minScale, scale_ * settings_.lowerFactor);
  } else if (median < settings_.targetMs * settings_.raiseBelow) {
    next = std::min(settings_.maxScale, scale_ * settings_.raiseFactor);
  }
  const bool changed = next != scale_;
  scale_ = next;
  return changed;
}

}  // namespace cleave::render
