// SPDX-License-Identifier: MIT
// Cap simplification: the caps of a piece cut by several planes in turn (a fracture cell) made
// again from their borders, without the points that only caps use.
//
// Each cut of a piece also cuts the caps that earlier cuts made: where the plane crosses a cap
// triangle's inner edge it adds a point on the line where the two cap planes meet, and that point
// stays in both caps. Over a cell's five to fifteen planes the caps fill with such points and the
// thin triangles between them (a 16-cell fracture of a 12-triangle box gave 2,227 cap triangles, 139
// per piece), which every later cut pays for again and the game draws. CapSimplifier drops every
// point used only by the caps of two planes (it lies on their common line, between two others of
// that line) and ear-clips each cap plane's region again from its border loops.
//
// Input: a closed piece (its weld closed) in source space, `sourceTriangles` per triangle with
// kFromCap | k for the caps of plane k (planes[k], in cut space: the piece's positions times
// `model`). Positions that stay are not moved, and no point is added: the piece stays closed and
// manifold on its float positions, and its volume and cap areas change only by the rounding of the
// dropped points off their line (the mass properties of the piece must be worked out again).
// A cap region whose border cannot be traced (it touches itself at a point) or triangulated is
// left as it was. The vertex arrays are compacted (unused vertices dropped, order kept) and the weld
// renumbered to match.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "cleave/geometry/mesh_data.h"
#include "cleave/geometry/split_types.h"

namespace cleave::geometry {

struct CapSimplifyStats {
  uint32_t regions = 0;         // cap regions made again
  uint32_t droppedPoints = 0;   // welded points no triangle uses any more
  uint32_t keptRegions = 0;     // regions left as they were (border not traced or not triangulated)
  uint32_t trianglesBefore = 0, trianglesAfter = 0;
};

class CapTriangulator;

// Keeps its scratch memory (and its triangulator's) between calls; one per thread.
class CapSimplifier {
 public:
  CapSimplifier();
  ~CapSimplifier();
  CapSimplifier(const CapSimplifier&) = delete;
  CapSimplifier& operator=(const CapSimplifier&) = delete;

  // Returns what it did; the piece is unchanged when no region had a point to drop.
  CapSimplifyStats simplify(MeshData& mesh, MeshWeld& weld, std::vector<uint32_t>& sourceTriangles,
                            std::span<const Plane> planes, const glm::dmat4& model);

  struct Scratch;

 private:
  std::unique_ptr<Scratch> scratch_;
};

}  // namespace cleave::geometry
