// SPDX-License-Identifier: MIT
// Where the events of each tick come from: the live window, or a replay.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "cleave/input/input_event.h"
#include "cleave/input/replay.h"

namespace cleave::input {

class InputSource {
 public:
  virtual ~InputSource() = default;
  // Fills `out` with the events of `tick` (out.tick = tick; out.events may be empty). Returns
  // false, with no events, once the source has nothing more to give (a replay past its length).
  // Ticks are asked for in non-decreasing order.
  virtual bool next(uint64_t tick, InputFrame& out) = 0;
};

// Events pushed by the window layer (GLFW callbacks) between ticks, handed out by the next tick.
// Single-threaded: push and next are called from the thread that polls the window. Never finishes.
class LiveQueue final : public InputSource {
 public:
  void push(const InputEvent& event) { pending_.push_back(event); }
  size_t pending() const { return pending_.size(); }
  // Drains all pushed events into `out`, in push order. Always returns true.
  bool next(uint64_t tick, InputFrame& out) override;

 private:
  std::vector<InputEvent> pending_;
};

// Plays back a parsed replay.
class ReplaySource final : public InputSource {
 public:
  explicit ReplaySource(Replay replay) : replay_(std::move(replay)) {}

  // Events recorded for `tick`; false once tick >= length() (the replay is finished). Frames of
  // ticks that were skipped over are dropped and counted in droppedFrames(); asking for the same
  // tick twice gives its events only the first time.
  bool next(uint64_t tick, InputFrame& out) override;

  bool finished() const { return finished_; }  // next() has returned false
  uint64_t length() const { return replay_.length(); }
  const Replay& replay() const { return replay_; }
  size_t droppedFrames() const { return dropped_; }

 private:
  Replay replay_;
  size_t cursor_ = 0;
  size_t dropped_ = 0;
  bool finished_ = false;
};

}  // namespace cleave::input
