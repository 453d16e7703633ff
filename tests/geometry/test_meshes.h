// SPDX-License-Identifier: MIT
// Shared helpers for the geometry tests: topology and volume checks, a section area computed
// independently of the splitter, seeded random planes, and a dump of a failing case in a text form
// (an OBJ file with the plane and transforms in comment lines) that can become a corpus entry.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <numeric>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cleave/geometry/mesh_data.h"
#include "cleave/geometry/mesh_splitter.h"

namespace cleave::geometry::testing {

// splitmix64: a tiny generator whose sequence is the same on every platform and standard library
// (std:: distributions are not specified bit for bit).
class SeededRandom {
 public:
  explicit SeededRandom(uint64_t seed) : state_(seed) {}
  uint64_t next() {
    uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  double uniform() { return double(next() >> 11) * 0x1.0p-53; }  // [0, 1)
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  glm::dvec3 unitVector() {
    for (;;) {
      glm::dvec3 v(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
      double l = glm::length(v);
      if (l > 0.1 && l <= 1.0) return v / l;
    }
  }

 private:
  uint64_t state_;
};

// Tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1), wound outwards; every face listed starting at the
// origin when it holds it, so the first vertex of three faces lies on a plane through the origin.
inline MeshData cornerTetrahedron() {
  MeshData m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.indices = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  return m;
}

inline std::vector<glm::dvec3> toCutSpace(const MeshData& mesh, const glm::dmat4& model) {
  std::vector<glm::dvec3> out(mesh.positions.size());
  for (size_t i = 0; i < out.size(); ++i) {
    out[i] = glm::dvec3(model * glm::dvec4(glm::dvec3(mesh.positions[i]), 1.0));
  }
  return out;
}

// Over a span of doubles or a container's cut positions (the source floats or its own doubles).
template <class Points>
void bounds(const Points& p, glm::dvec3& lo, glm::dvec3& hi) {
  lo = glm::dvec3(INFINITY);
  hi = glm::dvec3(-INFINITY);
  for (const glm::dvec3 q : p) {
    lo = glm::min(lo, q);
    hi = glm::max(hi, q);
  }
}

inline double boundsDiagonal(std::span<const glm::dvec3> p) {
  glm::dvec3 lo, hi;
  bounds(p, lo, hi);
  return p.empty() ? 0.0 : glm::length(hi - lo);
}

// Planes through a random point of the middle 80% of the box [lo, hi], random orientation.
inline std::vector<Plane> randomPlanes(uint64_t seed, size_t count, const glm::dvec3& lo,
                                       const glm::dvec3& hi) {
  SeededRandom rng(seed);
  std::vector<Plane> planes;
  planes.reserve(count);
  for (size_t k = 0; k < count; ++k) {
    glm::dvec3 point;
    for (int a = 0; a < 3; ++a) point[a] = lo[a] + (hi[a] - lo[a]) * rng.uniform(0.1, 0.9);
    Plane plane;
    plane.normal = rng.unitVector();
    plane.offset = glm::dot(plane.normal, point);
    planes.push_back(plane);
  }
  return planes;
}

// Vertices welded when within `weldTolerance` (sweep over x, union-find); returns an id per vertex.
inline std::vector<uint32_t> weldWithin(std::span<const glm::dvec3> p, double weldTolerance) {
  const uint32_t n = static_cast<uint32_t>(p.size());
  std::vector<uint32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  std::vector<uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    return p[a].x != p[b].x ? p[a].x < p[b].x : a < b;
  });
  for (uint32_t i = 0; i < n; ++i) {
    for (uint32_t j = i + 1; j < n && p[order[j]].x - p[order[i]].x <= weldTolerance; ++j) {
      if (glm::length(p[order[j]] - p[order[i]]) <= weldTolerance) {
        uint32_t a = find(order[i]), b = find(order[j]);
        if (a != b) parent[std::max(a, b)] = std::min(a, b);
      }
    }
  }
  std::vector<uint32_t> id(n);
  for (uint32_t i = 0; i < n; ++i) id[i] = find(i);
  return id;
}

// Every undirected edge (after welding) used by exactly two triangles, once in each direction.
// Triangles that collapse under the weld are ignored (their edges cancel in pairs).
inline ::testing::AssertionResult closedAndOriented(std::span<const glm::dvec3> p,
                                                    std::span<const uint32_t> indices,
                                                    double weldTolerance) {
  if (indices.size() % 3 != 0) return ::testing::AssertionFailure() << "index count not a multiple of 3";
  if (indices.empty()) return ::testing::AssertionFailure() << "no triangle";
  for (uint32_t i : indices) {
    if (i >= p.size()) return ::testing::AssertionFailure() << "index " << i << " out of range";
  }
  std::vector<uint32_t> id = weldWithin(p, weldTolerance);
  std::vector<uint64_t> edges;
  for (size_t t = 0; t < indices.size(); t += 3) {
    uint32_t a = id[indices[t]], b = id[indices[t + 1]], c = id[indices[t + 2]];
    if (a == b || b == c || c == a) continue;
    edges.push_back((uint64_t(a) << 32) | b);
    edges.push_back((uint64_t(b) << 32) | c);
    edges.push_back((uint64_t(c) << 32) | a);
  }
  std::sort(edges.begin(), edges.end());
  size_t duplicated = 0, unmatched = 0;
  uint64_t firstBad = 0;
  for (size_t k = 0; k < edges.size(); ++k) {
    uint64_t e = edges[k];
    if (k > 0 && edges[k - 1] == e) {
      if (duplicated++ == 0 && unmatched == 0) firstBad = e;
      continue;
    }
    uint64_t reverse = (e << 32) | (e >> 32);
    if (!std::binary_search(edges.begin(), edges.end(), reverse)) {
      if (unmatched++ == 0 && duplicated == 0) firstBad = e;
    }
  }
  if (duplicated == 0 && unmatched == 0) return ::testing::AssertionSuccess();
  const glm::dvec3 a = p[firstBad >> 32], b = p[firstBad & 0xffffffffu];
  return ::testing::AssertionFailure()
         << unmatched << " edge(s) without an opposite twin (open or misoriented), " << duplicated
         << " edge(s) used twice in one direction; first bad edge (" << a.x << ", " << a.y << ", "
         << a.z << ") -> (" << b.x << ", " << b.y << ", " << b.z << ")";
}

inline void expectClosedAndOriented(const MeshData& mesh, double relativeWeld = 1e-7) {
  std::vector<glm::dvec3> p = toCutSpace(mesh, glm::dmat4(1.0));
  EXPECT_TRUE(closedAndOriented(p, mesh.indices, relativeWeld * boundsDiagonal(p)));
}

// What welding a mesh by exact float position (a file written from it, read back) finds: edges
// used other than once in each direction, and triangles of zero area on the float positions
// (exact: the differences and cross products of float coordinates are exact in double, so a
// zero cross product means three collinear or coinciding points, not a rounding of a thin one).
struct FloatWeldReport {
  size_t triangles = 0;
  size_t zeroArea = 0;         // triangles whose float corners are collinear or coincide
  size_t coincident = 0;       // of these, the ones with two corners at one float position
  size_t openEdges = 0;        // directed edges without their reverse
  size_t overusedEdges = 0;    // directed edges used more than once
  bool manifold() const { return zeroArea == 0 && openEdges == 0 && overusedEdges == 0; }
};

inline FloatWeldReport floatWeldReport(const MeshData& mesh) {
  FloatWeldReport report;
  const uint32_t n = static_cast<uint32_t>(mesh.positions.size());
  auto key = [&](uint32_t i) {  // -0 and +0 are one position, as a reader parsing the text sees them
    const glm::vec3 p = mesh.positions[i] + glm::vec3(0.f);
    return std::array<float, 3>{p.x, p.y, p.z};
  };
  std::vector<uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return key(a) < key(b); });
  std::vector<uint32_t> id(n);
  for (uint32_t k = 0; k < n; ++k) id[order[k]] = k > 0 && key(order[k]) == key(order[k - 1]) ? id[order[k - 1]] : k;
  std::vector<uint64_t> edges;
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    ++report.triangles;
    const uint32_t v[3] = {mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
    const glm::dvec3 a(mesh.positions[v[0]]), b(mesh.positions[v[1]]), c(mesh.positions[v[2]]);
    if (glm::cross(b - a, c - a) == glm::dvec3(0.0)) {
      ++report.zeroArea;
      report.coincident += id[v[0]] == id[v[1]] || id[v[1]] == id[v[2]] || id[v[2]] == id[v[0]];
      continue;
    }
    for (int e = 0; e < 3; ++e) edges.push_back((uint64_t(id[v[e]]) << 32) | id[v[(e + 1) % 3]]);
  }
  std::sort(edges.begin(), edges.end());
  for (size_t k = 0; k < edges.size(); ++k) {
    if (k > 0 && edges[k] == edges[k - 1]) {
      ++report.overusedEdges;
      continue;
    }
    const uint64_t reverse = (edges[k] << 32) | (edges[k] >> 32);
    if (!std::binary_search(edges.begin(), edges.end(), reverse)) ++report.openEdges;
  }
  return report;
}

inline ::testing::AssertionResult manifoldOnFloats(const MeshData& mesh) {
  const FloatWeldReport r = floatWeldReport(mesh);
  if (r.manifold()) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "welded by float position, " << r.zeroArea << " of " << r.triangles
                                       << " triangle(s) have zero area (" << r.coincident << " with two corners at one point), " << r.openEdges
                                       << " edge(s) lack their reverse, " << r.overusedEdges
                                       << " edge(s) are used twice in one direction";
}

inline double signedVolume(std::span<const glm::dvec3> p, std::span<const uint32_t> indices) {
  glm::dvec3 lo, hi;
  bounds(p, lo, hi);
  const glm::dvec3 ref = 0.5 * (lo + hi);
  double sixV = 0.0;
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    sixV += glm::dot(p[indices[t]] - ref,
                     glm::cross(p[indices[t + 1]] - ref, p[indices[t + 2]] - ref));
  }
  return sixV / 6.0;
}

inline ::testing::AssertionResult volumeKept(double original, std::span<const double> pieces,
                                             double relativeTolerance) {
  double sum = 0.0;
  for (double v : pieces) sum += v;
  const double error = std::abs(sum - original);
  if (error <= relativeTolerance * std::abs(original)) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "pieces sum to " << sum << ", original " << original
                                       << ", relative error " << error / std::abs(original);
}

inline void expectVolumeKept(double original, std::span<const double> pieces,
                             double relativeTolerance = 1e-6) {
  EXPECT_TRUE(volumeKept(original, pieces, relativeTolerance));
}

// Area of the section of a closed, outward-wound surface by the plane, without building loops:
// each crossing triangle contributes its intersection segment, oriented so that the section lies to
// its left seen from the plane's normal side; the shoelace sum over the segments telescopes over
// every loop, outer borders counting positive and holes negative, for any nesting. Vertices are
// classified exactly (d > 0 above, else below) and an edge's crossing point is always computed from
// its above end, so both triangles of an edge get the same point.
inline double sectionArea(std::span<const glm::dvec3> p, std::span<const uint32_t> indices,
                          const Plane& plane) {
  const double len = glm::length(plane.normal);
  const glm::dvec3 n = plane.normal / len;
  const double offset = plane.offset / len;
  const glm::dvec3 origin = n * offset;
  std::vector<double> d(p.size());
  for (size_t i = 0; i < p.size(); ++i) d[i] = glm::dot(n, p[i]) - offset;
  auto cross = [&](uint32_t a, uint32_t b) {  // crossing point on edge (a, b), either order
    if (!(d[a] > 0.0)) std::swap(a, b);
    const double t = d[a] / (d[a] - d[b]);
    return p[a] + t * (p[b] - p[a]) - origin;
  };
  double twice = 0.0;
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    const uint32_t v[3] = {indices[t], indices[t + 1], indices[t + 2]};
    const bool up[3] = {d[v[0]] > 0.0, d[v[1]] > 0.0, d[v[2]] > 0.0};
    const int count = int(up[0]) + int(up[1]) + int(up[2]);
    if (count == 0 || count == 3) continue;
    const bool loneAbove = count == 1;
    int k = 0;
    while (up[k] != loneAbove) ++k;
    const uint32_t a = v[k], next = v[(k + 1) % 3], prev = v[(k + 2) % 3];
    glm::dvec3 from = cross(a, next), to = cross(prev, a);
    if (!loneAbove) std::swap(from, to);
    twice += glm::dot(glm::cross(from, to), n);
  }
  return 0.5 * twice;
}

inline double triangleArea(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  return 0.5 * glm::length(glm::cross(b - a, c - a));
}

// Sum of the areas of the triangles in runs of `capMaterialId`, positions mapped by `model`.
inline double capArea(const MeshData& mesh, uint32_t capMaterialId, const glm::dmat4& model,
                      uint32_t* capTriangleCount = nullptr) {
  std::vector<glm::dvec3> p = toCutSpace(mesh, model);
  double area = 0.0;
  uint32_t triangles = 0;
  for (const SubMesh& run : mesh.submeshes) {
    if (run.materialId != capMaterialId) continue;
    for (uint32_t k = run.firstIndex; k + 2 < run.firstIndex + run.indexCount; k += 3) {
      if (k + 2 >= mesh.indices.size()) break;
      area += triangleArea(p[mesh.indices[k]], p[mesh.indices[k + 1]], p[mesh.indices[k + 2]]);
      ++triangles;
    }
  }
  if (capTriangleCount) *capTriangleCount = triangles;
  return area;
}

// Writes the case as an OBJ file with the plane and transforms in comment lines, under the build
// directory (test_failures/<name>.obj); returns the path written, or an empty string.
inline std::string dumpCase(const std::string& name, const MeshData& mesh, const glm::dmat4& model,
                            const Plane& plane, const std::string& reason,
                            std::span<const glm::mat4> jointMatrices = {}) {
#ifdef CLEAVE_BINARY_DIR
  const std::filesystem::path dir = std::filesystem::path(CLEAVE_BINARY_DIR) / "test_failures";
#else
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "cleave_test_failures";
#endif
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  std::string safe = name;
  for (char& c : safe) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  }
  const std::filesystem::path path = dir / (safe + ".obj");
  FILE* f = std::fopen(path.string().c_str(), "w");
  if (!f) return {};
  std::fprintf(f, "# cleave split case: %s\n# reason: %s\n", name.c_str(), reason.c_str());
  std::fprintf(f, "# plane %.17g %.17g %.17g %.17g\n", plane.normal.x, plane.normal.y,
               plane.normal.z, plane.offset);
  std::fprintf(f, "# model (column-major)");
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) std::fprintf(f, " %.17g", model[c][r]);
  }
  std::fprintf(f, "\n");
  for (const glm::mat4& m : jointMatrices) {
    std::fprintf(f, "# joint (column-major)");
    for (int c = 0; c < 4; ++c) {
      for (int r = 0; r < 4; ++r) std::fprintf(f, " %.9g", m[c][r]);
    }
    std::fprintf(f, "\n");
  }
  const bool skinned = !mesh.joints.empty() && mesh.weights.size() == mesh.joints.size();
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3& p = mesh.positions[i];
    std::fprintf(f, "v %.9g %.9g %.9g\n", p.x, p.y, p.z);
    if (skinned) {
      const glm::u16vec4& j = mesh.joints[i];
      const glm::vec4& w = mesh.weights[i];
      std::fprintf(f, "# skin %u %u %u %u %.9g %.9g %.9g %.9g\n", j.x, j.y, j.z, j.w, w.x, w.y,
                   w.z, w.w);
    }
  }
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    std::fprintf(f, "f %u %u %u\n", mesh.indices[t] + 1, mesh.indices[t + 1] + 1,
                 mesh.indices[t + 2] + 1);
  }
  std::fclose(f);
  return path.string();
}

}  // namespace cleave::geometry::testing
