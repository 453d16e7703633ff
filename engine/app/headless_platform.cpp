// SPDX-License-Identifier: MIT
#include <chrono>

#include "cleave/app/platform.h"
#include "cleave/render/gl_context.h"

namespace cleave::app {

namespace {

class HeadlessPlatform final : public Platform {
 public:
  HeadlessPlatform(std::unique_ptr<render::HeadlessGlContext> context, int width, int height)
      : context_(std::move(context)), size_(width, height),
        start_(std::chrono::steady_clock::now()) {}

  bool headless() const override { return true; }
  const char* backendName() const override { return context_->apiName(); }
  glm::ivec2 frameSize() const override { return size_; }
  void pollEvents(const std::function<void(const input::InputEvent&)>&) override {}
  bool closeRequested() const override { return false; }
  void present(const std::function<void(int, int)>&) override {}
  void setCursorMode(CursorMode) override {}
  void setTitle(const std::string&) override {}
  void setVsync(bool) override {}
  double timeSeconds() const override {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::unique_ptr<render::HeadlessGlContext> context_;
  glm::ivec2 size_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace

base::Expected<std::unique_ptr<Platform>> createHeadlessPlatform(int width, int height) {
  auto context = render::HeadlessGlContext::create(render::HeadlessApi::Auto);
  if (!context.ok()) return context.status();
  return std::unique_ptr<Platform>(std::make_unique<HeadlessPlatform>(std::move(context).value(), width, height));
}

}  // namespace cleave::app
