// SPDX-License-Identifier: MIT
// Convex polytopes as face loops. Clipping follows Sutherland-Hodgman per face, editing only the
// faces a plane reaches: each keeps its corners below the plane and gains a section point where an
// edge crosses it; the section points of one edge are shared by its two faces (keyed by the edge),
// and the new face is the hole the clipped faces leave, edge for edge (or, where that does not chain
// into one loop, the ring of section points ordered by angle about their mean). Shrinking moves each
// vertex to where its faces' moved planes meet, splitting it where they no longer meet in one point,
// and falls back to one clip per face where faces vanish. The order of everything follows the input
// order, so the output is deterministic.
#include "cleave/geometry/convex_polytope.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <cstdio>

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

// Appends corner `v` to the loop that starts at `first`, unless it repeats the corner before it.
void pushCorner(std::vector<uint32_t>& corners, size_t first, uint32_t v) {
  if (corners.size() == first || corners.back() != v) corners.push_back(v);
}

// Drops the last corners of the loop that starts at `first` while they repeat its first one; its
// corner count.
uint32_t closeLoop(std::vector<uint32_t>& corners, size_t first) {
  while (corners.size() > first + 1 && corners.back() == corners[first]) corners.pop_back();
  return uint32_t(corners.size() - first);
}

// Reusable memory of the clips of one shrink (and of a single clip).
struct ClipScratch {
  std::vector<double> dist;
  std::vector<std::pair<uint64_t, uint32_t>> crossings;  // edge key -> section vertex
  std::vector<uint32_t> section, ring;
  std::vector<std::pair<uint32_t, uint32_t>> merges;  // section points merged into a ring point
  std::vector<std::pair<uint32_t, uint32_t>> hole;    // directed edges around the hole a clip leaves
  std::vector<char> cancelled;
  std::vector<std::pair<double, uint32_t>> byAngle;
  std::vector<uint32_t> remap;
  std::vector<glm::dvec3> compacted;
};

// `corners`, indices into `from`, renumbered to the vertices they use in the order they first use
// them, those vertices written to `into` (which must not be `from`).
void renumberByFirstUse(const std::vector<glm::dvec3>& from, std::vector<uint32_t>& corners,
                        std::vector<glm::dvec3>& into, ClipScratch& s) {
  constexpr uint32_t kUnseen = std::numeric_limits<uint32_t>::max();
  s.remap.assign(from.size(), kUnseen);
  into.clear();
  into.reserve(from.size());  // at most one allocation
  for (uint32_t& c : corners) {
    if (s.remap[c] == kUnseen) {
      s.remap[c] = uint32_t(into.size());
      into.push_back(from[c]);
    }
    c = s.remap[c];
  }
}

// Drops vertices no face uses and renumbers the loops (in the order the loops first use them).
void compact(ConvexPolytope& p, ClipScratch& s) {
  renumberByFirstUse(p.vertices, p.corners, s.compacted, s);
  std::swap(p.vertices, s.compacted);  // the buffers change hands: the scratch keeps the old one
}

// The scratch of this thread's clips: clipping allocates nothing once it has grown.
ClipScratch& threadScratch() {
  thread_local ClipScratch scratch;
  return scratch;
}

// A stand-in for atan2(y, x) that orders directions the same way, from just above -pi up to pi
// (the diamond angle: exact rational steps, no trigonometry).
double pseudoAngle(double x, double y) {
  const double sum = std::abs(x) + std::abs(y);
  if (!(sum > 0.0)) return 0.0;
  double d = 0.0;  // 0 along +x, 1 along +y, 2 along -x, 3 along -y
  if (y >= 0.0)
    d = x >= 0.0 ? y / sum : 1.0 - x / sum;
  else
    d = x < 0.0 ? 2.0 - y / sum : 3.0 + x / sum;
  if (d > 2.0 || (d == 2.0 && std::signbit(y))) d -= 4.0;
  return d;
}

// Orders the section points (indices into `vertices`, all on the plane) counter-clockwise seen from
// the side `normal` points to, merging points closer than `tolerance`, into s.ring.
void sectionRing(const std::vector<glm::dvec3>& vertices, ClipScratch& s, const glm::dvec3& n, double tolerance) {
  std::vector<uint32_t>& points = s.section;
  std::vector<uint32_t>& ring = s.ring;
  ring.clear();
  s.merges.clear();
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return;
  glm::dvec3 mean(0.0);
  for (uint32_t v : points) mean += vertices[v];
  mean /= double(points.size());
  const glm::dvec3 helper = std::abs(n.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 u = glm::normalize(glm::cross(helper, n));
  const glm::dvec3 w = glm::cross(n, u);
  s.byAngle.clear();
  for (uint32_t v : points) {
    const glm::dvec3 d = vertices[v] - mean;
    s.byAngle.emplace_back(pseudoAngle(glm::dot(d, u), glm::dot(d, w)), v);
  }
  std::sort(s.byAngle.begin(), s.byAngle.end());
  for (const auto& [angle, v] : s.byAngle) {
    if (!ring.empty() && glm::length(vertices[v] - vertices[ring.back()]) <= tolerance) {
      s.merges.emplace_back(v, ring.back());
      continue;
    }
    ring.push_back(v);
  }
  while (ring.size() > 1 && glm::length(vertices[ring.front()] - vertices[ring.back()]) <= tolerance) {
    for (auto& [from, to] : s.merges)
      if (to == ring.back()) to = ring.front();
    s.merges.emplace_back(ring.back(), ring.front());
    ring.pop_back();
  }
  if (ring.size() < 3) ring.clear();
}

// A polytope clipped by many planes in turn, edited where each plane cuts: faces no plane reaches
// keep their loops, dropped vertices are only marked, and nothing is renumbered until the end. The
// same solid as the one-plane clips one after another (which rebuild the whole polytope each time).
class PolytopeEditor {
  static constexpr uint32_t kNoVertex = std::numeric_limits<uint32_t>::max();

 public:
  void reset(const ConvexPolytope& p) {
    vertices_ = p.vertices;
    live_.resize(vertices_.size());
    for (uint32_t v = 0; v < live_.size(); ++v) live_[v] = v;
    pool_ = p.corners;
    faces_ = p.faces;
    faceAlive_.assign(faces_.size(), 1);
  }

  // Keeps the part with dot(n, x) <= d (n unit). False when nothing is left.
  bool clip(const glm::dvec3& n, double d, double tolerance, ClipScratch& s) {
    s.dist.resize(vertices_.size());
    bool anyBelow = false, anyAbove = false;
    for (const uint32_t v : live_) {
      s.dist[v] = glm::dot(n, vertices_[v]) - d;
      anyBelow |= s.dist[v] < -tolerance;
      anyAbove |= s.dist[v] > tolerance;
    }
    if (!anyBelow) return false;
    if (!anyAbove) return true;
    const size_t vertexMark = vertices_.size(), poolMark = pool_.size();
    s.crossings.clear();
    s.section.clear();
    s.hole.clear();
    touched_.clear();
    for (uint32_t f = 0; f < faces_.size(); ++f) {
      if (!faceAlive_[f]) continue;
      const Reach reach = reachOf(faces_[f], s, tolerance);
      if (reach == Reach::Crossed) clipFace(f, s, tolerance);
      if (reach == Reach::Above) touched_.push_back({f, uint32_t(pool_.size()), 0});  // nothing kept, no hole
    }
    if (!holeRing(s)) {
      // The section points for the angle ring: the corners of the new loops on the plane.
      for (const Touched& t : touched_)
        for (uint32_t i = 0; i < t.count; ++i)
          if (std::abs(s.dist[pool_[t.first + i]]) <= tolerance) s.section.push_back(pool_[t.first + i]);
      sectionRing(vertices_, s, n, tolerance);
    }
    if (s.ring.size() < 3) {  // the cut-off part is a sliver whose section collapses: keep the polytope whole
      vertices_.resize(vertexMark);
      pool_.resize(poolMark);
      return true;
    }
    for (const Touched& t : touched_) {
      faceAlive_[t.face] = t.count >= 3;
      faces_[t.face].first = t.first;
      faces_[t.face].count = t.count;
    }
    if (!s.merges.empty()) mergeSectionPoints(s);
    live_.erase(std::remove_if(live_.begin(), live_.end(), [&](uint32_t v) { return s.dist[v] > tolerance; }),
                live_.end());
    for (uint32_t v = uint32_t(vertexMark); v < vertices_.size(); ++v)
      if (!(s.dist[v] > tolerance)) live_.push_back(v);
    ConvexPolytope::Face cap;
    cap.normal = n;
    cap.offset = d;
    cap.first = uint32_t(pool_.size());
    cap.count = uint32_t(s.ring.size());
    pool_.insert(pool_.end(), s.ring.begin(), s.ring.end());
    faces_.push_back(cap);
    faceAlive_.push_back(1);
    return true;
  }

  // The polytope, its vertices numbered in the order the face loops first use them, each array
  // allocated once.
  void write(ConvexPolytope& out, ClipScratch& s) const {
    out.corners.clear();
    out.faces.clear();
    size_t faces = 0, corners = 0;
    for (uint32_t f = 0; f < faces_.size(); ++f)
      if (faceAlive_[f]) ++faces, corners += faces_[f].count;
    out.faces.reserve(faces);
    out.corners.reserve(corners);
    for (uint32_t f = 0; f < faces_.size(); ++f) {
      if (!faceAlive_[f]) continue;
      ConvexPolytope::Face face = faces_[f];
      face.first = uint32_t(out.corners.size());
      out.corners.insert(out.corners.end(), pool_.begin() + faces_[f].first,
                         pool_.begin() + faces_[f].first + faces_[f].count);
      out.faces.push_back(face);
    }
    renumberByFirstUse(vertices_, out.corners, out.vertices, s);
    if (out.empty()) {
      out.vertices.clear();
      out.corners.clear();
      out.faces.clear();
    }
  }

 private:
  // The cap as the hole the clipped faces leave: the edges where their loops skip corners above the
  // plane (clipFace), less any whose reverse is one too, each taken the other way round and chained
  // into one loop. So the cap meets every side face edge for edge, even where the section is a
  // sliver within the tolerance. False (and s.ring empty) when they do not chain into one simple loop.
  bool holeRing(ClipScratch& s) {
    s.ring.clear();
    s.merges.clear();
    // Sorted by end vertex: a new edge whose reverse is new too leaves no hole there (the plane
    // passed through both its ends); every other end vertex must end exactly one hole edge.
    std::sort(s.hole.begin(), s.hole.end(), [](const auto& x, const auto& y) {
      return x.second != y.second ? x.second < y.second : x.first < y.first;
    });
    auto ending = [&](uint32_t v) {
      return std::lower_bound(s.hole.begin(), s.hole.end(), v, [](const auto& e, uint32_t w) { return e.second < w; });
    };
    s.cancelled.assign(s.hole.size(), 0);
    for (size_t i = 0; i < s.hole.size(); ++i)
      for (auto it = ending(s.hole[i].first); it != s.hole.end() && it->second == s.hole[i].first; ++it)
        if (it->first == s.hole[i].second) s.cancelled[i] = 1;
    size_t kept = 0;
    for (size_t i = 0; i < s.hole.size(); ++i)
      if (!s.cancelled[i]) s.hole[kept++] = s.hole[i];
    s.hole.resize(kept);  // still sorted by end vertex
    if (s.hole.size() < 3) return false;
    // Cap edge b -> a for every hole edge a -> b: from a hole edge's end, go to its start.
    const uint32_t start = s.hole[0].second;
    uint32_t at = start;
    for (size_t step = 0; step < s.hole.size(); ++step) {
      s.ring.push_back(at);
      const auto it = ending(at);
      if (it == s.hole.end() || it->second != at || (it + 1 != s.hole.end() && (it + 1)->second == at)) break;
      at = it->first;
    }
    if (at != start || s.ring.size() != s.hole.size()) {
      s.ring.clear();
      return false;
    }
    return true;
  }

  // Section points the ring merged (closer than the tolerance) become the ring point in every loop,
  // a corner repeated by that is dropped, and the merged points are marked for dropping.
  void mergeSectionPoints(ClipScratch& s) {
    auto target = [&](uint32_t v) {
      for (const auto& [from, to] : s.merges)
        if (from == v) return to;
      return v;
    };
    for (uint32_t f = 0; f < faces_.size(); ++f) {
      if (!faceAlive_[f]) continue;
      ConvexPolytope::Face& face = faces_[f];
      uint32_t count = 0;
      for (uint32_t i = 0; i < face.count; ++i) {
        const uint32_t v = target(pool_[face.first + i]);
        if (count == 0 || pool_[face.first + count - 1] != v) pool_[face.first + count++] = v;
      }
      while (count > 1 && pool_[face.first + count - 1] == pool_[face.first]) --count;
      face.count = count;
      faceAlive_[f] = count >= 3;
    }
    for (const auto& [from, to] : s.merges) s.dist[from] = std::numeric_limits<double>::infinity();
  }

  // Whether the plane leaves face f whole (every corner within the tolerance or below), drops it
  // (every corner above) or cuts it.
  enum class Reach : uint8_t { Below, Above, Crossed };
  Reach reachOf(const ConvexPolytope::Face& face, const ClipScratch& s, double tolerance) const {
    uint32_t above = 0;
    for (uint32_t i = 0; i < face.count; ++i) above += s.dist[pool_[face.first + i]] > tolerance ? 1 : 0;
    return above == 0 ? Reach::Below : (above == face.count ? Reach::Above : Reach::Crossed);
  }

  // The loop of face f below the plane, appended to the pool (Sutherland-Hodgman, one section
  // point per crossed edge shared by its two faces).
  void clipFace(uint32_t f, ClipScratch& s, double tolerance) {
    const ConvexPolytope::Face face = faces_[f];
    const uint32_t first = uint32_t(pool_.size());
    // Where the loop skips the corners above the plane, it crosses the hole the clip leaves: that
    // edge of the new loop is a hole edge (the cap takes it the other way round).
    bool skipped = false, skippedFirst = false;
    auto push = [&](uint32_t v) {
      if (skipped && pool_.size() > first) s.hole.emplace_back(pool_.back(), v);
      skippedFirst |= skipped && pool_.size() == first;
      skipped = false;
      pool_.push_back(v);
    };
    for (uint32_t i = 0; i < face.count; ++i) {
      const uint32_t a = pool_[face.first + i];
      const uint32_t b = pool_[face.first + (i + 1 == face.count ? 0 : i + 1)];
      const double da = s.dist[a], db = s.dist[b];
      if (da <= tolerance) {
        push(a);
      } else {
        skipped = true;
      }
      if ((da < -tolerance && db > tolerance) || (da > tolerance && db < -tolerance)) {
        const uint32_t c = crossing(a, b, s);
        push(c);
      }
    }
    if ((skipped || skippedFirst) && pool_.size() > first + 1) s.hole.emplace_back(pool_.back(), pool_[first]);
    touched_.push_back({f, first, uint32_t(pool_.size()) - first});
  }

  uint32_t crossing(uint32_t a, uint32_t b, ClipScratch& s) {
    const uint32_t lo = std::min(a, b), hi = std::max(a, b);
    const uint64_t key = (uint64_t(lo) << 32) | hi;
    for (const auto& [k, v] : s.crossings)
      if (k == key) return v;
    const double t = s.dist[lo] / (s.dist[lo] - s.dist[hi]);
    const uint32_t v = uint32_t(vertices_.size());
    vertices_.push_back(vertices_[lo] + (vertices_[hi] - vertices_[lo]) * t);
    s.dist.push_back(0.0);
    s.crossings.emplace_back(key, v);
    return v;
  }

  std::vector<glm::dvec3> vertices_;
  std::vector<uint32_t> live_;  // the vertices no plane has dropped
  std::vector<uint32_t> pool_;  // face loops; a clipped face's new loop is appended
  std::vector<ConvexPolytope::Face> faces_;
  std::vector<char> faceAlive_;
  struct Touched {
    uint32_t face, first, count;  // a face cut by this plane and its new loop in the pool
  };
  std::vector<Touched> touched_;
};

PolytopeEditor& threadEditor() {
  thread_local PolytopeEditor editor;
  return editor;
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
  const HalfSpace h{normal, offset};
  clipPolytope(p, std::span<const HalfSpace>(&h, 1), tolerance, out);
}

void clipPolytope(const ConvexPolytope& p, std::span<const HalfSpace> halfSpaces, double tolerance,
                  ConvexPolytope& out) {
  out.vertices.clear();
  out.corners.clear();
  out.faces.clear();
  if (p.empty()) return;
  PolytopeEditor& editor = threadEditor();
  ClipScratch& scratch = threadScratch();
  editor.reset(p);
  for (const HalfSpace& h : halfSpaces) {
    const double length = glm::length(h.normal);
    if (!(length > 0.0) || !std::isfinite(h.offset) || !editor.clip(h.normal / length, h.offset / length, tolerance, scratch))
      return;
  }
  editor.write(out, scratch);
}

ConvexPolytope transformPolytope(const ConvexPolytope& p, const glm::dmat4& m) {
  ConvexPolytope out;
  if (p.empty()) return out;
  out.vertices.reserve(p.vertices.size());
  for (const glm::dvec3& v : p.vertices) out.vertices.push_back(glm::dvec3(m * glm::dvec4(v, 1.0)));
  const bool mirrored = glm::determinant(glm::dmat3(m)) < 0.0;
  out.corners.reserve(p.corners.size());
  out.faces.reserve(p.faces.size());
  std::vector<uint32_t> loop;
  for (const ConvexPolytope::Face& face : p.faces) {
    loop.assign(p.corners.begin() + face.first, p.corners.begin() + face.first + face.count);
    if (mirrored) std::reverse(loop.begin(), loop.end());
    addFace(out, loop);
  }
  if (out.empty()) return ConvexPolytope{};
  return out;
}

namespace {

// One vertex of the shrunk polytope: where the moved planes of three faces at an input vertex meet
// (a, b, c: positions in the turn of the faces around it), or of all of them (`whole`).
struct MovedCorner {
  uint32_t a = 0, b = 0, c = 0;
  uint32_t vertex = 0;  // into the output's vertices
  bool whole = false;
};

// Reusable memory of the shrinks of this thread.
struct ShrinkScratch {
  std::vector<uint32_t> firstFace, faceOf, cursor;  // the faces at each vertex (offsets, concatenation)
  std::vector<uint32_t> firstMoved;                 // per input vertex, into moved
  std::vector<MovedCorner> moved;
  std::vector<uint32_t> origin;  // per output vertex, the input vertex it moved from
  std::vector<std::pair<uint32_t, uint32_t>> chords;
  std::vector<std::pair<uint32_t, uint32_t>> fan;  // (order key, output vertex)
  std::vector<uint32_t> mergedTo;                  // per point of one split: the point it became
  std::vector<double> edgeTime;                    // per corner: the margin its edge shrinks to nothing at
  ConvexPolytope step, collapsed;                   // the shrink's polytope after a change, and the next
};

ShrinkScratch& threadShrinkScratch() {
  thread_local ShrinkScratch scratch;
  return scratch;
}

// Fills s.firstFace and s.faceOf: the faces at vertex v are s.faceOf[s.firstFace[v] .. s.firstFace[v + 1]).
void facesAtVertices(const ConvexPolytope& p, ShrinkScratch& s) {
  s.firstFace.assign(p.vertices.size() + 1, 0);
  for (uint32_t c : p.corners) ++s.firstFace[c + 1];
  for (size_t v = 0; v < p.vertices.size(); ++v) s.firstFace[v + 1] += s.firstFace[v];
  s.faceOf.resize(p.corners.size());
  s.cursor.assign(s.firstFace.begin(), s.firstFace.end() - 1);
  for (uint32_t f = 0; f < p.faces.size(); ++f)
    for (uint32_t i = 0; i < p.faces[f].count; ++i) s.faceOf[s.cursor[p.corners[p.faces[f].first + i]]++] = f;
}

// The corners before and after `v` in the loop of face `f`.
void besideIn(const ConvexPolytope& p, uint32_t f, uint32_t v, uint32_t& before, uint32_t& after) {
  const ConvexPolytope::Face& face = p.faces[f];
  for (uint32_t i = 0; i < face.count; ++i) {
    if (p.corners[face.first + i] != v) continue;
    before = p.corners[face.first + (i == 0 ? face.count - 1 : i - 1)];
    after = p.corners[face.first + (i + 1 == face.count ? 0 : i + 1)];
    return;
  }
}

// Orders `faces` (those at `v`) in turn around it: each next one holds the edge leaving v in the one
// before, the other way round. False when they do not close one fan.
bool turnAround(const ConvexPolytope& p, uint32_t v, uint32_t* faces, uint32_t count) {
  uint32_t before = 0, after = 0, firstBefore = 0;
  besideIn(p, faces[0], v, firstBefore, after);
  for (uint32_t t = 0; t + 1 < count; ++t) {
    besideIn(p, faces[t], v, before, after);
    uint32_t found = count;
    for (uint32_t u = t + 1; u < count && found == count; ++u) {
      uint32_t hisBefore = 0, hisAfter = 0;
      besideIn(p, faces[u], v, hisBefore, hisAfter);
      if (hisBefore == after) found = u;
    }
    if (found == count) return false;
    std::swap(faces[t + 1], faces[found]);
  }
  besideIn(p, faces[count - 1], v, before, after);
  return after == firstBefore;
}

// Where the planes of faces a, b and c, moved inwards by `margin`, meet: solved as a move from `v`
// (which is on all three), so nothing large cancels. False when the planes are nearly dependent.
bool meetOfMoved(const ConvexPolytope::Face& a, const ConvexPolytope::Face& b, const ConvexPolytope::Face& c,
                 const glm::dvec3& v, double margin, glm::dvec3& out) {
  const glm::dvec3 ab = glm::cross(a.normal, b.normal);
  const double det = glm::dot(ab, c.normal);
  if (!(std::abs(det) > 1e-9)) return false;
  auto lift = [&](const ConvexPolytope::Face& f) { return f.offset - margin - glm::dot(f.normal, v); };
  out = v + (lift(a) * glm::cross(b.normal, c.normal) + lift(b) * glm::cross(c.normal, a.normal) + lift(c) * ab) / det;
  return true;
}

// Whether `x` is within `tolerance` below (or on) every moved plane of `faces`; with `onAll`, on every one.
bool withinMoved(const ConvexPolytope& p, const uint32_t* faces, uint32_t count, double margin, double tolerance,
                 const glm::dvec3& x, bool onAll) {
  for (uint32_t i = 0; i < count; ++i) {
    const ConvexPolytope::Face& f = p.faces[faces[i]];
    const double d = glm::dot(f.normal, x) - (f.offset - margin);
    if (d > tolerance || (onAll && d < -tolerance)) return false;
  }
  return true;
}

// One moved vertex where the moved planes of all the faces at `v` still meet in one point (three
// faces always do; more do when their normals lie on one cone, as at a sphere's pole).
bool moveWhole(const ConvexPolytope& p, const glm::dvec3& v, const uint32_t* faces, uint32_t count, double margin,
               double tolerance, glm::dvec3& out) {
  if (count < 3) return false;
  const ConvexPolytope::Face& a = p.faces[faces[0]];
  uint32_t b = 1, c = 0;
  for (uint32_t i = 2; i < count; ++i)
    if (std::abs(glm::dot(p.faces[faces[i]].normal, a.normal)) < std::abs(glm::dot(p.faces[faces[b]].normal, a.normal)))
      b = i;
  const glm::dvec3 ab = glm::cross(a.normal, p.faces[faces[b]].normal);
  double best = 0.0;
  for (uint32_t i = 1; i < count; ++i)
    if (i != b && std::abs(glm::dot(ab, p.faces[faces[i]].normal)) > best)
      best = std::abs(glm::dot(ab, p.faces[faces[i]].normal)), c = i;
  return c != 0 && meetOfMoved(a, p.faces[faces[b]], p.faces[faces[c]], v, margin, out) &&
         withinMoved(p, faces, count, margin, tolerance, out, true);
}

// Points of one split that coincide within the tolerance (normals of four or more of its faces on
// one circle: their planes still meet in one point there) become one vertex, the first of them; the
// moved corners that had the others take it, and writeLoops drops the repeated corners.
void mergeCoincident(size_t first, size_t firstMoved, double tolerance, ConvexPolytope& out, ShrinkScratch& s) {
  std::vector<uint32_t>& to = s.mergedTo;
  to.resize(out.vertices.size() - first);
  uint32_t kept = 0;
  for (size_t i = first; i < out.vertices.size(); ++i) {
    size_t j = first;
    while (j < i && !(to[j - first] == j - first && glm::length(out.vertices[i] - out.vertices[j]) <= tolerance))
      ++j;
    to[i - first] = uint32_t(j - first);  // itself when none before it coincides
  }
  for (size_t i = first; i < out.vertices.size(); ++i) {  // compacted: kept points renumbered in order
    if (to[i - first] != i - first) {
      to[i - first] = to[to[i - first]];
      continue;
    }
    out.vertices[first + kept] = out.vertices[i];
    s.origin[first + kept] = s.origin[i];
    to[i - first] = kept++;
  }
  if (kept == out.vertices.size() - first) return;
  for (size_t m = firstMoved; m < s.moved.size(); ++m)
    s.moved[m].vertex = uint32_t(first) + to[s.moved[m].vertex - first];
  out.vertices.resize(first + kept);
  s.origin.resize(first + kept);
}

// A vertex whose moved planes no longer meet in one point splits into one vertex per triangle of
// the Delaunay triangulation of its face normals (in turn around it): a triangle's point is below
// every other moved plane exactly when no other normal is inside its circle. Built from the edge
// (count - 1, 0) inwards, each chord taking the first apex whose point passes all the planes.
bool splitVertex(const ConvexPolytope& p, uint32_t v, const uint32_t* faces, uint32_t count, double margin,
                 double tolerance, ConvexPolytope& out, ShrinkScratch& s) {
  const size_t first = out.vertices.size(), firstMoved = s.moved.size();
  s.chords.assign(1, {0u, count - 1});
  while (!s.chords.empty()) {
    const auto [a, b] = s.chords.back();
    s.chords.pop_back();
    if (b - a < 2) continue;
    glm::dvec3 x(0.0);
    uint32_t apex = a + 1;
    for (; apex < b; ++apex)
      if (meetOfMoved(p.faces[faces[a]], p.faces[faces[apex]], p.faces[faces[b]], p.vertices[v], margin, x) &&
          withinMoved(p, faces, count, margin, tolerance, x, false))
        break;
    if (apex == b) return false;
    s.moved.push_back({a, apex, b, uint32_t(out.vertices.size()), false});
    out.vertices.push_back(x);
    s.origin.push_back(v);
    s.chords.emplace_back(a, apex);
    s.chords.emplace_back(apex, b);
  }
  // Normals on one circle (or nearly: within the tolerance) give points that coincide: all of them,
  // the vertex stays whole there (each point is below all its moved planes); some of them, those
  // become one vertex (mergeCoincident).
  bool allAtFirst = true;
  for (size_t i = first + 1; i < out.vertices.size(); ++i)
    allAtFirst = allAtFirst && glm::length(out.vertices[i] - out.vertices[first]) <= tolerance;
  if (allAtFirst) {
    s.moved.resize(firstMoved);
    s.moved.push_back({0, 0, 0, uint32_t(first), true});
    out.vertices.resize(first + 1);
    s.origin.resize(first + 1);
    return true;
  }
  mergeCoincident(first, firstMoved, tolerance, out, s);
  return true;
}

// The moved vertices of every input vertex into out.vertices and s.moved.
bool moveVertices(const ConvexPolytope& p, double margin, double tolerance, ConvexPolytope& out, ShrinkScratch& s) {
  out.vertices.clear();
  // A vertex of k >= 3 faces gives at most k - 2 (moveWhole refuses fewer than three: false below).
  const size_t twice = 2 * p.vertices.size();
  out.vertices.reserve(p.corners.size() > twice ? p.corners.size() - twice : p.vertices.size());
  s.moved.clear();
  s.origin.clear();
  s.firstMoved.resize(p.vertices.size() + 1);
  for (uint32_t v = 0; v < p.vertices.size(); ++v) {
    s.firstMoved[v] = uint32_t(s.moved.size());
    uint32_t* faces = s.faceOf.data() + s.firstFace[v];
    const uint32_t count = s.firstFace[v + 1] - s.firstFace[v];
    glm::dvec3 x(0.0);
    if (moveWhole(p, p.vertices[v], faces, count, margin, tolerance, x)) {
      s.moved.push_back({0, 0, 0, uint32_t(out.vertices.size()), true});
      out.vertices.push_back(x);
      s.origin.push_back(v);
    } else if (count < 4 || !turnAround(p, v, faces, count) ||
               !splitVertex(p, v, faces, count, margin, tolerance, out, s)) {
      return false;
    }
  }
  s.firstMoved[p.vertices.size()] = uint32_t(s.moved.size());
  return true;
}

// The face loops of the shrunk polytope: each corner becomes its moved vertex, or for a split
// vertex the split's triangles holding the face, from the one beside the edge that comes in to the
// one beside the edge that goes out (the order around the face's own position in the turn). False
// when merged split points leave a face fewer than three corners.
bool writeLoops(const ConvexPolytope& p, double margin, ConvexPolytope& out, ShrinkScratch& s) {
  out.corners.clear();
  out.faces.clear();
  // Each moved vertex is in the loops of its faces: a whole one in all those of its input vertex, a
  // split one in three.
  size_t corners = 0;
  for (uint32_t v = 0; v < p.vertices.size(); ++v) {
    const uint32_t splits = s.firstMoved[v + 1] - s.firstMoved[v];
    corners += s.moved[s.firstMoved[v]].whole ? s.firstFace[v + 1] - s.firstFace[v] : 3 * splits;
  }
  out.corners.reserve(corners);
  out.faces.reserve(p.faces.size());
  for (uint32_t f = 0; f < p.faces.size(); ++f) {
    ConvexPolytope::Face face = p.faces[f];
    face.offset -= margin;
    face.first = uint32_t(out.corners.size());
    for (uint32_t i = 0; i < p.faces[f].count; ++i) {
      const uint32_t v = p.corners[p.faces[f].first + i];
      const MovedCorner* moved = s.moved.data() + s.firstMoved[v];
      const uint32_t splits = s.firstMoved[v + 1] - s.firstMoved[v];
      if (moved[0].whole) {
        out.corners.push_back(moved[0].vertex);
        continue;
      }
      const uint32_t count = s.firstFace[v + 1] - s.firstFace[v];
      const uint32_t* turn = s.faceOf.data() + s.firstFace[v];
      const uint32_t t = uint32_t(std::find(turn, turn + count, f) - turn);
      auto away = [&](uint32_t q) { return (q + count - t) % count; };  // steps from t in the turn
      s.fan.clear();
      for (uint32_t k = 0; k < splits; ++k)
        if (moved[k].a == t || moved[k].b == t || moved[k].c == t)
          s.fan.emplace_back(std::max({away(moved[k].a), away(moved[k].b), away(moved[k].c)}), moved[k].vertex);
      std::sort(s.fan.begin(), s.fan.end(), std::greater<>());
      for (const auto& [key, vertex] : s.fan) pushCorner(out.corners, face.first, vertex);
    }
    face.count = closeLoop(out.corners, face.first);
    if (face.count < 3) return false;  // merged into fewer than three corners: the clips decide
    out.faces.push_back(face);
  }
  return true;
}

// Whether the shrunk polytope is the inner parallel body: no edge shrank to nothing or turned over,
// and every vertex is below every moved plane (else a face vanished and the clips must decide).
bool shrunkHolds(const ConvexPolytope& p, double tolerance, const ConvexPolytope& out,
                 const ShrinkScratch& s) {
  for (const ConvexPolytope::Face& f : out.faces) {
    for (uint32_t i = 0; i < f.count; ++i) {
      const uint32_t a = out.corners[f.first + i], b = out.corners[f.first + (i + 1 == f.count ? 0 : i + 1)];
      const glm::dvec3 edge = out.vertices[b] - out.vertices[a];
      if (glm::length(edge) <= tolerance) return false;
      if (s.origin[a] != s.origin[b] && !(glm::dot(edge, p.vertices[s.origin[b]] - p.vertices[s.origin[a]]) > 0.0))
        return false;
    }
    for (const glm::dvec3& x : out.vertices)
      if (glm::dot(f.normal, x) > f.offset + tolerance) return false;
  }
  return true;
}

// The margin, at most `margin`, at which the first edge of `p` shrinks to nothing, from the moved
// polytope `out` at `margin` (moveVertices and writeLoops): every moved vertex is the meet of three
// moved planes, so it moves on a line, v + (t / margin) (x - v), and an edge between the vertices
// moved from its two ends keeps its direction, its length falling linearly to nothing at t =
// margin / (1 - lambda), lambda its length at `margin` over its length in `p` (signed). Each edge's
// time (infinite for one that does not shrink) is kept in s.edgeTime, by the corner it leaves.
double firstCollapse(const ConvexPolytope& p, double margin, const ConvexPolytope& out, ShrinkScratch& s) {
  double first = margin;
  s.edgeTime.assign(out.corners.size(), std::numeric_limits<double>::infinity());
  for (const ConvexPolytope::Face& f : out.faces) {
    for (uint32_t i = 0; i < f.count; ++i) {
      const uint32_t a = out.corners[f.first + i], b = out.corners[f.first + (i + 1 == f.count ? 0 : i + 1)];
      if (s.origin[a] == s.origin[b]) continue;  // an edge a split made: it grows
      const glm::dvec3 before = p.vertices[s.origin[b]] - p.vertices[s.origin[a]];
      const double lambda = glm::dot(out.vertices[b] - out.vertices[a], before) / glm::dot(before, before);
      if (!(lambda < 1.0 - 1e-12)) continue;
      s.edgeTime[f.first + i] = margin / (1.0 - lambda);
      first = std::min(first, s.edgeTime[f.first + i]);
    }
  }
  return first;
}

// `p` shrunk by `t` (below the first collapse at `margin`, or at it) from the moved polytope `out` at
// `margin`: every vertex moved back along its line to `t`, the ends of every edge that has shrunk
// to nothing by then (within a relative 1e-9 of it) merged, the loops cleaned of repeated corners
// and the faces left with fewer than three dropped (a small face that vanished).
void collapseAt(const ConvexPolytope& p, double margin, double t, ConvexPolytope& out, ShrinkScratch& s,
                ClipScratch& clip) {
  const double share = t / margin;
  for (uint32_t v = 0; v < out.vertices.size(); ++v) {
    const glm::dvec3& from = p.vertices[s.origin[v]];
    out.vertices[v] = from + share * (out.vertices[v] - from);
  }
  std::vector<uint32_t>& root = s.cursor;
  root.resize(out.vertices.size());
  for (uint32_t v = 0; v < root.size(); ++v) root[v] = v;
  auto find = [&](uint32_t x) {
    while (root[x] != x) x = root[x] = root[root[x]];
    return x;
  };
  const double limit = t * (1.0 + 1e-9);
  // Lengths at t are tiny exactly where the edges collapse; decide on the times (firstCollapse's).
  for (const ConvexPolytope::Face& f : out.faces) {
    for (uint32_t i = 0; i < f.count; ++i) {
      const uint32_t a = out.corners[f.first + i], b = out.corners[f.first + (i + 1 == f.count ? 0 : i + 1)];
      if (s.edgeTime[f.first + i] <= limit) root[find(a)] = find(b);
    }
  }
  ConvexPolytope& next = s.collapsed;
  next.corners.clear();
  next.faces.clear();
  for (const ConvexPolytope::Face& f : out.faces) {
    ConvexPolytope::Face face = f;
    face.offset += margin - t;
    face.first = uint32_t(next.corners.size());
    for (uint32_t i = 0; i < f.count; ++i) {
      pushCorner(next.corners, face.first, find(out.corners[f.first + i]));
    }
    face.count = closeLoop(next.corners, face.first);
    if (face.count < 3) {
      next.corners.resize(face.first);
      continue;
    }
    next.faces.push_back(face);
  }
  std::swap(next.vertices, out.vertices);
  compact(next, clip);
  std::swap(out, next);
}

// Whether every vertex of `shrunk` is below every face plane of `p` moved in by `margin` (the faces
// that vanished on the way too): the shrink never reaches outside the inner parallel body.
bool belowMovedFaces(const ConvexPolytope& p, double margin, double tolerance, const ConvexPolytope& shrunk) {
  for (const ConvexPolytope::Face& f : p.faces)
    for (const glm::dvec3& x : shrunk.vertices)
      if (glm::dot(f.normal, x) > f.offset - margin + tolerance) return false;
  return true;
}

// The shrink followed through the changes of its faces: moved in place (vertices may split) up to
// the first edge that shrinks to nothing, that edge's ends merged there (a vertex where four faces
// meet, which the next step splits the other way: the edge turned over; a face whose edges all went
// vanished), and on from there, up to a few times. False, with `out` unusable, where the clips must
// decide (a vertex that cannot be moved, a change that is not one of these, too many changes).
bool shrinkInPlace(const ConvexPolytope& p, double margin, double tolerance, ConvexPolytope& out) {
  constexpr int kMaxChanges = 6;
  ShrinkScratch& s = threadShrinkScratch();
  ClipScratch& clip = threadScratch();
  const ConvexPolytope* from = &p;
  double left = margin;
  for (int step = 0; step <= kMaxChanges; ++step) {
    facesAtVertices(*from, s);
    if (!moveVertices(*from, left, tolerance, out, s)) return false;
    if (!writeLoops(*from, left, out, s)) return false;
    // An edge that turns over before `left` is the next change; else the result must hold.
    const double t = firstCollapse(*from, left, out, s);
    if (!(t < left))
      return shrunkHolds(*from, tolerance, out, s) && (step == 0 || belowMovedFaces(p, margin, tolerance, out));
    if (!(t > 0.0)) return false;
    collapseAt(*from, left, t, out, s, clip);
    if (out.faces.size() < 4) return false;
    std::swap(s.step, out);
    from = &s.step;
    left -= t;
  }
  return false;
}

}  // namespace

ConvexPolytope shrinkPolytope(const ConvexPolytope& p, double margin) {
  if (p.empty() || !(margin > 0.0)) return p;
  glm::dvec3 lo, hi;
  polytopeBounds(p, lo, hi);
  const double tolerance = 1e-9 * std::max(glm::length(hi - lo), 1e-30);
  ClipScratch& scratch = threadScratch();
  ConvexPolytope current;
  if (shrinkInPlace(p, margin, tolerance, current)) return current;
  // Distinct planes only: hull triangles of one flat side share a plane and clip once.
  std::vector<std::pair<glm::dvec3, double>> planes;
  for (const ConvexPolytope::Face& f : p.faces) {
    bool seen = false;
    for (const auto& [n, o] : planes)
      if (glm::dot(n, f.normal) > 1.0 - 1e-12 && std::abs(o - f.offset) <= 1e-12 * (1.0 + std::abs(o))) seen = true;
    if (!seen) planes.emplace_back(f.normal, f.offset);
  }
  PolytopeEditor& editor = threadEditor();
  editor.reset(p);
  for (const auto& [n, o] : planes)
    if (!editor.clip(n, o - margin, tolerance, scratch)) return ConvexPolytope{};
  editor.write(current, scratch);
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
