// SPDX-License-Identifier: MIT
#include "cleave/geometry/fracture.h"

#include <algorithm>
#include <utility>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>

#include "cleave/geometry/cap_simplify.h"
#include "cleave/geometry/cell_clipper.h"
#include "cleave/geometry/convex_polytope.h"
#include "cleave/geometry/mesh_splitter.h"

namespace cleave::geometry {

namespace {

// A part of the mesh on its way through a cell's planes. The first is the container's mesh itself
// (`whole`: no copy is made until a plane cuts it).
struct Part {
  bool whole = false;
  MeshData mesh;
  MeshWeld weld;
  std::vector<uint32_t> source;  // per triangle: see FracturePiece::sourceTriangles
  MassProperties mass;
  bool massStale = false;  // its caps were made again (CapSimplifier): pieceOf integrates it anew
  uint32_t capTriangles = 0;
  // The part set up for cutting (cut-space positions, weld), made once when a plane first meets it
  // and kept while later planes leave the part whole.
  std::unique_ptr<MeshContainer> container;
};

enum class Against { Inside, Outside, Crossing };

// Where the part's cut-space positions lie against the plane.
Against classify(const CutPositions& points, const Plane& plane, double tolerance) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (size_t i = 0; i < points.size(); ++i) {
    const double d = glm::dot(plane.normal, points[i]) - plane.offset;
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  if (hi <= tolerance) return Against::Inside;
  if (lo >= -tolerance) return Against::Outside;
  return Against::Crossing;
}

// The below pieces of one cut of `part` by plane `planeIndex` of `cell`, with their provenance taken
// back to the container's mesh (kFromCap | the plane for its caps) and their caps made again
// without the points only caps use (cap_simplify.h). Their mass is worked out once, for the pieces
// that come out of the cell (pieceOf). Returns the split status.
SplitStatus cutPart(IMeshSplitter& splitter, CapSimplifier& simplifier, const MeshContainer& container, const Part& part,
                    const ConvexCell& cell, uint32_t planeIndex, const SplitOptions& options, std::vector<Part>& below,
                    uint32_t& openChains) {
  SplitResult result;
  SplitOptions inside = options;
  inside.keepSide = -1;
  inside.computeMass = false;
  splitter.split(container, cell.planes[planeIndex], inside, result);
  if (result.status != SplitStatus::Ok) return result.status;
  openChains += result.openChains;
  for (SplitPiece& piece : result.pieces) {
    if (piece.side > 0) continue;
    Part next;
    next.source.resize(piece.sourceTriangles.size());
    for (size_t t = 0; t < piece.sourceTriangles.size(); ++t) {
      const uint32_t s = piece.sourceTriangles[t];
      next.source[t] = (s & kFromCap) ? (kFromCap | planeIndex) : part.source[s];
    }
    next.mesh = std::move(piece.mesh);
    next.weld = std::move(piece.weld);
    next.massStale = true;
    next.capTriangles = piece.capTriangles;
    // (A posed part's caps are planar in the pose only, not in the source space it is kept in: they
    // stay as cut.)
    if (container.jointMatrices().empty()) {
      const CapSimplifyStats simplified =
          simplifier.simplify(next.mesh, next.weld, next.source, cell.planes, container.model());
      next.capTriangles = next.capTriangles + simplified.trianglesAfter - simplified.trianglesBefore;
    }
    below.push_back(std::move(next));
  }
  return SplitStatus::Ok;
}

// Mass properties of a part no plane cut (it lay wholly inside its cell): integrated in cut space.
MassProperties massOfWhole(const MeshContainer& container) {
  std::vector<glm::dvec3> scratch;
  const std::span<const glm::dvec3> positions = container.cutPositions().doubles(scratch);
  if (container.closed()) {
    return integrateClosedSurface(positions, container.mesh().indices, container.mirrored(), false);
  }
  std::vector<uint32_t> indices = container.mesh().indices;
  if (container.mirrored()) {
    for (size_t t = 0; t + 2 < indices.size(); t += 3) std::swap(indices[t + 1], indices[t + 2]);
  }
  return computeMassProperties(positions, indices);
}

struct CellRun {
  IMeshSplitter& splitter;
  CapSimplifier& simplifier;
  const MeshContainer& source;
  const SplitOptions& options;
  double tolerance;
  FractureResult& result;
};

// The container a part is cut from: the source itself, or the part's own, set up on first use. Null
// (with the result's status set) when the part's mesh is refused.
const MeshContainer* containerOf(CellRun& run, Part& part) {
  if (part.whole) return &run.source;
  if (part.container) return part.container.get();
  auto container = std::make_unique<MeshContainer>();
  MeshStatus set = container->setMesh(part.mesh, part.weld);
  if (!set.ok()) set = container->setMesh(part.mesh);
  if (!set.ok()) {
    run.result.status = SplitStatus::InvalidInput;
    run.result.message = "a fracture part cannot be cut again: " + set.message;
    return nullptr;
  }
  // The part's cut space is the source's: its model matrix, and its skinning pose when it is posed
  // (the parts of a posed skinned mesh keep their skin, in source space).
  const std::span<const glm::dmat4> joints = run.source.jointMatrices();
  if (joints.empty() || part.mesh.joints.empty()) {
    container->setTransform(glm::mat4(run.source.model()));
  } else {
    std::vector<glm::mat4> pose(joints.begin(), joints.end());
    const MeshStatus posed = container->setSkinningPose(pose, glm::mat4(run.source.model()));
    if (!posed.ok()) {
      run.result.status = SplitStatus::InvalidInput;
      run.result.message = "a fracture part cannot be posed: " + posed.message;
      return nullptr;
    }
  }
  part.container = std::move(container);
  return part.container.get();
}

FracturePiece pieceOf(CellRun& run, Part& part, uint32_t cellIndex) {
  FracturePiece piece;
  piece.cell = cellIndex;
  if (part.whole) {  // the whole source lies in this cell
    piece.mesh = run.source.mesh();
    run.source.copyWeld(piece.weld);
    piece.mass = massOfWhole(run.source);
  } else {
    if (part.massStale) {
      const MeshContainer* c = containerOf(run, part);
      part.mass = c ? massOfWhole(*c) : MassProperties{};
    }
    piece.mesh = std::move(part.mesh);
    piece.weld = std::move(part.weld);
    piece.mass = part.mass;
  }
  piece.capTriangles = part.capTriangles;
  piece.sourceTriangles = std::move(part.source);
  return piece;
}

// The parts of the source inside one cell, appended to the result. False when a cut failed (the
// result then has its status and message).
bool carveCell(CellRun& run, const ConvexCell& cell, uint32_t cellIndex) {
  std::vector<Part> parts(1);
  parts[0].whole = true;
  parts[0].source.resize(run.source.mesh().indices.size() / 3);
  std::iota(parts[0].source.begin(), parts[0].source.end(), 0u);
  for (uint32_t k = 0; k < cell.planes.size() && !parts.empty(); ++k) {
    std::vector<Part> kept;
    for (Part& part : parts) {
      const MeshContainer* c = containerOf(run, part);
      if (!c) return false;
      const Against where = classify(c->cutPositions(), cell.planes[k], run.tolerance);
      if (where == Against::Outside) continue;
      if (where == Against::Inside) {
        kept.push_back(std::move(part));
        continue;
      }
      ++run.result.cuts;
      const SplitStatus status = cutPart(run.splitter, run.simplifier, *c, part, cell, k, run.options, kept, run.result.openChains);
      if (status == SplitStatus::PlaneMissesMesh) continue;  // the part below collapsed to nothing
      if (status != SplitStatus::Ok) {
        run.result.status = status;
        run.result.message = "cell " + std::to_string(cellIndex) + ", plane " + std::to_string(k) + ": " + toString(status);
        return false;
      }
    }
    parts = std::move(kept);
  }
  for (Part& part : parts) run.result.pieces.push_back(pieceOf(run, part, cellIndex));
  return true;
}

}  // namespace

FractureResult fracture(const MeshContainer& container, std::span<const ConvexCell> cells, const SplitOptions& options,
                        FractureMethod method) {
  FractureResult result;
  if (container.mesh().indices.empty()) {
    result.status = SplitStatus::InvalidInput;
    result.message = "the container holds no mesh";
    return result;
  }
  std::unique_ptr<IMeshSplitter> splitter = makeConcaveSplitter();
  CapSimplifier simplifier;
  CellRun run{*splitter, simplifier, container, options, options.relativeTolerance * container.boundsDiagonal(), result};
  // One clipper per thread, kept between calls: its tables and pools have grown to the meshes this
  // thread breaks, so a fracture allocates little (begin() forgets the previous container).
  thread_local CellClipper clipper;
  const bool clip = method == FractureMethod::Clipper && clipper.begin(container, options);
  for (uint32_t i = 0; i < cells.size(); ++i) {
    if (cells[i].empty) continue;
    if (clip) {
      FracturePiece piece;
      const CellClipper::Outcome outcome = clipper.clip(cells[i], i, options, run.tolerance, piece, result.cuts);
      if (outcome == CellClipper::Outcome::Nothing) continue;
      if (outcome == CellClipper::Outcome::Piece) {
        result.pieces.push_back(std::move(piece));
        continue;
      }
    }
    result.carvedBySplits += 1;
    if (!carveCell(run, cells[i], i)) {
      result.pieces.clear();
      return result;
    }
  }
  return result;
}

namespace {

ConvexPolytope boxPolytope(const glm::dvec3& lo, const glm::dvec3& hi) {
  std::vector<glm::vec3> corners;
  for (int k = 0; k < 8; ++k)
    corners.emplace_back(glm::vec3((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z));
  return polytopeOfPoints(corners);
}

// The bisector plane of seeds a and b, normalised: the points nearer a are below it.
Plane bisector(const glm::dvec3& a, const glm::dvec3& b) {
  const glm::dvec3 n = b - a;
  const double length = glm::length(n);
  return Plane{n / length, (glm::dot(b, b) - glm::dot(a, a)) * 0.5 / length};
}

double farthestAbove(const ConvexPolytope& p, const Plane& plane) {
  double most = -std::numeric_limits<double>::infinity();
  for (const glm::dvec3& v : p.vertices) most = std::max(most, glm::dot(plane.normal, v) - plane.offset);
  return most;
}

ConvexCell voronoiCell(std::span<const glm::dvec3> seeds, size_t i, const ConvexPolytope& box, double tolerance) {
  ConvexCell cell;
  cell.seed = seeds[i];
  std::vector<size_t> order;
  for (size_t j = 0; j < seeds.size(); ++j)
    if (j != i) order.push_back(j);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return glm::length(seeds[a] - seeds[i]) < glm::length(seeds[b] - seeds[i]);
  });
  // The bisectors nearest first, a batch at a time (one in-place clip by all of a batch's planes),
  // until a seed is more than twice the cell's reach away: its bisector and all after it miss.
  constexpr size_t kBatch = 8;
  ConvexPolytope p = box, next;
  std::vector<Plane> candidates;
  std::vector<HalfSpace> batch;
  // A batch holds up to kBatch bisectors that touch the cell (those that miss are passed over).
  bool done = false;  // no seed is left, or every one left is too far for its bisector to touch the cell
  for (size_t at = 0; !done;) {
    double reach = 0.0;
    for (const glm::dvec3& v : p.vertices) reach = std::max(reach, glm::length(v - seeds[i]));
    batch.clear();
    for (; at < order.size() && batch.size() < kBatch; ++at) {
      const size_t j = order[at];
      if (glm::length(seeds[j] - seeds[i]) > 2.0 * reach + tolerance) {
        done = true;
        break;
      }
      if (glm::length(seeds[j] - seeds[i]) <= tolerance) continue;  // a repeated seed: no bisector
      const Plane plane = bisector(seeds[i], seeds[j]);
      if (farthestAbove(p, plane) <= tolerance) continue;
      batch.push_back({plane.normal, plane.offset});
      candidates.push_back(plane);
    }
    done = done || at == order.size();
    if (batch.empty()) continue;
    clipPolytope(p, batch, tolerance, next);
    std::swap(p, next);
    if (p.empty()) return ConvexCell{{}, seeds[i], true};
  }
  // A plane that clipped early may no longer touch the final cell: only those with a vertex on them.
  for (const Plane& plane : candidates) {
    if (farthestAbove(p, plane) >= -tolerance) cell.planes.push_back(plane);
  }
  return cell;
}

// splitmix64: a small generator with the same sequence everywhere.
struct SplitMix {
  uint64_t state;
  uint64_t next() {
    uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  double unit() { return double(next() >> 11) * 0x1.0p-53; }  // [0, 1)
};

}  // namespace

std::vector<ConvexCell> voronoiCells(std::span<const glm::dvec3> seeds, const glm::dvec3& lo, const glm::dvec3& hi) {
  std::vector<ConvexCell> cells(seeds.size());
  const double diagonal = glm::length(hi - lo);
  const double tolerance = 1e-9 * diagonal;
  const ConvexPolytope box = boxPolytope(lo, hi);
  for (size_t i = 0; i < seeds.size(); ++i) {
    cells[i].seed = seeds[i];
    bool repeated = false;
    for (size_t j = 0; j < i && !repeated; ++j) repeated = glm::length(seeds[j] - seeds[i]) <= tolerance;
    cells[i].empty = repeated || box.empty();  // a repeated seed: the earlier twin's cell covers it
    if (cells[i].empty) continue;
    cells[i] = voronoiCell(seeds, i, box, tolerance);
  }
  return cells;
}

std::vector<glm::dvec3> fractureSeeds(uint32_t count, uint64_t seed, const glm::dvec3& lo, const glm::dvec3& hi,
                                      const glm::dvec3& impactPoint, double impactRadius, double impactShare) {
  SplitMix rng{seed};
  std::vector<glm::dvec3> seeds;
  seeds.reserve(count);
  const uint32_t near = impactRadius > 0.0 ? uint32_t(double(count) * std::clamp(impactShare, 0.0, 1.0)) : 0u;
  const glm::dvec3 centre = glm::clamp(impactPoint, lo, hi);
  for (uint32_t k = 0; k < count; ++k) {
    glm::dvec3 p;
    if (k < near) {
      do {  // uniform in the ball, by rejection from its cube; kept inside the box
        p = glm::dvec3(rng.unit(), rng.unit(), rng.unit()) * 2.0 - 1.0;
      } while (glm::dot(p, p) > 1.0);
      p = glm::clamp(centre + p * impactRadius, lo, hi);
    } else {
      p = lo + glm::dvec3(rng.unit(), rng.unit(), rng.unit()) * (hi - lo);
    }
    seeds.push_back(p);
  }
  return seeds;
}

}  // namespace cleave::geometry
