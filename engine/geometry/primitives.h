// SPDX-License-Identifier: MIT
// Procedural closed meshes for the demo, the tests and the benchmarks.
//
// Units: metres, centred on the origin unless stated; +y is "up" (the axis of cylinders, capsules,
// tori and prisms). Every mesh is closed once vertices are welded on exactly equal positions (seam
// vertices repeat their twin's coordinates bit for bit), has no zero-area triangle, and is wound
// counter-clockwise seen from outside. Every mesh carries positions, unit normals, tangents (xyz
// unit, w = +1 or -1 handedness) and uv0, and one implicit submesh of material 0.
//
// Arguments are clamped to the smallest sensible value (at least 3 segments, 2 rings, ...) instead
// of failing; lengths are taken by absolute value and a zero length gives an empty mesh. The
// returned mesh is owned by the caller.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "cleave/geometry/mesh_data.h"

namespace cleave::geometry::primitives {

// Axis-aligned box, 24 vertices (4 per face, split seams), 12 triangles.
MeshData box(const glm::vec3& halfExtents);
// UV sphere: `segments` around y, `rings` from pole to pole; 2 * segments * (rings - 1) triangles.
MeshData uvSphere(float radius, uint32_t segments, uint32_t rings);
// Ellipsoid with semi-axes `radii` (x, y, z), same tessellation as uvSphere.
MeshData ellipsoid(const glm::vec3& radii, uint32_t segments, uint32_t rings);
// Cylinder along y from -height/2 to +height/2 with flat caps (separate cap vertices).
MeshData cylinder(float radius, float height, uint32_t segments);
// Torus around the y axis in the xz plane: ring radius `major`, tube radius `minor` (< major).
MeshData torus(float major, float minor, uint32_t segments, uint32_t sides);
// Capsule along y: a cylinder of `cylinderHeight` closed by two hemispheres of `radius`.
// `rings` counts the rings of the two hemispheres together (rounded up to an even number).
MeshData capsule(float radius, float cylinderHeight, uint32_t segments, uint32_t rings);
// A solid spherical shell: an outward outer sphere and an inward-facing inner sphere
// (innerRadius < outerRadius); volume 4/3 pi (R^3 - r^3) up to tessellation.
MeshData hollowSphere(float outerRadius, float innerRadius, uint32_t segments, uint32_t rings);
// n concentric spheres of radii outerRadius * (n - k) / n, k = 0..n-1, alternately facing out and
// in: solid shells, with a solid ball in the middle when n is odd.
MeshData nestedShells(uint32_t n, float outerRadius, uint32_t segments, uint32_t rings);
// A comb: a spine along x (width teeth * pitch, spine depth along y) with `teeth` teeth pointing
// +y, extruded along z by `depth`. Outline in xy; the spine's bottom is at y = 0.
MeshData combPrism(uint32_t teeth, float pitch = 0.2f, float toothLength = 0.6f,
                   float spineHeight = 0.2f, float depth = 0.3f);
// A star with `points` tips (outer radius, inner radius) in the xz plane, extruded along y from
// -height/2 to +height/2.
MeshData starPrism(uint32_t points, float outerRadius = 1.f, float innerRadius = 0.4f,
                   float height = 0.5f);
// Regular tetrahedron inscribed in a sphere of radius `circumRadius`, split seams (12 vertices).
MeshData tetrahedron(float circumRadius);
// Two UV spheres of `radius`, centred at x = -(radius + gap/2) and x = +(radius + gap/2).
MeshData twoDisjointSpheres(float radius, float gap, uint32_t segments, uint32_t rings);

// Concatenation: b's indices are offset, submesh runs are kept (an absent run list counts as one
// run of material 0). An attribute present in only one input is filled with a neutral value
// (normal (0,1,0), tangent (1,0,0,1), uv 0, colour white, joint 0 with weight (1,0,0,0)).
MeshData merge(const MeshData& a, const MeshData& b);
// Applies an affine transform in place: positions by `m`, normals by the inverse transpose
// (renormalised), tangent xyz by `m` (renormalised, handedness flipped when m mirrors). A mirroring
// matrix (negative determinant) also reverses every triangle so the winding stays CCW from outside.
void transform(MeshData& mesh, const glm::mat4& m);

}  // namespace cleave::geometry::primitives
