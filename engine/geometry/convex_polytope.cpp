// SPDX-License-Identifier: MIT
// Convex polytopes as face loops. Clipping follows Sutherland-Hodgman per face: each face polygon
// keeps its corners below the plane and gains a section point where an edge crosses it; the section
// points of one edge are shared by its two faces (keyed by the edge), and the new face is the ring of
// section points (and of the vertices on the plane) ordered by angle about their mean. The order of
// everything follows the input order, so the output is deterministic.
#include "cleave/geometry/convex_polytope.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace cleave::geometry {
namespace {

// Newell normal (unnormalised, twice the area) of a loop.
glm::dvec3 newellNormal(const std::vector<glm::dvec3>& v, const uint32_t* loop, uint32_t count) {
  glm::dvec3 n(0.0);
  for (uint32_t i = 0; i < count; ++i) {
    const glm::dvec3& a = v[loop[i]];
    const glm::dvec3& b = v[loop[(i + 1) % count]];
    n.x += (a.y - b.y) * (a.z + b.z);
    n.y += (a.z - b.z) * (a.x + b.x);
    n.z += (a.x - b.x) * (a.y + b.y);
  }
  return n;
}

// Adds a face from `loop`, its plane from the loop itself. Loops of no area are dropped.
void addFace(ConvexPolytope& p, const std::vector<uint32_t>& loop) {
  if (loop.size() < 3) return;
  const glm::dvec3 n = newellNormal(p.vertices, loop.data(), uint32_t(loop.size()));
  const double length = glm::length(n);
  if (!(length > 0.0)) return;
  ConvexPolytope::Face face;
  face.normal = n / length;
  glm::dvec3 mean(0.0);
  for (uint32_t v : loop) mean += p.vertices[v];
  face.offset = glm::dot(face.normal, mean / double(loop.size()));
  face.first = uint32_t(p.corners.size());
  face.count = uint32_t(loop.size());
  p.corners.insert(p.corners.end(), loop.begin(), loop.end());
  p.faces.push_back(face);
}

// Reusable memory of the clips of one shrink (and of a single clip).
struct ClipScratch {
  std::vector<double> dist;
  std::vector<uint32_t> kept;
  std::vector<std::pair<uint64_t, uint32_t>> crossings;  // edge key -> section vertex
  std::vector<uint32_t> section, loop, ring;
  std::vector<std::pair<double, uint32_t>> byAngle;
  std::vector<uint32_t> remap;
  std::vector<glm::dvec3> compacted;
};

// Drops vertices no face uses and renumbers the loops (in the order the loops first use them).
void compact(ConvexPolytope& p, ClipScratch& s) {
  constexpr uint32_t kUnseen = std::numeric_limits<uint32_t>::max();
  s.remap.assign(p.vertices.size(), kUnseen);
  s.compacted.clear();
  for (uint32_t& c : p.corners) {
    if (s.remap[c] == kUnseen) {
      s.remap[c] = uint32_t(s.compacted.size());
      s.compacted.push_back(p.vertices[c]);
    }
    c = s.remap[c];
  }
  std::swap(p.vertices, s.compacted);
}

// The scratch of this thread's clips: clipping allocates nothing once it has grown.
ClipScratch& threadScratch() {
  thread_local ClipScratch scratch;
  return scratch;
}

// Orders the section points (indices into p.vertices, all on the plane) counter-clockwise seen from
// the side `normal` points to, merging points closer than `tolerance`, into s.ring.
void sectionRing(const ConvexPolytope& p, ClipScratch& s, const glm::dvec3& n, double tolerance) {
  std::vector<uint32_t>& points = s.section;
  std::vector<uint32_t>& ring = s.ring;
  ring.clear();
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return;
  glm::dvec3 mean(0.0);
  for (uint32_t v : points) mean += p.vertices[v];
  mean /= double(points.size());
  const glm::dvec3 helper = std::abs(n.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 u = glm::normalize(glm::cross(helper, n));
  const glm::dvec3 w = glm::cross(n, u);
  s.byAngle.clear();
  for (uint32_t v : points) {
    const glm::dvec3 d = p.vertices[v] - mean;
    s.byAngle.emplace_back(std::atan2(glm::dot(d, w), glm::dot(d, u)), v);
  }
  std::sort(s.byAngle.begin(), s.byAngle.end());
  for (const auto& [angle, v] : s.byAngle) {
    if (!ring.empty() && glm::length(p.vertices[v] - p.vertices[ring.back()]) <= tolerance) continue;
    ring.push_back(v);
  }
  while (ring.size() > 1 && glm::length(p.vertices[ring.front()] - p.vertices[ring.back()]) <= tolerance)
    ring.pop_back();
  if (ring.size() < 3) ring.clear();
}

// clipPolytope into `out` (cleared first; its capacity is reused), with unit normal `n`.
void clipInto(const ConvexPolytope& p, const glm::dvec3& n, double d, double tolerance, ConvexPolytope& out,
              ClipScratch& s) {
  out.vertices.clear();
  out.corners.clear();
  out.faces.clear();
  s.dist.resize(p.vertices.size());
  bool anyBelow = false, anyAbove = false;
  for (size_t v = 0; v < p.vertices.size(); ++v) {
    s.dist[v] = glm::dot(n, p.vertices[v]) - d;
    anyBelow |= s.dist[v] < -tolerance;
    anyAbove |= s.dist[v] > tolerance;
  }
  if (!anyBelow) return;
  if (!anyAbove) {
    out = p;
    return;
  }
  constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();
  s.kept.assign(p.vertices.size(), kNone);
  for (size_t v = 0; v < p.vertices.size(); ++v) {
    if (s.dist[v] > tolerance) continue;
    s.kept[v] = uint32_t(out.vertices.size());
    out.vertices.push_back(p.vertices[v]);
  }
  s.crossings.clear();
  s.section.clear();
  auto crossing = [&](uint32_t a, uint32_t b) {
    const uint32_t lo = std::min(a, b), hi = std::max(a, b);
    const uint64_t key = (uint64_t(lo) << 32) | hi;
    for (const auto& [k, v] : s.crossings)
      if (k == key) return v;
    const double t = s.dist[lo] / (s.dist[lo] - s.dist[hi]);
    const uint32_t v = uint32_t(out.vertices.size());
    out.vertices.push_back(p.vertices[lo] + (p.vertices[hi] - p.vertices[lo]) * t);
    s.crossings.emplace_back(key, v);
    return v;
  };
  for (const ConvexPolytope::Face& face : p.faces) {
    s.loop.clear();
    for (uint32_t i = 0; i < face.count; ++i) {
      const uint32_t a = p.corners[face.first + i];
      const uint32_t b = p.corners[face.first + (i + 1 == face.count ? 0 : i + 1)];
      const double da = s.dist[a], db = s.dist[b];
      if (s.kept[a] != kNone) {
        s.loop.push_back(s.kept[a]);
        if (std::abs(da) <= tolerance) s.section.push_back(s.kept[a]);
      }
      if ((da < -tolerance && db > tolerance) || (da > tolerance && db < -tolerance)) {
        const uint32_t c = crossing(a, b);
        s.loop.push_back(c);
        s.section.push_back(c);
      }
    }
    if (s.loop.size() < 3) continue;
    ConvexPolytope::Face clipped = face;
    clipped.first = uint32_t(out.corners.size());
    clipped.count = uint32_t(s.loop.size());
    out.corners.insert(out.corners.end(), s.loop.begin(), s.loop.end());
    out.faces.push_back(clipped);
  }
  sectionRing(out, s, n, tolerance);
  if (s.ring.size() < 3) {  // the cut-off part is a sliver whose section collapses: keep `p` whole
    out = p;
    return;
  }
  {
    ConvexPolytope::Face cap;
    cap.normal = n;
    cap.offset = d;
    cap.first = uint32_t(out.corners.size());
    cap.count = uint32_t(s.ring.size());
    out.corners.insert(out.corners.end(), s.ring.begin(), s.ring.end());
    out.faces.push_back(cap);
  }
  compact(out, s);
}

}  // namespace

ConvexPolytope polytopeFromHull(const ConvexHull& hull) {
  ConvexPolytope p;
  if (hull.status != HullStatus::Ok || hull.indices.size() < 12) return p;
  p.vertices = hull.positions;
  // Coplanar hull triangles become one polygon face (a box has six faces, not twelve), so a clip adds
  // no section point on a triangle's diagonal and a shrink clips once per plane.
  const size_t triangles = hull.indices.size() / 3;
  std::vector<glm::dvec3> normals(triangles);
  std::vector<double> offsets(triangles);
  for (size_t t = 0; t < triangles; ++t) {
    const glm::dvec3& a = p.vertices[hull.indices[3 * t]];
    const glm::dvec3 n = glm::cross(p.vertices[hull.indices[3 * t + 1]] - a, p.vertices[hull.indices[3 * t + 2]] - a);
    const double length = glm::length(n);
    normals[t] = length > 0.0 ? n / length : glm::dvec3(0.0);
    offsets[t] = glm::dot(normals[t], a);
  }
  glm::dvec3 lo, hi;
  polytopeBounds(p, lo, hi);
  const double tolerance = 1e-9 * std::max(glm::length(hi - lo), 1e-30);
  std::vector<char> used(triangles, 0);
  std::vector<std::pair<uint32_t, uint32_t>> edges;  // directed edges of one coplanar group
  std::vector<uint32_t> loop;
  for (size_t t = 0; t < triangles; ++t) {
    if (used[t] || normals[t] == glm::dvec3(0.0)) continue;
    edges.clear();
    for (size_t u = t; u < triangles; ++u) {
      if (used[u] || glm::dot(normals[u], normals[t]) < 1.0 - 1e-12 || std::abs(offsets[u] - offsets[t]) > tolerance)
        continue;
      used[u] = 1;
      for (int k = 0; k < 3; ++k) edges.emplace_back(hull.indices[3 * u + k], hull.indices[3 * u + (k + 1) % 3]);
    }
    // The boundary: directed edges whose reverse is not in the group, chained into one loop.
    std::vector<std::pair<uint32_t, uint32_t>> boundary;
    for (const auto& [a, b] : edges)
      if (std::find(edges.begin(), edges.end(), std::make_pair(b, a)) == edges.end()) boundary.emplace_back(a, b);
    loop.clear();
    if (boundary.empty()) continue;
    loop.push_back(boundary[0].first);
    uint32_t at = boundary[0].second;
    for (size_t guard = 0; at != loop[0] && guard < boundary.size(); ++guard) {
      loop.push_back(at);
      const auto next = std::find_if(boundary.begin(), boundary.end(), [&](const auto& e) { return e.first == at; });
      if (next == boundary.end()) break;
      at = next->second;
    }
    if (at == loop[0] && loop.size() == boundary.size()) {
      addFace(p, loop);
      continue;
    }
    // Not one simple loop (triangles only nearly coplanar): keep the group's triangles as faces.
    for (size_t e = 0; e + 2 < edges.size(); e += 3) addFace(p, {edges[e].first, edges[e + 1].first, edges[e + 2].first});
  }
  compact(p, threadScratch());
  if (p.empty()) return ConvexPolytope{};
  return p;
}

ConvexPolytope polytopeOfPoints(std::span<const glm::vec3> points) {
  if (points.size() < 4) return ConvexPolytope{};
  return polytopeFromHull(computeConvexHull(points));
}

ConvexPolytope clipPolytope(const ConvexPolytope& p, const glm::dvec3& normal, double offset,
                            double tolerance) {
  ConvexPolytope out;
  clipPolytope(p, normal, offset, tolerance, out);
  return out;
}

void clipPolytope(const ConvexPolytope& p, const glm::dvec3& normal, double offset, double tolerance,
                  ConvexPolytope& out) {
  out.vertices.clear();
  out.corners.clear();
  out.faces.clear();
  const double length = glm::length(normal);
  if (p.empty() || !(length > 0.0) || !std::isfinite(offset)) return;
  clipInto(p, normal / length, offset / length, tolerance, out, threadScratch());
  if (out.empty()) {
    out.vertices.clear();
    out.corners.clear();
    out.faces.clear();
  }
}

ConvexPolytope transformPolytope(const ConvexPolytope& p, const glm::dmat4& m) {
  ConvexPolytope out;
  if (p.empty()) return out;
  out.vertices.reserve(p.vertices.size());
  for (const glm::dvec3& v : p.vertices) out.vertices.push_back(glm::dvec3(m * glm::dvec4(v, 1.0)));
  const bool mirrored = glm::determinant(glm::dmat3(m)) < 0.0;
  std::vector<uint32_t> loop;
  for (const ConvexPolytope::Face& face : p.faces) {
    loop.assign(p.corners.begin() + face.first, p.corners.begin() + face.first + face.count);
    if (mirrored) std::reverse(loop.begin(), loop.end());
    addFace(out, loop);
  }
  if (out.empty()) return ConvexPolytope{};
  return out;
}

ConvexPolytope shrinkPolytope(const ConvexPolytope& p, double margin) {
  if (p.empty() || !(margin > 0.0)) return p;
  // Distinct planes only: hull triangles of one flat side share a plane and clip once.
  std::vector<std::pair<glm::dvec3, double>> planes;
  for (const ConvexPolytope::Face& f : p.faces) {
    bool seen = false;
    for (const auto& [n, o] : planes)
      if (glm::dot(n, f.normal) > 1.0 - 1e-12 && std::abs(o - f.offset) <= 1e-12 * (1.0 + std::abs(o))) seen = true;
    if (!seen) planes.emplace_back(f.normal, f.offset);
  }
  glm::dvec3 lo, hi;
  polytopeBounds(p, lo, hi);
  const double tolerance = 1e-9 * std::max(glm::length(hi - lo), 1e-30);
  ConvexPolytope current = p, next;
  ClipScratch& scratch = threadScratch();
  for (const auto& [n, o] : planes) {
    clipInto(current, n, o - margin, tolerance, next, scratch);
    if (next.empty()) return ConvexPolytope{};
    std::swap(current, next);
  }
  return current;
}

std::vector<uint32_t> extremeVertices(const ConvexPolytope& p, uint32_t count) {
  if (p.vertices.size() > count) return extremePoints(p.vertices, count);
  std::vector<uint32_t> all(p.vertices.size());
  for (uint32_t v = 0; v < all.size(); ++v) all[v] = v;
  return all;
}

ConvexPolytope simplifyPolytope(const ConvexPolytope& p, uint32_t maxVertices) {
  if (p.empty() || p.vertices.size() <= maxVertices || maxVertices < 4) return p;
  std::vector<glm::dvec3> kept;
  for (uint32_t v : extremeVertices(p, maxVertices)) kept.push_back(p.vertices[v]);
  ConvexPolytope simple = polytopeFromHull(computeConvexHull(std::span<const glm::dvec3>(kept)));
  return simple.empty() ? p : simple;
}

double polytopeVolume(const ConvexPolytope& p) {
  if (p.empty()) return 0.0;
  const glm::dvec3 origin = p.vertices[0];
  double six = 0.0;
  for (const ConvexPolytope::Face& f : p.faces) {
    const glm::dvec3 a = p.vertices[p.corners[f.first]] - origin;
    for (uint32_t i = 1; i + 1 < f.count; ++i) {
      const glm::dvec3 b = p.vertices[p.corners[f.first + i]] - origin;
      const glm::dvec3 c = p.vertices[p.corners[f.first + i + 1]] - origin;
      six += glm::dot(a, glm::cross(b, c));
    }
  }
  return six / 6.0;
}

glm::dvec3 polytopeCentroid(const ConvexPolytope& p) {
  glm::dvec3 mean(0.0);
  for (const glm::dvec3& v : p.vertices) mean += v;
  if (!p.vertices.empty()) mean /= double(p.vertices.size());
  if (p.empty()) return mean;
  double six = 0.0;
  glm::dvec3 moment(0.0);
  for (const ConvexPolytope::Face& f : p.faces) {
    const glm::dvec3 a = p.vertices[p.corners[f.first]] - mean;
    for (uint32_t i = 1; i + 1 < f.count; ++i) {
      const glm::dvec3 b = p.vertices[p.corners[f.first + i]] - mean;
      const glm::dvec3 c = p.vertices[p.corners[f.first + i + 1]] - mean;
      const double v = glm::dot(a, glm::cross(b, c));
      six += v;
      moment += v * (a + b + c) / 4.0;
    }
  }
  return six > 0.0 ? mean + moment / six : mean;
}

double polytopeWidth(const ConvexPolytope& p) {
  if (p.empty()) return 0.0;
  double best = std::numeric_limits<double>::infinity();
  for (const ConvexPolytope::Face& f : p.faces) {
    double depth = 0.0;
    for (const glm::dvec3& v : p.vertices) depth = std::max(depth, f.offset - glm::dot(f.normal, v));
    best = std::min(best, depth);
  }
  return std::isfinite(best) ? best : 0.0;
}

void polytopeBounds(const ConvexPolytope& p, glm::dvec3& lo, glm::dvec3& hi) {
  lo = glm::dvec3(std::numeric_limits<double>::infinity());
  hi = -lo;
  for (const glm::dvec3& v : p.vertices) {
    lo = glm::min(lo, v);
    hi = glm::max(hi, v);
  }
  if (p.vertices.empty()) lo = hi = glm::dvec3(0.0);
}

}  // namespace cleave::geometry
