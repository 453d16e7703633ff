// SPDX-License-Identifier: MIT
// Forward renderer on OpenGL 3.3 core: a directional sun with a shadow map, ambient and specular
// light, textured materials, a procedural sky, a world-space checker floor and a debug-normals view.
//
// Usage per frame: beginFrame(view) -> submit(...) for each mesh -> endFrame() renders the shadow pass,
// the lit pass, the sky and the overlay into the renderer's own framebuffer object (the scene at the
// render scale, the overlay at full size); then readPixels() for a
// screenshot and/or presentToDefaultFramebuffer() in a window. Requires a current GL context with
// the loader initialised (see gl_context.h). Meshes and textures live behind generational handles;
// destroying them frees the GPU memory at once, and a stale handle is ignored.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cleave/base/status.h"
#include "cleave/geometry/mesh_data.h"
#include "cleave/render/packed_mesh.h"

namespace cleave::render {

struct MeshHandle {
  uint32_t index = 0;
  uint32_t generation = 0;  // 0 = invalid
  bool valid() const { return generation != 0; }
  friend bool operator==(MeshHandle, MeshHandle) = default;
};

struct TextureHandle {
  uint32_t index = 0;
  uint32_t generation = 0;  // 0 = invalid: the material uses its base colour only
  bool valid() const { return generation != 0; }
  friend bool operator==(TextureHandle, TextureHandle) = default;
};

enum class Shading : uint8_t {
  Lit,            // base colour (x albedo texture) lit by sun + ambient + specular, shadowed
  Checker,        // lit, with a world-space checker pattern (floor); `checkerScale` squares per metre
  DebugNormals,   // world normal as colour, unlit
  Unlit,          // base colour (x texture), no light
  CheckerCube,    // lit, checker pattern by world position in 3D (a "solid texture": caps line up)
};

struct Material {
  Shading shading = Shading::Lit;
  glm::vec4 baseColor{1.f};        // linear RGBA multiplier
  TextureHandle albedo;            // optional sRGB-ish RGBA8 texture
  float specular = 0.25f;          // specular intensity
  float shininess = 32.f;          // Blinn-Phong exponent
  float reflectivity = 0.f;        // 0..1 mix of the sky reflected about the normal (metal)
  float checkerScale = 1.f;        // Checker / CheckerCube: squares per metre
  glm::vec4 checkerColor{0.2f, 0.2f, 0.22f, 1.f};  // second checker colour
  bool castsShadow = true;         // read from a draw's first material: false for floors and walls
                                   // that only receive shadows (saves the shadow pass their area)
  friend bool operator==(const Material&, const Material&) = default;
};

struct Camera {
  glm::vec3 position{0.f, 2.f, 6.f};
  glm::mat4 view{1.f};
  float verticalFovRadians = 1.0f;
  float nearPlane = 0.05f;
  float farPlane = 300.f;
};

struct Lighting {
  glm::vec3 sunDirection{-0.55f, -0.75f, -0.38f};  // direction the light travels (towards the ground)
  glm::vec3 sunColor{1.0f, 0.95f, 0.85f};
  float sunIntensity = 1.5f;
  glm::vec3 ambientColor{0.22f, 0.25f, 0.32f};
  glm::vec3 shadowCenter{0.f};                 // the shadow map covers a sphere around this point
  float shadowRadius = 20.f;
  bool shadows = true;
};

struct FrameStats {
  uint32_t drawCalls = 0;
  uint32_t triangles = 0;
};

class Renderer {
 public:
  Renderer();
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Compiles shaders and creates the shadow map. Needs a current GL 3.3 core context: Unavailable
  // (with the reason) without one, or when a shader or the shadow map cannot be made.
  base::Status init();

  // Render scale: the 3D scene (shadow, lit, sky and world-line passes) is drawn into an offscreen
  // target of scale x the frame size and stretched over the frame with linear filtering; the HUD
  // (overlay lines, rectangles, text) is drawn after it at the frame's full resolution. Clamped to
  // [kMinRenderScale, 1]; 1 (the default) draws the scene straight into the frame. Below 1 the
  // shadow map shrinks with the scale (1024 texels above 0.7, 512 from 0.3, 256 below) and its
  // filtering drops from four taps to one. Takes effect at the next beginFrame.
  static constexpr float kMinRenderScale = 0.25f;
  void setRenderScale(float scale);
  float renderScale() const;
  int shadowMapSize() const;  // texels per side
  // The GL_RENDERER string of the current context, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  std::string deviceName() const;
  // True for Mesa's and others' CPU rasterisers (llvmpipe, softpipe, swrast, ...), where a game
  // chooses a lower render scale by default.
  static bool isSoftwareRasterizer(const std::string& deviceName);
  // Window mode: endFrame composes the frame (the scene stretched, the HUD) straight into the
  // default framebuffer, and presentToDefaultFramebuffer has nothing left to do; readPixels reads
  // the window's back buffer. Off (the default): the frame is the renderer's own framebuffer object.
  void setDrawIntoWindow(bool on);

  // Uploads positions, normals (computed flat if absent), uv0 (zero if absent) and tangents, with the
  // submesh runs, and the skin (joints and weights) when the mesh has one, for submitSkinned.
  // InvalidArgument (with the reason) for empty or malformed meshes; `.valueOr({})` gives an invalid
  // handle then.
  base::Expected<MeshHandle> uploadMesh(const geometry::MeshData& mesh);
  // The same for a mesh packed before (packMesh, on any thread): only the GL buffers are made here.
  base::Expected<MeshHandle> uploadPacked(const PackedMesh& packed);
  void destroyMesh(MeshHandle mesh);
  // Frees a mesh's vertex and index storage and keeps its handle, bounds and submeshes, for a cache
  // that draws the mesh another way for a while (static batches): on a software rasterizer the
  // storage is process memory. An evicted mesh submitted draws nothing. restoreMesh gives it storage
  // again from a packing of the same mesh (InvalidArgument when the packing is malformed or empty;
  // the mesh stays evicted). Both ignore an invalid handle; restoring a resident mesh does nothing.
  void evictMesh(MeshHandle mesh);
  base::Status restoreMesh(MeshHandle mesh, const PackedMesh& packed);
  // Valid and holding its storage (not evicted).
  bool isResident(MeshHandle mesh) const;
  uint32_t liveMeshCount() const;
  uint32_t liveTextureCount() const;
  // False for a null, destroyed or stale handle (slots are reused with a new generation).
  bool isValid(MeshHandle mesh) const;
  bool isValid(TextureHandle texture) const;

  // RGBA8 pixels, rows top to bottom, width*height*4 bytes. Mipmapped, repeating.
  // InvalidArgument when the size does not match the pixel data.
  base::Expected<TextureHandle> createTexture(int width, int height, std::span<const uint8_t> rgba);
  void destroyTexture(TextureHandle texture);

  // Starts a frame of the given size in pixels; resizes the offscreen target when needed.
  void beginFrame(int width, int height, const Camera& camera, const Lighting& lighting);
  // Queues a mesh. `materials` is indexed by the submesh material id (clamped to the last entry).
  // `closed`: the mesh is closed and wound counter-clockwise seen from outside, so its back faces
  // are never seen and both passes skip them (a third of a frame of many pieces on a software
  // rasterizer). Open meshes draw both sides (a piece cut open in hollow mode shows its inside).
  // A mirroring `model` (negative determinant) is drawn with its winding turned, so it is lit and
  // culled as its unmirrored self.
  void submit(MeshHandle mesh, const glm::mat4& model, std::span<const Material> materials, bool closed = false);
  // Queues a skinned mesh, posed on the GPU: world = model * sum_k w_k * jointMatrices[j_k] * p (the
  // blend divided by the weight sum), with each joint matrix = joint global * inverse bind (see
  // anim::poseToJointMatrices); normals use the blend's 3x3 part. The same pose on the CPU is
  // geometry::MeshContainer::setSkinningPose(jointMatrices, model). jointMatrices must cover every
  // joint id the mesh uses (at most kMaxSkinJoints are read). A mesh uploaded without a skin, or an
  // empty jointMatrices, draws as submit() would.
  void submitSkinned(MeshHandle mesh, const glm::mat4& model, std::span<const glm::mat4> jointMatrices,
                     std::span<const Material> materials);
  // Queues a line list in world space (debug drawing, the drag-cut line), drawn unlit on top.
  void submitLines(std::span<const glm::vec3> points, const glm::vec4& color);
  // Queues a 2D line list in pixel coordinates (origin top-left), for the HUD.
  void submitOverlayLines(std::span<const glm::vec2> points, const glm::vec4& color);
  // Queues filled 2D rectangles (x, y, w, h in pixels) for the HUD.
  void submitOverlayRect(const glm::vec4& rect, const glm::vec4& color);
  // Queues text at a pixel position (top-left) in stb_easy_font glyphs (about 7 px high) times `scale`.
  void submitText(const std::string& text, glm::vec2 position, float scale, const glm::vec4& color);
  // The width in pixels `text` takes at `scale` (its longest line), to fit a box around it.
  static float textWidth(const std::string& text, float scale);
  // Renders everything queued since beginFrame.
  FrameStats endFrame();
  // Binds the last frame's target (the renderer's framebuffer object, or the window's in window
  // mode) with a viewport over all of it, for a pass drawn on top after endFrame (the inspector's
  // Dear ImGui pass). Returns the frame size in pixels.
  glm::ivec2 bindFrame();

  // Reads the last frame back as RGBA8, rows top to bottom.
  void readPixels(std::vector<uint8_t>& rgba, int& width, int& height) const;
  // Copies the last frame to the window's default framebuffer (window backends only).
  void presentToDefaultFramebuffer(int windowWidth, int windowHeight) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Writes RGBA8 pixels (rows top to bottom) as a PNG. On failure InvalidArgument (the pixels do not
// match the size) or IoError, with a reason naming the file.
base::Status writePng(const std::string& path, int width, int height, std::span<const uint8_t> rgba);
// Reads a PNG as RGBA8 (rows top to bottom). On failure IoError with a reason naming the file.
base::Status readPng(const std::string& path, int& width, int& height, std::vector<uint8_t>& rgba);

}  // namespace cleave::render
