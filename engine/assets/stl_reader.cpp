// SPDX-License-Identifier: MIT
// STL reader, ascii and binary.
//
// Detection: a file is ascii when it starts with "solid" (after optional whitespace) AND holds only
// text bytes. Binary files whose 80-byte header happens to start with "solid" (many exporters write
// that) always contain control bytes in the triangle records (a float 0, 1 or 2 has zero bytes; the
// attribute word is usually 0), so the text test tells them apart without trusting the header.
// Corners at bit-identical positions are welded into one vertex, so a closed STL is closed by index.
// STL has no per-vertex normals (facet normals are ignored; the winding is trusted).
#include <cstring>
#include <unordered_map>

#include "cleave/assets/line_scanner.h"
#include "cleave/assets/mesh_finish.h"
#include "cleave/assets/mesh_reader.h"

namespace cleave::assets::detail {

namespace {

struct PositionKey {
  uint32_t bits[3];
  bool operator==(const PositionKey& o) const {
    return bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2];
  }
};

struct PositionKeyHash {
  size_t operator()(const PositionKey& k) const {
    uint64_t h = k.bits[0];
    h = h * 0x9E3779B97F4A7C15ull ^ k.bits[1];
    h = h * 0x9E3779B97F4A7C15ull ^ k.bits[2];
    return static_cast<size_t>(h ^ (h >> 31));
  }
};

class Welder {
 public:
  explicit Welder(geometry::MeshData& mesh) : mesh_(mesh) {}
  uint32_t add(glm::vec3 p) {
    PositionKey key;
    for (int i = 0; i < 3; ++i) {
      const float value = p[i] + 0.0f;  // -0 becomes +0
      std::memcpy(&key.bits[i], &value, sizeof(float));
    }
    auto [it, inserted] = ids_.try_emplace(key, static_cast<uint32_t>(mesh_.positions.size()));
    if (inserted) mesh_.positions.push_back(p);
    return it->second;
  }

 private:
  geometry::MeshData& mesh_;
  std::unordered_map<PositionKey, uint32_t, PositionKeyHash> ids_;
};

bool startsWithSolid(std::span<const uint8_t> bytes) {
  size_t i = 0;
  while (i < bytes.size() && (bytes[i] == ' ' || bytes[i] == '\t' || bytes[i] == '\r' ||
                              bytes[i] == '\n')) {
    ++i;
  }
  static constexpr char kSolid[] = "solid";
  if (bytes.size() - i < 5) return false;
  return std::memcmp(bytes.data() + i, kSolid, 5) == 0;
}

bool allText(std::span<const uint8_t> bytes) {
  for (uint8_t b : bytes) {
    if (b < 0x20 && b != '\t' && b != '\n' && b != '\r' && b != '\f' && b != '\v') return false;
    if (b == 0x7f) return false;
  }
  return true;
}

float readFloatLE(const uint8_t* p) {
  const uint32_t bits = static_cast<uint32_t>(p[0]) | (static_cast<uint32_t>(p[1]) << 8) |
                        (static_cast<uint32_t>(p[2]) << 16) | (static_cast<uint32_t>(p[3]) << 24);
  float value;
  std::memcpy(&value, &bits, sizeof(value));
  return value;
}

MeshReadResult readBinary(std::span<const uint8_t> bytes, const std::string& name) {
  constexpr size_t kHeader = 84;
  constexpr size_t kRecord = 50;
  if (bytes.size() < kHeader) {
    return failure(name, "binary STL shorter than its 84-byte header (" +
                             std::to_string(bytes.size()) + " bytes)");
  }
  const uint32_t count = static_cast<uint32_t>(bytes[80]) | (static_cast<uint32_t>(bytes[81]) << 8) |
                         (static_cast<uint32_t>(bytes[82]) << 16) |
                         (static_cast<uint32_t>(bytes[83]) << 24);
  const uint64_t needed = kHeader + uint64_t{count} * kRecord;
  if (needed > bytes.size()) {
    return failure(name, "binary STL announces " + std::to_string(count) + " triangles (" +
                             std::to_string(needed) + " bytes) but the file has " +
                             std::to_string(bytes.size()) + " bytes");
  }
  MeshReadResult result;
  geometry::MeshData& mesh = result.mesh;
  mesh.indices.reserve(size_t{count} * 3);
  Welder welder(mesh);
  for (uint32_t t = 0; t < count; ++t) {
    const uint8_t* record = bytes.data() + kHeader + size_t{t} * kRecord;
    for (int corner = 0; corner < 3; ++corner) {
      const uint8_t* p = record + 12 + corner * 12;
      mesh.indices.push_back(welder.add({readFloatLE(p), readFloatLE(p + 4), readFloatLE(p + 8)}));
    }
  }
  return finish(std::move(result), name);
}

MeshReadResult readAscii(std::span<const uint8_t> bytes, const std::string& name) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  LineScanner scanner(text, '\0');
  MeshReadResult result;
  geometry::MeshData& mesh = result.mesh;
  Welder welder(mesh);
  std::vector<uint32_t> loop;
  bool inLoop = false;
  bool inFacet = false;
  while (scanner.nextLine()) {
    const std::string_view keyword = scanner.nextToken();
    if (keyword.empty()) continue;
    const size_t line = scanner.lineNumber();
    if (keyword == "solid" || keyword == "endsolid") {
      if (inFacet) return failureAt(name, line, quoted(keyword) + " inside a facet");
      continue;  // the rest of the line is the solid's name
    }
    if (keyword == "facet") {
      if (inFacet) return failureAt(name, line, "'facet' inside a facet");
      inFacet = true;  // "normal nx ny nz" follows; the winding is trusted instead
    } else if (keyword == "outer") {
      if (!inFacet || inLoop) return failureAt(name, line, "'outer loop' outside a facet");
      inLoop = true;
      loop.clear();
    } else if (keyword == "vertex") {
      if (!inLoop) return failureAt(name, line, "'vertex' outside a loop");
      float p[3];
      for (float& value : p) {
        const std::string_view t = scanner.nextToken();
        if (!parseFloat(t, value)) return failureAt(name, line, "bad coordinate " + quoted(t));
      }
      loop.push_back(welder.add({p[0], p[1], p[2]}));
    } else if (keyword == "endloop") {
      if (!inLoop) return failureAt(name, line, "'endloop' without 'outer loop'");
      if (loop.size() < 3) return failureAt(name, line, "a facet needs at least 3 vertices");
      for (size_t k = 1; k + 1 < loop.size(); ++k) {
        mesh.indices.push_back(loop[0]);
        mesh.indices.push_back(loop[k]);
        mesh.indices.push_back(loop[k + 1]);
      }
      inLoop = false;
    } else if (keyword == "endfacet") {
      if (!inFacet || inLoop) return failureAt(name, line, "'endfacet' without a closed facet");
      inFacet = false;
    } else {
      return failureAt(name, line, "unexpected " + quoted(keyword) + " in ascii STL");
    }
  }
  if (inFacet) return failure(name, "file ends inside a facet");
  return finish(std::move(result), name);
}

}  // namespace

MeshReadResult readStl(std::span<const uint8_t> bytes, const std::string& name) {
  if (startsWithSolid(bytes) && allText(bytes)) return readAscii(bytes, name);
  return readBinary(bytes, name);
}

}  // namespace cleave::assets::detail
