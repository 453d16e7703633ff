// SPDX-License-Identifier: MIT
// Collider parts: the convex parts a mesh's collider is made of, worked out once per authored mesh
// and carried with it through every cut.
//
// An authored mesh is decomposed once (decomposeConvex); its instances share the parts. A cut never
// decomposes again: each part is clipped by the plane (clipPolytope, exact and linear in the part
// size) and each clipped part goes to the piece (island) that holds it (clipPartsToPieces). Pieces of
// pieces clip again. Parts too small to matter are dropped; mass never comes from the collider (it is
// the mesh's), so dropping a part loses no mass.
//
// Spaces: parts live in the mesh space of the mesh they belong to (the space of MeshData::positions,
// before any model matrix), so every instance of a mesh, and every piece cut from it, shares them.
// Failure: the functions never throw; a mesh that cannot be decomposed gives the convex hull of its
// points as one part, or no part when even that is flat.
#pragma once

#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "cleave/geometry/convex_polytope.h"
#include "cleave/geometry/mesh_data.h"
#include "cleave/geometry/mesh_splitter.h"

namespace cleave::geometry {

// A part is convex enough to be its own hull when geometry::isConvex holds with this relative
// tolerance (a dent shallower than 0.2% of the part's size is filled by the hull, by design).
inline constexpr double kPartConvexTolerance = 2e-3;

// Parts keep at most this many vertices (simplifyPolytope): a collider hull needs no more, and a
// clip or a shrink costs in proportion to the part size.
inline constexpr uint32_t kMaxPartVertices = 48;

// Our own convex decomposition for colliders: the mesh is cut through the middle of its longest
// bounding-box extent, recursively, until each part is convex (isConvex within
// kPartConvexTolerance) or `maxDepth` cuts are made;
// each part's convex hull, simplified to kMaxPartVertices, is one polytope (mesh space).
// Deterministic.
std::vector<ConvexPolytope> decomposeConvex(const MeshData& mesh, IMeshSplitter& splitter, int maxDepth = 4);

// The immutable part set shared by a mesh's instances and carried by its pieces.
using ColliderPartSet = std::vector<ConvexPolytope>;
using SharedColliderParts = std::shared_ptr<const ColliderPartSet>;

struct PartClipOptions {
  // Parts whose clipped volume is below this share of their piece's volume are dropped (slivers
  // that only cost contacts), unless the piece would keep no part at all.
  double minVolumeShare = 1e-3;
  double relativeTolerance = 1e-9;  // on-plane tolerance, times the part's bounding-box diagonal
};

// Clips `parts` (mesh space) by `plane` (mesh space; above = dot(normal, x) > offset) and gives each
// piece of `result` the clipped parts it holds: out[i] for result.pieces[i]. A clipped part goes to
// the piece on its side whose bounds contain its centroid, the nearest such piece by vertex distance
// when several do; clipped parts are simplified to kMaxPartVertices again. A piece left without a
// part gets none (its caller decides on a fallback).
void clipPartsToPieces(const ColliderPartSet& parts, const Plane& plane, const SplitResult& result,
                       const PartClipOptions& options, std::vector<ColliderPartSet>& out);

// What clipping and shrinking the parts costs, in units of one vertex-corner pair (the shrink of a
// part clips it once per face plane, each clip walks every face corner): the sum over parts of
// vertices x face corners. The split budget's estimates scale with it.
double partsWork(const ColliderPartSet& parts);

// Sum of the part volumes (overlaps counted twice; our parts do not overlap).
double partsVolume(const ColliderPartSet& parts);

}  // namespace cleave::geometry
