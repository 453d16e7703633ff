// SPDX-License-Identifier: MIT
#include "cleave/components/split_stats.h"

#include <algorithm>
#include <vector>

namespace cleave::components {

SplitTickTimes splitTickTimes(const SplitSystem& splits) {
  SplitTickTimes t;
  for (const SplitEvent& ev : splits.lastEvents()) {
    t.wait += ev.times.wait;
    t.workers += ev.times.compute.total;
  }
  t.work = std::max(0.0, splits.lastTickMainMilliseconds() - t.wait);
  return t;
}

void SplitTickStats::record(const SplitSystem& splits) {
  const SplitBudgetStats& stats = splits.budget().stats();
  deferredTotal += stats.deferred;
  maxQueue = std::max(maxQueue, stats.queueLength);
  splitsThisTick = stats.executed;
  if (stats.executed > 0) lastSplitMs = stats.lastSplitMilliseconds;
  maxSplitMs = stats.maxSplitMilliseconds;
  msThisTick = splits.lastTickMainMilliseconds();
  maxMsInATick = std::max(maxMsInATick, msThisTick);
  maxChargedMsInATick = std::max(maxChargedMsInATick, stats.millisecondsCharged);
  times = splitTickTimes(splits);
  maxWorkMsInATick = std::max(maxWorkMsInATick, times.work);
  maxWaitMsInATick = std::max(maxWaitMsInATick, times.wait);
  history.push_back(float(msThisTick));
  if (history.size() > kHistory) history.pop_front();
}

void drawSplitGraph(render::Renderer& r, const std::deque<float>& history, double budgetMs, const glm::vec4& rect) {
  const float gx = rect.x, gy = rect.y, gw = rect.z, gh = rect.w;
  const float budget = float(budgetMs);
  const float scale = gh / (budget * 2.f);
  const float n = float(SplitTickStats::kHistory);
  std::vector<glm::vec2> lines;
  for (size_t i = 0; i + 1 < history.size(); ++i) {
    lines.push_back({gx + gw * float(i) / n, gy + gh - std::min(gh, history[i] * scale)});
    lines.push_back({gx + gw * float(i + 1) / n, gy + gh - std::min(gh, history[i + 1] * scale)});
  }
  r.submitOverlayLines(lines, glm::vec4(0.4f, 1.f, 0.5f, 1.f));
  const glm::vec2 budgetLine[2] = {{gx, gy + gh - budget * scale}, {gx + gw, gy + gh - budget * scale}};
  r.submitOverlayLines(budgetLine, glm::vec4(1.f, 0.4f, 0.3f, 1.f));
}

}  // namespace cleave::components
