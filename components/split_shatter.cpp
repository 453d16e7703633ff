// SPDX-License-Identifier: MIT
// Shatter jobs (split_shatter.h).
#include "cleave/components/split_shatter.h"

#include <algorithm>
#include <limits>

#include "cleave/components/skinned.h"
#include "cleave/geometry/convex_polytope.h"

namespace cleave::components {

namespace {

struct PieceBounds {
  glm::dvec3 lo{std::numeric_limits<double>::infinity()}, hi{-std::numeric_limits<double>::infinity()};
};

// Of the pieces `mates` (one cell's), the one whose bounds are nearest `point` (0 inside them); the
// larger piece on a tie.
size_t ownerOf(const std::vector<geometry::SplitPiece>& pieces, std::span<const PieceBounds> bounds,
               std::span<const size_t> mates, const glm::dvec3& point) {
  size_t owner = mates.front();
  double best = std::numeric_limits<double>::infinity();
  for (size_t j : mates) {
    const glm::dvec3 lo = bounds[j].lo, hi = bounds[j].hi;
    const double d = glm::length(glm::max(glm::max(lo - point, point - hi), glm::dvec3(0.0)));
    if (d < best || (d == best && pieces[j].mass.volume > pieces[owner].mass.volume)) {
      best = d;
      owner = j;
    }
  }
  return owner;
}

}  // namespace

// A shatter: the container broken into the Voronoi cells of the request's seeds (cut space), the
// pieces put into s.result as a split's would be (side +1, their cell's caps as the cap run).
geometry::SplitStatus shatterInto(const SplitJob& job, SplitComputeScratch& s, std::string& message,
                                  std::vector<geometry::ConvexCell>& cells, std::vector<uint32_t>& pieceCell) {
  const ShatterSpec& spec = job.request.shatterSpec;
  const glm::dvec3 lo = s.container.boundsMin(), hi = s.container.boundsMax();
  const glm::dvec3 margin = 0.01 * (hi - lo) + glm::dvec3(1e-6);
  const std::vector<glm::dvec3> seeds =
      geometry::fractureSeeds(std::max<uint32_t>(spec.cells, 1), spec.seed, lo, hi, spec.impactPoint, spec.impactRadius);
  cells = geometry::voronoiCells(seeds, lo - margin, hi + margin);
  // A posed skinned mesh is broken in its pose: the cells of a shatter are rigid (baked) pieces, so
  // the mesh is baked first and every plane of a cell cuts the same posed surface (a part cut by
  // one plane and posed again would move its cut points: skinning is not linear along an edge).
  geometry::MeshContainer baked;
  const geometry::MeshContainer* source = &s.container;
  if (job.skinned()) {
    geometry::MeshData posed;
    bakeSkin(s.container.mesh(), job.jointMatrices, posed);
    geometry::MeshWeld weld;
    s.container.copyWeld(weld);
    if (geometry::MeshStatus set = baked.setMesh(posed, weld); !set.ok()) {
      message = std::move(set.message);
      return set.code;
    }
    baked.setTransform(glm::mat4(job.model));
    source = &baked;
  }
  geometry::FractureResult fractured = geometry::fracture(*source, cells, job.options);
  message = fractured.message;
  s.result.pieces.clear();
  s.result.openChains = fractured.openChains;
  pieceCell.clear();
  if (fractured.status != geometry::SplitStatus::Ok) return fractured.status;
  for (geometry::FracturePiece& f : fractured.pieces) {
    pieceCell.push_back(f.cell);
    geometry::SplitPiece piece;
    piece.mesh = std::move(f.mesh);
    piece.weld = std::move(f.weld);
    piece.side = 1;
    piece.capTriangles = f.capTriangles;
    piece.mass = f.mass;
    piece.reached = true;
    piece.sourceTriangles = std::move(f.sourceTriangles);
    s.result.pieces.push_back(std::move(piece));
  }
  return geometry::SplitStatus::Ok;
}

void clipPartsToCells(const geometry::ColliderPartSet& parts, const glm::dmat4& model,
                      const std::vector<geometry::SplitPiece>& pieces, std::span<const geometry::ConvexCell> cells,
                      std::span<const uint32_t> pieceCell, std::vector<geometry::ColliderPartSet>& clipped) {
  clipped.assign(pieces.size(), {});
  std::vector<PieceBounds> bounds(pieces.size());
  std::vector<geometry::HalfSpace> halfSpaces;
  for (size_t i = 0; i < pieces.size(); ++i)
    for (const glm::vec3& p : pieces[i].mesh.positions)
      bounds[i].lo = glm::min(bounds[i].lo, glm::dvec3(p)), bounds[i].hi = glm::max(bounds[i].hi, glm::dvec3(p));
  std::vector<char> cellDone(cells.size(), 0);  // its parts went to its pieces with an earlier piece
  for (size_t i = 0; i < pieces.size(); ++i) {
    if (cellDone[pieceCell[i]]) continue;
    cellDone[pieceCell[i]] = 1;
    const geometry::ConvexCell& cell = cells[pieceCell[i]];
    std::vector<size_t> mates;
    for (size_t j = i; j < pieces.size(); ++j)
      if (pieceCell[j] == pieceCell[i]) mates.push_back(j);
    halfSpaces.clear();
    for (const geometry::Plane& world : cell.planes) {
      const geometry::Plane plane = planeInMeshSpace(world, model);
      halfSpaces.push_back({plane.normal, plane.offset});
    }
    for (const geometry::ConvexPolytope& part : parts) {
      geometry::ConvexPolytope piecePart;
      geometry::clipPolytope(part, halfSpaces, 1e-9, piecePart);
      if (piecePart.empty()) continue;
      const size_t owner =
          mates.size() == 1 ? i : ownerOf(pieces, bounds, mates, geometry::polytopeCentroid(piecePart));
      clipped[owner].push_back(std::move(piecePart));
    }
  }
}


// Shatter pieces: named by their order, moving with the parent plus the outward impulse.
void finishShatterPiece(const SplitJob& job, uint32_t k, PieceSpec& spec) {
  const ShatterSpec& shatter = job.request.shatterSpec;
  const glm::dvec3 away = spec.frame.position - shatter.impactPoint;
  const double length = glm::length(away);
  spec.impulse = length > 1e-9 ? away * (shatter.outwardImpulse / length) : glm::dvec3(0.0);
  spec.velocity = job.parent.velocity + glm::cross(job.parent.angularVelocity, spec.offsetFromParent) + spec.impulse;
  spec.name = (job.targetName.empty() ? std::string("piece") : job.targetName) + "/s" + std::to_string(k);
}

}  // namespace cleave::components
