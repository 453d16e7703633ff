// SPDX-License-Identifier: MIT
// Shared scene pieces for the physics tests.
#pragma once

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>
#include <glm/glm.hpp>

#include "cleave/physics/physics_world.h"

namespace cleave::physics::testing {

inline constexpr double kDt = 1.0 / 60.0;

// A static box ground whose top face is the plane y = 0 (50 x 50 m).
inline BodyId addGround(PhysicsWorld& world, bool mesh = false) {
  ShapeDef def = ShapeDef::box(glm::vec3(50.0f, 1.0f, 50.0f));
  glm::vec3 position(0.0f, -1.0f, 0.0f);
  if (mesh) {
    const std::vector<glm::vec3> positions = {
        {-50.0f, 0.0f, -50.0f}, {-50.0f, 0.0f, 50.0f}, {50.0f, 0.0f, 50.0f}, {50.0f, 0.0f, -50.0f}};
    const std::vector<uint32_t> indices = {0, 1, 2, 0, 2, 3};  // counter-clockwise seen from +y
    def = ShapeDef::staticMesh(positions, indices);
    position = glm::vec3(0.0f);
  }
  const Result<ShapeId> shape = world.createShape(def);
  EXPECT_TRUE(shape.ok()) << shape.message();
  BodyDef body;
  body.shape = shape.value();
  body.position = position;
  const Result<BodyId> ground = world.createBody(body);
  EXPECT_TRUE(ground.ok()) << ground.message();
  world.destroyShape(shape.value());  // the body keeps it alive
  return ground.value();
}

inline std::vector<glm::vec3> boxCorners(glm::vec3 half, glm::vec3 offset = glm::vec3(0.0f)) {
  std::vector<glm::vec3> corners;
  for (int i = 0; i < 8; ++i) {
    corners.push_back(offset + glm::vec3((i & 1) ? half.x : -half.x, (i & 2) ? half.y : -half.y,
                                         (i & 4) ? half.z : -half.z));
  }
  return corners;
}

// A dynamic body with the given shape, failing the test if creation fails.
inline BodyId addBody(PhysicsWorld& world, const ShapeDef& shapeDef, float mass,
                      glm::vec3 position, BodyDef body = {}) {
  const Result<ShapeId> shape = world.createShape(shapeDef);
  EXPECT_TRUE(shape.ok()) << shape.message();
  body.shape = shape.value();
  body.mass = mass;
  body.position = position;
  const Result<BodyId> id = world.createBody(body);
  EXPECT_TRUE(id.ok()) << id.message();
  world.destroyShape(shape.value());
  return id.value();
}

inline void stepFor(PhysicsWorld& world, int steps) {
  for (int i = 0; i < steps; ++i) ASSERT_EQ(world.step(kDt), PhysicsStatus::Ok);
}

// An L-shaped prism (legs 1 m long, 0.5 m wide, 0.5 m thick along z), closed and counter-clockwise
// seen from outside, with its centre of mass (5/12, 5/12, 0) moved to the origin. Its flat bottom
// is then at y = -5/12.
struct LShape {
  std::vector<glm::vec3> positions;
  std::vector<uint32_t> indices;
};
inline constexpr float kLShapeCentre = 5.0f / 12.0f;

inline LShape makeLShape() {
  const glm::vec2 outline[6] = {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 0.5f},
                                {0.5f, 0.5f}, {0.5f, 1.0f}, {0.0f, 1.0f}};  // ccw from +z
  LShape l;
  for (float z : {-0.25f, 0.25f}) {
    for (const glm::vec2& p : outline) {
      l.positions.push_back(glm::vec3(p.x - kLShapeCentre, p.y - kLShapeCentre, z));
    }
  }
  for (uint32_t k = 1; k + 1 < 6; ++k) {  // the outline is star-shaped from corner 0
    l.indices.insert(l.indices.end(), {6, 6 + k, 6 + k + 1});  // top cap, normal +z
    l.indices.insert(l.indices.end(), {0, k + 1, k});          // bottom cap, normal -z
  }
  for (uint32_t i = 0; i < 6; ++i) {
    const uint32_t j = (i + 1) % 6;
    l.indices.insert(l.indices.end(), {i, j, 6 + j, i, 6 + j, 6 + i});
  }
  return l;
}

}  // namespace cleave::physics::testing
