// SPDX-License-Identifier: MIT
#include "cleave/input/input_source.h"

#include <utility>

namespace cleave::input {

bool LiveQueue::next(uint64_t tick, InputFrame& out) {
  out.tick = tick;
  out.events = std::move(pending_);
  pending_.clear();
  return true;
}

bool ReplaySource::next(uint64_t tick, InputFrame& out) {
  out.tick = tick;
  out.events.clear();
  if (tick >= replay_.length()) {
    finished_ = true;
    return false;
  }
  const std::vector<InputFrame>& frames = replay_.frames;
  while (cursor_ < frames.size() && frames[cursor_].tick < tick) {
    ++cursor_;
    ++dropped_;
  }
  if (cursor_ < frames.size() && frames[cursor_].tick == tick) {
    out.events = frames[cursor_].events;
    ++cursor_;
  }
  return true;
}

}  // namespace cleave::input
