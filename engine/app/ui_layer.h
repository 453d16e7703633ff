// SPDX-License-Identifier: MIT
// The in-game UI layer: a Dear ImGui context (libimgui-dev), started on first use, fed and drawn
// once per rendered frame on top of the HUD. The games' inspector (F1) is built on it.
//
// Input and time: in a window the GLFW backend of libimgui-dev reads the window (size, clock,
// mouse, keys, text), chained before the engine's own callbacks; headless there is no input, and
// the display size and the time come from the app (the frame size, the fixed ticks). Headless
// frames are drawn only on screenshot ticks, so each one is laid out twice (ImGui sizes windows
// and table columns from the frame before) and the picture is the same on every run.
//
// No imgui.ini is read or written: a run's windows start where the code puts them.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "cleave/app/platform.h"
#include "cleave/base/status.h"
#include "cleave/render/ui_renderer.h"

struct ImGuiContext;

namespace cleave::render {
class Renderer;
}

namespace cleave::app {

class UiLayer {
 public:
  UiLayer() = default;
  ~UiLayer();  // before the platform and the GL context go
  UiLayer(const UiLayer&) = delete;
  UiLayer& operator=(const UiLayer&) = delete;

  // True when the engine was built with Dear ImGui.
  static bool built();
  // Creates the context (font and sizes scaled to the frame: 1 up to 1439 lines, 2 from 1440),
  // the GL backend and, in a window, the input backend. Unavailable with a reason when ImGui is not
  // built in or a backend cannot start; nothing is left half made then.
  base::Status start(Platform& platform, glm::ivec2 frameSize);
  bool started() const { return context_ != nullptr; }

  // One UI frame: ImGui::NewFrame, `build` (ImGui calls), ImGui::Render, drawn into the renderer's
  // frame. `seconds` is the app's clock (headless: the tick time).
  void frame(render::Renderer& renderer, glm::ivec2 frameSize, double seconds,
             const std::function<void()>& build);

  // The UI has the mouse (the pointer is over one of its windows, or it is dragging) or the
  // keyboard (a text field is active), as of the last frame: the game leaves those events alone.
  bool wantsMouse() const;
  bool wantsKeyboard() const;

  // The UI is shown again: mouse buttons pressed while it was hidden (a drag in the game) are not
  // clicks on it. Its mouse buttons read as up until every button has been released.
  void ignoreHeldButtons() { ignoreHeldButtons_ = true; }

 private:
  void newFrame(glm::ivec2 frameSize, double deltaSeconds);

  ImGuiContext* context_ = nullptr;
  Platform* platform_ = nullptr;
  bool platformInput_ = false;  // the window's input backend is attached
  std::unique_ptr<render::UiRenderer> renderer_;  // made by start
  double lastSeconds_ = -1.0;
  bool ignoreHeldButtons_ = false;
};

}  // namespace cleave::app
