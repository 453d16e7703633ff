// SPDX-License-Identifier: MIT
// OpenGL context creation and the GL function loader.
//
// The renderer needs a current OpenGL 3.3 core context. A window backend (GLFW, in engine/app) makes
// its own and calls loadGl() with its getProcAddress; headless runs use HeadlessGlContext, which
// tries EGL surfaceless on Mesa first and falls back to OSMesa. Headless contexts have no default
// framebuffer: the renderer always draws into its own framebuffer object.
#pragma once

#include <memory>
#include <string>

#include "cleave/base/status.h"

namespace cleave::render {

using GlProc = void (*)();
using GlGetProcAddress = GlProc (*)(const char* name);

// Loads the GL 3.3 core entry points through `getProcAddress` for the current context.
// Unavailable (with a reason) if the context is missing or older than 3.3.
base::Status loadGl(GlGetProcAddress getProcAddress);

// "renderer | version" of the current context, for logs.
std::string glDescription();

enum class HeadlessApi { Auto, Egl, OsMesa };

// A current, windowless OpenGL 3.3 core context for the calling thread. Destroying it releases the
// context. Creation failure is reported, never fatal.
class HeadlessGlContext {
 public:
  ~HeadlessGlContext();
  HeadlessGlContext(const HeadlessGlContext&) = delete;
  HeadlessGlContext& operator=(const HeadlessGlContext&) = delete;

  // Creates the context and loads GL. `api` Auto tries EGL then OSMesa (also settable with the
  // environment variable CLEAVE_HEADLESS=egl|osmesa). Unavailable, with the reasons of every API
  // tried, on failure.
  static base::Expected<std::unique_ptr<HeadlessGlContext>> create(HeadlessApi api);

  const char* apiName() const;

  struct Impl;  // backend state, defined in the .cpp

 private:
  HeadlessGlContext() = default;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cleave::render
