// SPDX-License-Identifier: MIT
// Draws the current Dear ImGui frame (ImGui::GetDrawData after ImGui::Render) on top of the
// renderer's last frame, through the OpenGL 3 backend that ships with libimgui-dev. The backend
// takes its GL entry points from the engine's loader, so it draws in a window and on the headless
// EGL and OSMesa contexts alike.
//
// Needs a current GL 3.3 core context and a current ImGui context (made by app::UiLayer). Built
// without Dear ImGui (CMake found no libimgui-dev), init() fails with that reason and nothing draws.
#pragma once

#include <string>

#include "cleave/base/status.h"

namespace cleave::render {

class Renderer;

class UiRenderer {
 public:
  UiRenderer() = default;
  ~UiRenderer();  // frees the backend's GL objects (the GL context must still be current)
  UiRenderer(const UiRenderer&) = delete;
  UiRenderer& operator=(const UiRenderer&) = delete;

  // True when the engine was built with Dear ImGui.
  static bool built();
  // Creates the backend's shader, buffers and font texture for the current ImGui context.
  // Unavailable, with the reason, when ImGui is not built in or the GL objects cannot be made.
  base::Status init();
  // Before each ImGui::NewFrame: makes the shader, buffers and font texture the first time.
  void newFrame();
  // Draws the ImGui draw data of the frame just ended (ImGui::Render) into `renderer`'s frame.
  void draw(Renderer& renderer);

 private:
  bool started_ = false;
};

}  // namespace cleave::render
