// SPDX-License-Identifier: MIT
// The start of every rendering test: a headless OpenGL context and a renderer initialised on it.
#pragma once

#include <memory>
#include <string>
#include <utility>

#include "cleave/base/status.h"
#include "cleave/render/gl_context.h"
#include "cleave/render/renderer.h"

namespace cleave::testing {

// False with the reason (for GTEST_SKIP) when this machine has no headless context.
inline bool startHeadless(std::unique_ptr<render::HeadlessGlContext>& context, render::Renderer& renderer,
                          std::string& why) {
  base::Expected<std::unique_ptr<render::HeadlessGlContext>> created =
      render::HeadlessGlContext::create(render::HeadlessApi::Auto);
  if (!created.ok()) {
    why = created.message();
    return false;
  }
  context = std::move(created).value();
  const base::Status started = renderer.init();
  why = started.message;
  return started.ok();
}

}  // namespace cleave::testing
