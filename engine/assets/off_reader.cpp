// SPDX-License-Identifier: MIT
// Geomview OFF reader: the optional header "[ST][C][N]OFF", counts "vertices faces edges", one vertex
// per line (x y z, then nx ny nz with N, a colour with C, s t with ST), one polygon per line
// ("n i0 ... i(n-1)" with 0-based indices, an optional colour after it is ignored).
#include <cmath>

#include "cleave/assets/mesh_reader.h"

namespace cleave::assets::detail {

namespace {

struct OffHeader {
  bool normals = false;
  bool colors = false;
  bool texcoords = false;
};

// Parses "[ST][C][N]OFF"; false when the token is not an OFF keyword.
bool parseKeyword(std::string_view token, OffHeader& header, std::string& reason) {
  if (token.size() < 3 || token.substr(token.size() - 3) != "OFF") return false;
  std::string_view prefix = token.substr(0, token.size() - 3);
  if (prefix.starts_with("ST")) {
    header.texcoords = true;
    prefix.remove_prefix(2);
  }
  if (prefix.starts_with("C")) {
    header.colors = true;
    prefix.remove_prefix(1);
  }
  if (prefix.starts_with("N")) {
    header.normals = true;
    prefix.remove_prefix(1);
  }
  if (!prefix.empty()) {
    reason = "unsupported OFF variant " + quoted(token) + " (4D and n-dimensional OFF are not read)";
  }
  return true;
}

}  // namespace

MeshReadResult readOff(std::span<const uint8_t> bytes, const std::string& name) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  LineScanner scanner(text, '#');

  // The next token, moving over line ends, empty lines and comments. Empty at the end of the text.
  auto nextAnyLine = [&scanner]() -> std::string_view {
    for (;;) {
      const std::string_view token = scanner.nextToken();
      if (!token.empty()) return token;
      if (!scanner.nextLine()) return {};
    }
  };
  // Moves to the next line that has a token; false at the end.
  auto nextDataLine = [&scanner]() -> bool {
    while (scanner.nextLine()) {
      if (!scanner.rest().empty()) return true;
    }
    return false;
  };

  if (!scanner.nextLine()) return failure(name, "empty file");
  OffHeader header;
  std::string_view token = nextAnyLine();
  std::string reason;
  if (parseKeyword(token, header, reason)) {
    if (!reason.empty()) return failureAt(name, scanner.lineNumber(), reason);
    token = nextAnyLine();
  }
  int64_t counts[3] = {0, 0, 0};
  for (int i = 0; i < 3; ++i) {
    if (i > 0) token = nextAnyLine();
    if (token.empty()) return failureAt(name, scanner.lineNumber(), "missing vertex/face/edge counts");
    if (!parseInt64(token, counts[i]) || counts[i] < 0) {
      return failureAt(name, scanner.lineNumber(), "bad count " + quoted(token));
    }
  }
  const int64_t vertexCount = counts[0];
  const int64_t faceCount = counts[1];
  // Each vertex line needs at least 5 bytes ("0 0 0") and each face at least 7 ("3 0 1 2").
  const int64_t remaining = static_cast<int64_t>(text.size() - scanner.offset()) + 1;
  if (vertexCount > remaining / 5 || faceCount > remaining / 7 ||
      vertexCount * 5 + faceCount * 7 > remaining + 2) {
    return failureAt(name, scanner.lineNumber(),
                     "counts (" + std::to_string(vertexCount) + " vertices, " +
                         std::to_string(faceCount) + " faces) exceed what the file can hold");
  }
  if (vertexCount > UINT32_MAX / 2) return failure(name, "too many vertices");

  MeshReadResult result;
  geometry::MeshData& mesh = result.mesh;
  mesh.positions.reserve(static_cast<size_t>(vertexCount));
  std::vector<std::string_view> extra;
  for (int64_t i = 0; i < vertexCount; ++i) {
    if (!nextDataLine()) {
      return failure(name, "file ends after " + std::to_string(i) + " of " +
                               std::to_string(vertexCount) + " vertices");
    }
    float p[3];
    for (float& value : p) {
      const std::string_view t = scanner.nextToken();
      if (!parseFloat(t, value)) {
        return failureAt(name, scanner.lineNumber(), "bad vertex coordinate " + quoted(t));
      }
    }
    mesh.positions.emplace_back(p[0], p[1], p[2]);
    if (header.normals) {
      float n[3];
      for (float& value : n) {
        const std::string_view t = scanner.nextToken();
        if (!parseFloat(t, value)) {
          return failureAt(name, scanner.lineNumber(), "bad vertex normal " + quoted(t));
        }
      }
      mesh.normals.emplace_back(n[0], n[1], n[2]);
    }
    if (header.colors || header.texcoords) {
      extra.clear();
      for (std::string_view t = scanner.nextToken(); !t.empty() && extra.size() < 8;
           t = scanner.nextToken()) {
        extra.push_back(t);
      }
      if (header.texcoords) {
        if (extra.size() < 2) {
          return failureAt(name, scanner.lineNumber(), "missing texture coordinates");
        }
        glm::vec2 uv;
        if (!parseFloat(extra[extra.size() - 2], uv.x) || !parseFloat(extra.back(), uv.y)) {
          return failureAt(name, scanner.lineNumber(), "bad texture coordinates");
        }
        mesh.uv0.push_back(uv);
        extra.resize(extra.size() - 2);
      }
      if (header.colors) {
        if (extra.size() < 3 || extra.size() > 4) {
          return failureAt(name, scanner.lineNumber(), "a colour needs 3 or 4 values");
        }
        glm::vec4 color(1.f);
        bool integral = true;
        for (size_t k = 0; k < extra.size(); ++k) {
          if (!parseFloat(extra[k], color[static_cast<int>(k)])) {
            return failureAt(name, scanner.lineNumber(), "bad colour " + quoted(extra[k]));
          }
          integral = integral && extra[k].find('.') == std::string_view::npos;
        }
        if (integral) {
          // Integer colours are 0..255.
          for (size_t k = 0; k < extra.size(); ++k) color[static_cast<int>(k)] /= 255.f;
        }
        mesh.colors.push_back(color);
      }
    }
  }

  PolygonTriangulator faces;
  std::vector<uint32_t> polygon;
  std::vector<glm::vec3> cornerPositions;
  for (int64_t f = 0; f < faceCount; ++f) {
    if (!nextDataLine()) {
      return failure(name, "file ends after " + std::to_string(f) + " of " +
                               std::to_string(faceCount) + " faces");
    }
    const std::string_view countToken = scanner.nextToken();
    int64_t corners = 0;
    if (!parseInt64(countToken, corners)) {
      return failureAt(name, scanner.lineNumber(), "bad polygon size " + quoted(countToken));
    }
    if (corners < 3) {
      return failureAt(name, scanner.lineNumber(), "a face needs at least 3 corners");
    }
    polygon.clear();
    cornerPositions.clear();
    for (int64_t k = 0; k < corners; ++k) {
      const std::string_view t = scanner.nextToken();
      int64_t index = 0;
      if (t.empty()) {
        return failureAt(name, scanner.lineNumber(),
                         "face has fewer than the " + std::to_string(corners) + " announced corners");
      }
      if (!parseInt64(t, index)) return failureAt(name, scanner.lineNumber(), "bad index " + quoted(t));
      if (index < 0 || index >= vertexCount) {
        return failureAt(name, scanner.lineNumber(),
                         "index " + std::to_string(index) + " out of range (" +
                             std::to_string(vertexCount) + " vertices)");
      }
      polygon.push_back(static_cast<uint32_t>(index));
      cornerPositions.push_back(mesh.positions[polygon.back()]);
    }
    faces.append(polygon, cornerPositions, mesh.indices);
  }
  if (mesh.normals.size() == mesh.positions.size()) {
    bool degenerate = false;
    for (glm::vec3& n : mesh.normals) {
      const float length = glm::length(n);
      if (length > 0.f && std::isfinite(length)) n /= length;
      else degenerate = true;
    }
    if (degenerate) {
      mesh.normals.clear();
      result.warnings.push_back(name + ": a normal has zero length or is not finite; normals dropped");
    }
  }
  return finish(std::move(result), name);
}

}  // namespace cleave::assets::detail
