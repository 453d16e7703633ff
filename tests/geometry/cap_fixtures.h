// SPDX-License-Identifier: MIT
// Cap polygons as test fixtures, in the style of earcut's: a polygon with holes taken from a real
// section, with the triangle count and area deviation its triangulation gave when it was recorded.
//
// A polygon is taken back out of a split: the cap triangles of one outer loop (provenance
// kFromCap | loop) on the below pieces, their boundary chained into rings (outer counter-clockwise,
// holes clockwise, seen from the plane normal) and projected on an orthonormal basis of the plane.
//
// File format (text, one fixture per file, numbers in %.17g so they read back exactly):
//   # free comment lines
//   tolerance T          the triangulator's tolerance for this polygon
//   triangles N          triangles the triangulation gave when recorded
//   deviation D          |sum of triangle areas - polygon area| / polygon area, when recorded
//   ring K               then K lines "x y"; the first ring is the outer border, the rest holes
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <array>

#include <glm/glm.hpp>

#include "cleave/geometry/cap_triangulator.h"
#include "cleave/geometry/split_types.h"

namespace cleave::geometry::testing {

struct CapFixture {
  std::string name;
  std::string comment;
  double tolerance = 0.0;
  size_t triangles = 0;
  double deviation = 0.0;
  std::vector<std::vector<glm::dvec2>> rings;
};

// The cap polygons of a split's below pieces (one per outer loop), in the plane's coordinates.
inline std::vector<CapFixture> capPolygonsOf(const SplitResult& result, const Plane& plane) {
  const glm::dvec3 n = glm::normalize(plane.normal);
  const glm::dvec3 helper = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 u = glm::normalize(glm::cross(n, helper)), v = glm::cross(n, u);
  std::vector<CapFixture> out;
  for (const SplitPiece& piece : result.pieces) {
    if (piece.side > 0 || piece.sourceTriangles.size() != piece.mesh.triangleCount()) continue;
    const MeshData& m = piece.mesh;
    std::map<uint32_t, std::vector<size_t>> byLoop;
    for (size_t t = 0; t < piece.sourceTriangles.size(); ++t) {
      if (piece.sourceTriangles[t] & kFromCap) byLoop[piece.sourceTriangles[t] & ~kFromCap].push_back(t);
    }
    for (const auto& [loop, triangles] : byLoop) {
      // Boundary edges by exact float position (cap vertices of one point may be several).
      std::map<std::array<float, 3>, uint32_t> ids;
      std::vector<glm::dvec3> points;
      auto idOf = [&](uint32_t vertex) {
        const glm::vec3 p = m.positions[vertex];
        const auto [it, added] = ids.insert({{p.x, p.y, p.z}, uint32_t(points.size())});
        if (added) points.push_back(glm::dvec3(p));
        return it->second;
      };
      std::multimap<uint32_t, uint32_t> edges;
      std::vector<std::pair<uint32_t, uint32_t>> directed;
      for (size_t t : triangles) {
        const uint32_t c[3] = {idOf(m.indices[3 * t]), idOf(m.indices[3 * t + 1]), idOf(m.indices[3 * t + 2])};
        for (int e = 0; e < 3; ++e) directed.push_back({c[e], c[(e + 1) % 3]});
      }
      std::sort(directed.begin(), directed.end());
      for (const auto& [a, b] : directed) {
        if (!std::binary_search(directed.begin(), directed.end(), std::make_pair(b, a))) edges.insert({a, b});
      }
      CapFixture fixture;
      while (!edges.empty()) {
        std::vector<glm::dvec2> ring;
        const uint32_t start = edges.begin()->first;
        uint32_t at = start;
        while (true) {
          const auto it = edges.find(at);
          if (it == edges.end()) break;
          ring.push_back({glm::dot(points[at], u), glm::dot(points[at], v)});
          at = it->second;
          edges.erase(it);
          if (at == start) break;
        }
        if (ring.size() >= 3) fixture.rings.push_back(std::move(ring));
      }
      if (fixture.rings.empty()) continue;
      // The outer border first: the ring of largest absolute area.
      auto area = [](const std::vector<glm::dvec2>& r) {
        double twice = 0.0;
        for (size_t k = 0; k < r.size(); ++k) twice += r[k].x * r[(k + 1) % r.size()].y - r[(k + 1) % r.size()].x * r[k].y;
        return 0.5 * twice;
      };
      std::stable_sort(fixture.rings.begin(), fixture.rings.end(),
                       [&](const auto& a, const auto& b) { return std::abs(area(a)) > std::abs(area(b)); });
      if (area(fixture.rings[0]) < 0.0) continue;  // not a polygon of the below cap's orientation
      out.push_back(std::move(fixture));
    }
  }
  return out;
}

struct Triangulated {
  bool ok = false;
  size_t triangles = 0;
  double deviation = 0.0;   // |sum of triangle areas - polygon area| / polygon area
  size_t flat = 0;          // triangles without area
  size_t ringEdgesMissing = 0;
};

inline Triangulated triangulateFixture(const CapFixture& f) {
  std::vector<glm::dvec2> points;
  std::vector<CapRing> rings;
  double polygon = 0.0;
  for (const auto& ring : f.rings) {
    const uint32_t begin = uint32_t(points.size());
    points.insert(points.end(), ring.begin(), ring.end());
    rings.push_back({begin, uint32_t(points.size())});
    polygon += 0.5 * CapTriangulator::twiceSignedArea(points, rings.back());
  }
  CapTriangulator triangulator;
  std::vector<uint32_t> triangles;
  Triangulated out;
  out.ok = triangulator.triangulate(points, rings, triangles, f.tolerance);
  out.triangles = triangles.size() / 3;
  double sum = 0.0;
  std::vector<std::pair<uint32_t, uint32_t>> edges;
  for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
    const glm::dvec2 a = points[triangles[t]], b = points[triangles[t + 1]], c = points[triangles[t + 2]];
    const double twice = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    sum += 0.5 * std::abs(twice);
    out.flat += twice == 0.0;
    for (int e = 0; e < 3; ++e) edges.push_back({triangles[t + e], triangles[t + (e + 1) % 3]});
  }
  std::sort(edges.begin(), edges.end());
  for (const CapRing& r : rings) {
    for (uint32_t k = r.begin; k < r.end; ++k) {
      const uint32_t next = k + 1 == r.end ? r.begin : k + 1;
      out.ringEdgesMissing += !std::binary_search(edges.begin(), edges.end(), std::make_pair(k, next));
    }
  }
  out.deviation = polygon > 0.0 ? std::abs(sum - polygon) / polygon : 0.0;
  return out;
}

inline bool writeFixture(const std::string& path, const CapFixture& f) {
  FILE* file = std::fopen(path.c_str(), "w");
  if (!file) return false;
  std::fprintf(file, "# cap fixture %s\n# %s\n", f.name.c_str(), f.comment.c_str());
  std::fprintf(file, "tolerance %.17g\ntriangles %zu\ndeviation %.17g\n", f.tolerance, f.triangles, f.deviation);
  for (const auto& ring : f.rings) {
    std::fprintf(file, "ring %zu\n", ring.size());
    for (const glm::dvec2& p : ring) std::fprintf(file, "%.17g %.17g\n", p.x, p.y);
  }
  return std::fclose(file) == 0;
}

// Reads a fixture; an empty string, or the reason it could not be read.
inline std::string readFixture(const std::string& path, CapFixture& f) {
  std::ifstream in(path);
  if (!in) return path + ": cannot open";
  std::string line;
  size_t lineNumber = 0;
  while (std::getline(in, line)) {
    ++lineNumber;
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    std::string key;
    words >> key;
    bool ok = true;
    if (key == "tolerance") {
      ok = bool(words >> f.tolerance);
    } else if (key == "triangles") {
      ok = bool(words >> f.triangles);
    } else if (key == "deviation") {
      ok = bool(words >> f.deviation);
    } else if (key == "ring") {
      size_t count = 0;
      ok = bool(words >> count) && count >= 3;
      std::vector<glm::dvec2> ring(count);
      for (size_t k = 0; ok && k < count; ++k, ++lineNumber) {
        ok = std::getline(in, line) && bool(std::istringstream(line) >> ring[k].x >> ring[k].y);
      }
      f.rings.push_back(std::move(ring));
    } else {
      ok = false;
    }
    if (!ok) return path + ":" + std::to_string(lineNumber) + ": cannot read '" + line + "'";
  }
  if (f.rings.empty()) return path + ": no ring";
  return {};
}

}  // namespace cleave::geometry::testing
