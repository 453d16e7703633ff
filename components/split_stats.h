// SPDX-License-Identifier: MIT
// The split figures a game shows and dumps, updated once a tick at commit (SplittingHooks::committed),
// and the split-time graph the HUDs draw against the budget line.
#pragma once

#include <cstdint>
#include <deque>

#include <glm/glm.hpp>

#include "cleave/components/split_system.h"
#include "cleave/render/renderer.h"

namespace cleave::components {

// One tick's split time on the main thread, apart: its own work (prepare and commit) and the time
// it stood waiting for workers at commit; and the compute time the workers spent on the splits that
// committed (on the main thread itself with 0 threads, then inside `work`).
struct SplitTickTimes {
  double work = 0.0, wait = 0.0, workers = 0.0;  // ms
};
SplitTickTimes splitTickTimes(const SplitSystem& splits);

struct SplitTickStats {
  static constexpr size_t kHistory = 120;  // ticks the graph shows
  uint32_t splitsThisTick = 0;
  double msThisTick = 0.0;           // main-thread split time of the last tick (prepare and commit)
  double maxMsInATick = 0.0;         // the most msThisTick has been
  double maxChargedMsInATick = 0.0;  // the most the budget charged in one tick
  SplitTickTimes times;              // msThisTick apart, and the workers' time
  double maxWorkMsInATick = 0.0;     // the most times.work has been
  double maxWaitMsInATick = 0.0;     // the most times.wait has been
  double lastSplitMs = 0.0;          // of the last split done (kept over ticks without one)
  double maxSplitMs = 0.0;           // the budget's largest single split, over the run
  uint64_t deferredTotal = 0;        // requests left waiting at the end of a tick, summed over ticks
  uint32_t maxQueue = 0;             // the longest the queue has been
  std::deque<float> history;         // msThisTick of the last kHistory ticks, oldest first

  // Takes this tick's figures from the split system and its budget.
  void record(const SplitSystem& splits);
};

// The split-time graph: `history` (ms per tick) from left to right in `rect` (x, y, width, height,
// pixels), scaled so the budget line (`budgetMs`) is at half height, as overlay lines.
void drawSplitGraph(render::Renderer& r, const std::deque<float>& history, double budgetMs, const glm::vec4& rect);

}  // namespace cleave::components
