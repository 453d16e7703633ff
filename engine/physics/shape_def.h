// SPDX-License-Identifier: MIT
// ShapeDef: the checked description of a collision shape, given to PhysicsWorld::createShape.
//
// Units: metres. Every shape is expressed in the local frame of the body that uses it, whose origin
// is the body's centre of mass: give hull points and mesh positions relative to the centre of mass
// (MassProperties::centerOfMass of the piece), not in model space.
// Mesh winding: triangles counter-clockwise seen from outside (only the static mesh cares about the
// side; the contact normals of GImpact meshes are two-sided).
// The def owns copies of its arrays; createShape copies what it needs, so the def can be discarded
// afterwards.
//
// Convex margins (why hulls do not grow): Bullet rounds convex hulls by a collision margin that is
// added *outside* the given points. The default of 4 cm would make a 2 cm split piece float 4 cm
// above the ground. createShape therefore computes the exact hull, picks
//   margin = min(kMaxConvexMargin, kRelativeConvexMargin * smallest width of the hull),
// and moves every face of the hull inwards by that margin (btConvexHullComputer's face shrinking).
// The shrunken hull plus the rounding margin has its faces exactly where the input faces were; only
// edges and corners are rounded by at most the margin. So a piece never grows, and tiny pieces keep
// a proportionally tiny margin. Boxes, spheres and capsules keep their margin inside the shape too.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace cleave::physics {

inline constexpr float kMaxConvexMargin = 0.01f;       // metres
inline constexpr float kRelativeConvexMargin = 0.1f;   // of the smallest width of a hull
inline constexpr uint32_t kDefaultMaxHullVertices = 64;
// Triangle margin of ConcaveMesh (GImpact) shapes, metres. GImpact needs a margin for robust
// triangle contacts and it lies outside the surface (a concave mesh cannot be shrunk like a hull),
// so concave bodies rest this much above what they stand on. Prefer hulls or compounds of hulls for
// small pieces.
inline constexpr float kConcaveMeshMargin = 0.002f;

enum class ShapeType : uint8_t {
  Box,          // halfExtents
  Sphere,       // radius
  Capsule,      // radius, halfHeight of the cylindrical part, axis = local Y
  ConvexHull,   // points (hull of them is taken; interior points are ignored)
  Compound,     // parts: convex hulls, each with a local transform
  ConcaveMesh,  // positions + indices, GImpact: for dynamic concave bodies (pieces of a cut)
  StaticMesh,   // positions + indices, BVH: static bodies only (levels, big props)
};
const char* toString(ShapeType type);

// One convex part of a compound shape, in the compound's local frame.
struct ConvexPart {
  std::vector<glm::vec3> points;            // hull points in the part's own frame
  glm::vec3 position{0.0f};                 // part frame origin in the compound frame, metres
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // part frame rotation (normalised by createShape)
  // Prepared parts: margin >= 0 says `points` are the vertices of a convex polytope whose faces were
  // already moved inwards by `margin` (geometry::shrinkPolytope; the carried collider parts of split
  // pieces). createShape then uses them as they are, with this margin, and runs no hull computation.
  // margin must be at most kMaxConvexMargin. Negative (the default): the hull is computed and shrunk.
  float margin = -1.0f;
};

struct ShapeDef {
  ShapeType type = ShapeType::Box;
  glm::vec3 halfExtents{0.5f};  // Box; each > 0
  float radius = 0.5f;          // Sphere, Capsule; > 0
  float halfHeight = 0.5f;      // Capsule: half the length of the cylinder between the caps; >= 0
  std::vector<glm::vec3> points;     // ConvexHull: >= 4 points, not coplanar
  std::vector<ConvexPart> parts;     // Compound: >= 1 part, each a valid hull
  std::vector<glm::vec3> positions;  // ConcaveMesh, StaticMesh
  std::vector<uint32_t> indices;     // ConcaveMesh, StaticMesh: triangle list, counter-clockwise
  // ConvexHull and Compound parts: a (shrunken) hull with more vertices keeps only the vertices
  // that are extreme along maxHullVertices fixed, evenly spread directions. They are a subset of
  // its vertices, so the reduced hull lies inside the exact one: reduction never inflates a piece.
  uint32_t maxHullVertices = kDefaultMaxHullVertices;  // >= 4
  // ConvexHull: >= 0 means `points` are already a shrunken hull with this margin (see
  // ConvexPart::margin); negative: computed.
  float preparedMargin = -1.0f;

  static ShapeDef box(glm::vec3 halfExtents);
  static ShapeDef sphere(float radius);
  static ShapeDef capsule(float radius, float halfHeight);
  static ShapeDef convexHull(std::span<const glm::vec3> points);
  static ShapeDef compound(std::vector<ConvexPart> parts);
  // A convex hull given by the vertices of an already shrunken polytope and its margin.
  static ShapeDef preparedHull(std::span<const glm::vec3> points, float margin);
  static ShapeDef concaveMesh(std::span<const glm::vec3> positions,
                              std::span<const uint32_t> indices);
  static ShapeDef staticMesh(std::span<const glm::vec3> positions,
                             std::span<const uint32_t> indices);
};

}  // namespace cleave::physics
