// SPDX-License-Identifier: MIT
// Collider parts: decomposition by recursive mid-plane cuts (each part then hulled), and the
// clipping of carried parts by a cut plane into the pieces of the split.
#include "cleave/geometry/collider_parts.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include "cleave/geometry/convex_hull.h"
#include "cleave/geometry/mass_properties.h"

namespace cleave::geometry {
namespace {

void decomposeInto(const MeshData& mesh, IMeshSplitter& splitter, int depth, ColliderPartSet& parts) {
  if (mesh.positions.size() < 4) return;
  auto wholeHull = [&] {
    ConvexPolytope part = simplifyPolytope(polytopeOfPoints(mesh.positions), kMaxPartVertices);
    if (!part.empty()) parts.push_back(std::move(part));
  };
  if (depth <= 0 || isConvex(mesh, kPartConvexTolerance)) return wholeHull();
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const glm::vec3& p : mesh.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const glm::vec3 extent = hi - lo;
  int axis = 0;
  if (extent.y > extent[axis]) axis = 1;
  if (extent.z > extent[axis]) axis = 2;
  Plane plane;
  plane.normal = glm::dvec3(0.0);
  plane.normal[axis] = 1.0;
  plane.offset = 0.5 * (double(lo[axis]) + double(hi[axis]));
  MeshContainer container;
  if (container.setMesh(mesh).code != SplitStatus::Ok) return wholeHull();
  SplitOptions options;
  options.computeMass = false;
  options.separateIslands = true;
  SplitResult result;
  if (splitter.split(container, plane, options, result) != SplitStatus::Ok) return wholeHull();
  for (const SplitPiece& piece : result.pieces) decomposeInto(piece.mesh, splitter, depth - 1, parts);
}

// Squared distance from `c` to the nearest vertex of `mesh`.
double nearestVertex(const MeshData& mesh, const glm::dvec3& c) {
  double best = std::numeric_limits<double>::infinity();
  for (const glm::vec3& p : mesh.positions) {
    const glm::dvec3 d = glm::dvec3(p) - c;
    best = std::min(best, glm::dot(d, d));
  }
  return best;
}

// The piece of `result` on `side` that holds a part centred at `c`, or -1.
int holdingPiece(const SplitResult& result, int side, const glm::dvec3& c,
                 const std::vector<std::pair<glm::dvec3, glm::dvec3>>& bounds) {
  int best = -1, candidates = 0;
  for (size_t i = 0; i < result.pieces.size(); ++i) {
    if (result.pieces[i].side != side) continue;
    ++candidates;
    best = int(i);
  }
  if (candidates <= 1) return best;
  best = -1;
  double bestDistance = std::numeric_limits<double>::infinity();
  for (int pass = 0; pass < 2 && best < 0; ++pass) {
    for (size_t i = 0; i < result.pieces.size(); ++i) {
      if (result.pieces[i].side != side) continue;
      const auto& [lo, hi] = bounds[i];
      const glm::dvec3 slack = (hi - lo) * 1e-6;
      const bool inside = glm::all(glm::greaterThanEqual(c, lo - slack)) && glm::all(glm::lessThanEqual(c, hi + slack));
      if (pass == 0 && !inside) continue;  // second pass: any piece of the side, by distance
      const double d = nearestVertex(result.pieces[i].mesh, c);
      if (d < bestDistance) {
        bestDistance = d;
        best = int(i);
      }
    }
  }
  return best;
}

}  // namespace

std::vector<ConvexPolytope> decomposeConvex(const MeshData& mesh, IMeshSplitter& splitter, int maxDepth) {
  ColliderPartSet parts;
  decomposeInto(mesh, splitter, maxDepth, parts);
  return parts;
}

void clipPartsToPieces(const ColliderPartSet& parts, const Plane& plane, const SplitResult& result,
                       const PartClipOptions& options, std::vector<ColliderPartSet>& out) {
  out.assign(result.pieces.size(), ColliderPartSet{});
  std::vector<std::pair<glm::dvec3, glm::dvec3>> bounds(result.pieces.size());
  std::vector<double> pieceVolume(result.pieces.size(), 0.0);
  for (size_t i = 0; i < result.pieces.size(); ++i) {
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (const glm::vec3& p : result.pieces[i].mesh.positions) {
      lo = glm::min(lo, glm::dvec3(p));
      hi = glm::max(hi, glm::dvec3(p));
    }
    bounds[i] = {lo, hi};
  }
  // Clipped parts per piece with their volumes, before the small ones are dropped.
  std::vector<std::vector<std::pair<double, ConvexPolytope>>> held(result.pieces.size());
  for (const ConvexPolytope& part : parts) {
    glm::dvec3 lo, hi;
    polytopeBounds(part, lo, hi);
    const double tolerance = options.relativeTolerance * std::max(glm::length(hi - lo), 1e-30);
    for (int side : {+1, -1}) {
      // Above = dot(n, x) > offset: keep the negated half-space for side +1.
      ConvexPolytope clipped = side > 0 ? clipPolytope(part, -plane.normal, -plane.offset, tolerance)
                                        : clipPolytope(part, plane.normal, plane.offset, tolerance);
      if (clipped.empty()) continue;
      clipped = simplifyPolytope(clipped, kMaxPartVertices);
      const int piece = holdingPiece(result, side, polytopeCentroid(clipped), bounds);
      if (piece < 0) continue;
      const double volume = polytopeVolume(clipped);
      pieceVolume[size_t(piece)] += volume;
      held[size_t(piece)].emplace_back(volume, std::move(clipped));
    }
  }
  for (size_t i = 0; i < held.size(); ++i) {
    double largest = 0.0;
    for (const auto& [volume, part] : held[i]) largest = std::max(largest, volume);
    for (auto& [volume, part] : held[i]) {
      const bool keep = volume >= options.minVolumeShare * pieceVolume[i] || volume == largest;
      if (keep && volume > 0.0) out[i].push_back(std::move(part));
    }
  }
}

double partsWork(const ColliderPartSet& parts) {
  double work = 0.0;
  for (const ConvexPolytope& part : parts) work += double(part.vertices.size()) * double(part.corners.size());
  return work;
}

double partsVolume(const ColliderPartSet& parts) {
  double sum = 0.0;
  for (const ConvexPolytope& part : parts) sum += polytopeVolume(part);
  return sum;
}

}  // namespace cleave::geometry
