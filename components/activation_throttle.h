// SPDX-License-Identifier: MIT
// ActivationThrottle: bodies made by splits are woken at most `maxPerTick` per tick, so that a burst
// of pieces (a shatter, a blade through a heap) does not wake the whole solver at once. A piece's
// body starts awake while the tick has room (admitAwake), otherwise it is made asleep and queued;
// each tick starts by waking the oldest queued bodies, up to the limit, and those count against the
// tick's room. Deterministic: creation order, no clock.
//
// Threads: the main thread only. A queued body destroyed meanwhile comes back as a stale handle,
// which PhysicsWorld::activate ignores.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "cleave/physics/physics_ids.h"

namespace cleave::components {

class ActivationThrottle {
 public:
  // Starts a tick: returns the oldest queued bodies, at most `maxPerTick`, to be woken now (they
  // take the tick's room first).
  std::vector<physics::BodyId> beginTick(uint32_t maxPerTick);
  // A body made this tick may start awake (and takes room), or must start asleep and be queued.
  bool admitAwake(uint32_t maxPerTick);
  void queue(physics::BodyId body) { queued_.push_back(body); }
  size_t queued() const { return queued_.size(); }
  void clear();

 private:
  std::vector<physics::BodyId> queued_;  // creation order
  uint32_t usedThisTick_ = 0;
};

}  // namespace cleave::components
