// SPDX-License-Identifier: MIT
// The engine loop: fixed 60 Hz ticks run as phases of registered systems, on a window or headless
// platform, with input from the live window or a replay, optional recording, screenshots, a state
// hash and a JSON-lines state dump.
//
// Window: ticks follow the wall clock (at most a few catch-up ticks per frame), one frame is rendered
// per loop. Headless: ticks run as fast as they can and a frame is rendered only on ticks that write a
// screenshot, so long replays stay cheap.
#pragma once

#include <array>
#include <cstdint>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>

#include "cleave/app/app_options.h"
#include "cleave/app/phase.h"
#include "cleave/app/platform.h"
#include "cleave/app/ui_layer.h"
#include "cleave/base/status.h"
#include "cleave/ecs/world.h"
#include "cleave/input/input_state.h"
#include "cleave/input/input_source.h"
#include "cleave/input/replay.h"
#include "cleave/render/dynamic_scale.h"
#include "cleave/render/renderer.h"

namespace cleave::app {

class App;

struct TickContext {
  App& app;
  uint64_t tick = 0;             // index of the current tick, from 0
  double dt = kTickSeconds;      // fixed
  ecs::World& world;
  const input::InputState& input;
  render::Renderer& renderer;
  Platform& platform;
  glm::ivec2 frameSize{0};
  bool rendering = false;        // this tick produces a frame (Render phase runs)
};

using System = std::function<void(TickContext&)>;

// Adds fields to an entity's line in the state dump (mass, velocity, split parent, ...).
using StateDumpExtension = std::function<void(ecs::Entity, nlohmann::json&)>;
// Adds fields to a whole line of the state dump (split log, budget stats, ...).
using FrameDumpExtension = std::function<void(nlohmann::json&)>;

class App {
 public:
  App();
  ~App();
  App(const App&) = delete;
  App& operator=(const App&) = delete;

  // Creates the platform (window unless options.headless; falls back to headless if no display is
  // available), the renderer, the input source (replay or live) and the recorder. Errors name the
  // file and reason (a corrupt replay, an unwritable record file).
  base::Status init(const AppOptions& options, const std::string& title);

  void addSystem(Phase phase, std::string name, System system);
  void setStateDumpExtension(StateDumpExtension extension);
  void setFrameDumpExtension(FrameDumpExtension extension);
  // Runs until the replay or --ticks ends (headless) or the window closes. Returns the exit code.
  int run();
  void requestQuit() { quit_ = true; }

  // The in-game UI (Dear ImGui, app/ui_layer.h; the games' inspector). `build` makes its windows
  // with ImGui calls once per rendered frame while the UI is open, after the Render systems, and
  // the UI is drawn over the HUD. While it is open in a window, mouse presses and scrolls over it
  // (and keys while one of its text fields is active; F1-F12 always pass) go to it, not to the
  // game: they are neither seen by the game nor recorded. What the UI changes is not recorded.
  void setUi(std::function<void(TickContext&)> build);
  // Opens (starting ImGui on first use) or closes the UI. Unavailable with a reason when it cannot
  // open: the engine was built without Dear ImGui, or its GL backend did not start.
  base::Status setUiOpen(bool open);
  bool uiOpen() const { return uiOpen_; }
  static bool uiBuilt() { return UiLayer::built(); }

  ecs::World& world() { return world_; }
  render::Renderer& renderer() { return *renderer_; }
  Platform& platform() { return *platform_; }
  const AppOptions& options() const { return options_; }
  const input::InputState& input() const { return inputState_; }
  uint64_t tick() const { return tick_; }
  // Milliseconds the last tick spent in each phase, and the last frame's wall time.
  const std::array<double, size_t(Phase::Count)>& phaseMilliseconds() const { return phaseMs_; }
  double lastTickMilliseconds() const { return lastTickMs_; }
  double framesPerSecond() const { return fps_; }
  // Ticks per second of wall time, over the last half second: 60 in a window that keeps up, as
  // fast as the ticks run headless.
  double ticksPerSecond() const { return tps_ > 0.0 ? tps_ : tpsProvisional_; }
  bool headless() const { return platform_ && platform_->headless(); }
  // Paths of the screenshots written so far.
  const std::vector<std::string>& screenshots() const { return screenshots_; }

  // FNV-1a over every entity with a Transform, in ascending entity order: index, generation,
  // position and rotation bits. Equal hashes mean equal states, bit for bit.
  uint64_t stateHash() const;
  // Takes a screenshot of the last rendered frame into `path`.
  base::Status writeScreenshot(const std::string& path);

 private:
  bool runTick(bool render);
  void renderFrame(TickContext& context);
  void dumpState();
  int64_t totalTicks() const;
  void applyRenderScale();
  void countTickRate();
  void runWindowLoop();
  bool uiTakes(const input::InputEvent& event) const;

  AppOptions options_;
  std::unique_ptr<Platform> platform_;
  std::unique_ptr<render::Renderer> renderer_;
  std::unique_ptr<UiLayer> ui_;  // made when the UI first opens
  std::function<void(TickContext&)> uiBuild_;
  bool uiOpen_ = false;
  ecs::World world_;
  input::InputState inputState_;
  std::unique_ptr<input::ReplaySource> replay_;
  input::LiveQueue liveQueue_;
  std::unique_ptr<input::ReplayRecorder> recorder_;
  std::array<std::vector<std::pair<std::string, System>>, size_t(Phase::Count)> systems_;
  StateDumpExtension dumpExtension_;
  FrameDumpExtension frameDumpExtension_;
  std::unique_ptr<std::ofstream> dumpFile_;
  std::vector<std::string> screenshots_;
  std::vector<double> frameMs_;  // window runs: milliseconds between presented frames
  std::array<double, size_t(Phase::Count)> phaseMs_{};
  double lastTickMs_ = 0.0;
  double fps_ = 0.0;
  std::optional<render::DynamicRenderScale> dynamicScale_;  // auto scale on a software rasteriser
  double tps_ = 0.0;
  double tpsProvisional_ = 0.0;
  double tpsWindowStart_ = -1.0;  // wall-clock ms where the current tick-rate window began
  int tpsTicks_ = 0;
  uint64_t tick_ = 0;
  bool quit_ = false;
  bool framePending_ = false;
};

}  // namespace cleave::app
