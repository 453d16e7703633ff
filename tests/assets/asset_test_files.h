// SPDX-License-Identifier: MIT
// Test helpers for the mesh readers: a temporary folder, the unit cube [0,1]^3 written in every
// format the engine reads (built here byte by byte, so the tests need no files from elsewhere), and
// where the set-up puts the npm packages that some tests use when they are there.
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>

#include "cleave/assets/mesh_io.h"
#include "cleave/geometry/mass_properties.h"

namespace cleave::assets::test {

// A fresh folder under the system temporary folder, removed with everything in it on destruction.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    path_ = std::filesystem::temp_directory_path() /
            ("cleave_assets_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::string write(const std::string& name, const std::string& bytes) const {
    const std::string path = file(name);
    std::ofstream out(path, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return path;
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// The folder whose node_modules/ holds the npm packages tools/install-deps.sh installs for the tests
// (gltf-validator, bunny): CLEAVE_NPM_DIR, else <build>/npm, where ./cleave test and sanitize put them.
inline std::filesystem::path npmDir() {
  if (const char* env = std::getenv("CLEAVE_NPM_DIR"); env != nullptr && *env != '\0') return env;
  return std::filesystem::path(CLEAVE_BINARY_DIR) / "npm";
}

// The unit cube: 8 corners and 6 quads, counter-clockwise seen from outside.
inline const float kCubeCorners[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                         {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
inline const int kCubeQuads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                     {3, 7, 6, 2}, {0, 4, 7, 3}, {1, 2, 6, 5}};

inline std::string cubeObj() {
  std::string s = "# unit cube\no cube\n";
  for (const auto& c : kCubeCorners) {
    s += "v " + std::to_string(c[0]) + " " + std::to_string(c[1]) + " " + std::to_string(c[2]) + "\n";
  }
  s += "usemtl wood\n";
  for (int f = 0; f < 6; ++f) {
    if (f == 4) s += "usemtl stone\n";
    if (f == 5) s += "usemtl wood\n";
    s += "f";
    for (int k : kCubeQuads[f]) {
      s += ' ';
      s += std::to_string(k + 1);
    }
    s += "\n";
  }
  return s;
}

inline std::string cubeOff() {
  std::string s = "OFF\n# unit cube\n8 6 12\n";
  for (const auto& c : kCubeCorners) {
    s += std::to_string(c[0]) + " " + std::to_string(c[1]) + " " + std::to_string(c[2]) + "\n";
  }
  for (const auto& q : kCubeQuads) {
    s += "4 " + std::to_string(q[0]) + " " + std::to_string(q[1]) + " " + std::to_string(q[2]) + " " +
         std::to_string(q[3]) + " 255 0 0\n";  // a trailing face colour, ignored
  }
  return s;
}

// The cube's 12 triangles as corner triples (fan per quad).
inline std::vector<std::array<int, 3>> cubeTriangles() {
  std::vector<std::array<int, 3>> triangles;
  for (const auto& q : kCubeQuads) {
    triangles.push_back({q[0], q[1], q[2]});
    triangles.push_back({q[0], q[2], q[3]});
  }
  return triangles;
}

inline std::string cubeStlAscii() {
  std::string s = "solid cube\n";
  for (const auto& t : cubeTriangles()) {
    s += "  facet normal 0 0 0\n    outer loop\n";
    for (int k : t) {
      const auto& c = kCubeCorners[k];
      s += "      vertex " + std::to_string(c[0]) + " " + std::to_string(c[1]) + " " +
           std::to_string(c[2]) + "\n";
    }
    s += "    endloop\n  endfacet\n";
  }
  s += "endsolid cube\n";
  return s;
}

inline void putU32(std::string& s, uint32_t v) {
  for (int i = 0; i < 4; ++i) s += static_cast<char>((v >> (8 * i)) & 0xff);
}
inline void putF32(std::string& s, float f) { putU32(s, std::bit_cast<uint32_t>(f)); }

// Binary STL; `header` is padded with spaces to 80 bytes.
inline std::string cubeStlBinary(const std::string& header) {
  std::string s = header.substr(0, 80);
  s.resize(80, ' ');
  const auto triangles = cubeTriangles();
  putU32(s, static_cast<uint32_t>(triangles.size()));
  for (const auto& t : triangles) {
    for (int i = 0; i < 3; ++i) putF32(s, 0.f);  // facet normal
    for (int k : t) {
      for (float v : kCubeCorners[k]) putF32(s, v);
    }
    s += std::string(2, '\0');  // attribute byte count
  }
  return s;
}

inline std::string cubePlyAscii() {
  std::string s =
      "ply\nformat ascii 1.0\ncomment unit cube\nelement vertex 8\nproperty float x\n"
      "property float y\nproperty float z\nproperty uchar red\nproperty uchar green\n"
      "property uchar blue\nelement face 6\nproperty list uchar int vertex_indices\n"
      "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n";
  for (const auto& c : kCubeCorners) {
    s += std::to_string(c[0]) + " " + std::to_string(c[1]) + " " + std::to_string(c[2]) + " 255 128 0\n";
  }
  for (const auto& q : kCubeQuads) {
    s += "4 " + std::to_string(q[0]) + " " + std::to_string(q[1]) + " " + std::to_string(q[2]) + " " +
         std::to_string(q[3]) + "\n";
  }
  s += "0 1\n";
  return s;
}

// Binary PLY with double positions, float normals (pointing away from the centre), float s t,
// an unused int property, and faces as a ushort-counted list of uint indices.
inline std::string cubePlyBinary(bool bigEndian) {
  std::string s = std::string("ply\nformat ") +
                  (bigEndian ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\nelement vertex 8\nproperty double x\nproperty double y\nproperty double z\n"
                  "property float nx\nproperty float ny\nproperty float nz\nproperty float s\n"
                  "property float t\nproperty int flags\nelement face 6\n"
                  "property uchar quality\nproperty list ushort uint vertex_indices\nend_header\n";
  auto put = [&](const void* data, size_t size) {
    std::string bytes(static_cast<const char*>(data), size);
    if (bigEndian) std::reverse(bytes.begin(), bytes.end());
    s += bytes;
  };
  for (const auto& c : kCubeCorners) {
    for (float v : c) {
      const double d = v;
      put(&d, 8);
    }
    for (float v : c) {
      const float n = (v - 0.5f) * 2.f / std::sqrt(3.f);
      put(&n, 4);
    }
    const float st[2] = {c[0], c[1]};
    put(&st[0], 4);
    put(&st[1], 4);
    const int32_t flags = 7;
    put(&flags, 4);
  }
  for (const auto& q : kCubeQuads) {
    s += static_cast<char>(9);  // quality
    const uint16_t count = 4;
    put(&count, 2);
    for (int k : q) {
      const uint32_t index = static_cast<uint32_t>(k);
      put(&index, 4);
    }
  }
  return s;
}

inline std::string base64(const std::string& bytes) {
  static const char kTable[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const uint32_t v = (uint32_t(uint8_t(bytes[i])) << 16) | (uint32_t(uint8_t(bytes[i + 1])) << 8) |
                       uint8_t(bytes[i + 2]);
    out += kTable[(v >> 18) & 63];
    out += kTable[(v >> 12) & 63];
    out += kTable[(v >> 6) & 63];
    out += kTable[v & 63];
  }
  if (i + 1 == bytes.size()) {
    const uint32_t v = uint32_t(uint8_t(bytes[i])) << 16;
    out += kTable[(v >> 18) & 63];
    out += kTable[(v >> 12) & 63];
    out += "==";
  } else if (i + 2 == bytes.size()) {
    const uint32_t v = (uint32_t(uint8_t(bytes[i])) << 16) | (uint32_t(uint8_t(bytes[i + 1])) << 8);
    out += kTable[(v >> 18) & 63];
    out += kTable[(v >> 12) & 63];
    out += kTable[(v >> 6) & 63];
    out += '=';
  }
  return out;
}

// A .gltf with the cube (8 float positions, 36 ushort indices) in one data-URI buffer. `extra`
// is spliced into the top-level object (for example an extensionsRequired array), `indexPatch`
// replaces index 0 of the first triangle, `nodes` is the JSON of the node array.
inline std::string cubeGltf(const std::string& extra = "", int indexPatch = -1,
                            const std::string& nodes = R"([{"mesh":0}])") {
  std::string buffer;
  for (const auto& c : kCubeCorners) {
    for (float v : c) putF32(buffer, v);
  }
  bool first = true;
  for (const auto& t : cubeTriangles()) {
    for (int k : t) {
      const uint16_t index = static_cast<uint16_t>(first && indexPatch >= 0 ? indexPatch : k);
      first = false;
      buffer += static_cast<char>(index & 0xff);
      buffer += static_cast<char>(index >> 8);
    }
  }
  const std::string uri = "data:application/octet-stream;base64," + base64(buffer);
  return std::string(R"({"asset":{"version":"2.0"},)") + extra +
         R"("scene":0,"scenes":[{"nodes":[0]}],"nodes":)" + nodes +
         R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
         R"("accessors":[{"bufferView":0,"componentType":5126,"count":8,"type":"VEC3",)"
         R"("min":[0,0,0],"max":[1,1,1]},{"bufferView":1,"componentType":5123,"count":36,"type":"SCALAR"}],)"
         R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":96},)"
         R"({"buffer":0,"byteOffset":96,"byteLength":72}],)"
         R"("buffers":[{"byteLength":)" +
         std::to_string(buffer.size()) + R"(,"uri":")" + uri + R"("}]})";
}

// The checks every reader of the cube must pass: 12 triangles, closed and outward (volume +1).
inline void expectUnitCube(const MeshReadResult& result, size_t expectedVertices = 8) {
  ASSERT_TRUE(result.ok()) << result.message;
  EXPECT_TRUE(result.message.empty());
  EXPECT_EQ(result.mesh.triangleCount(), 12u);
  EXPECT_EQ(result.mesh.vertexCount(), expectedVertices);
  EXPECT_TRUE(geometry::isClosedAndOriented(result.mesh.positions, result.mesh.indices));
  const geometry::MassProperties mass = geometry::computeMassProperties(result.mesh);
  EXPECT_NEAR(mass.volume, 1.0, 1e-6);
  EXPECT_NEAR(mass.centerOfMass.x, 0.5, 1e-6);
  EXPECT_NEAR(mass.centerOfMass.y, 0.5, 1e-6);
  EXPECT_NEAR(mass.centerOfMass.z, 0.5, 1e-6);
}

}  // namespace cleave::assets::test
