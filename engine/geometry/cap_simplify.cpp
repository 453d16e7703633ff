// SPDX-License-Identifier: MIT
#include "cleave/geometry/cap_simplify.h"

#include <algorithm>
#include <cmath>

#include "cleave/geometry/cap_triangulator.h"

namespace cleave::geometry {

namespace {

constexpr uint32_t kNone = 0xffffffffu;

uint64_t edgeKey(uint32_t a, uint32_t b) { return (uint64_t(a) << 32) | b; }

// Which planes' caps and whether surface (non-cap) triangles use a welded point.
struct Usage {
  uint32_t planeA = kNone, planeB = kNone;
  bool morePlanes = false;
  bool surface = false;
  // Used by the caps of exactly two planes and nothing else: on their common line, droppable.
  bool droppable() const { return !surface && !morePlanes && planeB != kNone; }
  // Used by one plane's caps only: inside that cap region.
  bool inner() const { return !surface && !morePlanes && planeA != kNone && planeB == kNone; }
};

// A cap region: the triangles of one plane's caps, and what replaces them.
struct Region {
  uint32_t plane = 0;
  std::vector<uint32_t> triangles;
  bool redo = false;                 // has a droppable or inner point
  std::vector<uint32_t> replacement;  // vertex indices, three per triangle
};

}  // namespace

struct CapSimplifier::Scratch {
  std::vector<Usage> usage;
  std::vector<Region> regions;  // the first `regionCount` are in use (kept for their buffers)
  uint32_t regionCount = 0;
  std::vector<uint32_t> regionOfPlane;
  std::vector<uint64_t> edges, border;
  std::vector<uint8_t> used;
  std::vector<uint32_t> loopIds, loopStart;  // border loops: ids, and where each loop starts
  std::vector<glm::dvec2> points;
  std::vector<CapRing> rings, polygon;
  std::vector<double> area;
  std::vector<uint32_t> outerOf, local, vertexOfId;
  std::vector<uint32_t> indices, sources, remap, idRemap, ids, representatives;
  std::vector<SubMesh> runs;
  CapTriangulator triangulator;
};

namespace {

struct Simplifier {
  MeshData& mesh;
  MeshWeld& weld;
  std::vector<uint32_t>& source;
  std::span<const Plane> planes;
  glm::dmat4 model;
  CapSimplifier::Scratch& x;

  uint32_t idOf(uint32_t t, int c) const { return weld.positionIds[mesh.indices[3 * t + c]]; }
  uint32_t planeOf(uint32_t t) const {
    return (source[t] & kFromCap) && (source[t] & ~kFromCap) < planes.size() ? source[t] & ~kFromCap : kNone;
  }
  Region& regionFor(uint32_t plane);
  void gather();
  bool traceLoops(const Region& r);
  bool retriangulate(Region& r);
  void projectLoops(const Region& r, double& largest);
  bool assignHoles();
  void rebuild();
  void compact();
};

Region& Simplifier::regionFor(uint32_t plane) {
  if (x.regionOfPlane[plane] == kNone) {
    x.regionOfPlane[plane] = x.regionCount;
    if (x.regions.size() <= x.regionCount) x.regions.emplace_back();
    Region& r = x.regions[x.regionCount++];
    r.plane = plane;
    r.triangles.clear();
    r.redo = false;
    r.replacement.clear();
  }
  return x.regions[x.regionOfPlane[plane]];
}

// Per welded point, which planes' caps and whether surface triangles use it; per plane, its region.
void Simplifier::gather() {
  x.usage.assign(weld.representatives.size(), Usage{});
  x.regionOfPlane.assign(planes.size(), kNone);
  x.regionCount = 0;
  const uint32_t triangles = static_cast<uint32_t>(mesh.indices.size() / 3);
  for (uint32_t t = 0; t < triangles; ++t) {
    const uint32_t plane = planeOf(t);
    if (plane != kNone) regionFor(plane).triangles.push_back(t);
    for (int c = 0; c < 3; ++c) {
      Usage& u = x.usage[idOf(t, c)];
      if (plane == kNone) {
        u.surface = true;
      } else if (u.planeA == kNone || u.planeA == plane) {
        u.planeA = plane;
      } else if (u.planeB == kNone || u.planeB == plane) {
        u.planeB = plane;
      } else {
        u.morePlanes = true;
      }
    }
  }
  for (uint32_t k = 0; k < x.regionCount; ++k) {
    Region& r = x.regions[k];
    for (uint32_t t : r.triangles) {
      for (int c = 0; c < 3; ++c) r.redo = r.redo || x.usage[idOf(t, c)].droppable() || x.usage[idOf(t, c)].inner();
    }
  }
}

// The border loops of a region (x.loopIds from x.loopStart[k]), in welded ids, in the triangles'
// winding, without the droppable points. False when the border cannot be traced (a point with two
// border edges leaving it) or a loop keeps fewer than three points.
bool Simplifier::traceLoops(const Region& r) {
  x.edges.clear();
  for (uint32_t t : r.triangles) {
    for (int c = 0; c < 3; ++c) x.edges.push_back(edgeKey(idOf(t, c), idOf(t, (c + 1) % 3)));
  }
  std::sort(x.edges.begin(), x.edges.end());
  x.border.clear();  // directed edges whose reverse the region does not have
  for (uint64_t e : x.edges) {
    if (!std::binary_search(x.edges.begin(), x.edges.end(), edgeKey(uint32_t(e), uint32_t(e >> 32)))) {
      x.border.push_back(e);
    }
  }
  for (size_t k = 1; k < x.border.size(); ++k) {
    if ((x.border[k] >> 32) == (x.border[k - 1] >> 32)) return false;  // touches itself at a point
  }
  x.used.assign(x.border.size(), 0);
  x.loopIds.clear();
  x.loopStart.clear();
  for (size_t first = 0; first < x.border.size(); ++first) {
    if (x.used[first]) continue;
    x.loopStart.push_back(static_cast<uint32_t>(x.loopIds.size()));
    size_t at = first;
    while (!x.used[at]) {
      x.used[at] = 1;
      const uint32_t from = uint32_t(x.border[at] >> 32), to = uint32_t(x.border[at]);
      if (!x.usage[from].droppable()) x.loopIds.push_back(from);
      const auto next = std::lower_bound(x.border.begin(), x.border.end(), edgeKey(to, 0));
      if (next == x.border.end() || (*next >> 32) != to) return false;
      at = static_cast<size_t>(next - x.border.begin());
    }
    if (at != first || x.loopIds.size() - x.loopStart.back() < 3) return false;
  }
  x.loopStart.push_back(static_cast<uint32_t>(x.loopIds.size()));
  return x.loopStart.size() > 1;
}

// The loops' points on the region's plane (cut space), mirrored when the loops run clockwise there
// so that outer borders run counter-clockwise; their rings and signed areas.
void Simplifier::projectLoops(const Region& r, double& largest) {
  const glm::dvec3 n = glm::normalize(planes[r.plane].normal);
  const glm::dvec3 axis = std::abs(n.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 u = glm::normalize(glm::cross(n, axis)), v = glm::cross(n, u);
  x.points.clear();
  x.rings.clear();
  largest = 0.0;
  for (uint32_t id : x.loopIds) {
    const glm::dvec3 q = glm::dvec3(model * glm::dvec4(glm::dvec3(mesh.positions[weld.representatives[id]]), 1.0));
    x.points.emplace_back(glm::dot(q, u), glm::dot(q, v));
    largest = std::max({largest, std::abs(q.x), std::abs(q.y), std::abs(q.z)});
  }
  for (size_t k = 0; k + 1 < x.loopStart.size(); ++k) x.rings.push_back({x.loopStart[k], x.loopStart[k + 1]});
  double total = 0.0;
  for (CapRing ring : x.rings) total += CapTriangulator::twiceSignedArea(x.points, ring);
  if (total < 0.0) {
    for (glm::dvec2& p : x.points) p.x = -p.x;
  }
  x.area.resize(x.rings.size());
  for (size_t k = 0; k < x.rings.size(); ++k) x.area[k] = CapTriangulator::twiceSignedArea(x.points, x.rings[k]);
}

// Each hole (clockwise ring) to the smallest outer border around it; false for a hole in none.
bool Simplifier::assignHoles() {
  x.outerOf.assign(x.rings.size(), kNone);
  for (size_t h = 0; h < x.rings.size(); ++h) {
    if (x.area[h] > 0.0) continue;
    for (size_t o = 0; o < x.rings.size(); ++o) {
      if (x.area[o] > 0.0 && CapTriangulator::ringContains(x.points, x.rings[o], x.points[x.rings[h].begin]) &&
          (x.outerOf[h] == kNone || x.area[o] < x.area[x.outerOf[h]])) {
        x.outerOf[h] = static_cast<uint32_t>(o);
      }
    }
    if (x.outerOf[h] == kNone) return false;
  }
  return true;
}

// The region's new triangles from its border loops, each polygon (an outer border and its holes)
// ear-clipped, as vertex indices (the vertex this region's triangles use at each point). False when
// any step fails.
bool Simplifier::retriangulate(Region& r) {
  if (!traceLoops(r)) return false;
  double largest = 0.0;
  projectLoops(r, largest);
  if (!assignHoles()) return false;
  x.local.clear();
  for (size_t o = 0; o < x.rings.size(); ++o) {
    if (!(x.area[o] > 0.0)) continue;
    x.polygon.assign(1, x.rings[o]);
    for (size_t h = 0; h < x.rings.size(); ++h) {
      if (x.outerOf[h] == o) x.polygon.push_back(x.rings[h]);
    }
    if (!x.triangulator.triangulate(x.points, x.polygon, x.local, 4.0 * 0x1.0p-24 * largest)) return false;
  }
  if (x.vertexOfId.size() < weld.representatives.size()) x.vertexOfId.resize(weld.representatives.size(), kNone);
  for (uint32_t t : r.triangles) {
    for (int c = 0; c < 3; ++c) x.vertexOfId[idOf(t, c)] = mesh.indices[3 * t + c];
  }
  r.replacement.clear();
  for (uint32_t index : x.local) r.replacement.push_back(x.vertexOfId[x.loopIds[index]]);
  for (uint32_t t : r.triangles) {
    for (int c = 0; c < 3; ++c) x.vertexOfId[idOf(t, c)] = kNone;
  }
  return true;
}

// The triangle list with each redone region's triangles replaced, in the place of its first one
// (in that triangle's submesh run).
void Simplifier::rebuild() {
  x.indices.clear();
  x.sources.clear();
  x.runs = mesh.submeshes;
  if (x.runs.empty()) x.runs.push_back({0, static_cast<uint32_t>(mesh.indices.size()), 0});
  for (SubMesh& run : x.runs) {
    const uint32_t begin = static_cast<uint32_t>(x.indices.size());
    for (uint32_t t = run.firstIndex / 3; t < (run.firstIndex + run.indexCount) / 3; ++t) {
      const uint32_t plane = planeOf(t);
      Region* r = plane == kNone ? nullptr : &x.regions[x.regionOfPlane[plane]];
      if (!r || !r->redo) {
        x.indices.insert(x.indices.end(), mesh.indices.begin() + 3 * t, mesh.indices.begin() + 3 * t + 3);
        x.sources.push_back(source[t]);
      } else if (r->triangles.front() == t) {
        x.indices.insert(x.indices.end(), r->replacement.begin(), r->replacement.end());
        x.sources.insert(x.sources.end(), r->replacement.size() / 3, kFromCap | r->plane);
      }
    }
    run.firstIndex = begin;
    run.indexCount = static_cast<uint32_t>(x.indices.size()) - begin;
  }
  if (!mesh.submeshes.empty()) mesh.submeshes.assign(x.runs.begin(), x.runs.end());
  mesh.indices.assign(x.indices.begin(), x.indices.end());
  source.assign(x.sources.begin(), x.sources.end());
}

// Drops the vertices no triangle uses (order kept) and numbers the weld's ids again by first vertex.
void Simplifier::compact() {
  const size_t n = mesh.positions.size();
  x.remap.assign(n, kNone);
  for (uint32_t index : mesh.indices) x.remap[index] = 0;
  uint32_t count = 0;
  for (size_t i = 0; i < n; ++i) {
    if (x.remap[i] != kNone) x.remap[i] = count++;
  }
  auto keep = [&](auto& values) {
    if (values.empty()) return;
    for (size_t i = 0; i < n; ++i) {
      if (x.remap[i] != kNone) values[x.remap[i]] = values[i];
    }
    values.resize(count);
  };
  keep(mesh.positions);
  keep(mesh.normals);
  keep(mesh.tangents);
  keep(mesh.uv0);
  keep(mesh.uv1);
  keep(mesh.colors);
  keep(mesh.joints);
  keep(mesh.weights);
  for (uint32_t& index : mesh.indices) index = x.remap[index];
  x.idRemap.assign(weld.representatives.size(), kNone);
  x.ids.resize(count);
  x.representatives.clear();
  for (size_t i = 0; i < n; ++i) {
    if (x.remap[i] == kNone) continue;
    uint32_t& id = x.idRemap[weld.positionIds[i]];
    if (id == kNone) {
      id = static_cast<uint32_t>(x.representatives.size());
      x.representatives.push_back(x.remap[i]);
    }
    x.ids[x.remap[i]] = id;
  }
  weld.positionIds.assign(x.ids.begin(), x.ids.end());
  weld.representatives.assign(x.representatives.begin(), x.representatives.end());
}

}  // namespace

CapSimplifier::CapSimplifier() : scratch_(std::make_unique<Scratch>()) {}
CapSimplifier::~CapSimplifier() = default;

CapSimplifyStats CapSimplifier::simplify(MeshData& mesh, MeshWeld& weld, std::vector<uint32_t>& sourceTriangles,
                                         std::span<const Plane> planes, const glm::dmat4& model) {
  CapSimplifyStats stats;
  if (!weld.closed || sourceTriangles.size() * 3 != mesh.indices.size() ||
      weld.positionIds.size() != mesh.positions.size()) {
    return stats;
  }
  Simplifier s{mesh, weld, sourceTriangles, planes, model, *scratch_};
  s.gather();
  for (uint32_t k = 0; k < scratch_->regionCount; ++k) {
    Region& r = scratch_->regions[k];
    if (!r.redo) continue;
    // A region that cannot be made again would keep points its neighbours drop: leave all as is.
    if (!s.retriangulate(r)) {
      stats.keptRegions = 1;
      return stats;
    }
    ++stats.regions;
    stats.trianglesBefore += static_cast<uint32_t>(r.triangles.size());
    stats.trianglesAfter += static_cast<uint32_t>(r.replacement.size() / 3);
  }
  if (stats.regions == 0) return stats;
  const size_t idsBefore = weld.representatives.size();
  s.rebuild();
  s.compact();
  stats.droppedPoints = static_cast<uint32_t>(idsBefore - weld.representatives.size());
  return stats;
}

}  // namespace cleave::geometry
