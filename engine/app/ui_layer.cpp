// SPDX-License-Identifier: MIT
#include "cleave/app/ui_layer.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "cleave/render/renderer.h"

#if CLEAVE_HAVE_IMGUI
#include <imgui.h>
#endif

namespace cleave::app {

bool UiLayer::built() { return render::UiRenderer::built(); }

#if CLEAVE_HAVE_IMGUI

UiLayer::~UiLayer() {
  if (!context_) return;
  ImGui::SetCurrentContext(context_);
  if (platformInput_ && platform_) platform_->detachUiInput();
  renderer_.reset();  // the GL backend goes while its ImGui context is current
  ImGui::DestroyContext(context_);
}

base::Status UiLayer::start(Platform& platform, glm::ivec2 frameSize) {
  if (context_) return {};
  context_ = ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;
  io.LogFilename = nullptr;
  // A pixel font (ProggyClean, built into ImGui) stays sharp at whole multiples of its 13 px.
  const float scale = std::max(1.f, std::floor(float(frameSize.y) / 1440.f) + 1.f);
  ImFontConfig font;
  font.SizePixels = 13.f * scale;
  io.Fonts->AddFontDefault(&font);
  ImGui::StyleColorsDark();
  ImGui::GetStyle().ScaleAllSizes(scale);
  ImGui::GetStyle().WindowRounding = 0.f;
  platform_ = &platform;
  renderer_ = std::make_unique<render::UiRenderer>();
  if (base::Status started = renderer_->init(); !started.ok()) {
    renderer_.reset();
    ImGui::DestroyContext(context_);
    context_ = nullptr;
    return started;
  }
  platformInput_ = platform.attachUiInput();
  return {};
}

void UiLayer::newFrame(glm::ivec2 frameSize, double deltaSeconds) {
  ImGuiIO& io = ImGui::GetIO();
  renderer_->newFrame();
  if (platformInput_) {
    platform_->uiNewFrame();  // the window's size, clock and mouse
    if (ignoreHeldButtons_) {
      bool held = false;
      for (bool& down : io.MouseDown) held = std::exchange(down, false) || held;
      ignoreHeldButtons_ = held;
    }
  } else {
    io.DisplaySize = ImVec2(float(frameSize.x), float(frameSize.y));
    io.DisplayFramebufferScale = ImVec2(1.f, 1.f);
    io.DeltaTime = float(std::max(deltaSeconds, 1e-4));
  }
  ImGui::NewFrame();
}

void UiLayer::frame(render::Renderer& renderer, glm::ivec2 frameSize, double seconds,
                    const std::function<void()>& build) {
  if (!context_) return;
  ImGui::SetCurrentContext(context_);
  const double delta = lastSeconds_ < 0.0 ? 1.0 / 60.0 : seconds - lastSeconds_;
  lastSeconds_ = seconds;
  if (!platformInput_) {
    // The settle pass: layout from a frame before, so that this frame is complete.
    newFrame(frameSize, delta * 0.5);
    build();
    ImGui::EndFrame();
  }
  newFrame(frameSize, platformInput_ ? delta : delta * 0.5);
  build();
  ImGui::Render();
  renderer_->draw(renderer);
}

bool UiLayer::wantsMouse() const { return context_ && ImGui::GetIO().WantCaptureMouse; }
bool UiLayer::wantsKeyboard() const { return context_ && ImGui::GetIO().WantCaptureKeyboard; }

#else

UiLayer::~UiLayer() = default;

base::Status UiLayer::start(Platform&, glm::ivec2) {
  return render::UiRenderer().init();  // fails with the reason: not built
}

void UiLayer::newFrame(glm::ivec2, double) {}
void UiLayer::frame(render::Renderer&, glm::ivec2, double, const std::function<void()>&) {}
bool UiLayer::wantsMouse() const { return false; }
bool UiLayer::wantsKeyboard() const { return false; }

#endif

}  // namespace cleave::app
