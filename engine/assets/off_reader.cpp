// SPDX-License-Identifier: MIT
// Geomview OFF reader: the optional header "[ST][C][N]OFF", counts "vertices faces edges", one vertex
// per line (x y z, then nx ny nz with N, a colour with C, s t with ST), one polygon per line
// ("n i0 ... i(n-1)" with 0-based indices, an optional colour after it is ignored).
#include <cmath>

#include "cleave/assets/line_scanner.h"
#include "cleave/assets/mesh_finish.h"
#include "cleave/assets/mesh_reader.h"
#include "cleave/assets/polygon_triangulator.h"

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
    reason =
        "unsupported OFF variant " + quoted(token) + " (4D and n-dimensional OFF are not read)";
  }
  return true;
}

// Reads a colour of 3 or 4 values; integer colours are 0..255.
std::string parseColor(std::span<const std::string_view> values, glm::vec4& color) {
  if (values.size() < 3 || values.size() > 4) return "a colour needs 3 or 4 values";
  color = glm::vec4(1.f);
  bool integral = true;
  for (size_t k = 0; k < values.size(); ++k) {
    if (!parseFloat(values[k], color[static_cast<int>(k)]))
      return "bad colour " + quoted(values[k]);
    integral = integral && values[k].find('.') == std::string_view::npos;
  }
  if (integral) {
    for (size_t k = 0; k < values.size(); ++k) color[static_cast<int>(k)] /= 255.f;
  }
  return {};
}

class OffReader {
 public:
  OffReader(std::string_view text, const std::string& name)
      : text_(text), scanner_(text, '#'), name_(name) {}

  MeshReadResult read() {
    if (!scanner_.nextLine()) return failure(name_, "empty file");
    std::string reason = header();
    if (!reason.empty()) return failureAt(name_, scanner_.lineNumber(), reason);
    if (vertexCount_ > UINT32_MAX / 2) return failure(name_, "too many vertices");
    result_.mesh.positions.reserve(static_cast<size_t>(vertexCount_));
    for (int64_t i = 0; i < vertexCount_; ++i) {
      if (!scanner_.nextDataLine()) return endsAfter(i, vertexCount_, "vertices");
      reason = vertex();
      if (!reason.empty()) return failureAt(name_, scanner_.lineNumber(), reason);
    }
    for (int64_t f = 0; f < faceCount_; ++f) {
      if (!scanner_.nextDataLine()) return endsAfter(f, faceCount_, "faces");
      reason = face();
      if (!reason.empty()) return failureAt(name_, scanner_.lineNumber(), reason);
    }
    if (!result_.mesh.normals.empty()) normalizeNormals(result_, name_);
    return finish(std::move(result_), name_);
  }

 private:
  MeshReadResult endsAfter(int64_t done, int64_t count, const char* what) const {
    return failure(name_, "file ends after " + std::to_string(done) + " of " +
                              std::to_string(count) + " " + what);
  }

  // The optional keyword and the three counts, checked against the bytes that follow them.
  std::string header() {
    std::string_view token = scanner_.nextTokenAnyLine();
    std::string reason;
    if (parseKeyword(token, header_, reason)) {
      if (!reason.empty()) return reason;
      token = scanner_.nextTokenAnyLine();
    }
    int64_t counts[3] = {0, 0, 0};
    for (int i = 0; i < 3; ++i) {
      if (i > 0) token = scanner_.nextTokenAnyLine();
      if (token.empty()) return "missing vertex/face/edge counts";
      if (!parseInt64(token, counts[i]) || counts[i] < 0) return "bad count " + quoted(token);
    }
    vertexCount_ = counts[0];
    faceCount_ = counts[1];
    // Each vertex line needs at least 5 bytes ("0 0 0") and each face at least 7 ("3 0 1 2").
    const int64_t remaining = static_cast<int64_t>(text_.size() - scanner_.offset()) + 1;
    if (vertexCount_ > remaining / 5 || faceCount_ > remaining / 7 ||
        vertexCount_ * 5 + faceCount_ * 7 > remaining + 2) {
      return "counts (" + std::to_string(vertexCount_) + " vertices, " +
             std::to_string(faceCount_) + " faces) exceed what the file can hold";
    }
    return {};
  }

  std::string vertex() {
    geometry::MeshData& mesh = result_.mesh;
    float p[3];
    std::string_view bad;
    if (!scanner_.nextFloats(p, bad)) return "bad vertex coordinate " + quoted(bad);
    mesh.positions.emplace_back(p[0], p[1], p[2]);
    if (header_.normals) {
      float n[3];
      if (!scanner_.nextFloats(n, bad)) return "bad vertex normal " + quoted(bad);
      mesh.normals.emplace_back(n[0], n[1], n[2]);
    }
    if (!header_.colors && !header_.texcoords) return {};
    extra_.clear();
    for (std::string_view t = scanner_.nextToken(); !t.empty() && extra_.size() < 8;
         t = scanner_.nextToken()) {
      extra_.push_back(t);
    }
    if (header_.texcoords) {
      if (extra_.size() < 2) return "missing texture coordinates";
      glm::vec2 uv;
      if (!parseFloat(extra_[extra_.size() - 2], uv.x) || !parseFloat(extra_.back(), uv.y)) {
        return "bad texture coordinates";
      }
      mesh.uv0.push_back(uv);
      extra_.resize(extra_.size() - 2);
    }
    if (header_.colors) {
      glm::vec4 color;
      const std::string reason = parseColor(extra_, color);
      if (!reason.empty()) return reason;
      mesh.colors.push_back(color);
    }
    return {};
  }

  // "n i0 ... i(n-1)"; what follows the indices (a colour) is ignored.
  std::string face() {
    const std::string_view countToken = scanner_.nextToken();
    int64_t corners = 0;
    if (!parseInt64(countToken, corners)) return "bad polygon size " + quoted(countToken);
    if (corners < 3) return "a face needs at least 3 corners";
    polygon_.clear();
    for (int64_t k = 0; k < corners; ++k) {
      const std::string_view t = scanner_.nextToken();
      int64_t index = 0;
      if (t.empty()) {
        return "face has fewer than the " + std::to_string(corners) + " announced corners";
      }
      if (!parseInt64(t, index)) return "bad index " + quoted(t);
      if (index < 0 || index >= vertexCount_) {
        return "index " + std::to_string(index) + " out of range (" + std::to_string(vertexCount_) +
               " vertices)";
      }
      polygon_.push_back(static_cast<uint32_t>(index));
    }
    faces_.appendIndexed(polygon_, result_.mesh.positions, result_.mesh.indices);
    return {};
  }

  std::string_view text_;
  LineScanner scanner_;
  const std::string& name_;
  OffHeader header_;
  int64_t vertexCount_ = 0;
  int64_t faceCount_ = 0;
  MeshReadResult result_;
  std::vector<std::string_view> extra_;
  std::vector<uint32_t> polygon_;
  PolygonTriangulator faces_;
};

}  // namespace

MeshReadResult readOff(std::span<const uint8_t> bytes, const std::string& name) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  return OffReader(text, name).read();
}

}  // namespace cleave::assets::detail
