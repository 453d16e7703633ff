// SPDX-License-Identifier: MIT
// Wavefront OBJ reader: v (optionally with r g b), vt, vn, f with any polygon size (triangulated)
// and 1-based or negative (relative) indices, usemtl as material runs. Corners with the same
// v/vt/vn triple become one vertex, so a closed OBJ stays closed by index where its seams allow.
#include <cmath>
#include <unordered_map>

#include "cleave/assets/line_scanner.h"
#include "cleave/assets/mesh_finish.h"
#include "cleave/assets/mesh_reader.h"
#include "cleave/assets/polygon_triangulator.h"

namespace cleave::assets::detail {

namespace {

constexpr uint32_t kAbsent = UINT32_MAX;

struct Corner {
  uint32_t v = kAbsent;
  uint32_t t = kAbsent;
  uint32_t n = kAbsent;
  bool operator==(const Corner&) const = default;
};

struct CornerHash {
  size_t operator()(const Corner& c) const {
    uint64_t h = c.v;
    h = h * 0x9E3779B97F4A7C15ull ^ c.t;
    h = h * 0x9E3779B97F4A7C15ull ^ c.n;
    return static_cast<size_t>(h ^ (h >> 29));
  }
};

// Resolves one OBJ index (1-based, or negative = relative to the end) against `count` elements.
bool resolveIndex(std::string_view token, size_t count, uint32_t& index, std::string& reason) {
  int64_t value = 0;
  if (!parseInt64(token, value)) {
    reason = "bad index " + quoted(token);
    return false;
  }
  int64_t resolved = -1;
  if (value > 0)
    resolved = value - 1;
  else if (value < 0)
    resolved = static_cast<int64_t>(count) + value;
  else {
    reason = "index 0 is not valid (OBJ indices start at 1)";
    return false;
  }
  if (resolved < 0 || resolved >= static_cast<int64_t>(count)) {
    reason = "index " + std::string(token) + " out of range (" + std::to_string(count) +
             " defined so far)";
    return false;
  }
  index = static_cast<uint32_t>(resolved);
  return true;
}

// One pass over the lines of an OBJ file. Each line handler returns the reason of a failure on
// that line, empty when the line is good.
class ObjReader {
 public:
  ObjReader(std::string_view text, const std::string& name) : scanner_(text, '#'), name_(name) {}

  MeshReadResult read() {
    while (scanner_.nextLine()) {
      const std::string reason = readLine(scanner_.nextToken());
      if (!reason.empty()) return failureAt(name_, scanner_.lineNumber(), reason);
    }
    if (vertices_.empty()) return failure(name_, "no faces in the file");
    build();
    return finish(std::move(result_), name_);
  }

 private:
  std::string readLine(std::string_view keyword) {
    if (keyword == "v") return vertex();
    if (keyword == "vt") return texcoord();
    if (keyword == "vn") return normal();
    if (keyword == "f" || keyword == "fo") return face();
    if (keyword == "usemtl") {
      const std::string_view materialName = scanner_.rest();
      currentMaterial_ =
          materialId(materialName.empty() ? std::string_view("default") : materialName);
    }
    // Everything else (o, g, s, l, p, mtllib, vp, curves, ...) does not change the triangle mesh.
    return {};
  }

  std::string vertex() {
    float values[7];
    int count = 0;
    for (std::string_view token = scanner_.nextToken(); !token.empty() && count < 7;
         token = scanner_.nextToken()) {
      if (!parseFloat(token, values[count])) return "bad number " + quoted(token);
      ++count;
    }
    if (count < 3) return "a vertex needs 3 coordinates";
    positions_.emplace_back(values[0], values[1], values[2]);
    // `v x y z r g b` (a common extension); 7 values means x y z w r g b is not standard, so only
    // the 6-value form is read as a colour.
    if (count == 6)
      vertexColors_.emplace_back(values[3], values[4], values[5], 1.f);
    else
      allColored_ = false;
    return {};
  }

  std::string texcoord() {
    float u = 0.f, v = 0.f;
    const std::string_view tu = scanner_.nextToken();
    const std::string_view tv = scanner_.nextToken();
    if (!parseFloat(tu, u) || (!tv.empty() && !parseFloat(tv, v))) return "bad texture coordinate";
    texcoords_.emplace_back(u, v);
    return {};
  }

  std::string normal() {
    float n[3];
    std::string_view bad;
    if (!scanner_.nextFloats(n, bad)) return "bad normal " + quoted(bad);
    normals_.emplace_back(n[0], n[1], n[2]);
    return {};
  }

  // "v", "v/t", "v//n" or "v/t/n".
  std::string corner(std::string_view token, Corner& c) {
    std::string reason;
    const size_t slash1 = token.find('/');
    if (!resolveIndex(token.substr(0, slash1), positions_.size(), c.v, reason)) {
      return "vertex " + reason;
    }
    if (slash1 == std::string_view::npos) return {};
    const std::string_view afterV = token.substr(slash1 + 1);
    const size_t slash2 = afterV.find('/');
    const std::string_view tToken = afterV.substr(0, slash2);
    if (!tToken.empty() && !resolveIndex(tToken, texcoords_.size(), c.t, reason)) {
      return "texture coordinate " + reason;
    }
    if (slash2 == std::string_view::npos) return {};
    const std::string_view nToken = afterV.substr(slash2 + 1);
    if (!nToken.empty() && !resolveIndex(nToken, normals_.size(), c.n, reason)) {
      return "normal " + reason;
    }
    return {};
  }

  std::string face() {
    face_.clear();
    facePositions_.clear();
    for (std::string_view token = scanner_.nextToken(); !token.empty();
         token = scanner_.nextToken()) {
      Corner c;
      const std::string reason = corner(token, c);
      if (!reason.empty()) return reason;
      anyUv_ = anyUv_ || c.t != kAbsent;
      allNormals_ = allNormals_ && c.n != kAbsent;
      auto [it, inserted] = cornerIds_.try_emplace(c, static_cast<uint32_t>(vertices_.size()));
      if (inserted) vertices_.push_back(c);
      face_.push_back(it->second);
      facePositions_.push_back(positions_[c.v]);
    }
    if (face_.size() < 3) return "a face needs at least 3 corners";
    if (currentMaterial_ < 0) currentMaterial_ = materialId("default");
    geometry::MeshData& mesh = result_.mesh;
    const uint32_t material = static_cast<uint32_t>(currentMaterial_);
    if (mesh.submeshes.empty() || mesh.submeshes.back().materialId != material) {
      mesh.submeshes.push_back(
          geometry::SubMesh{static_cast<uint32_t>(mesh.indices.size()), 0, material});
    }
    faces_.append(face_, facePositions_, mesh.indices);
    mesh.submeshes.back().indexCount =
        static_cast<uint32_t>(mesh.indices.size()) - mesh.submeshes.back().firstIndex;
    return {};
  }

  int64_t materialId(std::string_view materialName) {
    std::vector<std::string>& materials = result_.materialNames;
    for (size_t i = 0; i < materials.size(); ++i) {
      if (materials[i] == materialName) return static_cast<int64_t>(i);
    }
    materials.emplace_back(materialName);
    return static_cast<int64_t>(materials.size() - 1);
  }

  // One mesh vertex per unique corner, in order of first use.
  void build() {
    geometry::MeshData& mesh = result_.mesh;
    mesh.positions.reserve(vertices_.size());
    for (const Corner& c : vertices_) mesh.positions.push_back(positions_[c.v]);
    if (allColored_ && vertexColors_.size() == positions_.size()) {
      mesh.colors.reserve(vertices_.size());
      for (const Corner& c : vertices_) mesh.colors.push_back(vertexColors_[c.v]);
    }
    if (anyUv_) {
      mesh.uv0.reserve(vertices_.size());
      for (const Corner& c : vertices_) {
        mesh.uv0.push_back(c.t == kAbsent ? glm::vec2(0.f) : texcoords_[c.t]);
      }
    }
    if (allNormals_) {
      mesh.normals.reserve(vertices_.size());
      for (const Corner& c : vertices_) mesh.normals.push_back(normals_[c.n]);
      normalizeNormals(result_, name_);
    }
  }

  LineScanner scanner_;
  const std::string& name_;
  std::vector<glm::vec3> positions_;
  std::vector<glm::vec4> vertexColors_;  // one per position when every `v` line has r g b
  bool allColored_ = true;
  std::vector<glm::vec2> texcoords_;
  std::vector<glm::vec3> normals_;
  std::vector<Corner> vertices_;  // unique corners in order of first use
  std::unordered_map<Corner, uint32_t, CornerHash> cornerIds_;
  MeshReadResult result_;
  int64_t currentMaterial_ = -1;
  bool anyUv_ = false;
  bool allNormals_ = true;
  std::vector<uint32_t> face_;
  std::vector<glm::vec3> facePositions_;
  PolygonTriangulator faces_;
};

}  // namespace

MeshReadResult readObj(std::span<const uint8_t> bytes, const std::string& name) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  return ObjReader(text, name).read();
}

}  // namespace cleave::assets::detail
