// SPDX-License-Identifier: MIT
// The in-game inspector of the demo and the arena (F1, or --inspector at start): a Dear ImGui
// window over the game showing, and editing, the Splitable of the object under the crosshair (cap
// UV mode and scale, collider mode, density, split impulse, islands, hollow), the split budget's
// settings, the frame and tick times, the piece count, the split-time graph against the budget
// line and the split log as a table. Edits go through components/live_tuning.h and apply from the
// next split (budget: the next tick). They are not recorded in replays.
//
// Built without Dear ImGui (no libimgui-dev at configure time), toggle() says so and nothing opens.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>

#include "cleave/components/live_tuning.h"
#include "cleave/components/split_log.h"
#include "cleave/components/split_system.h"
#include "cleave/app/app.h"

namespace cleave::inspector {

// What the game shows in the inspector this frame.
struct InspectorFeed {
  ecs::World& world;
  components::SplitSystem& splits;
  const components::SplitLog& log;
  const std::deque<float>& splitMsHistory;  // main-thread split ms per tick, oldest first
  ecs::Entity target;                        // the splitable under the crosshair (null: none)
  uint32_t pieces = 0;                       // pieces in the world
};

class Inspector {
 public:
  // F1: opens or closes the inspector (the app's UI). Returns what to tell the player when it
  // cannot open (the reason: not built, or the UI could not start); empty otherwise.
  std::string toggle(app::App& app);
  // Opens it (--inspector). Unavailable with the reason when it cannot.
  base::Status open(app::App& app);
  void close(app::App& app);
  bool isOpen() const { return open_; }

  // The window, with ImGui calls: call it from the App::setUi callback.
  void draw(app::TickContext& c, const InspectorFeed& feed);

  // Pixel rectangles (x, y, w, h) of what follows the wall clock as of the last draw: the frame and
  // tick times, the split-time graph and the milliseconds column of the log. Golden tests blank them.
  const std::vector<glm::vec4>& clockRects() const { return clockRects_; }
  // {"open", "target" (name of the object shown, "" for none), "settings" of it (cap_uv_mode,
  // cap_uv_per_metre, collider, density, split_impulse, islands, hollow; null for none), "window"
  // rect, "clock" rects}.
  void writeJson(nlohmann::json& out) const;

 private:
  void drawTarget(const InspectorFeed& feed);
  void drawBudget(const InspectorFeed& feed);
  void drawPieceBudget(const InspectorFeed& feed);
  void drawTiming(app::TickContext& c, const InspectorFeed& feed);
  void drawGraph(const InspectorFeed& feed);
  void drawLog(const InspectorFeed& feed);
  void markClock();  // the last ImGui item is wall-clock

  bool open_ = false;
  std::string targetName_;
  std::optional<components::SplitableTuning> targetTuning_;  // as the last draw left it
  std::string lastError_;  // of the last edit that was refused
  std::vector<glm::vec4> clockRects_;
  glm::vec4 window_{0.f};
};

}  // namespace cleave::inspector
