// SPDX-License-Identifier: MIT
// Where frames go and live input comes from: a real window (GLFW, OpenGL 3.3 core) or a headless
// offscreen context (EGL surfaceless on Mesa, OSMesa as fallback). Both give the renderer a current
// GL context; only the window delivers live input and shows frames.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "cleave/base/status.h"
#include "cleave/input/input_event.h"

namespace cleave::app {

enum class CursorMode { Normal, Captured };

class Platform {
 public:
  virtual ~Platform() = default;
  virtual bool headless() const = 0;
  virtual const char* backendName() const = 0;
  // Pixel size of the frames to render.
  virtual glm::ivec2 frameSize() const = 0;
  // Window: pumps the OS events and hands each input event to `sink`. Headless: nothing.
  virtual void pollEvents(const std::function<void(const input::InputEvent&)>& sink) = 0;
  // True once the user closed the window (never for headless).
  virtual bool closeRequested() const = 0;
  // Window: blit the rendered frame and swap. Headless: nothing.
  virtual void present(const std::function<void(int width, int height)>& blit) = 0;
  virtual void setCursorMode(CursorMode mode) = 0;
  virtual void setTitle(const std::string& title) = 0;
  // Window: wait for the display's refresh at each swap (on, the default) or not. Headless: nothing.
  virtual void setVsync(bool on) = 0;
  // Seconds since the platform started (monotonic).
  virtual double timeSeconds() const = 0;

  // Dear ImGui input (app/ui_layer.h), with the current ImGui context. Window: attaches the GLFW
  // backend of libimgui-dev (its callbacks run before the engine's, which still get every event)
  // and returns true; uiNewFrame gives ImGui the window's size, clock and mouse; detach restores the
  // callbacks. Headless (and built without ImGui): no input, false.
  virtual bool attachUiInput() { return false; }
  virtual void uiNewFrame() {}
  virtual void detachUiInput() {}
};

// A GLFW window with an OpenGL 3.3 core context, loaded for the renderer. Unavailable with a reason
// when no display is available or the context cannot be created.
base::Expected<std::unique_ptr<Platform>> createWindowPlatform(int width, int height, const std::string& title);
// An offscreen GL context of the given frame size.
base::Expected<std::unique_ptr<Platform>> createHeadlessPlatform(int width, int height);

}  // namespace cleave::app
