// The GLFW window backend: an OpenGL 3.3 core context in a real window, with keyboard and mouse
// callbacks turned into engine input events. GLFW appears only here (and GL only in engine/render).
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstdio>

#include "engine/app/platform.h"
#include "engine/input/glfw_keys.h"
#include "engine/render/gl_context.h"

namespace cleave::app {

namespace {

class WindowPlatform final : public Platform {
 public:
  explicit WindowPlatform(GLFWwindow* window) : window_(window) {
    glfwSetWindowUserPointer(window_, this);
    glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int) {
      auto* self = static_cast<WindowPlatform*>(glfwGetWindowUserPointer(w));
      if (action == GLFW_REPEAT) return;
      const input::Key k = input::keyFromGlfw(key);
      if (k == input::Key::Unknown) return;
      self->emit(action == GLFW_PRESS ? input::InputEvent::keyDown(k) : input::InputEvent::keyUp(k));
    });
    glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double x, double y) {
      auto* self = static_cast<WindowPlatform*>(glfwGetWindowUserPointer(w));
      const glm::vec2 p(float(x), float(y));
      const glm::vec2 d = self->haveCursor_ ? p - self->cursor_ : glm::vec2(0.f);
      self->cursor_ = p;
      self->haveCursor_ = true;
      self->emit(input::InputEvent::mouseMove(p, d));
    });
    glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int button, int action, int) {
      auto* self = static_cast<WindowPlatform*>(glfwGetWindowUserPointer(w));
      input::MouseButton b = input::MouseButton::Left;
      if (button == GLFW_MOUSE_BUTTON_RIGHT) b = input::MouseButton::Right;
      else if (button == GLFW_MOUSE_BUTTON_MIDDLE) b = input::MouseButton::Middle;
      else if (button != GLFW_MOUSE_BUTTON_LEFT) return;
      self->emit(action == GLFW_PRESS ? input::InputEvent::mouseDown(b, self->cursor_)
                                      : input::InputEvent::mouseUp(b, self->cursor_));
    });
    glfwSetScrollCallback(window_, [](GLFWwindow* w, double dx, double dy) {
      auto* self = static_cast<WindowPlatform*>(glfwGetWindowUserPointer(w));
      self->emit(input::InputEvent::scroll(glm::vec2(float(dx), float(dy))));
    });
    glfwSetFramebufferSizeCallback(window_, [](GLFWwindow* w, int width, int height) {
      auto* self = static_cast<WindowPlatform*>(glfwGetWindowUserPointer(w));
      self->emit(input::InputEvent::resize(glm::ivec2(width, height)));
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

std::unique_ptr<Platform> createWindowPlatform(int width, int height, const std::string& title,
                                               std::string* error) {
  glfwSetErrorCallback([](int code, const char* text) {
    std::fprintf(stderr, "glfw: error 0x%x: %s\n", code, text);
  });
  if (!glfwInit()) {
    if (error) *error = "GLFW could not initialise (no display?)";
    return nullptr;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  GLFWwindow* window = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window) {
    glfwTerminate();
    if (error) *error = "GLFW could not create an OpenGL 3.3 core window";
    return nullptr;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(1);
  if (!render::loadGl(reinterpret_cast<render::GlGetProcAddress>(glfwGetProcAddress), error)) {
    glfwDestroyWindow(window);
    glfwTerminate();
    return nullptr;
  }
  return std::make_unique<WindowPlatform>(window);
}

}  // namespace cleave::app
