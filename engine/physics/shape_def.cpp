// SPDX-License-Identifier: MIT
#include "cleave/physics/shape_def.h"

#include <utility>

namespace cleave::physics {

const char* toString(ShapeType type) {
  switch (type) {
    case ShapeType::Box: return "box";
    case ShapeType::Sphere: return "sphere";
    case ShapeType::Capsule: return "capsule";
    case ShapeType::ConvexHull: return "convex hull";
    case ShapeType::Compound: return "compound";
    case ShapeType::ConcaveMesh: return "concave mesh";
    case ShapeType::StaticMesh: return "static mesh";
  }
  return "unknown shape type";
}

ShapeDef ShapeDef::box(glm::vec3 halfExtents) {
  ShapeDef def;
  def.type = ShapeType::Box;
  def.halfExtents = halfExtents;
  return def;
}

ShapeDef ShapeDef::sphere(float radius) {
  ShapeDef def;
  def.type = ShapeType::Sphere;
  def.radius = radius;
  return def;
}

ShapeDef ShapeDef::capsule(float radius, float halfHeight) {
  ShapeDef def;
  def.type = ShapeType::Capsule;
  def.radius = radius;
  def.halfHeight = halfHeight;
  return def;
}

ShapeDef ShapeDef::convexHull(std::span<const glm::vec3> points) {
  ShapeDef def;
  def.type = ShapeType::ConvexHull;
  def.points.assign(points.begin(), points.end());
  return def;
}

ShapeDef ShapeDef::preparedHull(std::span<const glm::vec3> points, float margin) {
  ShapeDef def = convexHull(points);
  def.preparedMargin = margin;
  return def;
}

ShapeDef ShapeDef::compound(std::vector<ConvexPart> parts) {
  ShapeDef def;
  def.type = ShapeType::Compound;
  def.parts = std::move(parts);
  return def;
}

ShapeDef ShapeDef::concaveMesh(std::span<const glm::vec3> positions,
                               std::span<const uint32_t> indices) {
  ShapeDef def;
  def.type = ShapeType::ConcaveMesh;
  def.positions.assign(positions.begin(), positions.end());
  def.indices.assign(indices.begin(), indices.end());
  return def;
}

ShapeDef ShapeDef::staticMesh(std::span<const glm::vec3> positions,
                              std::span<const uint32_t> indices) {
  ShapeDef def = concaveMesh(positions, indices);
  def.type = ShapeType::StaticMesh;
  return def;
}

}  // namespace cleave::physics
