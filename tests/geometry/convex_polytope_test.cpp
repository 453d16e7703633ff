// SPDX-License-Identifier: MIT
// Convex polytopes as carried collider parts: exact clips of small cases, clips through vertices and
// faces that add no sliver, shrinking by a margin, mirrored transforms, simplification that never
// grows a part, and invariants of random clips (volumes add up, both sides stay convex).
#include "cleave/geometry/convex_polytope.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "cleave/geometry/primitives.h"
#include "tests/geometry/test_meshes.h"

namespace cleave::geometry {
namespace {

ConvexPolytope unitBox(glm::vec3 half = glm::vec3(0.5f)) { return polytopeOfPoints(primitives::box(half).positions); }

// Every vertex within `tol` behind every face plane, every face loop planar and counter-clockwise
// from outside (its Newell normal agrees with the plane normal).
::testing::AssertionResult convexAndOriented(const ConvexPolytope& p, double tol) {
  if (p.empty()) return ::testing::AssertionFailure() << "empty polytope";
  for (size_t f = 0; f < p.faces.size(); ++f) {
    const auto& face = p.faces[f];
    for (const glm::dvec3& v : p.vertices)
      if (glm::dot(face.normal, v) - face.offset > tol)
        return ::testing::AssertionFailure() << "a vertex lies " << glm::dot(face.normal, v) - face.offset
                                             << " above face " << f;
    glm::dvec3 n(0.0);
    for (uint32_t i = 0; i < face.count; ++i) {
      const glm::dvec3 a = p.vertices[p.corners[face.first + i]];
      const glm::dvec3 b = p.vertices[p.corners[face.first + (i + 1) % face.count]];
      n += glm::cross(a, b);
      if (std::abs(glm::dot(face.normal, a) - face.offset) > tol)
        return ::testing::AssertionFailure() << "face " << f << " is not planar";
    }
    if (glm::dot(n, face.normal) <= 0.0) return ::testing::AssertionFailure() << "face " << f << " winds inwards";
  }
  return ::testing::AssertionSuccess();
}

TEST(ConvexPolytope, BoxCutThroughItsMiddleGivesTwoExactHalves) {
  const ConvexPolytope box = unitBox();
  EXPECT_NEAR(polytopeVolume(box), 1.0, 1e-12);
  const ConvexPolytope below = clipPolytope(box, {0, 1, 0}, 0.1, 1e-12);
  const ConvexPolytope above = clipPolytope(box, {0, -1, 0}, -0.1, 1e-12);
  EXPECT_NEAR(polytopeVolume(below), 0.6, 1e-12);
  EXPECT_NEAR(polytopeVolume(above), 0.4, 1e-12);
  EXPECT_NEAR(polytopeCentroid(below).y, -0.2, 1e-12);
  EXPECT_EQ(below.vertices.size(), 8u);  // still a box: four kept corners and four section points
  EXPECT_TRUE(convexAndOriented(below, 1e-12));
  EXPECT_TRUE(convexAndOriented(above, 1e-12));
}

TEST(ConvexPolytope, ClipThroughAVertexOrAFaceAddsNoSliver) {
  const ConvexPolytope box = unitBox();
  // The plane of the top face: everything is kept, nothing is added.
  const ConvexPolytope same = clipPolytope(box, {0, 1, 0}, 0.5, 1e-9);
  EXPECT_EQ(same.vertices.size(), box.vertices.size());
  EXPECT_NEAR(polytopeVolume(same), 1.0, 1e-12);
  // Above the top face: nothing is left.
  EXPECT_TRUE(clipPolytope(box, {0, -1, 0}, -0.5, 1e-9).empty());
  // Through a corner and the diagonal of the opposite... a plane through three corners: the section
  // points are the corners themselves, no new vertex within the tolerance of one.
  const glm::dvec3 a(0.5, 0.5, -0.5), b(-0.5, 0.5, 0.5), c(0.5, -0.5, 0.5);
  const glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
  const ConvexPolytope corner = clipPolytope(box, -n, -glm::dot(n, a), 1e-9);  // the corner (0.5, 0.5, 0.5) side
  ASSERT_FALSE(corner.empty());
  EXPECT_EQ(corner.vertices.size(), 4u);  // a tetrahedron of four box corners
  EXPECT_NEAR(polytopeVolume(corner), 1.0 / 6.0, 1e-12);
  EXPECT_TRUE(convexAndOriented(corner, 1e-12));
}

TEST(ConvexPolytope, ShrinkMovesEveryFaceInwardsByTheMargin) {
  const ConvexPolytope box = unitBox(glm::vec3(0.5f, 0.25f, 1.f));
  EXPECT_NEAR(polytopeWidth(box), 0.5, 1e-12);
  const ConvexPolytope shrunk = shrinkPolytope(box, 0.05);
  EXPECT_NEAR(polytopeVolume(shrunk), 0.9 * 0.4 * 1.9, 1e-12);
  glm::dvec3 lo, hi;
  polytopeBounds(shrunk, lo, hi);
  EXPECT_NEAR(hi.x, 0.45, 1e-12);
  EXPECT_NEAR(lo.y, -0.2, 1e-12);
  EXPECT_NEAR(hi.z, 0.95, 1e-12);
  EXPECT_TRUE(shrinkPolytope(box, 0.3).empty());  // more than half the width
  // A sphere's hull: every shrunk vertex is at least the margin inside every original face.
  const ConvexPolytope ball = polytopeOfPoints(primitives::uvSphere(0.5f, 16, 8).positions);
  const ConvexPolytope inner = shrinkPolytope(ball, 0.01);
  ASSERT_FALSE(inner.empty());
  for (const auto& f : ball.faces)
    for (const glm::dvec3& v : inner.vertices) ASSERT_LE(glm::dot(f.normal, v) - f.offset, -0.01 + 1e-8);
  EXPECT_TRUE(convexAndOriented(inner, 1e-9));
}

TEST(ConvexPolytope, ClipIntoAnotherPolytopeGivesTheSameBitsAsTheValueForm) {
  const ConvexPolytope ball = polytopeOfPoints(primitives::uvSphere(0.5f, 16, 8).positions);
  ConvexPolytope out = unitBox();  // holds something first: it must be replaced, not appended to
  for (const double offset : {0.3, 0.0, -0.49, -0.6}) {
    const glm::dvec3 n(0.2, -1.0, 0.4);
    const ConvexPolytope value = clipPolytope(ball, n, offset, 1e-9);
    clipPolytope(ball, n, offset, 1e-9, out);
    EXPECT_EQ(out.vertices, value.vertices);
    EXPECT_EQ(out.corners, value.corners);
    ASSERT_EQ(out.faces.size(), value.faces.size());
    for (size_t f = 0; f < out.faces.size(); ++f) {
      EXPECT_EQ(out.faces[f].normal, value.faces[f].normal);
      EXPECT_EQ(out.faces[f].first, value.faces[f].first);
    }
    EXPECT_EQ(out.empty(), value.empty());
  }
  EXPECT_TRUE(out.empty());  // the last plane is below the whole ball
}

TEST(ConvexPolytope, MirroredTransformKeepsThePolytopeOutwardAndItsVolume) {
  const ConvexPolytope box = unitBox();
  const glm::dmat4 m = glm::scale(glm::translate(glm::dmat4(1.0), glm::dvec3(2, 0, 0)), glm::dvec3(-1, 2, 3));
  const ConvexPolytope mapped = transformPolytope(box, m);
  EXPECT_NEAR(polytopeVolume(mapped), 6.0, 1e-12);
  EXPECT_NEAR(polytopeCentroid(mapped).x, 2.0, 1e-12);
  EXPECT_TRUE(convexAndOriented(mapped, 1e-12));
}

TEST(ConvexPolytope, SimplifiedPartLiesInsideTheOriginal) {
  const ConvexPolytope ball = polytopeOfPoints(primitives::uvSphere(0.5f, 32, 16).positions);
  ASSERT_GT(ball.vertices.size(), 48u);
  const ConvexPolytope simple = simplifyPolytope(ball, 48);
  EXPECT_LE(simple.vertices.size(), 48u);
  EXPECT_TRUE(convexAndOriented(simple, 1e-9));
  for (const auto& f : ball.faces)
    for (const glm::dvec3& v : simple.vertices) ASSERT_LE(glm::dot(f.normal, v) - f.offset, 1e-8);
  EXPECT_LT(polytopeVolume(simple), polytopeVolume(ball));
  EXPECT_GT(polytopeVolume(simple), 0.85 * polytopeVolume(ball));
}

TEST(ConvexPolytope, RandomClipsKeepVolumeAndConvexityAndAreDeterministic) {
  const ConvexPolytope ball = polytopeOfPoints(primitives::uvSphere(0.5f, 24, 12).positions);
  const double whole = polytopeVolume(ball);
  testing::SeededRandom rng(11);
  size_t cut = 0;
  for (int k = 0; k < 300; ++k) {
    glm::dvec3 n(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    if (glm::length(n) < 1e-3) continue;
    n = glm::normalize(n);
    // One plane in five through a vertex of the ball.
    const double d = k % 5 == 0 ? glm::dot(n, ball.vertices[size_t(k) % ball.vertices.size()]) : rng.uniform(-0.45, 0.45);
    const ConvexPolytope below = clipPolytope(ball, n, d, 1e-10);
    const ConvexPolytope above = clipPolytope(ball, -n, -d, 1e-10);
    const double sum = polytopeVolume(below) + polytopeVolume(above);
    ASSERT_NEAR(sum, whole, 1e-9 * whole) << "plane " << k;
    if (!below.empty()) {
      ASSERT_TRUE(convexAndOriented(below, 1e-8)) << "plane " << k;
    }
    if (!above.empty()) {
      ASSERT_TRUE(convexAndOriented(above, 1e-8)) << "plane " << k;
    }
    cut += !below.empty() && !above.empty();
    const ConvexPolytope again = clipPolytope(ball, n, d, 1e-10);
    ASSERT_EQ(again.vertices, below.vertices);
    ASSERT_EQ(again.corners, below.corners);
  }
  EXPECT_GT(cut, 200u);
}

}  // namespace
}  // namespace cleave::geometry
