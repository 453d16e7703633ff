// SPDX-License-Identifier: MIT
// Wavefront OBJ reader: v (optionally with r g b), vt, vn, f with any polygon size (triangulated)
// and 1-based or negative (relative) indices, usemtl as material runs. Corners with the same
// v/vt/vn triple become one vertex, so a closed OBJ stays closed by index where its seams allow.
#include <cmath>
#include <unordered_map>

#include "cleave/assets/mesh_reader.h"

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
  if (value > 0) resolved = value - 1;
  else if (value < 0) resolved = static_cast<int64_t>(count) + value;
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

}  // namespace

MeshReadResult readObj(std::span<const uint8_t> bytes, const std::string& name) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  LineScanner scanner(text, '#');

  std::vector<glm::vec3> positions;
  std::vector<glm::vec4> vertexColors;  // one per position when every `v` line has r g b
  bool allColored = true;
  std::vector<glm::vec2> texcoords;
  std::vector<glm::vec3> normals;

  std::vector<Corner> vertices;  // unique corners in order of first use
  std::unordered_map<Corner, uint32_t, CornerHash> cornerIds;
  MeshReadResult result;
  geometry::MeshData& mesh = result.mesh;
  std::vector<std::string>& materials = result.materialNames;
  int64_t currentMaterial = -1;
  bool anyUv = false;
  bool allNormals = true;
  std::vector<uint32_t> face;
  std::vector<glm::vec3> facePositions;
  PolygonTriangulator faces;

  auto materialId = [&](std::string_view materialName) {
    for (size_t i = 0; i < materials.size(); ++i) {
      if (materials[i] == materialName) return static_cast<int64_t>(i);
    }
    materials.emplace_back(materialName);
    return static_cast<int64_t>(materials.size() - 1);
  };

  while (scanner.nextLine()) {
    const std::string_view keyword = scanner.nextToken();
    if (keyword.empty()) continue;
    if (keyword == "v") {
      float values[7];
      int count = 0;
      for (std::string_view token = scanner.nextToken(); !token.empty();
           token = scanner.nextToken()) {
        if (count == 7) break;
        if (!parseFloat(token, values[count])) {
          return failureAt(name, scanner.lineNumber(), "bad number " + quoted(token));
        }
        ++count;
      }
      if (count < 3) {
        return failureAt(name, scanner.lineNumber(), "a vertex needs 3 coordinates");
      }
      positions.emplace_back(values[0], values[1], values[2]);
      if (count == 6 || count == 7) {
        // `v x y z r g b` (a common extension); 7 values means x y z w r g b is not standard, so
        // only the 6-value form is read as a colour.
        if (count == 6) vertexColors.emplace_back(values[3], values[4], values[5], 1.f);
        else allColored = false;
      } else {
        allColored = false;
      }
    } else if (keyword == "vt") {
      float u = 0.f, v = 0.f;
      const std::string_view tu = scanner.nextToken();
      const std::string_view tv = scanner.nextToken();
      if (!parseFloat(tu, u) || (!tv.empty() && !parseFloat(tv, v))) {
        return failureAt(name, scanner.lineNumber(), "bad texture coordinate");
      }
      texcoords.emplace_back(u, v);
    } else if (keyword == "vn") {
      float n[3];
      for (float& value : n) {
        const std::string_view token = scanner.nextToken();
        if (!parseFloat(token, value)) {
          return failureAt(name, scanner.lineNumber(), "bad normal " + quoted(token));
        }
      }
      normals.emplace_back(n[0], n[1], n[2]);
    } else if (keyword == "f" || keyword == "fo") {
      face.clear();
      facePositions.clear();
      for (std::string_view token = scanner.nextToken(); !token.empty();
           token = scanner.nextToken()) {
        Corner corner;
        std::string reason;
        const size_t slash1 = token.find('/');
        const std::string_view vToken = token.substr(0, slash1);
        if (!resolveIndex(vToken, positions.size(), corner.v, reason)) {
          return failureAt(name, scanner.lineNumber(), "vertex " + reason);
        }
        if (slash1 != std::string_view::npos) {
          const std::string_view afterV = token.substr(slash1 + 1);
          const size_t slash2 = afterV.find('/');
          const std::string_view tToken = afterV.substr(0, slash2);
          if (!tToken.empty() && !resolveIndex(tToken, texcoords.size(), corner.t, reason)) {
            return failureAt(name, scanner.lineNumber(), "texture coordinate " + reason);
          }
          if (slash2 != std::string_view::npos) {
            const std::string_view nToken = afterV.substr(slash2 + 1);
            if (!nToken.empty() && !resolveIndex(nToken, normals.size(), corner.n, reason)) {
              return failureAt(name, scanner.lineNumber(), "normal " + reason);
            }
          }
        }
        anyUv = anyUv || corner.t != kAbsent;
        allNormals = allNormals && corner.n != kAbsent;
        auto [it, inserted] = cornerIds.try_emplace(corner, static_cast<uint32_t>(vertices.size()));
        if (inserted) vertices.push_back(corner);
        face.push_back(it->second);
        facePositions.push_back(positions[corner.v]);
      }
      if (face.size() < 3) {
        return failureAt(name, scanner.lineNumber(), "a face needs at least 3 corners");
      }
      if (currentMaterial < 0) currentMaterial = materialId("default");
      const uint32_t material = static_cast<uint32_t>(currentMaterial);
      if (mesh.submeshes.empty() || mesh.submeshes.back().materialId != material) {
        mesh.submeshes.push_back(
            geometry::SubMesh{static_cast<uint32_t>(mesh.indices.size()), 0, material});
      }
      faces.append(face, facePositions, mesh.indices);
      mesh.submeshes.back().indexCount =
          static_cast<uint32_t>(mesh.indices.size()) - mesh.submeshes.back().firstIndex;
    } else if (keyword == "usemtl") {
      const std::string_view materialName = scanner.rest();
      currentMaterial = materialId(materialName.empty() ? std::string_view("default") : materialName);
    }
    // Everything else (o, g, s, l, p, mtllib, vp, curves, ...) does not change the triangle mesh.
  }

  if (vertices.empty()) return failure(name, "no faces in the file");

  mesh.positions.reserve(vertices.size());
  for (const Corner& c : vertices) mesh.positions.push_back(positions[c.v]);
  if (allColored && vertexColors.size() == positions.size()) {
    mesh.colors.reserve(vertices.size());
    for (const Corner& c : vertices) mesh.colors.push_back(vertexColors[c.v]);
  }
  if (anyUv) {
    mesh.uv0.reserve(vertices.size());
    for (const Corner& c : vertices) {
      mesh.uv0.push_back(c.t == kAbsent ? glm::vec2(0.f) : texcoords[c.t]);
    }
  }
  if (allNormals) {
    mesh.normals.reserve(vertices.size());
    bool degenerate = false;
    for (const Corner& c : vertices) {
      const glm::vec3 n = normals[c.n];
      const float length = glm::length(n);
      if (!(length > 0.f) || !std::isfinite(length)) degenerate = true;
      mesh.normals.push_back(degenerate ? n : n / length);
    }
    if (degenerate) {
      mesh.normals.clear();
      result.warnings.push_back(name + ": a normal has zero length or is not finite; normals dropped");
    }
  }
  return finish(std::move(result), name);
}

}  // namespace cleave::assets::detail
