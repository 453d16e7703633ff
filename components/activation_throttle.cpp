// SPDX-License-Identifier: MIT
// Waking split pieces a few per tick (activation_throttle.h).
#include "cleave/components/activation_throttle.h"

#include <algorithm>

namespace cleave::components {

std::vector<physics::BodyId> ActivationThrottle::beginTick(uint32_t maxPerTick) {
  const size_t n = std::min<size_t>(queued_.size(), maxPerTick);
  std::vector<physics::BodyId> woken(queued_.begin(), queued_.begin() + ptrdiff_t(n));
  queued_.erase(queued_.begin(), queued_.begin() + ptrdiff_t(n));
  usedThisTick_ = uint32_t(n);
  return woken;
}

bool ActivationThrottle::admitAwake(uint32_t maxPerTick) {
  if (usedThisTick_ >= maxPerTick) return false;
  ++usedThisTick_;
  return true;
}

void ActivationThrottle::clear() {
  queued_.clear();
  usedThisTick_ = 0;
}

}  // namespace cleave::components
