#include "engine/render/renderer.h"

#include <glad/gl.h>

#include <algorithm>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "engine/render/shaders.h"

#include <stb_easy_font.h>
#include <stb_image.h>
#include <stb_image_write.h>

namespace cleave::render {

namespace {

constexpr int kShadowMapSize = 1024;

GLuint compileShader(GLenum type, const char* source, std::string* error) {
  GLuint shader = glCreateShader(type);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetShaderInfoLog(shader, sizeof(log), nullptr, log);
    if (error) *error = std::string("shader compile failed: ") + log;
    glDeleteShader(shader);
    return 0;
  }
  return shader;
}

GLuint linkProgram(const char* vertex, const char* fragment, std::string* error) {
  GLuint vs = compileShader(GL_VERTEX_SHADER, vertex, error);
  if (!vs) return 0;
  GLuint fs = compileShader(GL_FRAGMENT_SHADER, fragment, error);
  if (!fs) {
    glDeleteShader(vs);
    return 0;
  }
  GLuint program = glCreateProgram();
  glAttachShader(program, vs);
  glAttachShader(program, fs);
  glLinkProgram(program);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetProgramInfoLog(program, sizeof(log), nullptr, log);
    if (error) *error = std::string("shader link failed: ") + log;
    glDeleteProgram(program);
    return 0;
  }
  return program;
}

struct GpuSubMesh {
  uint32_t firstIndex;
  uint32_t indexCount;
  uint32_t materialId;
};

struct GpuMesh {
  GLuint vao = 0, vbo = 0, ibo = 0;
  GLuint skinVbo = 0;  // joints (4 x uint16) and weights (4 x float) per vertex; 0 without a skin
  std::vector<GpuSubMesh> submeshes;
  uint32_t generation = 0;
  bool alive = false;
  uint32_t triangles = 0;
};

struct GpuTexture {
  GLuint id = 0;
  uint32_t generation = 0;
  bool alive = false;
};

struct DrawItem {
  uint32_t mesh;
  glm::mat4 model;
  uint32_t firstMaterial;  // into Impl::materials
  uint32_t materialCount;
  uint32_t firstJoint = 0;  // into Impl::jointMatrices
  uint32_t jointCount = 0;  // 0: drawn unskinned
};

struct ColoredVertex {
  glm::vec3 position;
  glm::vec4 color;
};

}  // namespace

struct Renderer::Impl {
  GLuint meshProgram = 0, shadowProgram = 0, skyProgram = 0, lineProgram = 0;
  GLuint emptyVao = 0, lineVao = 0, lineVbo = 0;
  GLuint shadowFbo = 0, shadowTexture = 0;
  GLuint fbo = 0, colorBuffer = 0, depthBuffer = 0;
  int width = 0, height = 0;
  std::vector<GpuMesh> meshes;
  std::vector<uint32_t> freeMeshes;
  std::vector<GpuTexture> textures;
  std::vector<uint32_t> freeTextures;
  std::vector<DrawItem> draws;
  std::vector<Material> materials;
  std::vector<glm::mat4> jointMatrices;
  std::vector<ColoredVertex> worldLines;
  std::vector<ColoredVertex> overlayLines;
  std::vector<ColoredVertex> overlayTriangles;
  Camera camera;
  Lighting lighting;
  std::vector<char> textScratch;

  GpuMesh* mesh(MeshHandle h) {
    if (h.generation == 0 || h.index >= meshes.size()) return nullptr;
    GpuMesh& m = meshes[h.index];
    return (m.alive && m.generation == h.generation) ? &m : nullptr;
  }
  const GpuMesh* mesh(MeshHandle h) const { return const_cast<Impl*>(this)->mesh(h); }
  GLuint texture(TextureHandle h) const {
    if (h.generation == 0 || h.index >= textures.size()) return 0;
    const GpuTexture& t = textures[h.index];
    return (t.alive && t.generation == h.generation) ? t.id : 0;
  }

  void ensureTarget(int w, int h) {
    if (fbo && w == width && h == height) return;
    if (fbo) {
      glDeleteFramebuffers(1, &fbo);
      glDeleteRenderbuffers(1, &colorBuffer);
      glDeleteRenderbuffers(1, &depthBuffer);
    }
    width = w;
    height = h;
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glGenRenderbuffers(1, &colorBuffer);
    glBindRenderbuffer(GL_RENDERBUFFER, colorBuffer);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colorBuffer);
    glGenRenderbuffers(1, &depthBuffer);
    glBindRenderbuffer(GL_RENDERBUFFER, depthBuffer);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                              depthBuffer);
  }

  glm::mat4 lightViewProj() const {
    const glm::vec3 dir = glm::normalize(lighting.sunDirection);
    const glm::vec3 center = lighting.shadowCenter;
    const float r = lighting.shadowRadius;
    const glm::vec3 up = std::abs(dir.y) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    const glm::mat4 view = glm::lookAt(center - dir * (2.f * r), center, up);
    // Snap the shadow window to whole texels so the shadow edges do not shimmer as the centre moves.
    glm::mat4 proj = glm::ortho(-r, r, -r, r, 0.01f, 4.f * r);
    glm::mat4 vp = proj * view;
    glm::vec4 origin = vp * glm::vec4(0, 0, 0, 1);
    const float texel = 2.f / kShadowMapSize;
    glm::vec2 snapped = glm::round(glm::vec2(origin) / texel) * texel;
    glm::mat4 snap = glm::translate(glm::mat4(1.f), glm::vec3(snapped - glm::vec2(origin), 0.f));
    return snap * vp;
  }

  // Skinning uniforms of the bound program for one draw.
  void setSkin(const DrawItem& d, GLint skinnedLocation, GLint jointsLocation) const {
    glUniform1i(skinnedLocation, d.jointCount > 0 ? 1 : 0);
    if (d.jointCount > 0) {
      glUniformMatrix4fv(jointsLocation, GLsizei(d.jointCount), GL_FALSE,
                         glm::value_ptr(jointMatrices[d.firstJoint]));
    }
  }

  void uploadColored(const std::vector<ColoredVertex>& vertices) {
    glBindVertexArray(lineVao);
    glBindBuffer(GL_ARRAY_BUFFER, lineVbo);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(ColoredVertex)),
                 vertices.data(), GL_STREAM_DRAW);
  }
};

Renderer::Renderer() : impl_(std::make_unique<Impl>()) {}

Renderer::~Renderer() {
  if (!impl_ || !glDeleteProgram) return;
  for (auto& m : impl_->meshes) {
    if (!m.alive) continue;
    glDeleteVertexArrays(1, &m.vao);
    glDeleteBuffers(1, &m.vbo);
    glDeleteBuffers(1, &m.ibo);
    if (m.skinVbo) glDeleteBuffers(1, &m.skinVbo);
  }
  for (auto& t : impl_->textures)
    if (t.alive) glDeleteTextures(1, &t.id);
  glDeleteProgram(impl_->meshProgram);
  glDeleteProgram(impl_->shadowProgram);
  glDeleteProgram(impl_->skyProgram);
  glDeleteProgram(impl_->lineProgram);
  glDeleteVertexArrays(1, &impl_->emptyVao);
  glDeleteVertexArrays(1, &impl_->lineVao);
  glDeleteBuffers(1, &impl_->lineVbo);
  glDeleteFramebuffers(1, &impl_->shadowFbo);
  glDeleteTextures(1, &impl_->shadowTexture);
  if (impl_->fbo) {
    glDeleteFramebuffers(1, &impl_->fbo);
    glDeleteRenderbuffers(1, &impl_->colorBuffer);
    glDeleteRenderbuffers(1, &impl_->depthBuffer);
  }
}

bool Renderer::init(std::string* error) {
  Impl& r = *impl_;
  if (!glCreateProgram) {
    if (error) *error = "no OpenGL context is loaded";
    return false;
  }
  r.meshProgram = linkProgram(shaders::kMeshVertex, shaders::kMeshFragment, error);
  r.shadowProgram = linkProgram(shaders::kShadowVertex, shaders::kShadowFragment, error);
  r.skyProgram = linkProgram(shaders::kSkyVertex, shaders::kSkyFragment, error);
  r.lineProgram = linkProgram(shaders::kLineVertex, shaders::kLineFragment, error);
  if (!r.meshProgram || !r.shadowProgram || !r.skyProgram || !r.lineProgram) return false;

  glGenVertexArrays(1, &r.emptyVao);
  glGenVertexArrays(1, &r.lineVao);
  glGenBuffers(1, &r.lineVbo);
  glBindVertexArray(r.lineVao);
  glBindBuffer(GL_ARRAY_BUFFER, r.lineVbo);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(ColoredVertex), nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, sizeof(ColoredVertex),
                        reinterpret_cast<void*>(offsetof(ColoredVertex, color)));
  glBindVertexArray(0);

  glGenTextures(1, &r.shadowTexture);
  glBindTexture(GL_TEXTURE_2D, r.shadowTexture);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, kShadowMapSize, kShadowMapSize, 0,
               GL_DEPTH_COMPONENT, GL_FLOAT, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  glGenFramebuffers(1, &r.shadowFbo);
  glBindFramebuffer(GL_FRAMEBUFFER, r.shadowFbo);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, r.shadowTexture, 0);
  glDrawBuffer(GL_NONE);
  glReadBuffer(GL_NONE);
  const bool complete = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (!complete) {
    if (error) *error = "the shadow-map framebuffer is incomplete";
    return false;
  }
  return true;
}

MeshHandle Renderer::uploadMesh(const geometry::MeshData& mesh, std::string* error) {
  return uploadPacked(packMesh(mesh), error);
}

MeshHandle Renderer::uploadPacked(const PackedMesh& packed, std::string* error) {
  if (!packed.ok() || packed.vertices.empty()) {
    if (error) *error = packed.ok() ? "mesh has no triangles" : packed.error;
    return {};
  }
  Impl& r = *impl_;
  uint32_t index;
  if (!r.freeMeshes.empty()) {
    index = r.freeMeshes.back();
    r.freeMeshes.pop_back();
  } else {
    index = uint32_t(r.meshes.size());
    r.meshes.emplace_back();
  }
  GpuMesh& g = r.meshes[index];
  g.generation = g.generation + 1;
  if (g.generation == 0) g.generation = 1;
  g.alive = true;
  g.triangles = uint32_t(packed.indices.size() / 3);
  g.submeshes.clear();
  for (const auto& s : packed.submeshes) g.submeshes.push_back({s.firstIndex, s.indexCount, s.materialId});
  glGenVertexArrays(1, &g.vao);
  glGenBuffers(1, &g.vbo);
  glGenBuffers(1, &g.ibo);
  glBindVertexArray(g.vao);
  glBindBuffer(GL_ARRAY_BUFFER, g.vbo);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(packed.vertices.size() * sizeof(float)), packed.vertices.data(),
               GL_STATIC_DRAW);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, g.ibo);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(packed.indices.size() * sizeof(uint32_t)),
               packed.indices.data(), GL_STATIC_DRAW);
  const GLsizei stride = 12 * sizeof(float);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, nullptr);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(3 * sizeof(float)));
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(6 * sizeof(float)));
  glEnableVertexAttribArray(3);
  glVertexAttribPointer(3, 4, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(8 * sizeof(float)));
  g.skinVbo = 0;
  if (!packed.skin.empty()) {
    // Skin: 4 unsigned shorts of joints, then 4 floats of weights, per vertex (24 bytes).
    using SkinVertex = PackedMesh::SkinVertex;
    static_assert(sizeof(SkinVertex) == 24);
    glGenBuffers(1, &g.skinVbo);
    glBindBuffer(GL_ARRAY_BUFFER, g.skinVbo);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(packed.skin.size() * sizeof(SkinVertex)), packed.skin.data(),
                 GL_STATIC_DRAW);
    glEnableVertexAttribArray(4);
    glVertexAttribIPointer(4, 4, GL_UNSIGNED_SHORT, sizeof(SkinVertex), nullptr);
    glEnableVertexAttribArray(5);
    glVertexAttribPointer(5, 4, GL_FLOAT, GL_FALSE, sizeof(SkinVertex),
                          reinterpret_cast<void*>(offsetof(SkinVertex, weights)));
  }
  glBindVertexArray(0);
  return {index, g.generation};
}

void Renderer::destroyMesh(MeshHandle handle) {
  GpuMesh* m = impl_->mesh(handle);
  if (!m) return;
  glDeleteVertexArrays(1, &m->vao);
  glDeleteBuffers(1, &m->vbo);
  glDeleteBuffers(1, &m->ibo);
  if (m->skinVbo) glDeleteBuffers(1, &m->skinVbo);
  m->vao = m->vbo = m->ibo = m->skinVbo = 0;
  m->alive = false;
  m->submeshes.clear();
  impl_->freeMeshes.push_back(handle.index);
}

uint32_t Renderer::liveMeshCount() const {
  uint32_t count = 0;
  for (const auto& m : impl_->meshes) count += m.alive ? 1 : 0;
  return count;
}

uint32_t Renderer::liveTextureCount() const {
  uint32_t count = 0;
  for (const auto& t : impl_->textures) count += t.alive ? 1 : 0;
  return count;
}

bool Renderer::isValid(MeshHandle mesh) const { return impl_->mesh(mesh) != nullptr; }

bool Renderer::isValid(TextureHandle texture) const { return impl_->texture(texture) != 0; }

TextureHandle Renderer::createTexture(int width, int height, std::span<const uint8_t> rgba,
                                      std::string* error) {
  if (width <= 0 || height <= 0 || rgba.size() != size_t(width) * size_t(height) * 4) {
    if (error) *error = "texture size does not match its pixel data";
    return {};
  }
  Impl& r = *impl_;
  uint32_t index;
  if (!r.freeTextures.empty()) {
    index = r.freeTextures.back();
    r.freeTextures.pop_back();
  } else {
    index = uint32_t(r.textures.size());
    r.textures.emplace_back();
  }
  GpuTexture& t = r.textures[index];
  t.generation = t.generation + 1;
  if (t.generation == 0) t.generation = 1;
  t.alive = true;
  glGenTextures(1, &t.id);
  glBindTexture(GL_TEXTURE_2D, t.id);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  glGenerateMipmap(GL_TEXTURE_2D);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  return {index, t.generation};
}

void Renderer::destroyTexture(TextureHandle handle) {
  GLuint id = impl_->texture(handle);
  if (!id) return;
  glDeleteTextures(1, &id);
  impl_->textures[handle.index].alive = false;
  impl_->textures[handle.index].id = 0;
  impl_->freeTextures.push_back(handle.index);
}

void Renderer::beginFrame(int width, int height, const Camera& camera, const Lighting& lighting) {
  Impl& r = *impl_;
  r.ensureTarget(std::max(width, 1), std::max(height, 1));
  r.camera = camera;
  r.lighting = lighting;
  r.draws.clear();
  r.materials.clear();
  r.jointMatrices.clear();
  r.worldLines.clear();
  r.overlayLines.clear();
  r.overlayTriangles.clear();
}

void Renderer::submit(MeshHandle mesh, const glm::mat4& model, std::span<const Material> materials) {
  Impl& r = *impl_;
  if (!r.mesh(mesh) || materials.empty()) return;
  const uint32_t first = uint32_t(r.materials.size());
  r.materials.insert(r.materials.end(), materials.begin(), materials.end());
  r.draws.push_back({mesh.index, model, first, uint32_t(materials.size())});
}

void Renderer::submitSkinned(MeshHandle mesh, const glm::mat4& model, std::span<const glm::mat4> jointMatrices,
                             std::span<const Material> materials) {
  Impl& r = *impl_;
  const GpuMesh* m = r.mesh(mesh);
  if (!m || materials.empty()) return;
  submit(mesh, model, materials);
  if (!m->skinVbo || jointMatrices.empty()) return;
  DrawItem& draw = r.draws.back();
  draw.firstJoint = uint32_t(r.jointMatrices.size());
  draw.jointCount = uint32_t(std::min<size_t>(jointMatrices.size(), kMaxSkinJoints));
  r.jointMatrices.insert(r.jointMatrices.end(), jointMatrices.begin(), jointMatrices.begin() + draw.jointCount);
}

void Renderer::submitLines(std::span<const glm::vec3> points, const glm::vec4& color) {
  for (const auto& p : points) impl_->worldLines.push_back({p, color});
}

void Renderer::submitOverlayLines(std::span<const glm::vec2> points, const glm::vec4& color) {
  for (const auto& p : points) impl_->overlayLines.push_back({glm::vec3(p, 0.f), color});
}

void Renderer::submitOverlayRect(const glm::vec4& rect, const glm::vec4& color) {
  const glm::vec3 a(rect.x, rect.y, 0), b(rect.x + rect.z, rect.y, 0),
      c(rect.x + rect.z, rect.y + rect.w, 0), d(rect.x, rect.y + rect.w, 0);
  for (const glm::vec3& p : {a, b, c, a, c, d}) impl_->overlayTriangles.push_back({p, color});
}

float Renderer::textWidth(const std::string& text, float scale) {
  return float(stb_easy_font_width(const_cast<char*>(text.c_str()))) * scale;
}

void Renderer::submitText(const std::string& text, glm::vec2 position, float scale,
                          const glm::vec4& color) {
  Impl& r = *impl_;
  // stb_easy_font emits quads of 4 vertices, 16 bytes each (x, y, z floats + RGBA8).
  const size_t bufferSize = text.size() * 270 + 1024;
  if (r.textScratch.size() < bufferSize) r.textScratch.resize(bufferSize);
  unsigned char white[4] = {255, 255, 255, 255};
  const int quads = stb_easy_font_print(0.f, 0.f, const_cast<char*>(text.c_str()), white,
                                        r.textScratch.data(), int(r.textScratch.size()));
  for (int q = 0; q < quads; ++q) {
    glm::vec3 corner[4];
    for (int k = 0; k < 4; ++k) {
      float xy[2];
      std::memcpy(xy, r.textScratch.data() + (q * 4 + k) * 16, 8);
      corner[k] = glm::vec3(position.x + xy[0] * scale, position.y + xy[1] * scale, 0.f);
    }
    for (int k : {0, 1, 2, 0, 2, 3}) r.overlayTriangles.push_back({corner[k], color});
  }
}

FrameStats Renderer::endFrame() {
  Impl& r = *impl_;
  FrameStats stats;
  const float aspect = float(r.width) / float(r.height);
  const glm::mat4 proj =
      glm::perspective(r.camera.verticalFovRadians, aspect, r.camera.nearPlane, r.camera.farPlane);
  const glm::mat4 viewProj = proj * r.camera.view;
  const glm::mat4 lightVp = r.lightViewProj();
  const glm::vec3 sunDir = glm::normalize(r.lighting.sunDirection);

  // Shadow pass.
  if (r.lighting.shadows) {
    glBindFramebuffer(GL_FRAMEBUFFER, r.shadowFbo);
    glViewport(0, 0, kShadowMapSize, kShadowMapSize);
    glClear(GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);  // closed and open meshes alike cast shadows
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.5f, 2.f);
    glUseProgram(r.shadowProgram);
    const GLint loc = glGetUniformLocation(r.shadowProgram, "uLightMvp");
    const GLint shadowSkinned = glGetUniformLocation(r.shadowProgram, "uSkinned");
    const GLint shadowJoints = glGetUniformLocation(r.shadowProgram, "uJoints");
    for (const DrawItem& d : r.draws) {
      const GpuMesh& m = r.meshes[d.mesh];
      // The floor (checker material) and materials marked so receive but do not cast.
      const Material& first = r.materials[d.firstMaterial];
      if (first.shading == Shading::Checker || !first.castsShadow) continue;
      r.setSkin(d, shadowSkinned, shadowJoints);
      glUniformMatrix4fv(loc, 1, GL_FALSE, glm::value_ptr(lightVp * d.model));
      glBindVertexArray(m.vao);
      for (const auto& s : m.submeshes)
        glDrawElements(GL_TRIANGLES, GLsizei(s.indexCount), GL_UNSIGNED_INT,
                       reinterpret_cast<void*>(uintptr_t(s.firstIndex) * 4));
    }
    glDisable(GL_POLYGON_OFFSET_FILL);
  }

  glBindFramebuffer(GL_FRAMEBUFFER, r.fbo);
  glViewport(0, 0, r.width, r.height);
  glClearColor(0.f, 0.f, 0.f, 1.f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

  glDisable(GL_CULL_FACE);

  // Lit pass. Back faces are drawn too (flipped normals) so open pieces in hollow mode look right.
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glUseProgram(r.meshProgram);
  const GLuint p = r.meshProgram;
  auto u = [p](const char* name) { return glGetUniformLocation(p, name); };
  glUniformMatrix4fv(u("uViewProj"), 1, GL_FALSE, glm::value_ptr(viewProj));
  glUniformMatrix4fv(u("uLightViewProj"), 1, GL_FALSE, glm::value_ptr(lightVp));
  glUniform3fv(u("uSunDir"), 1, glm::value_ptr(sunDir));
  const glm::vec3 sun = r.lighting.sunColor * r.lighting.sunIntensity;
  glUniform3fv(u("uSunColor"), 1, glm::value_ptr(sun));
  glUniform3fv(u("uAmbient"), 1, glm::value_ptr(r.lighting.ambientColor));
  glUniform3fv(u("uCameraPos"), 1, glm::value_ptr(r.camera.position));
  glUniform1i(u("uShadows"), r.lighting.shadows ? 1 : 0);
  glUniform1i(u("uAlbedo"), 0);
  glUniform1i(u("uShadowMap"), 1);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, r.shadowTexture);
  const GLint locModel = u("uModel"), locNormal = u("uNormalMatrix"), locShading = u("uShading"),
              locBase = u("uBaseColor"), locHasAlbedo = u("uHasAlbedo"), locSpec = u("uSpecular"),
              locShine = u("uShininess"), locRefl = u("uReflectivity"),
              locCheckerScale = u("uCheckerScale"), locCheckerColor = u("uCheckerColor"),
              locSkinned = u("uSkinned"), locJoints = u("uJoints");
  for (const DrawItem& d : r.draws) {
    const GpuMesh& m = r.meshes[d.mesh];
    r.setSkin(d, locSkinned, locJoints);
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(d.model)));
    glUniformMatrix4fv(locModel, 1, GL_FALSE, glm::value_ptr(d.model));
    glUniformMatrix3fv(locNormal, 1, GL_FALSE, glm::value_ptr(normalMatrix));
    glBindVertexArray(m.vao);
    for (const auto& s : m.submeshes) {
      const Material& mat =
          r.materials[d.firstMaterial + std::min(s.materialId, d.materialCount - 1)];
      const GLuint tex = r.texture(mat.albedo);
      glUniform1i(locShading, int(mat.shading));
      glUniform4fv(locBase, 1, glm::value_ptr(mat.baseColor));
      glUniform1i(locHasAlbedo, tex ? 1 : 0);
      glUniform1f(locSpec, mat.specular);
      glUniform1f(locShine, mat.shininess);
      glUniform1f(locRefl, mat.reflectivity);
      glUniform1f(locCheckerScale, mat.checkerScale);
      glUniform4fv(locCheckerColor, 1, glm::value_ptr(mat.checkerColor));
      glActiveTexture(GL_TEXTURE0);
      glBindTexture(GL_TEXTURE_2D, tex);
      glDrawElements(GL_TRIANGLES, GLsizei(s.indexCount), GL_UNSIGNED_INT,
                     reinterpret_cast<void*>(uintptr_t(s.firstIndex) * 4));
      stats.drawCalls++;
      stats.triangles += s.indexCount / 3;
    }
  }

  // Sky: a full-screen triangle at the far plane, drawn after the meshes so that only the pixels
  // nothing covers pay for the sky colour (the depth test keeps the rest).
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  glUseProgram(r.skyProgram);
  const glm::mat4 invViewProj = glm::inverse(viewProj);
  glUniformMatrix4fv(glGetUniformLocation(r.skyProgram, "uInvViewProj"), 1, GL_FALSE,
                     glm::value_ptr(invViewProj));
  glUniform3fv(glGetUniformLocation(r.skyProgram, "uSunDir"), 1, glm::value_ptr(sunDir));
  glBindVertexArray(r.emptyVao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);

  // World lines, then the 2D overlay on top.
  glUseProgram(r.lineProgram);
  const GLint locMatrix = glGetUniformLocation(r.lineProgram, "uMatrix");
  if (!r.worldLines.empty()) {
    glUniformMatrix4fv(locMatrix, 1, GL_FALSE, glm::value_ptr(viewProj));
    r.uploadColored(r.worldLines);
    glDrawArrays(GL_LINES, 0, GLsizei(r.worldLines.size()));
  }
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  const glm::mat4 ortho = glm::ortho(0.f, float(r.width), float(r.height), 0.f, -1.f, 1.f);
  glUniformMatrix4fv(locMatrix, 1, GL_FALSE, glm::value_ptr(ortho));
  if (!r.overlayTriangles.empty()) {
    r.uploadColored(r.overlayTriangles);
    glDrawArrays(GL_TRIANGLES, 0, GLsizei(r.overlayTriangles.size()));
  }
  if (!r.overlayLines.empty()) {
    r.uploadColored(r.overlayLines);
    glDrawArrays(GL_LINES, 0, GLsizei(r.overlayLines.size()));
  }
  glDisable(GL_BLEND);
  glBindVertexArray(0);
  return stats;
}

void Renderer::readPixels(std::vector<uint8_t>& rgba, int& width, int& height) const {
  const Impl& r = *impl_;
  width = r.width;
  height = r.height;
  rgba.resize(size_t(width) * size_t(height) * 4);
  if (!r.fbo) return;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, r.fbo);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  // GL rows run bottom to top; images run top to bottom.
  const size_t row = size_t(width) * 4;
  std::vector<uint8_t> tmp(row);
  for (int y = 0; y < height / 2; ++y) {
    uint8_t* a = rgba.data() + size_t(y) * row;
    uint8_t* b = rgba.data() + size_t(height - 1 - y) * row;
    std::memcpy(tmp.data(), a, row);
    std::memcpy(a, b, row);
    std::memcpy(b, tmp.data(), row);
  }
}

void Renderer::presentToDefaultFramebuffer(int windowWidth, int windowHeight) const {
  const Impl& r = *impl_;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, r.fbo);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glBlitFramebuffer(0, 0, r.width, r.height, 0, 0, windowWidth, windowHeight, GL_COLOR_BUFFER_BIT,
                    GL_LINEAR);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

bool writePng(const std::string& path, int width, int height, std::span<const uint8_t> rgba,
              std::string* error) {
  if (rgba.size() != size_t(width) * size_t(height) * 4) {
    if (error) *error = path + ": pixel data does not match " + std::to_string(width) + "x" +
                        std::to_string(height);
    return false;
  }
  // Level 4 instead of stb's 8: files about 10% larger, written several times faster (screenshots
  // of long headless runs).
  stbi_write_png_compression_level = 4;
  if (!stbi_write_png(path.c_str(), width, height, 4, rgba.data(), width * 4)) {
    if (error) *error = path + ": could not write the PNG file";
    return false;
  }
  return true;
}

bool readPng(const std::string& path, int& width, int& height, std::vector<uint8_t>& rgba,
             std::string* error) {
  int channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &width, &height, &channels, 4);
  if (!data) {
    if (error) *error = path + ": " + (stbi_failure_reason() ? stbi_failure_reason() : "unreadable");
    return false;
  }
  rgba.assign(data, data + size_t(width) * size_t(height) * 4);
  stbi_image_free(data);
  return true;
}

}  // namespace cleave::render
