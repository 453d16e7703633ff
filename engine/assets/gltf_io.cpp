// SPDX-License-Identifier: MIT
// glTF 2.0 through tinygltf: the static-mesh reader (default scene, node transforms applied, every
// triangle primitive merged into one MeshData with one material run per primitive) and the GLB
// writer (the GLB writing core of glb_builder.h without a skin). tinygltf parses the JSON and the
// GLB container; every index, offset, stride and count it hands over is checked here again before
// any read, because a file can claim anything.
#include <algorithm>
#include <cmath>
#include <limits>
#include <cstring>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

#include "cleave/assets/glb_builder.h"
#include "cleave/assets/gltf_access.h"
#include "cleave/assets/gltf_attributes.h"
#include "cleave/assets/mesh_finish.h"
#include "cleave/assets/mesh_reader.h"

namespace cleave::assets::detail {

// ------------------------------------------------------------------------------------------------
// Loading

namespace {

// tinygltf callbacks (their signatures are tinygltf's).
// Images are irrelevant to geometry: skip decoding them (it is also the costliest part of a bad file).
bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*,
               int, void*) {
  return true;
}

// File callbacks for glTF read from memory: there is no folder, so external files are refused.
bool noFileExists(const std::string&, void*) { return false; }
std::string sameFilePath(const std::string& path, void*) { return path; }
bool noReadWholeFile(std::vector<unsigned char>*, std::string* err, const std::string& path, void*) {
  if (err != nullptr) *err += "external file '" + path + "' cannot be read from memory input\n";
  return false;
}
bool noWriteWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err != nullptr) *err += "writing is disabled\n";
  return false;
}

}  // namespace

bool trianglesOfPrimitive(int mode, std::span<const uint32_t> corners, std::vector<uint32_t>& triangles) {
  triangles.clear();
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    triangles.assign(corners.begin(), corners.begin() + static_cast<std::ptrdiff_t>(corners.size() / 3 * 3));
    return corners.size() % 3 == 0;
  }
  for (size_t i = 0; i + 2 < corners.size(); ++i) {
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      const bool odd = (i % 2) == 1;
      triangles.insert(triangles.end(), {corners[i], corners[odd ? i + 2 : i + 1], corners[odd ? i + 1 : i + 2]});
    } else {
      triangles.insert(triangles.end(), {corners[i + 1], corners[i + 2], corners[0]});
    }
  }
  return true;
}

// One line out of tinygltf's multi-line messages.
std::string oneLine(const std::string& text) {
  std::string out;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (line.empty()) continue;
    if (!out.empty()) out += "; ";
    out += line;
  }
  return out;
}

GltfParse parseGltf(std::span<const uint8_t> bytes, const std::string& name, bool binary,
                    const std::optional<std::string>& baseDir, tinygltf::LoadImageDataFunction imageLoader,
                    void* imageUserData, tinygltf::Model& model) {
  GltfParse parse;
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(imageLoader, imageUserData);
  if (!baseDir) {
    tinygltf::FsCallbacks callbacks{noFileExists, sameFilePath, noReadWholeFile, noWriteWholeFile,
                                    nullptr};
    loader.SetFsCallbacks(callbacks);
  }
  std::string err, warn;
  bool loaded = false;
  try {
    const std::string dir = baseDir.value_or("");
    if (binary) {
      loaded = loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), static_cast<unsigned int>(bytes.size()),
                                           dir);
    } else {
      loaded = loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                          static_cast<unsigned int>(bytes.size()), dir);
    }
  } catch (const std::exception& e) {
    parse.setFailure(base::StatusCode::ParseError, std::string("glTF parse error: ") + e.what());
    return parse;
  } catch (...) {
    parse.setFailure(base::StatusCode::ParseError, "glTF parse error");
    return parse;
  }
  if (const std::string w = oneLine(warn); !w.empty()) parse.warnings.push_back(name + ": " + w);
  if (!loaded) {
    const std::string reason = oneLine(err);
    parse.setFailure(base::StatusCode::ParseError, reason.empty() ? "tinygltf could not load the file" : reason);
  }
  return parse;
}

// Extensions that only change materials or textures: geometry can be read without understanding them.
bool geometryNeutral(const std::string& extension) {
  return extension.starts_with("KHR_materials_") || extension.starts_with("KHR_texture_") ||
         extension.starts_with("EXT_texture_") || extension == "KHR_lights_punctual";
}

// ------------------------------------------------------------------------------------------------
// Accessors

bool viewAccessor(const tinygltf::Model& model, int index, AccessorView& view, std::string& reason) {
  if (index < 0 || static_cast<size_t>(index) >= model.accessors.size()) {
    reason = "accessor " + std::to_string(index) + " does not exist";
    return false;
  }
  const tinygltf::Accessor& accessor = model.accessors[static_cast<size_t>(index)];
  const std::string what = "accessor " + std::to_string(index);
  if (accessor.sparse.isSparse) {
    reason = what + " is sparse, which is not supported";
    return false;
  }
  if (accessor.bufferView < 0 || static_cast<size_t>(accessor.bufferView) >= model.bufferViews.size()) {
    reason = what + " has no valid buffer view";
    return false;
  }
  const tinygltf::BufferView& bufferView = model.bufferViews[static_cast<size_t>(accessor.bufferView)];
  if (bufferView.buffer < 0 || static_cast<size_t>(bufferView.buffer) >= model.buffers.size()) {
    reason = what + ": buffer view " + std::to_string(accessor.bufferView) +
             " refers to a missing buffer";
    return false;
  }
  const tinygltf::Buffer& buffer = model.buffers[static_cast<size_t>(bufferView.buffer)];
  const uint64_t viewEnd = uint64_t{bufferView.byteOffset} + bufferView.byteLength;
  if (bufferView.byteOffset > buffer.data.size() || viewEnd > buffer.data.size()) {
    reason = what + ": buffer view " + std::to_string(accessor.bufferView) + " lies outside buffer " +
             std::to_string(bufferView.buffer) + " (" + std::to_string(buffer.data.size()) +
             " bytes loaded)";
    return false;
  }
  const int componentSize = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(accessor.componentType));
  const int components = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(accessor.type));
  if (componentSize <= 0 || components <= 0) {
    reason = what + " has an invalid type or component type";
    return false;
  }
  const uint64_t elementSize = uint64_t(componentSize) * uint64_t(components);
  const uint64_t stride = bufferView.byteStride > 0 ? bufferView.byteStride : elementSize;
  if (stride < elementSize) {
    reason = what + ": byte stride smaller than an element";
    return false;
  }
  if (accessor.count > 0) {
    const uint64_t last = accessor.byteOffset + stride * (uint64_t{accessor.count} - 1) + elementSize;
    if (accessor.count > bufferView.byteLength || accessor.byteOffset > bufferView.byteLength ||
        last > bufferView.byteLength) {
      reason = what + " reads past the end of buffer view " + std::to_string(accessor.bufferView);
      return false;
    }
  }
  view.data = buffer.data.data() + bufferView.byteOffset + accessor.byteOffset;
  view.count = accessor.count;
  view.stride = static_cast<size_t>(stride);
  view.componentType = accessor.componentType;
  view.components = components;
  view.normalized = accessor.normalized;
  return true;
}

// Component c of element i as a double (normalized integers mapped to [0, 1] or [-1, 1]).
// glTF data is little-endian, as is every platform the engine builds for.
double component(const AccessorView& view, size_t i, int c) {
  const uint8_t* p = view.data + i * view.stride;
  switch (view.componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float v;
      std::memcpy(&v, p + 4 * c, 4);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      const double v = p[c];
      return view.normalized ? v / 255.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const double v = static_cast<int8_t>(p[c]);
      return view.normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p + 2 * c, 2);
      return view.normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v;
      std::memcpy(&v, p + 2 * c, 2);
      return view.normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t v;
      std::memcpy(&v, p + 4 * c, 4);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_INT: {
      int32_t v;
      std::memcpy(&v, p + 4 * c, 4);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_DOUBLE: {
      double v;
      std::memcpy(&v, p + 8 * c, 8);
      return v;
    }
    default: return 0.0;
  }
}

glm::dmat4 localMatrix(const tinygltf::Node& node) {
  if (node.matrix.size() == 16) {
    glm::dmat4 m(1.0);
    for (int c = 0; c < 4; ++c) {
      for (int r = 0; r < 4; ++r) m[c][r] = node.matrix[static_cast<size_t>(c * 4 + r)];
    }
    return m;
  }
  glm::dmat4 t(1.0), r(1.0), s(1.0);
  if (node.translation.size() == 3) {
    t = glm::translate(glm::dmat4(1.0),
                       glm::dvec3(node.translation[0], node.translation[1], node.translation[2]));
  }
  if (node.rotation.size() == 4) {
    const glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
    const double length = glm::length(q);
    if (length > 0.0 && std::isfinite(length)) r = glm::mat4_cast(q / length);
    else r = glm::dmat4(std::numeric_limits<double>::quiet_NaN());
  }
  if (node.scale.size() == 3) {
    s = glm::scale(glm::dmat4(1.0), glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
  }
  return t * r * s;
}

namespace {

struct MergeState {
  MergeState(geometry::MeshData& m, std::vector<std::string>& w, const std::string& n)
      : mesh(m), warnings(w), name(n) {}
  geometry::MeshData& mesh;
  std::vector<std::string>& warnings;
  const std::string& name;
  bool allNormals = true;
  bool anyUv = false;
  uint64_t elementBudget = 0;  // vertices + indices still allowed
  bool usesDefaultMaterial = false;
  bool degenerateNormal = false;  // a zero or non-finite normal: normals are dropped
  // Primitives of one node that use the same attribute accessors share one block of vertices, so a
  // mesh split into primitives per material stays connected by index (and GLB round trips exactly).
  uint64_t nodeVisit = 0;
  struct Shared {
    uint64_t nodeVisit = UINT64_MAX;
    int position = -1, normal = -1, uv = -1;
    size_t base = 0;
  } lastBlock;
};

// The accessors of POSITION, NORMAL and TEXCOORD_0 (the first three rows of the attribute table),
// each checked against what it accepts as soon as it is viewed; accessor -1 for one that is absent.
struct StaticViews {
  AccessorView views[3];
  int accessors[3] = {-1, -1, -1};
  const AccessorView& operator[](VertexField f) const { return views[size_t(f)]; }
  bool has(VertexField f) const { return accessors[size_t(f)] >= 0; }
};

bool viewStaticAttributes(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                          const std::string& where, StaticViews& v, std::string& reason) {
  for (size_t a = 0; a < 3; ++a) {
    const GltfAttribute& attribute = kGltfAttributes[a];
    if (!viewAttribute(model, primitive, attribute, v.views[a], v.accessors[a], reason)) {
      reason = where + reason;
      return false;
    }
    if (attribute.field == VertexField::Positions && v.accessors[a] < 0) {
      reason = where + "has no POSITION attribute";
      return false;
    }
    if (v.accessors[a] >= 0 && !attributeFits(attribute, v.views[a], v.views[0].count)) {
      reason = where + attribute.requirement;
      return false;
    }
  }
  return true;
}

// The triangles of a primitive of n vertices (its indices or 0..n-1, by its mode).
bool staticTriangles(const tinygltf::Model& model, const tinygltf::Primitive& primitive, int mode,
                     size_t n, const std::string& where, MergeState& state,
                     std::vector<uint32_t>& triangles, std::string& reason) {
  std::vector<uint32_t> corners;
  CornerFailure failure;
  if (!primitiveCorners(model, primitive, n, corners, failure)) {
    switch (failure.kind) {
      case CornerFailure::View:
        reason = where + failure.reason;
        break;
      case CornerFailure::Type:
        reason = where + "indices must be unsigned byte, short or int scalars";
        break;
      case CornerFailure::Range:
        reason = where + "index " + std::to_string(failure.index) + " out of range (" +
                 std::to_string(n) + " vertices)";
        break;
      case CornerFailure::TooManyVertices:
        reason = where + "too many vertices";
        break;
    }
    return false;
  }
  if (!trianglesOfPrimitive(mode, corners, triangles)) {
    state.warnings.push_back(state.name + ": " + where +
                             "index count not a multiple of 3; the last partial triangle is ignored");
  }
  return true;
}

// Appends the vertices: positions by `transform`, normals by its normal matrix (zero, and the
// mesh's normals dropped, when one is degenerate), uv0 (zero when absent).
void appendStaticVertices(const StaticViews& v, const glm::dmat4& transform, MergeState& state) {
  geometry::MeshData& mesh = state.mesh;
  const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(transform)));
  const AccessorView &positions = v[VertexField::Positions], &normals = v[VertexField::Normals],
                     &uvs = v[VertexField::Uv0];
  for (size_t i = 0; i < positions.count; ++i) {
    const glm::dvec4 p = transform * glm::dvec4(component(positions, i, 0), component(positions, i, 1),
                                                component(positions, i, 2), 1.0);
    mesh.positions.emplace_back(p);
    glm::vec3 n(0.f);
    if (v.has(VertexField::Normals)) {
      const glm::dvec3 transformed = normalMatrix * glm::dvec3(component(normals, i, 0),
                                                               component(normals, i, 1),
                                                               component(normals, i, 2));
      const double length = glm::length(transformed);
      if (length > 0.0 && std::isfinite(length)) n = glm::vec3(transformed / length);
      else state.degenerateNormal = true;
    }
    mesh.normals.push_back(n);
    mesh.uv0.push_back(v.has(VertexField::Uv0)
                           ? glm::vec2(component(uvs, i, 0), component(uvs, i, 1))
                           : glm::vec2(0.f));
  }
}

// The material id of a primitive: its material, or the default material after the file's.
bool staticMaterial(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                    const std::string& where, MergeState& state, uint32_t& materialId,
                    std::string& reason) {
  if (primitive.material < 0) {
    materialId = static_cast<uint32_t>(model.materials.size());
    state.usesDefaultMaterial = true;
    return true;
  }
  if (static_cast<size_t>(primitive.material) >= model.materials.size()) {
    reason = where + "material " + std::to_string(primitive.material) + " does not exist";
    return false;
  }
  materialId = static_cast<uint32_t>(primitive.material);
  return true;
}

bool appendPrimitive(const tinygltf::Model& model, size_t meshIndex, size_t primitiveIndex,
                     const glm::dmat4& transform, MergeState& state, std::string& reason) {
  const tinygltf::Primitive& primitive = model.meshes[meshIndex].primitives[primitiveIndex];
  const std::string where =
      "mesh " + std::to_string(meshIndex) + " primitive " + std::to_string(primitiveIndex) + ": ";
  if (usesDraco(primitive)) {
    reason = where + "uses KHR_draco_mesh_compression, which is not supported";
    return false;
  }
  int mode = 0;
  if (!triangleMode(primitive, mode)) {
    state.warnings.push_back(state.name + ": " + where + "mode " + std::to_string(mode) +
                             " (points or lines) skipped");
    return true;
  }
  StaticViews views;
  if (!viewStaticAttributes(model, primitive, where, views, reason)) return false;
  const size_t count = views[VertexField::Positions].count;
  std::vector<uint32_t> triangles;
  if (!staticTriangles(model, primitive, mode, count, where, state, triangles, reason))
    return false;
  if (triangles.empty()) return true;

  const MergeState::Shared& last = state.lastBlock;
  const int position = views.accessors[0], normal = views.accessors[1], uv = views.accessors[2];
  const bool reuse = last.nodeVisit == state.nodeVisit && last.position == position &&
                     last.normal == normal && last.uv == uv;
  const uint64_t elements = (reuse ? 0 : uint64_t{count}) + triangles.size();
  if (elements > state.elementBudget) {
    reason = "the scene instantiates more geometry than the file size allows";
    return false;
  }
  state.elementBudget -= elements;

  geometry::MeshData& mesh = state.mesh;
  const size_t base = reuse ? last.base : mesh.positions.size();
  if (base + count > UINT32_MAX) {
    reason = "too many vertices";
    return false;
  }
  if (!reuse) {
    state.lastBlock = {state.nodeVisit, position, normal, uv, base};
    appendStaticVertices(views, transform, state);
  }
  state.allNormals = state.allNormals && views.has(VertexField::Normals);
  state.anyUv = state.anyUv || views.has(VertexField::Uv0);

  uint32_t materialId = 0;
  if (!staticMaterial(model, primitive, where, state, materialId, reason)) return false;
  if (mesh.submeshes.empty() || mesh.submeshes.back().materialId != materialId) {
    mesh.submeshes.push_back(
        geometry::SubMesh{static_cast<uint32_t>(mesh.indices.size()), 0, materialId});
  }
  appendTriangles(triangles, base, glm::determinant(glm::dmat3(transform)) < 0.0, mesh.indices);
  mesh.submeshes.back().indexCount =
      static_cast<uint32_t>(mesh.indices.size()) - mesh.submeshes.back().firstIndex;
  return true;
}

// Roots: the default scene, else the first scene, else every node that is nobody's child.
bool sceneRoots(const tinygltf::Model& model, std::vector<int>& roots, std::string& reason) {
  if (!model.scenes.empty()) {
    const int sceneIndex = model.defaultScene < 0 ? 0 : model.defaultScene;
    if (static_cast<size_t>(sceneIndex) >= model.scenes.size()) {
      reason = "default scene " + std::to_string(sceneIndex) + " does not exist";
      return false;
    }
    roots = model.scenes[static_cast<size_t>(sceneIndex)].nodes;
    return true;
  }
  std::vector<uint8_t> isChild(model.nodes.size(), 0);
  for (const tinygltf::Node& node : model.nodes) {
    for (int child : node.children) {
      if (child >= 0 && static_cast<size_t>(child) < model.nodes.size())
        isChild[static_cast<size_t>(child)] = 1;
    }
  }
  for (size_t i = 0; i < model.nodes.size(); ++i) {
    if (!isChild[i]) roots.push_back(static_cast<int>(i));
  }
  return true;
}

// The primitives of node `nodeIndex`'s mesh into the merged mesh. A skinned mesh is placed by its
// joints only (the glTF rule); read statically it is the bind pose, so its node transform is not
// applied.
bool mergeNodeMesh(const tinygltf::Model& model, size_t nodeIndex, const glm::dmat4& world,
                   MergeState& state, std::string& reason, bool& primitiveFailed) {
  const tinygltf::Node& node = model.nodes[nodeIndex];
  if (node.mesh < 0) return true;
  if (static_cast<size_t>(node.mesh) >= model.meshes.size()) {
    reason = "node " + std::to_string(nodeIndex) + " refers to missing mesh " +
             std::to_string(node.mesh);
    return false;
  }
  const glm::dmat4 transform = node.skin >= 0 ? glm::dmat4(1.0) : world;
  const tinygltf::Mesh& mesh = model.meshes[static_cast<size_t>(node.mesh)];
  for (size_t p = 0; p < mesh.primitives.size(); ++p) {
    if (!appendPrimitive(model, static_cast<size_t>(node.mesh), p, transform, state, reason)) {
      primitiveFailed = true;
      return false;
    }
  }
  return true;
}

// Depth-first over the node tree with an explicit stack; a node reached twice means a cycle or a
// node with two parents, both invalid glTF. `primitiveFailed` tells a primitive's failure (which
// keeps the warnings so far) from a node's.
bool mergeNodes(const tinygltf::Model& model, const std::vector<int>& roots, MergeState& state,
                std::string& reason, bool& primitiveFailed) {
  std::vector<uint8_t> visited(model.nodes.size(), 0);
  struct Item {
    int node;
    glm::dmat4 parent;
  };
  std::vector<Item> stack;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, glm::dmat4(1.0)});
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    if (item.node < 0 || static_cast<size_t>(item.node) >= model.nodes.size()) {
      reason = "node " + std::to_string(item.node) + " does not exist";
      return false;
    }
    const size_t nodeIndex = static_cast<size_t>(item.node);
    if (visited[nodeIndex]) {
      reason = "node " + std::to_string(item.node) +
               " is reached twice from the scene (a cycle or a shared child)";
      return false;
    }
    visited[nodeIndex] = 1;
    ++state.nodeVisit;
    const tinygltf::Node& node = model.nodes[nodeIndex];
    const glm::dmat4 world = item.parent * localMatrix(node);
    if (!mergeNodeMesh(model, nodeIndex, world, state, reason, primitiveFailed)) return false;
    for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) {
      stack.push_back({*it, world});
    }
  }
  return true;
}

}  // namespace

MeshReadResult readGltf(std::span<const uint8_t> bytes, const std::string& name, bool binary,
                        const std::optional<std::string>& baseDir) {
  if (bytes.size() > UINT32_MAX) return failure(name, "file too large for glTF");
  tinygltf::Model model;
  const GltfParse parse = parseGltf(bytes, name, binary, baseDir, skipImage, nullptr, model);
  if (!parse.ok()) {
    MeshReadResult result = failure(name, parse.message);
    result.warnings = parse.warnings;
    return result;
  }
  std::vector<std::string> warnings = parse.warnings;
  for (const std::string& extension : model.extensionsRequired) {
    if (geometryNeutral(extension)) continue;
    return failure(name, "requires the glTF extension " + extension + ", which is not supported");
  }

  std::vector<int> roots;
  std::string reason;
  if (!sceneRoots(model, roots, reason)) return failure(name, reason);

  MeshReadResult result;
  result.warnings = std::move(warnings);
  MergeState state(result.mesh, result.warnings, name);
  state.elementBudget = (uint64_t{1} << 24) + 64 * uint64_t{bytes.size()};
  for (const tinygltf::Buffer& buffer : model.buffers) state.elementBudget += buffer.data.size();
  bool primitiveFailed = false;
  if (!mergeNodes(model, roots, state, reason, primitiveFailed)) {
    MeshReadResult failed = failure(name, reason);
    if (primitiveFailed) failed.warnings = std::move(result.warnings);
    return failed;
  }

  geometry::MeshData& mesh = result.mesh;
  if (state.allNormals && state.degenerateNormal) {
    result.warnings.push_back(name + ": a normal has zero length or is not finite; normals dropped");
  }
  if (!state.allNormals || state.degenerateNormal) mesh.normals.clear();
  if (!state.anyUv) mesh.uv0.clear();
  for (size_t i = 0; i < model.materials.size(); ++i) {
    const std::string& materialName = model.materials[i].name;
    result.materialNames.push_back(materialName.empty() ? "material_" + std::to_string(i) : materialName);
  }
  if (state.usesDefaultMaterial) result.materialNames.push_back("default");
  if (mesh.indices.empty()) {
    MeshReadResult failed = failure(name, "the default scene has no triangle mesh");
    failed.warnings = std::move(result.warnings);
    return failed;
  }
  return finish(std::move(result), name);
}

}  // namespace cleave::assets::detail

namespace cleave::assets {

// ------------------------------------------------------------------------------------------------
// GLB writer: the skin-less case of the GLB writing core (glb_builder.h) that the skinned writer
// uses too.

MeshWriteResult writeGlbToMemory(const geometry::MeshData& mesh, const MeshWriteOptions& options,
                                 std::vector<uint8_t>& out) {
  MeshWriteResult result;
  std::vector<geometry::SubMesh> runs;
  std::string reason;
  if (!detail::glbRuns(mesh, runs, reason)) {
    result.setFailure(base::StatusCode::InvalidArgument, "GLB: " + reason);
    return result;
  }
  tinygltf::Model model = detail::newGlbModel();
  const detail::GlbAttributes attributes = detail::addVertexAttributes(model, mesh, options);
  detail::addMesh(model, mesh, runs, attributes, options, detail::GlbColors::Omit);
  detail::addMeshScene(model, {}, -1);
  if (!detail::serialiseGlb(model, out)) {
    result.setFailure(base::StatusCode::InvalidArgument, "GLB: tinygltf could not serialise the mesh");
    return result;
  }
  result.code = base::StatusCode::Ok;
  return result;
}

MeshWriteResult writeGlb(const std::string& path, const geometry::MeshData& mesh,
                         const MeshWriteOptions& options) {
  std::vector<uint8_t> bytes;
  MeshWriteResult result = writeGlbToMemory(mesh, options, bytes);
  return detail::saveSerialised(path, std::move(result), bytes);
}

}  // namespace cleave::assets
