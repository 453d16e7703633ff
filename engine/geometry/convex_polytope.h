// SPDX-License-Identifier: MIT
// ConvexPolytope: a convex solid as faces (outward plane and corner loop), the form a carried
// collider part takes between cuts.
//
// Why faces and not points: a convex polytope cut by a plane is two convex polytopes, and with faces
// the cut is exact and linear in the size of the part (every face polygon is clipped, the new face
// is the ring of section points), with no hull computation. Shrinking a part by a collision margin
// is the same operation: each face plane moved inwards by the margin clips the part once.
//
// Units follow the vertices (metres in cut or body space). Winding: each face loop is
// counter-clockwise seen from outside, and its plane is {x : dot(normal, x) = offset} with `normal`
// pointing outwards, unit length. Ownership: plain values, copied freely. Failure: every operation
// that cannot give a solid (a clip that removes all, a flat input) returns an empty polytope
// (`empty()`), never a malformed one; the functions never throw.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "cleave/geometry/convex_hull.h"

namespace cleave::geometry {

struct ConvexPolytope {
  struct Face {
    glm::dvec3 normal{0.0, 0.0, 1.0};  // outward, unit
    double offset = 0.0;               // dot(normal, x) on the face
    uint32_t first = 0;                // into corners
    uint32_t count = 0;                // corners of the loop, >= 3
  };
  std::vector<glm::dvec3> vertices;
  std::vector<uint32_t> corners;  // face loops, concatenated, counter-clockwise from outside
  std::vector<Face> faces;

  bool empty() const { return faces.size() < 4 || vertices.size() < 4; }
};

// The polytope of a convex hull (one face per hull triangle). Empty when the hull is not Ok.
ConvexPolytope polytopeFromHull(const ConvexHull& hull);

// The convex hull of `points` as a polytope (Quickhull, convex_hull.h). Empty for fewer than four
// points not in one plane.
ConvexPolytope polytopeOfPoints(std::span<const glm::vec3> points);

// The part of `p` with dot(normal, x) <= offset (`normal` need not be unit length). Vertices within
// `tolerance` (distance, same units) of the plane count as on it, so a clip through a vertex or a
// face adds no sliver. Empty when nothing of `p` is below the plane by more than the tolerance.
// Deterministic: the same input gives the same vertices in the same order.
ConvexPolytope clipPolytope(const ConvexPolytope& p, const glm::dvec3& normal, double offset,
                            double tolerance);

// The same clip written into `out` (which must not be `p`), reusing its memory: for a part clipped
// by many planes in turn. `out` is empty exactly when the value form would be.
void clipPolytope(const ConvexPolytope& p, const glm::dvec3& normal, double offset, double tolerance,
                  ConvexPolytope& out);

// A half-space {x : dot(normal, x) <= offset} (`normal` need not be unit length).
struct HalfSpace {
  glm::dvec3 normal{0.0, 0.0, 1.0};
  double offset = 0.0;
};

// `p` clipped by each of `halfSpaces` in turn into `out` (which must not be `p`): the same solid as
// the one-plane clips one after another with the same tolerance, and empty exactly when they would
// give an empty one, but each plane edits only the faces it cuts instead of rebuilding the whole
// polytope. A half-space with a zero or non-finite normal or offset gives an empty polytope.
void clipPolytope(const ConvexPolytope& p, std::span<const HalfSpace> halfSpaces, double tolerance,
                  ConvexPolytope& out);

// `p` with every vertex mapped by the affine `m` (any invertible matrix; a mirroring one keeps the
// loops counter-clockwise from outside). Face planes are recomputed from the mapped loops.
ConvexPolytope transformPolytope(const ConvexPolytope& p, const glm::dmat4& m);

// The inner parallel body of `p`: every face plane moved inwards by `margin` (the polytope whose
// Minkowski sum with a ball of radius `margin` has the faces of `p`). Empty when margin exceeds half
// the width.
ConvexPolytope shrinkPolytope(const ConvexPolytope& p, double margin);

// `p` itself when it has at most `maxVertices` vertices, else the hull of its vertices that are
// extreme along `maxVertices` directions spread evenly over the sphere: a subset of its vertices,
// so the result lies inside `p` (a simplified collider never inflates). Deterministic.
ConvexPolytope simplifyPolytope(const ConvexPolytope& p, uint32_t maxVertices);

// The indices of the vertices of `p` that are extreme along `count` directions spread evenly over
// the sphere (all of them, ascending, when there are at most `count`). Ties keep the lower index.
std::vector<uint32_t> extremeVertices(const ConvexPolytope& p, uint32_t count);

// Volume (units^3) and centroid; 0 and the vertex mean for an empty polytope.
double polytopeVolume(const ConvexPolytope& p);
glm::dvec3 polytopeCentroid(const ConvexPolytope& p);

// The smallest distance from a face plane to the vertex farthest behind it: the width of a box or
// a prism exactly, an upper bound of the width otherwise. 0 for an empty polytope.
double polytopeWidth(const ConvexPolytope& p);

// Axis-aligned bounds of the vertices.
void polytopeBounds(const ConvexPolytope& p, glm::dvec3& lo, glm::dvec3& hi);

}  // namespace cleave::geometry
