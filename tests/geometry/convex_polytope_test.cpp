// SPDX-License-Identifier: MIT
// Convex polytopes as carried collider parts: exact clips of small cases, clips through vertices and
// faces that add no sliver, shrinking by a margin (against one clip per face, vertices that split),
// clips by many planes against the one-plane clips, mirrored transforms, simplification that never
// grows a part, and invariants of random clips (volumes add up, both sides stay convex).
#include "cleave/geometry/convex_polytope.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
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

// Every directed edge of the face loops used once, and its reverse once.
::testing::AssertionResult closedOnLoops(const ConvexPolytope& p) {
  std::vector<std::pair<uint32_t, uint32_t>> edges;
  for (const auto& f : p.faces)
    for (uint32_t i = 0; i < f.count; ++i)
      edges.emplace_back(p.corners[f.first + i], p.corners[f.first + (i + 1) % f.count]);
  std::sort(edges.begin(), edges.end());
  for (size_t e = 0; e < edges.size(); ++e) {
    if (e + 1 < edges.size() && edges[e] == edges[e + 1]) return ::testing::AssertionFailure() << "an edge used twice";
    if (!std::binary_search(edges.begin(), edges.end(), std::make_pair(edges[e].second, edges[e].first)))
      return ::testing::AssertionFailure() << "an edge without its reverse";
  }
  return ::testing::AssertionSuccess();
}

// The inner parallel body the slow way: one one-plane clip per distinct face plane moved inwards.
ConvexPolytope shrunkByClips(const ConvexPolytope& p, double margin) {
  glm::dvec3 lo, hi;
  polytopeBounds(p, lo, hi);
  const double tolerance = 1e-9 * glm::length(hi - lo);
  ConvexPolytope current = p;
  for (const auto& f : p.faces) {
    current = clipPolytope(current, f.normal, f.offset - margin, tolerance);
    if (current.empty()) return current;
  }
  return current;
}

// Every vertex of `a` within `tol` of a vertex of `b` and the other way round.
::testing::AssertionResult sameVertices(const ConvexPolytope& a, const ConvexPolytope& b, double tol) {
  if (a.vertices.size() != b.vertices.size())
    return ::testing::AssertionFailure() << a.vertices.size() << " vertices against " << b.vertices.size();
  for (int pass = 0; pass < 2; ++pass) {
    const ConvexPolytope& from = pass ? b : a;
    const ConvexPolytope& to = pass ? a : b;
    for (const glm::dvec3& v : from.vertices) {
      double nearest = 1e300;
      for (const glm::dvec3& w : to.vertices) nearest = std::min(nearest, glm::length(v - w));
      if (nearest > tol) return ::testing::AssertionFailure() << "a vertex " << nearest << " from the other polytope's";
    }
  }
  return ::testing::AssertionSuccess();
}

// The hull of a sphere cut by a few random planes: a carried part after cuts, with short edges and
// vertices where a plane passed near a corner.
ConvexPolytope cutBall(testing::SeededRandom& rng, int planes) {
  ConvexPolytope p = polytopeOfPoints(primitives::uvSphere(0.5f, 12, 8).positions);
  for (int k = 0; k < planes && !p.empty(); ++k) {
    glm::dvec3 n(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    if (glm::length(n) < 1e-3) continue;
    const ConvexPolytope next = clipPolytope(p, glm::normalize(n), rng.uniform(0.05, 0.4), 1e-10);
    if (!next.empty()) p = next;
  }
  return p;
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

TEST(ConvexPolytope, ShrinkSplitsAnApexWhoseMovedFacesNoLongerMeetInOnePoint) {
  // A pyramid over a 2 x 1 rectangle: four faces meet at the apex; moved inwards they meet along a
  // ridge, so the apex becomes two vertices. A square pyramid keeps one apex (its normals lie on a cone).
  const std::vector<glm::vec3> rectangle = {{-1, 0, -0.5f}, {1, 0, -0.5f}, {1, 0, 0.5f}, {-1, 0, 0.5f}, {0, 1, 0}};
  const ConvexPolytope pyramid = polytopeOfPoints(rectangle);
  ASSERT_EQ(pyramid.faces.size(), 5u);
  const ConvexPolytope ridge = shrinkPolytope(pyramid, 0.05);
  EXPECT_EQ(ridge.vertices.size(), 6u);
  EXPECT_TRUE(convexAndOriented(ridge, 1e-12));
  EXPECT_TRUE(sameVertices(ridge, shrunkByClips(pyramid, 0.05), 1e-12));
  EXPECT_NEAR(polytopeVolume(ridge), polytopeVolume(shrunkByClips(pyramid, 0.05)), 1e-14);
  const std::vector<glm::vec3> square = {{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}, {0, 1, 0}};
  const ConvexPolytope apex = shrinkPolytope(polytopeOfPoints(square), 0.05);
  EXPECT_EQ(apex.vertices.size(), 5u);
  EXPECT_TRUE(sameVertices(apex, shrunkByClips(polytopeOfPoints(square), 0.05), 1e-12));
}

TEST(ConvexPolytope, ShrinkMergesSplitPointsOfFacesWhoseNormalsShareACircle) {
  // A pyramid whose apex is met by six faces: four lean equally (their normals on one circle about
  // the axis), two lean further out. Moved inwards, the apex splits in four by the Delaunay of the
  // normals, two of them the same point (the four equal faces still meet there): one vertex.
  ConvexPolytope p = unitBox(glm::vec3(4.f));
  p = clipPolytope(p, glm::dvec3(0, -1, 0), 0.0, 1e-12);
  const double pi = 3.14159265358979323846;
  const double lean[6] = {1.0, 1.0, 1.0, 1.0, 0.7, 0.7};
  for (int k = 0; k < 6; ++k) {
    const double a = pi / 3.0 * k;
    const glm::dvec3 n(std::cos(a), lean[k], std::sin(a));  // through the apex (0, 1, 0) and a base line
    p = clipPolytope(p, n, lean[k], 1e-12);
  }
  ASSERT_EQ(p.faces.size(), 7u);
  const ConvexPolytope shrunk = shrinkPolytope(p, 0.02);
  const ConvexPolytope clips = shrunkByClips(p, 0.02);
  ASSERT_FALSE(shrunk.empty());
  EXPECT_TRUE(convexAndOriented(shrunk, 1e-12));
  EXPECT_TRUE(closedOnLoops(shrunk));
  EXPECT_TRUE(sameVertices(shrunk, clips, 1e-9));
  EXPECT_NEAR(polytopeVolume(shrunk), polytopeVolume(clips), 1e-12);
}

TEST(ConvexPolytope, ShrinkFollowsFacesThatVanishOnTheWay) {
  // An octahedron whose apex is a short ridge (0.02 long, along x): at a small margin the ridge and
  // its two thin faces stay; at 0.05 its edges shrink to nothing on the way, the thin faces vanish
  // and the four faces around meet in one apex on the axis, as clipping by every moved face gives.
  const std::vector<glm::vec3> ridged = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1},
                                         {-0.01f, 0, 1}, {0.01f, 0, 1}};
  const ConvexPolytope roof = polytopeOfPoints(ridged);
  ASSERT_EQ(roof.faces.size(), 10u);
  EXPECT_EQ(shrinkPolytope(roof, 0.001).faces.size(), 10u);
  const ConvexPolytope apex = shrinkPolytope(roof, 0.05);
  const ConvexPolytope clipped = shrunkByClips(roof, 0.05);
  ASSERT_FALSE(apex.empty());
  EXPECT_EQ(apex.faces.size(), 8u);
  EXPECT_EQ(apex.vertices.size(), 6u);
  EXPECT_TRUE(convexAndOriented(apex, 1e-12));
  EXPECT_TRUE(closedOnLoops(apex));
  EXPECT_TRUE(sameVertices(apex, clipped, 1e-12));
  EXPECT_NEAR(polytopeVolume(apex), polytopeVolume(clipped), 1e-14);
  glm::dvec3 lo, hi;
  polytopeBounds(apex, lo, hi);
  for (const glm::dvec3& v : apex.vertices)
    if (v.z > hi.z - 1e-9) {
      EXPECT_LT(std::abs(v.x) + std::abs(v.y), 1e-12);
    }
  // A unit box with one edge bevelled 0.014 wide: moved in by 0.02, the bevel face vanishes and the
  // box shrinks as if it had none.
  const ConvexPolytope bevelled =
      clipPolytope(unitBox(), glm::normalize(glm::dvec3(1, 1, 0)), 0.99 / std::sqrt(2.0), 1e-9);
  ASSERT_EQ(bevelled.faces.size(), 7u);
  const ConvexPolytope box = shrinkPolytope(bevelled, 0.02);
  EXPECT_EQ(box.faces.size(), 6u);
  EXPECT_EQ(box.vertices.size(), 8u);
  EXPECT_NEAR(polytopeVolume(box), 0.96 * 0.96 * 0.96, 1e-12);
  EXPECT_TRUE(sameVertices(box, shrunkByClips(bevelled, 0.02), 1e-12));
}

TEST(ConvexPolytope, ShrinkIsTheInnerParallelBodyOnCutPartsAndSpheres) {
  // Small margins keep every face (vertices move, some split); large ones make short edges turn over
  // and faces vanish. The shrunk polytope is closed and convex, every face on a moved face plane of
  // the part and every vertex below all of them: so it is exactly the part's inner parallel body.
  testing::SeededRandom rng(23);
  size_t compared = 0, vanished = 0;
  for (int k = 0; k < 120; ++k) {
    const ConvexPolytope part = k % 10 == 0 ? polytopeOfPoints(primitives::uvSphere(0.5f, 16, 8).positions)
                                            : cutBall(rng, 1 + k % 7);
    ASSERT_FALSE(part.empty());
    const double margin = std::array<double, 4>{0.002, 0.01, 0.03, 0.08}[size_t(k) % 4];
    const ConvexPolytope shrunk = shrinkPolytope(part, margin);
    const ConvexPolytope clips = shrunkByClips(part, margin);
    ASSERT_EQ(shrunk.empty(), clips.empty()) << "part " << k;
    if (shrunk.empty()) continue;
    ASSERT_TRUE(convexAndOriented(shrunk, 1e-8)) << "part " << k;
    for (const auto& face : shrunk.faces) {
      bool moved = false;
      for (const auto& f : part.faces)
        moved |= glm::length(f.normal - face.normal) < 1e-12 && std::abs(f.offset - margin - face.offset) < 1e-12;
      ASSERT_TRUE(moved) << "part " << k << ": a face not on a moved plane of the part";
    }
    for (const auto& f : part.faces)
      for (const glm::dvec3& v : shrunk.vertices) ASSERT_LE(glm::dot(f.normal, v) - f.offset, -margin + 1e-8);
    ASSERT_TRUE(closedOnLoops(shrunk)) << "part " << k;
    ASSERT_TRUE(closedOnLoops(clips)) << "part " << k;
    ASSERT_NEAR(polytopeVolume(shrunk), polytopeVolume(clips), 1e-9 * polytopeVolume(part)) << "part " << k;
    ++compared;
    vanished += shrunk.faces.size() < part.faces.size();
    ASSERT_EQ(shrinkPolytope(part, margin).vertices, shrunk.vertices);  // deterministic
  }
  std::printf("[ checked  ] shrink against one clip per face: %zu parts, all closed, %zu lost faces\n", compared,
              vanished);
  EXPECT_GT(compared, 90u);
  EXPECT_GT(vanished, 10u);
}

TEST(ConvexPolytope, ClipByManyPlanesIsTheSolidOfTheOnePlaneClipsInTurn) {
  const ConvexPolytope ball = polytopeOfPoints(primitives::uvSphere(0.5f, 24, 12).positions);
  testing::SeededRandom rng(31);
  size_t emptied = 0;
  for (int k = 0; k < 100; ++k) {
    std::vector<HalfSpace> planes;
    for (int j = 0; j < 2 + k % 14; ++j) {
      glm::dvec3 n(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
      if (glm::length(n) < 1e-3) continue;
      // Not unit length on purpose; one in five through a vertex of the ball.
      const double d = j % 5 == 0 ? glm::dot(n, ball.vertices[size_t(k + j) % ball.vertices.size()])
                                  : rng.uniform(0.0, 0.5) * glm::length(n);
      planes.push_back({n, d});
    }
    ConvexPolytope one = ball;
    for (const HalfSpace& h : planes) {
      one = clipPolytope(one, h.normal, h.offset, 1e-10);
      if (one.empty()) break;
    }
    ConvexPolytope many;
    clipPolytope(ball, planes, 1e-10, many);
    ASSERT_EQ(many.empty(), one.empty()) << "set " << k;
    if (many.empty()) {
      ++emptied;
      continue;
    }
    EXPECT_EQ(many.faces.size(), one.faces.size()) << "set " << k;
    ASSERT_TRUE(closedOnLoops(many)) << "set " << k;
    ASSERT_TRUE(sameVertices(many, one, 1e-12)) << "set " << k;
    ASSERT_NEAR(polytopeVolume(many), polytopeVolume(one), 1e-12) << "set " << k;
    ASSERT_TRUE(convexAndOriented(many, 1e-8)) << "set " << k;
  }
  EXPECT_GT(emptied, 0u);
  EXPECT_LT(emptied, 50u);
  ConvexPolytope out = unitBox();
  clipPolytope(ball, std::vector<HalfSpace>{{glm::dvec3(0.0), 1.0}}, 1e-10, out);
  EXPECT_TRUE(out.empty());  // a zero normal: nothing, and `out` replaced
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
      ASSERT_TRUE(closedOnLoops(below)) << "plane " << k;
    }
    if (!above.empty()) {
      ASSERT_TRUE(convexAndOriented(above, 1e-8)) << "plane " << k;
      ASSERT_TRUE(closedOnLoops(above)) << "plane " << k;
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
