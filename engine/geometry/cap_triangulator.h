// SPDX-License-Identifier: MIT
// Triangulation of the cap polygons of a split: planar polygons with holes, in 2D cap coordinates.
// (Also of the polygon faces of mesh files, for the readers: see triangulateFace.)
//
// Input: points (2D, metres in the cap plane) and rings as [begin, end) ranges of those points. The
// first ring of a polygon is its outer border, counter-clockwise (positive signed area); the others
// are its holes, clockwise (negative signed area). Rings must not cross each other.
// Output: triangles appended as indices into `points`, counter-clockwise. Every ring edge appears in
// exactly one output triangle, in the ring's direction, and every ring point is used: collinear and
// duplicate points are never dropped (that would leave a T-junction against the side triangles), they
// are fanned into the triangle that holds their edge. With a tolerance > 0, points within it of the
// segment joining the corners around them (nearly collinear zig-zag runs and near-coincident points
// left by rounding, which can make the exact ring overlap itself by a few ulps) are treated the same
// way. Triangles never overlap beyond that: the call checks that the unsigned areas of the triangles
// add up to the polygon area, counting inverted triangles narrower than twice the tolerance (the
// folds of those rounding runs) as slivers, and fails otherwise.
//
// Scratch memory is kept between calls, so after warm-up a same-size call does not allocate.
// Not thread-safe; one triangulator per splitter.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace cleave::geometry {

struct CapRing {
  uint32_t begin = 0;  // into the points
  uint32_t end = 0;    // one past the last point; at least 3 points
};

class CapTriangulator {
 public:
  // Ear clipping with hole bridging (the earcut method: Eberly's bridge search, z-order hashing of the
  // vertices for rings over 80 points so the ear test is near linear, repair passes for degenerate
  // input). Returns false when the polygon could not be triangulated without overlap or gap; the
  // output vector then keeps only what it held before the call.
  bool triangulate(std::span<const glm::dvec2> points, std::span<const CapRing> rings,
                   std::vector<uint32_t>& triangles, double tolerance = 0.0);

  // Fan from the first strictly convex point of a convex ring (collinear points removed first and
  // fanned back in). Returns false, with the output untouched, when the ring is not strictly convex
  // once collinear points are removed, or when fanning them back in inverts a triangle.
  bool triangulateConvex(std::span<const glm::dvec2> points, CapRing ring,
                         std::vector<uint32_t>& triangles, double tolerance = 0.0);

  // One polygon face of a mesh file (OBJ, OFF and PLY faces of more than three corners):
  // `corners` in the face's order, nearly planar. Appends corners.size() - 2 triangles of corner
  // numbers (0 .. corners.size() - 1), wound like the face. A strictly convex face is fanned from
  // its first corner, the usual reader triangulation; any other face is projected on its plane
  // (the Newell normal) and ear-clipped, so that a concave face does not fold over itself as its
  // fan would (a fan from a corner that does not see the whole face has inverted triangles: the
  // mesh intersects itself and no cut through the fold can be capped). When the projected face is
  // degenerate or crosses itself, the fan is appended all the same and false is returned.
  bool triangulateFace(std::span<const glm::vec3> corners, std::vector<uint32_t>& triangles);

  // Twice the signed area of a ring (positive counter-clockwise).
  static double twiceSignedArea(std::span<const glm::dvec2> points, CapRing ring);
  // Whether q lies inside the ring (crossing number; a point on the border may go either way).
  static bool ringContains(std::span<const glm::dvec2> points, CapRing ring, const glm::dvec2& q);

 private:
  struct Node {
    uint32_t i = 0;  // point index
    double x = 0.0, y = 0.0;
    int32_t prev = -1, next = -1;    // ring links
    int32_t prevZ = -1, nextZ = -1;  // z-order links
    uint32_t z = 0;
  };

  void prepareRing(std::span<const glm::dvec2> points, CapRing ring);
  bool hiddenFit(std::span<const glm::dvec2> points, uint32_t a, uint32_t c) const;
  int32_t linkKept(CapRing ring);
  int32_t newNode(uint32_t i);
  void removeNode(int32_t p);
  double area(int32_t p, int32_t q, int32_t r) const;
  bool equals(int32_t a, int32_t b) const;
  bool pointInTriangle(int32_t a, int32_t b, int32_t c, int32_t p) const;
  bool isEar(int32_t ear) const;
  bool isEarHashed(int32_t ear) const;
  bool blocksEar(int32_t a, int32_t b, int32_t c, int32_t p) const;
  void earcutLinked(int32_t ear, int pass);
  int32_t clipDegenerate(int32_t start);
  int32_t cureLocalIntersections(int32_t start);
  void splitEarcut(int32_t start);
  int32_t eliminateHoles(std::span<const CapRing> rings, int32_t outer);
  int32_t findHoleBridge(int32_t hole, int32_t outer) const;
  bool sectorContainsSector(int32_t m, int32_t p) const;
  int32_t splitPolygon(int32_t a, int32_t b);
  bool intersects(int32_t p1, int32_t q1, int32_t p2, int32_t q2) const;
  bool onSegment(int32_t p, int32_t q, int32_t r) const;
  bool intersectsPolygon(int32_t a, int32_t b) const;
  bool locallyInside(int32_t a, int32_t b) const;
  bool middleInside(int32_t a, int32_t b) const;
  bool isValidDiagonal(int32_t a, int32_t b) const;
  int32_t leftmost(int32_t start) const;
  uint32_t zOrder(double x, double y) const;
  void indexCurve(int32_t start);
  void sortLinked(int32_t list);
  void emit(int32_t a, int32_t b, int32_t c);
  bool sliver(int32_t a, int32_t b, int32_t c) const;
  void hide(int32_t a, int32_t b, int32_t c);
  bool finish(std::span<const glm::dvec2> points, std::span<const CapRing> rings,
              std::vector<uint32_t>& triangles, size_t outputStart);

  std::span<const glm::dvec2> points_;  // the points of the current call
  std::vector<Node> nodes_;
  std::vector<uint8_t> kept_;         // per point: still a corner after collinear filtering
  std::vector<uint32_t> nextPoint_;   // per point: successor in its ring
  std::vector<uint32_t> nextKept_;    // per point: next kept point in its ring
  std::vector<int32_t> ringPrev_, ringNext_;  // filtering links per point
  std::vector<int32_t> holeQueue_;  // leftmost node of each hole
  std::vector<uint32_t> raw_;         // triangles of kept points, before fanning collinear points in
  std::vector<uint32_t> stack_;
  // Points taken off the polygon during clipping without a triangle of their own (a sliver ear, or
  // an exactly collinear corner): edge a -> c of a later triangle hides b; finish() fans b back in.
  // Key a << 32 | c, value b; sorted before finish() looks them up.
  std::vector<std::pair<uint64_t, uint32_t>> hidden_;
  double minX_ = 0.0, minY_ = 0.0, invSize_ = 0.0;
  bool hashed_ = false;
  double tolerance_ = 0.0;  // of the current call
  bool strict_ = false;     // no inverted sliver accepted (triangulateConvex)
  std::vector<glm::dvec2> facePoints_;  // triangulateFace: the corners in the face's plane
};

}  // namespace cleave::geometry
