// SPDX-License-Identifier: MIT
#include "cleave/render/ui_renderer.h"

#include "cleave/render/renderer.h"

#if CLEAVE_HAVE_IMGUI
#include <imgui.h>
#include <imgui_impl_opengl3.h>
#endif

namespace cleave::render {

bool UiRenderer::built() { return CLEAVE_HAVE_IMGUI != 0; }

#if CLEAVE_HAVE_IMGUI

UiRenderer::~UiRenderer() {
  if (started_ && ImGui::GetCurrentContext()) ImGui_ImplOpenGL3_Shutdown();
}

base::Status UiRenderer::init() {
  if (started_) return {};
  if (!ImGui::GetCurrentContext())
    return base::Status::failure(base::StatusCode::Unavailable, "ui renderer: no Dear ImGui context");
  // The GLSL of the engine's own shaders (OpenGL 3.3 core).
  if (!ImGui_ImplOpenGL3_Init("#version 330 core")) {
    return base::Status::failure(base::StatusCode::Unavailable,
                                 "ui renderer: the Dear ImGui OpenGL 3 backend could not start");
  }
  started_ = true;
  return {};
}

void UiRenderer::newFrame() {
  if (started_) ImGui_ImplOpenGL3_NewFrame();
}

void UiRenderer::draw(Renderer& renderer) {
  if (!started_) return;
  ImDrawData* data = ImGui::GetDrawData();
  if (!data || data->CmdListsCount == 0) return;
  renderer.bindFrame();
  // The backend saves and restores the GL state it changes, so the next frame starts as before.
  ImGui_ImplOpenGL3_RenderDrawData(data);
}

#else

UiRenderer::~UiRenderer() = default;

base::Status UiRenderer::init() {
  return base::Status::failure(base::StatusCode::Unavailable,
                               "the inspector is not built (it needs Dear ImGui, libimgui-dev, at configure time)");
}

void UiRenderer::newFrame() {}
void UiRenderer::draw(Renderer&) {}

#endif

}  // namespace cleave::render
