// SPDX-License-Identifier: MIT
// Mass properties of closed triangle meshes, in double precision.
//
// Method: divergence theorem over signed tetrahedra from the origin (Mirtich 1996 / Eberly,
// "Polyhedral Mass Properties"), accumulated about a reference point near the mesh to keep the
// products small. Density is 1 (multiply mass and inertia by the real density). Units follow the
// positions: volume m^3, inertia m^5 (times density kg/m^3 gives kg m^2).
#pragma once

#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "cleave/geometry/mesh_data.h"

namespace cleave::geometry {

struct MassProperties {
  double volume = 0.0;                  // > 0 for a closed, outward-oriented mesh
  glm::dvec3 centerOfMass{0.0};         // in the space of the positions given
  glm::dmat3 inertia{0.0};              // about centerOfMass, density 1, symmetric
  bool closed = false;                  // every edge shared by exactly two triangles in opposite order
  bool fromConvexHull = false;          // the mesh was open: values are those of its convex hull
};

// Principal axes of a symmetric inertia tensor: inertia = axes * diag(moments) * transpose(axes),
// axes a rotation (determinant +1), moments sorted ascending.
struct PrincipalInertia {
  glm::dvec3 moments{0.0};
  glm::dmat3 axes{1.0};
};

// Properties of the closed surface given by positions (transformed by `transform`, which may scale,
// shear or mirror; a mirroring transform is handled so the volume stays positive) and a triangle list.
// Closedness is checked on positions welded exactly; an open mesh falls back to its convex hull, or,
// when it is made of several separate parts (multi-part art), to the sum of its parts: each closed
// part exact, each open part its convex hull (fromConvexHull is then set when any part used one;
// parts that pass into one another count their common volume twice).
MassProperties computeMassProperties(std::span<const glm::vec3> positions,
                                     std::span<const uint32_t> indices,
                                     const glm::dmat4& transform = glm::dmat4(1.0));
MassProperties computeMassProperties(const MeshData& mesh,
                                     const glm::dmat4& transform = glm::dmat4(1.0));

// The same on double-precision positions (for example a MeshContainer's cut-space positions).
MassProperties computeMassProperties(std::span<const glm::dvec3> positions,
                                     std::span<const uint32_t> indices,
                                     const glm::dmat4& transform = glm::dmat4(1.0));

// Allocation-free integration for callers that know the surface is closed (a splitter's pieces are
// closed by construction): no weld, no closedness check, no hull fallback; `closed` is reported true.
// `flipWinding` reverses every triangle (for a mirrored space). Only the vertices referenced by
// `indices` are read, unless `everyPointUsed` says every vertex is referenced (then the bounds that
// pick the integration origin are taken over the positions in order, which is faster). An index out
// of range or a ragged index list gives all-zero properties with closed = false.
MassProperties integrateClosedSurface(std::span<const glm::dvec3> positions,
                                      std::span<const uint32_t> indices, bool flipWinding = false,
                                      bool everyPointUsed = false);

// Invalid input (an index out of range, an index count not a multiple of 3, a NaN or infinite
// coordinate, no triangle) gives all-zero properties with closed = false and fromConvexHull = false.
// A closed mesh with zero volume (flat) gives volume 0, the vertex centroid as centre and a zero
// tensor. An open mesh whose convex hull is flat or degenerate gives the same, with fromConvexHull.

// The properties of two solids taken together (volumes add, centres weighted by volume, tensors
// moved to the common centre by the parallel axis theorem); closed when both are, fromConvexHull
// when either is. Both in the same space.
MassProperties combineMassProperties(const MassProperties& a, const MassProperties& b);

// True when, with positions welded on exactly equal coordinates, every undirected edge is used by
// exactly two triangles, once in each direction (closed, 2-manifold at edges, consistently wound).
// Triangles with two equal positions are ignored. False on invalid input.
bool isClosedAndOriented(std::span<const glm::vec3> positions, std::span<const uint32_t> indices);

// Jacobi eigen-decomposition of a symmetric 3x3 tensor.
PrincipalInertia principalInertia(const glm::dmat3& inertia);

}  // namespace cleave::geometry
