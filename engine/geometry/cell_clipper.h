// SPDX-License-Identifier: MIT
// Internal to fracture (not installed): the part of a closed mesh inside one convex cell, made in one
// pass over the cell's planes instead of one split per plane.
//
// The mesh's triangles are kept as convex polygons over shared points (the container's position ids,
// then the cut points each plane adds); those below every plane from the start are set aside. Each
// plane in turn drops the polygons above it and clips those it crosses (one cut point per point pair
// and plane, one interpolated vertex per vertex pair and plane, so neighbours and seams agree bit for
// bit). The section it leaves is the border of its cap: the on-plane edges of what is kept, reversed,
// opposite pairs cancelled. Caps stay borders (directed point pairs) until the end: a later plane
// clips each earlier cap's border and closes it along the line where the two planes meet, giving the
// later cap the same edges the other way, so a cap never gains a point that only caps use. At the
// end each cap's loops are traced, holes given to their borders and ear-clipped once
// (cap_triangulator.h), the polygons fanned into triangles, and the piece checked: one connected
// part, every edge met once each way on points, distinct float positions, no triangle of zero area
// in float.
//
// The clipper answers Fallback, having written nothing, whenever the input or a step is outside what
// it handles (an open, mirrored or posed container, skin, per-border cap UVs, a polygon lying in a
// plane, a cap border along the line of two planes or meeting it in points that do not alternate, a
// section point met twice, a cap not triangulated, more than one island, a check failing); fracture
// then carves that cell by splits, which handle all of it. Units, spaces, cap UVs (NormalizedBounds:
// over the cap as it ends) and provenance are those of fracture.h.
#pragma once

#include <cstdint>
#include <memory>

#include "cleave/geometry/fracture.h"

namespace cleave::geometry {

class CellClipper {
 public:
  enum class Outcome : uint8_t {
    Piece,     // `piece` holds the part of the mesh inside the cell
    Nothing,   // no part of the mesh lies inside the cell
    Fallback,  // not handled here (see above); nothing written
  };

  CellClipper();
  ~CellClipper();
  CellClipper(const CellClipper&) = delete;
  CellClipper& operator=(const CellClipper&) = delete;

  // Sets the clipper up for one container (kept by reference until the next call) and options;
  // false when the container or options are outside what it handles (every clip then falls back).
  bool begin(const MeshContainer& container, const SplitOptions& options);

  // The part of the container given to begin inside the cell. `tolerance`: the on-plane distance in
  // cut space. `cuts` is increased by the planes that crossed
  // the part (on Piece and Nothing only).
  Outcome clip(const ConvexCell& cell, uint32_t cellIndex, const SplitOptions& options, double tolerance,
               FracturePiece& piece, uint32_t& cuts);

  struct State;

 private:
  std::unique_ptr<State> s_;
};

}  // namespace cleave::geometry
