// SPDX-License-Identifier: MIT
// Fracture: a mesh broken into the parts that lie inside convex cells, each part capped, closed and
// with exact mass properties, as the split core makes any piece. A convex cell is an intersection
// of half-spaces, so the part of a mesh inside it is the mesh cut by each of the cell's planes,
// keeping the side below; the cells of a Voronoi diagram of seed points tile space, so the parts of
// all cells make up the whole mesh.
//
// Units: cut space (the container's model applied: metres in the world for the engine). Planes are
// {x : dot(normal, x) = offset}; a cell is the set where dot(normal, x) <= offset for all its planes.
// Caps get the split options' cap material and cap UVs; with CapUvMode::WorldPlanar (the default)
// the caps that two neighbouring cells leave on their shared plane carry the same texture
// coordinates, so they line up. Ownership: results are plain values. Failure: a cut the split core
// refuses makes the whole fracture fail (status and message of that cut); nothing is thrown.
// Deterministic: the same container, cells and options give the same bytes.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cleave/geometry/mass_properties.h"
#include "cleave/geometry/mesh_container.h"
#include "cleave/geometry/split_types.h"

namespace cleave::geometry {

struct ConvexCell {
  std::vector<Plane> planes;  // the cell is below every one (dot(normal, x) <= offset)
  glm::dvec3 seed{0.0};       // the point the cell was made for (informative)
  bool empty = false;         // holds nothing (no planes then means all space, unless empty)
};

struct FracturePiece {
  MeshData mesh;                // in the source space of the container, like a split piece
  MeshWeld weld;                // as SplitPiece::weld: to cut or fracture the piece again
  uint32_t cell = 0;            // index into the cells given
  uint32_t capTriangles = 0;    // triangles in the cap-material run
  MassProperties mass;          // in cut space
  // Per triangle of `mesh`: the triangle of the container's mesh it lies in, or kFromCap | k for a
  // cap on the cell's plane k.
  std::vector<uint32_t> sourceTriangles;
};

struct FractureResult {
  SplitStatus status = SplitStatus::Ok;
  std::string message;
  std::vector<FracturePiece> pieces;  // by cell, then as the cuts made them (deterministic)
  uint32_t openChains = 0;            // section chains left open over all cuts (open art)
  uint32_t cuts = 0;                  // plane cuts made (planes that missed a part are not counted)
  uint32_t carvedBySplits = 0;        // cells the clipper left to one split per plane (see FractureMethod)
};

// How the part inside a cell is made. Both give closed, capped pieces with exact mass properties and
// the same volumes (to rounding); their triangles differ where the clipper's caps are made once per
// plane instead of once per cut.
enum class FractureMethod : uint8_t {
  // The cell clipper (all of a cell's planes in one pass over the polygons near the cell), and one
  // split per plane for the cells it leaves: open, mirrored, posed or skinned containers, a mesh face
  // lying in a cell plane, loops that touch, a part that falls apart into islands, points that meet
  // in float precision.
  Clipper,
  Splits,  // one split per cell plane, each keeping the side below, for every cell
};

// The parts of the container's mesh inside each cell. The options are those of every cut (caps,
// cap UVs and material, islands, open sections); a cell that holds nothing of the mesh gives no
// piece. Cost (FractureMethod::Clipper): the triangles near each cell, once per plane that crosses
// them, plus a cap per plane; with Splits, one split per cell plane that crosses a part still inside.
FractureResult fracture(const MeshContainer& container, std::span<const ConvexCell> cells,
                        const SplitOptions& options = {}, FractureMethod method = FractureMethod::Clipper);

// The Voronoi cells of `seeds` inside the box [lo, hi]: cell i is the points nearer seed i than any
// other seed. Only the bisector planes that bound the cell within the box are kept (one that does
// not touch the cell clipped to the box is pruned); the box's own faces are not among them, so the
// box must hold the mesh (its bounds, or more). A seed within 1e-9 of the box diagonal of an
// earlier one gives an empty cell (`empty`, no piece: the earlier cell covers it). Deterministic.
std::vector<ConvexCell> voronoiCells(std::span<const glm::dvec3> seeds, const glm::dvec3& lo, const glm::dvec3& hi);

// `count` seed points in the box [lo, hi] from a seeded generator (our own, the same on every
// platform). With impactRadius > 0, `impactShare` of them (rounded down) lie in the ball of that
// radius around `impactPoint` (clamped to the box), so the cells are smaller there.
std::vector<glm::dvec3> fractureSeeds(uint32_t count, uint64_t seed, const glm::dvec3& lo, const glm::dvec3& hi,
                                      const glm::dvec3& impactPoint = glm::dvec3(0.0), double impactRadius = 0.0,
                                      double impactShare = 0.5);

}  // namespace cleave::geometry
