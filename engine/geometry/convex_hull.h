// SPDX-License-Identifier: MIT
// Convex hulls of point sets and a convexity test for closed meshes.
//
// Units follow the input positions (metres). Output triangles are counter-clockwise seen from
// outside (outward normals by the right-hand rule) and form a closed 2-manifold. Everything is
// computed in double precision with a deterministic visiting order, so the same input always gives
// the same output arrays.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cleave/geometry/mesh_data.h"

namespace cleave::geometry {

enum class HullStatus : uint8_t {
  Ok = 0,
  TooFewPoints,      // fewer than four distinct points
  Collinear,         // every point within tolerance of one line: no volume
  Coplanar,          // every point within tolerance of one plane: no volume
  InvalidInput,      // a NaN or infinite coordinate
  NumericalFailure,  // the horizon was not a simple loop (should not happen on sane data)
};
const char* toString(HullStatus status);

struct ConvexHull {
  HullStatus status = HullStatus::Ok;
  std::string message;                  // a reason a person can act on, empty when Ok
  std::vector<glm::dvec3> positions;    // hull vertices, exact copies of input points
  std::vector<uint32_t> sourceIndices;  // for each hull vertex, the index of the input point
  std::vector<uint32_t> indices;        // triangle list, counter-clockwise seen from outside
};

// Quickhull (Barber, Dobkin, Huhdanpaa 1996) with outside-point sets and a horizon walk.
// `relativeTolerance` times the bounding-box diagonal is the distance under which a point counts as
// on a face (coplanar and duplicate points are dropped, never make slivers). On any status but Ok the
// arrays are empty; the call never throws and never crashes on bad input.
ConvexHull computeConvexHull(std::span<const glm::dvec3> points, double relativeTolerance = 1e-9);
ConvexHull computeConvexHull(std::span<const glm::vec3> points, double relativeTolerance = 1e-9);

// The indices, ascending, of the points that are extreme along `count` directions spread evenly
// over the sphere (a Fibonacci lattice); ties keep the lower index. A subset of the points, so their
// hull lies inside the hull of all of them: the way a dense hull is reduced without growing.
std::vector<uint32_t> extremePoints(std::span<const glm::dvec3> points, uint32_t count);

// The hull as a MeshData (positions and indices only; float positions).
MeshData toMeshData(const ConvexHull& hull);

// True when the closed mesh bounds a convex solid within `relativeTolerance` times its bounding-box
// diagonal: (1) the mesh is closed and oriented on exactly equal positions, (2) at every edge the
// far vertex of each neighbouring triangle lies at most the tolerance above the other triangle's
// plane (no reflex edge), and (3) the volume of its convex hull exceeds the mesh volume by at most a
// layer of that thickness over the hull surface (catches a second component or a cavity). Open,
// empty or flat meshes return false, which is the safe answer for choosing a convex collider.
bool isConvex(const MeshData& mesh, double relativeTolerance = 1e-5);

}  // namespace cleave::geometry
