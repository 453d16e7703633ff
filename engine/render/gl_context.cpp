// SPDX-License-Identifier: MIT
#include "cleave/render/gl_context.h"

#include <glad/gl.h>

#define EGL_EGLEXT_PROTOTYPES
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <dlfcn.h>

#include <cstdlib>
#include <cstring>
#include <vector>

#if defined(CLEAVE_HAVE_OSMESA)
#include <GL/osmesa.h>
#endif

namespace cleave::render {

namespace {

base::Status unavailable(std::string reason) {
  return base::Status::failure(base::StatusCode::Unavailable, std::move(reason));
}

}  // namespace

base::Status loadGl(GlGetProcAddress getProcAddress) {
  const int version = gladLoadGL(reinterpret_cast<GLADloadfunc>(getProcAddress));
  if (version == 0) return unavailable("could not load OpenGL entry points (no current context?)");
  if (GLAD_VERSION_MAJOR(version) < 3 ||
      (GLAD_VERSION_MAJOR(version) == 3 && GLAD_VERSION_MINOR(version) < 3)) {
    return unavailable("OpenGL 3.3 core is required; the context offers " + glDescription());
  }
  return {};
}

std::string glDescription() {
  if (!glGetString) return "no GL loaded";
  const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  return std::string(renderer ? renderer : "?") + " | " + (version ? version : "?");
}

struct HeadlessGlContext::Impl {
  const char* api = "none";
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
#if defined(CLEAVE_HAVE_OSMESA)
  OSMesaContext osmesa = nullptr;
  std::vector<unsigned char> osmesaBuffer;
#endif
};

namespace {

#if defined(CLEAVE_SANITIZE) || defined(CLEAVE_TSAN)
// LeakSanitizer cannot symbolise leaks inside a driver that was unloaded at eglTerminate, and its
// tracer can crash on the stale TLS ranges the driver leaves; ThreadSanitizer refuses to see a
// library its suppressions name unloaded. Keeping the software driver mapped for the life of the
// process avoids all three (see docs/architecture.md, sanitizers).
void pinMesaDriver() {
  static bool pinned = false;
  if (pinned) return;
  pinned = true;
  const char* candidates[] = {"/usr/lib/x86_64-linux-gnu/dri/swrast_dri.so",
                              "/usr/lib/aarch64-linux-gnu/dri/swrast_dri.so", "swrast_dri.so"};
  for (const char* path : candidates) {
    if (dlopen(path, RTLD_NOW | RTLD_NODELETE)) return;
  }
}
#else
void pinMesaDriver() {}
#endif

base::Status createEgl(HeadlessGlContext::Impl& impl) {
  auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!getPlatformDisplay) {
    return unavailable("EGL: eglGetPlatformDisplayEXT is not available");
  }
  EGLDisplay display = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (display == EGL_NO_DISPLAY || !eglInitialize(display, nullptr, nullptr)) {
    return unavailable("EGL: the Mesa surfaceless platform could not be initialised");
  }
  if (!eglBindAPI(EGL_OPENGL_API)) {
    eglTerminate(display);
    return unavailable("EGL: OpenGL API not available");
  }
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK,
                               EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
  if (context == EGL_NO_CONTEXT ||
      !eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
    eglTerminate(display);
    return unavailable("EGL: could not create a surfaceless OpenGL 3.3 core context");
  }
  impl.display = display;
  impl.context = context;
  impl.api = "egl-surfaceless";
  return loadGl(reinterpret_cast<GlGetProcAddress>(eglGetProcAddress));
}

#if defined(CLEAVE_HAVE_OSMESA)
base::Status createOsMesa(HeadlessGlContext::Impl& impl) {
  const int attributes[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24,
                            OSMESA_STENCIL_BITS, 8, OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                            OSMESA_CONTEXT_MAJOR_VERSION, 3, OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
  OSMesaContext context = OSMesaCreateContextAttribs(attributes, nullptr);
  if (!context) {
    return unavailable("OSMesa: could not create an OpenGL 3.3 core context");
  }
  // OSMesa needs a colour buffer to make the context current; the renderer draws into its own FBO,
  // so a tiny one is enough.
  impl.osmesaBuffer.assign(16 * 16 * 4, 0);
  if (!OSMesaMakeCurrent(context, impl.osmesaBuffer.data(), GL_UNSIGNED_BYTE, 16, 16)) {
    OSMesaDestroyContext(context);
    return unavailable("OSMesa: could not make the context current");
  }
  impl.osmesa = context;
  impl.api = "osmesa";
  return loadGl(reinterpret_cast<GlGetProcAddress>(OSMesaGetProcAddress));
}
#endif

}  // namespace

HeadlessGlContext::~HeadlessGlContext() {
  if (!impl_) return;
  if (impl_->context != EGL_NO_CONTEXT) {
    eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(impl_->display, impl_->context);
    eglTerminate(impl_->display);
  }
#if defined(CLEAVE_HAVE_OSMESA)
  if (impl_->osmesa) OSMesaDestroyContext(impl_->osmesa);
#endif
}

base::Expected<std::unique_ptr<HeadlessGlContext>> HeadlessGlContext::create(HeadlessApi api) {
  if (api == HeadlessApi::Auto) {
    if (const char* env = std::getenv("CLEAVE_HEADLESS")) {
      if (std::strcmp(env, "egl") == 0) api = HeadlessApi::Egl;
      if (std::strcmp(env, "osmesa") == 0) api = HeadlessApi::OsMesa;
    }
  }
  pinMesaDriver();
  std::unique_ptr<HeadlessGlContext> context(new HeadlessGlContext());
  context->impl_ = std::make_unique<Impl>();
  std::string eglError;
  if (api != HeadlessApi::OsMesa) {
    const base::Status egl = createEgl(*context->impl_);
    if (egl.ok()) return context;
    if (api == HeadlessApi::Egl) return egl;
    eglError = egl.message;
  }
#if defined(CLEAVE_HAVE_OSMESA)
  const base::Status osmesa = createOsMesa(*context->impl_);
  if (osmesa.ok()) return context;
  return unavailable((eglError.empty() ? "" : eglError + "; ") + osmesa.message);
#else
  return unavailable(eglError.empty() ? "OSMesa support was not built" : eglError);
#endif
}

const char* HeadlessGlContext::apiName() const { return impl_ ? impl_->api : "none"; }

}  // namespace cleave::render
