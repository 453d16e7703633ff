// SPDX-License-Identifier: MIT
// The GLFW window backend: an OpenGL 3.3 core context in a real window, with keyboard and mouse
// callbacks turned into engine input events. GLFW appears only here (and GL only in engine/render).
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdio>
#include <optional>

#include "cleave/app/platform.h"
#include "cleave/input/key.h"
#include "cleave/log/log.h"
#include "cleave/render/gl_context.h"

#if CLEAVE_HAVE_IMGUI
#include <imgui_impl_glfw.h>
#endif

namespace cleave::app {

namespace {

// GLFW key code -> engine key; nullopt for keys the engine does not name.
std::optional<input::Key> keyFromGlfw(int key) {
  using input::Key;
  if (key >= GLFW_KEY_A && key <= GLFW_KEY_Z) return Key(int(Key::A) + (key - GLFW_KEY_A));
  if (key >= GLFW_KEY_0 && key <= GLFW_KEY_9) return Key(int(Key::Num0) + (key - GLFW_KEY_0));
  if (key >= GLFW_KEY_F1 && key <= GLFW_KEY_F12) return Key(int(Key::F1) + (key - GLFW_KEY_F1));
  switch (key) {
    case GLFW_KEY_SPACE: return Key::Space;
    case GLFW_KEY_ESCAPE: return Key::Escape;
    case GLFW_KEY_ENTER: return Key::Enter;
    case GLFW_KEY_TAB: return Key::Tab;
    case GLFW_KEY_BACKSPACE: return Key::Backspace;
    case GLFW_KEY_INSERT: return Key::Insert;
    case GLFW_KEY_DELETE: return Key::Delete;
    case GLFW_KEY_RIGHT: return Key::Right;
    case GLFW_KEY_LEFT: return Key::Left;
    case GLFW_KEY_DOWN: return Key::Down;
    case GLFW_KEY_UP: return Key::Up;
    case GLFW_KEY_PAGE_UP: return Key::PageUp;
    case GLFW_KEY_PAGE_DOWN: return Key::PageDown;
    case GLFW_KEY_HOME: return Key::Home;
    case GLFW_KEY_END: return Key::End;
    case GLFW_KEY_LEFT_SHIFT: return Key::LeftShift;
    case GLFW_KEY_LEFT_CONTROL: return Key::LeftControl;
    case GLFW_KEY_LEFT_ALT: return Key::LeftAlt;
    case GLFW_KEY_RIGHT_SHIFT: return Key::RightShift;
    case GLFW_KEY_RIGHT_CONTROL: return Key::RightControl;
    case GLFW_KEY_RIGHT_ALT: return Key::RightAlt;
    case GLFW_KEY_MINUS: return Key::Minus;
    case GLFW_KEY_EQUAL: return Key::Equal;
    case GLFW_KEY_COMMA: return Key::Comma;
    case GLFW_KEY_PERIOD: return Key::Period;
    case GLFW_KEY_SLASH: return Key::Slash;
    case GLFW_KEY_SEMICOLON: return Key::Semicolon;
    case GLFW_KEY_APOSTROPHE: return Key::Apostrophe;
    case GLFW_KEY_LEFT_BRACKET: return Key::LeftBracket;
    case GLFW_KEY_RIGHT_BRACKET: return Key::RightBracket;
    case GLFW_KEY_BACKSLASH: return Key::Backslash;
    case GLFW_KEY_GRAVE_ACCENT: return Key::GraveAccent;
    case GLFW_KEY_CAPS_LOCK: return Key::CapsLock;
    default: return std::nullopt;
  }
}

class WindowPlatform final : public Platform {
 public:
  explicit WindowPlatform(GLFWwindow* window) : window_(window) {
    glfwSetWindowUserPointer(window_, this);
    glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int) {
      auto* self = static_cast<WindowPlatform*>(glfwGetWindowUserPointer(w));
      if (action == GLFW_REPEAT) return;
      const std::optional<input::Key> k = keyFromGlfw(key);
      if (!k) return;
      if (action == GLFW_PRESS) {
        self->emit(input::KeyDown{*k});
      } else {
        self->emit(input::KeyUp{*k});
      }
    });
    glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double x, double y) {
      auto* self = static_cast<WindowPlatform*>(glfwGetWindowUserPointer(w));
      const glm::vec2 p{static_cast<float>(x), static_cast<float>(y)};
      const glm::vec2 d = self->haveCursor_ ? p - self->cursor_ : glm::vec2(0.f);
      self->cursor_ = p;
      self->haveCursor_ = true;
      self->emit(input::MouseMove{p.x, p.y, d.x, d.y});
    });
    glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int button, int action, int) {
      auto* self = static_cast<WindowPlatform*>(glfwGetWindowUserPointer(w));
      input::MouseButton b = input::MouseButton::Left;
      if (button == GLFW_MOUSE_BUTTON_RIGHT) b = input::MouseButton::Right;
      else if (button == GLFW_MOUSE_BUTTON_MIDDLE) b = input::MouseButton::Middle;
      else if (button != GLFW_MOUSE_BUTTON_LEFT) return;
      if (action == GLFW_PRESS) {
        self->emit(input::MouseDown{b, self->cursor_.x, self->cursor_.y});
      } else {
        self->emit(input::MouseUp{b, self->cursor_.x, self->cursor_.y});
      }
    });
    glfwSetScrollCallback(window_, [](GLFWwindow* w, double dx, double dy) {
      auto* self = static_cast<WindowPlatform*>(glfwGetWindowUserPointer(w));
      self->emit(input::Scroll{float(dx), float(dy)});
    });
    glfwSetFramebufferSizeCallback(window_, [](GLFWwindow* w, int width, int height) {
      auto* self = static_cast<WindowPlatform*>(glfwGetWindowUserPointer(w));
      self->emit(input::Resize{width, height});
    });
  }

  ~WindowPlatform() override {
    glfwDestroyWindow(window_);
    glfwTerminate();
  }

  bool headless() const override { return false; }
  const char* backendName() const override { return "glfw"; }
  glm::ivec2 frameSize() const override {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return {std::max(w, 1), std::max(h, 1)};
  }
  void pollEvents(const std::function<void(const input::InputEvent&)>& sink) override {
    sink_ = &sink;
    glfwPollEvents();
    sink_ = nullptr;
  }
  bool closeRequested() const override { return glfwWindowShouldClose(window_); }
  void present(const std::function<void(int, int)>& blit) override {
    const glm::ivec2 size = frameSize();
    blit(size.x, size.y);
    glfwSwapBuffers(window_);
  }
  void setCursorMode(CursorMode mode) override {
    glfwSetInputMode(window_, GLFW_CURSOR,
                     mode == CursorMode::Captured ? GLFW_CURSOR_DISABLED : GLFW_CURSOR_NORMAL);
    haveCursor_ = false;
  }
  void setTitle(const std::string& title) override { glfwSetWindowTitle(window_, title.c_str()); }
  double timeSeconds() const override { return glfwGetTime(); }
  void setVsync(bool on) override { glfwSwapInterval(on ? 1 : 0); }
#if CLEAVE_HAVE_IMGUI
  bool attachUiInput() override { return ImGui_ImplGlfw_InitForOpenGL(window_, true); }
  void uiNewFrame() override { ImGui_ImplGlfw_NewFrame(); }
  void detachUiInput() override { ImGui_ImplGlfw_Shutdown(); }
#endif

 private:
  void emit(const input::InputEvent& e) {
    if (sink_) (*sink_)(e);
  }

  GLFWwindow* window_;
  const std::function<void(const input::InputEvent&)>* sink_ = nullptr;
  glm::vec2 cursor_{0.f};
  bool haveCursor_ = false;
};

}  // namespace

base::Expected<std::unique_ptr<Platform>> createWindowPlatform(int width, int height, const std::string& title) {
  using Result = base::Expected<std::unique_ptr<Platform>>;
  glfwSetErrorCallback([](int code, const char* text) {
    log::warning("glfw", "error 0x%x: %s", code, text);
  });
  if (!glfwInit()) return Result::failure(base::StatusCode::Unavailable, "GLFW could not initialise (no display?)");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  GLFWwindow* window = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window) {
    glfwTerminate();
    return Result::failure(base::StatusCode::Unavailable, "GLFW could not create an OpenGL 3.3 core window");
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(1);
  const base::Status gl = render::loadGl(reinterpret_cast<render::GlGetProcAddress>(glfwGetProcAddress));
  if (!gl.ok()) {
    glfwDestroyWindow(window);
    glfwTerminate();
    return gl;
  }
  return std::unique_ptr<Platform>(std::make_unique<WindowPlatform>(window));
}

}  // namespace cleave::app
