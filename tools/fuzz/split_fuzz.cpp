// SPDX-License-Identifier: MIT
// Fuzz driver for the split core. Input layout (all bytes, so every mutation is a valid layout):
//   [0]     flags: bit 0 cap, bit 1 separate islands, bit 2 normalized-bounds cap UVs,
//           bit 3 convex splitter instead of concave, bit 4 a non-trivial model matrix
//   [1..4]  plane normal x, y, z and offset as signed bytes (normal / 16, offset / 32)
//   [5]     vertex count n = 3 + value % 30
//   next    3n signed bytes: coordinates / 16
//   rest    triangles as byte triples, each index modulo n (at most 96 triangles)
// Invariants checked: the split returns the status it stores; Ok means at least one piece and every
// piece a valid mesh (indices in range, attribute arrays sized, submeshes covering the indices);
// anything else means no pieces. With CLEAVE_FUZZ_STRICT=1 in the environment, a closed input cut
// with caps must also give closed pieces whose volumes add up to the input's.
#include <cmath>
#include <cstdlib>
#include <memory>
#include <string>

#include "cleave/geometry/mass_properties.h"
#include "cleave/geometry/mesh_splitter.h"
#include "tools/fuzz/fuzz_driver.h"

namespace cleave::fuzz {

namespace {

constexpr size_t kHeader = 6;
constexpr size_t kMaxTriangles = 96;

std::vector<uint8_t> encode(uint8_t flags, const int8_t plane[4], const std::vector<glm::ivec3>& vertices,
                            const std::vector<glm::ivec3>& triangles) {
  std::vector<uint8_t> bytes{flags};
  for (int i = 0; i < 4; ++i) bytes.push_back(static_cast<uint8_t>(plane[i]));
  bytes.push_back(static_cast<uint8_t>(vertices.size() - 3));
  for (const glm::ivec3& v : vertices) {
    for (int i = 0; i < 3; ++i) bytes.push_back(static_cast<uint8_t>(static_cast<int8_t>(v[i])));
  }
  for (const glm::ivec3& t : triangles) {
    for (int i = 0; i < 3; ++i) bytes.push_back(static_cast<uint8_t>(t[i]));
  }
  return bytes;
}

void checkPiece(const geometry::SplitPiece& piece) {
  const geometry::MeshData& mesh = piece.mesh;
  if (piece.side != 1 && piece.side != -1) fail("piece side is not +1 or -1");
  if (mesh.indices.empty() || mesh.indices.size() % 3 != 0) fail("piece index count");
  for (uint32_t index : mesh.indices) {
    if (index >= mesh.positions.size()) fail("piece index out of range");
  }
  for (const glm::vec3& p : mesh.positions) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) fail("piece position not finite");
  }
  if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size()) fail("piece normals");
  if (!mesh.uv0.empty() && mesh.uv0.size() != mesh.positions.size()) fail("piece uvs");
  uint64_t covered = 0;
  for (const geometry::SubMesh& sub : mesh.submeshes) {
    if (sub.firstIndex != covered || sub.indexCount % 3 != 0) fail("piece submeshes out of order");
    covered += sub.indexCount;
  }
  if (!mesh.submeshes.empty() && covered != mesh.indices.size()) fail("piece submeshes do not cover");
  if (piece.capTriangles > mesh.triangleCount()) fail("more cap triangles than triangles");
}

bool strictMode() {
  static const bool strict = [] {
    const char* value = std::getenv("CLEAVE_FUZZ_STRICT");
    return value != nullptr && std::string(value) == "1";
  }();
  return strict;
}

}  // namespace

std::vector<std::vector<uint8_t>> fuzzSeeds() {
  std::vector<std::vector<uint8_t>> seeds;
  const int8_t horizontal[4] = {0, 16, 0, 4};
  const int8_t tilted[4] = {5, 16, -3, 0};
  // A tetrahedron and a cube (coordinates in sixteenths), outward wound.
  const std::vector<glm::ivec3> tetra = {{0, 0, 0}, {16, 0, 0}, {0, 16, 0}, {0, 0, 16}};
  const std::vector<glm::ivec3> tetraTris = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const std::vector<glm::ivec3> cube = {{0, 0, 0},   {16, 0, 0},  {16, 16, 0}, {0, 16, 0},
                                        {0, 0, 16},  {16, 0, 16}, {16, 16, 16}, {0, 16, 16}};
  const std::vector<glm::ivec3> cubeTris = {{0, 3, 2}, {0, 2, 1}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                                            {3, 7, 6}, {3, 6, 2}, {0, 4, 7}, {0, 7, 3}, {1, 2, 6}, {1, 6, 5}};
  seeds.push_back(encode(0x03, horizontal, tetra, tetraTris));
  seeds.push_back(encode(0x03, tilted, cube, cubeTris));
  seeds.push_back(encode(0x0f, tilted, cube, cubeTris));
  seeds.push_back(encode(0x12, horizontal, cube, cubeTris));
  // Two disjoint tetrahedra: islands.
  std::vector<glm::ivec3> two = tetra;
  std::vector<glm::ivec3> twoTris = tetraTris;
  for (const glm::ivec3& v : tetra) two.push_back(v + glm::ivec3(40, 0, 0));
  for (const glm::ivec3& t : tetraTris) twoTris.push_back(t + glm::ivec3(4));
  seeds.push_back(encode(0x03, horizontal, two, twoTris));
  return seeds;
}

}  // namespace cleave::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace cleave;
  if (size < fuzz::kHeader) return -1;
  const uint8_t flags = data[0];
  geometry::Plane plane;
  plane.normal = glm::dvec3(static_cast<int8_t>(data[1]), static_cast<int8_t>(data[2]),
                            static_cast<int8_t>(data[3])) / 16.0;
  plane.offset = static_cast<int8_t>(data[4]) / 32.0;
  if (glm::length(plane.normal) == 0.0) return -1;
  const size_t vertexCount = 3 + data[5] % 30;
  if (size < fuzz::kHeader + 3 * vertexCount + 3) return -1;
  geometry::MeshData mesh;
  const uint8_t* cursor = data + fuzz::kHeader;
  for (size_t i = 0; i < vertexCount; ++i, cursor += 3) {
    mesh.positions.emplace_back(static_cast<int8_t>(cursor[0]) / 16.f, static_cast<int8_t>(cursor[1]) / 16.f,
                                static_cast<int8_t>(cursor[2]) / 16.f);
  }
  const size_t triangleBytes = std::min<size_t>((size - (cursor - data)) / 3, fuzz::kMaxTriangles) * 3;
  for (size_t i = 0; i < triangleBytes; ++i) mesh.indices.push_back(cursor[i] % vertexCount);
  // Simple per-vertex attributes so interpolation is exercised too.
  for (const glm::vec3& p : mesh.positions) {
    mesh.uv0.emplace_back(p.x, p.z);
    const float length = glm::length(p);
    mesh.normals.push_back(length > 0.f ? p / length : glm::vec3(0, 1, 0));
  }

  geometry::SplitOptions options;
  options.cap = (flags & 1) != 0;
  options.separateIslands = (flags & 2) != 0;
  options.uvMode = (flags & 4) != 0 ? geometry::CapUvMode::NormalizedBounds : geometry::CapUvMode::WorldPlanar;
  geometry::MeshContainer container;
  if (container.setMesh(mesh).code != geometry::SplitStatus::Ok) return -1;
  glm::mat4 model(1.f);
  if ((flags & 16) != 0) {
    model[0] = glm::vec4(1.5f, 0.2f, 0.f, 0.f);
    model[1] = glm::vec4(0.f, 1.f, 0.3f, 0.f);
    model[2] = glm::vec4(0.f, 0.f, -1.f, 0.f);  // mirrored
    model[3] = glm::vec4(0.25f, -0.5f, 1.f, 1.f);
  }
  container.setTransform(model);
  std::unique_ptr<geometry::IMeshSplitter> splitter =
      (flags & 8) != 0 ? geometry::makeConvexSplitter() : geometry::makeConcaveSplitter();
  geometry::SplitResult result;
  const geometry::SplitStatus status = splitter->split(container, plane, options, result);
  if (status != result.status) fuzz::fail("returned status differs from the stored one");
  if (status != geometry::SplitStatus::Ok) {
    if (!result.pieces.empty()) fuzz::fail("a failed split returned pieces");
    return 0;
  }
  if (result.pieces.empty()) fuzz::fail("an Ok split returned no pieces");
  for (const geometry::SplitPiece& piece : result.pieces) fuzz::checkPiece(piece);

  // A closed input whose section is all closed loops, every one capped (open art, cut anyway, is
  // left open where it is open or self-intersecting, and says so in the result).
  const bool sectionClosed = result.openChains == 0 && result.uncappedLoops == 0 && !result.sidesDisagree;
  if (fuzz::strictMode() && options.cap && sectionClosed &&
      geometry::isClosedAndOriented(mesh.positions, mesh.indices)) {
    // The input's volume in cut space; the transform argument keeps a mirrored volume positive. A
    // mesh wound inwards has a negative volume and is cut as if mirrored: its pieces are positive.
    const geometry::MassProperties whole =
        geometry::computeMassProperties(mesh.positions, mesh.indices, glm::dmat4(model));
    double total = 0.0;
    for (const geometry::SplitPiece& piece : result.pieces) {
      if (!piece.mass.closed) fuzz::fail("a capped piece of a closed mesh is not closed");
      total += piece.mass.volume;
    }
    const double scale = std::max(1.0, std::pow(container.boundsDiagonal(), 3.0));
    if (std::abs(total - std::abs(whole.volume)) > 1e-4 * scale) fuzz::fail("piece volumes do not add up");
  }
  return 0;
}
