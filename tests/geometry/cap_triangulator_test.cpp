// SPDX-License-Identifier: MIT
// CapTriangulator::triangulateFace: the polygon faces of mesh files. The concave faces here come
// from CGAL's data set. Fanned from their first corner, as the readers of engine/assets do, they
// fold: the mesh intersects itself (CGAL's self-intersection test finds 152 crossing triangle pairs
// in mpi.off as read, 12 in corner_poly.off, none once the faces are ear-clipped), and every corpus
// cut of mpi.off is refused with TriangulationFailed because its section overlaps itself.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <utility>
#include <vector>

#include "cleave/geometry/cap_triangulator.h"

namespace cleave::geometry {
namespace {

glm::dvec3 newellNormal(const std::vector<glm::vec3>& corners) {
  glm::dvec3 n(0.0);
  for (size_t k = 0; k < corners.size(); ++k) {
    n += glm::cross(glm::dvec3(corners[k]), glm::dvec3(corners[(k + 1) % corners.size()]));
  }
  return n;  // twice the vector area
}

double twiceArea(const std::vector<glm::vec3>& c, const glm::dvec3& unitNormal, uint32_t a,
                 uint32_t b, uint32_t d) {
  return glm::dot(
      glm::cross(glm::dvec3(c[b]) - glm::dvec3(c[a]), glm::dvec3(c[d]) - glm::dvec3(c[a])),
      unitNormal);
}

// No fold: every triangle turns like the face (positive area along its normal), the areas add up to
// the face's, and each face edge is an edge of one triangle, in the face's direction.
::testing::AssertionResult unfolded(const std::vector<glm::vec3>& corners,
                                    const std::vector<uint32_t>& triangles) {
  const uint32_t n = static_cast<uint32_t>(corners.size());
  if (triangles.size() != 3 * size_t(n - 2)) {
    return ::testing::AssertionFailure()
           << triangles.size() / 3 << " triangles for " << n << " corners";
  }
  const glm::dvec3 area2 = newellNormal(corners);
  const glm::dvec3 normal = glm::normalize(area2);
  double sum = 0.0;
  std::set<std::pair<uint32_t, uint32_t>> edges;
  for (size_t t = 0; t < triangles.size(); t += 3) {
    const double twice =
        twiceArea(corners, normal, triangles[t], triangles[t + 1], triangles[t + 2]);
    if (!(twice > 0.0)) {
      return ::testing::AssertionFailure()
             << "triangle " << t / 3 << " is inverted or flat (" << twice << ")";
    }
    sum += twice;
    for (int e = 0; e < 3; ++e) edges.insert({triangles[t + e], triangles[t + (e + 1) % 3]});
  }
  if (std::abs(sum - glm::length(area2)) > 1e-9 * glm::length(area2)) {
    return ::testing::AssertionFailure()
           << "triangle areas sum to " << sum / 2 << ", face area " << glm::length(area2) / 2;
  }
  for (uint32_t k = 0; k < n; ++k) {
    if (!edges.count({k, (k + 1) % n})) {
      return ::testing::AssertionFailure() << "face edge " << k << " missing";
    }
  }
  return ::testing::AssertionSuccess();
}

std::vector<uint32_t> fanOf(uint32_t n) {
  std::vector<uint32_t> fan;
  for (uint32_t k = 1; k + 1 < n; ++k) fan.insert(fan.end(), {0u, k, k + 1});
  return fan;
}

// corner_poly.off, face "6 8 6 10 2 1 0": an L in the plane z = 1 whose first corner is the end of
// the short arm, which does not see the far corner: the fan's first triangle is inverted.
const std::vector<glm::vec3> kCornerPolyFace = {{0, 1, 1}, {1, 1, 1}, {1, 0, 1},
                                                {2, 0, 1}, {2, 2, 1}, {0, 2, 1}};

// mpi.off, face "9 0 19 70 80 68 1 74 85 35": concave, and not quite planar (corners up to 4e-5
// off its plane, the file's rounding): two fan triangles are inverted.
const std::vector<glm::vec3> kMpiFace = {
    {-10.0402f, -10.0402f, -10.0402f},   {-9.99992f, -9.99992f, 10.0401f},
    {-9.99994f, -6.01721f, 10.0321f},    {-10.014f, 0.f, 3.01203f},
    {-9.99998f, 5.99657f, 10.008f},      {-10.f, 10.f, 10.f},
    {-10.0219f, -0.926781f, -0.926781f}, {-10.01f, -6.02406f, 5.02005f},
    {-10.0321f, -6.02409f, -6.02409f}};

TEST(CapTriangulatorFace, ConcaveFacesOfCgalFilesDoNotFold) {
  for (const std::vector<glm::vec3>* face : {&kCornerPolyFace, &kMpiFace}) {
    // The case is meaningful: the fan from the first corner folds.
    EXPECT_FALSE(unfolded(*face, fanOf(static_cast<uint32_t>(face->size()))));
    CapTriangulator triangulator;
    std::vector<uint32_t> triangles;
    EXPECT_TRUE(triangulator.triangulateFace(*face, triangles));
    EXPECT_TRUE(unfolded(*face, triangles));
  }
}

TEST(CapTriangulatorFace, ConvexFacesAreFannedAsBefore) {
  CapTriangulator triangulator;
  const std::vector<glm::vec3> quad = {{0, 0, 0}, {1, 0, 0}, {1.2f, 1, 0.1f}, {0, 1, 0}};
  const std::vector<glm::vec3> hexagon = {{1, 0, 0},  {0.5f, 0.866f, 0},   {-0.5f, 0.866f, 0},
                                          {-1, 0, 0}, {-0.5f, -0.866f, 0}, {0.5f, -0.866f, 0}};
  const std::vector<glm::vec3> triangle = {{0, 0, 0}, {0, 0, 1}, {0, 1, 0}};
  for (const std::vector<glm::vec3>* face : {&quad, &hexagon, &triangle}) {
    std::vector<uint32_t> triangles = {7, 8, 9};  // earlier output is kept
    EXPECT_TRUE(triangulator.triangulateFace(*face, triangles));
    std::vector<uint32_t> expected = {7, 8, 9};
    const std::vector<uint32_t> fan = fanOf(static_cast<uint32_t>(face->size()));
    expected.insert(expected.end(), fan.begin(), fan.end());
    EXPECT_EQ(triangles, expected);
  }
  // Clockwise seen from +z is counter-clockwise seen from -z: still convex, still the fan.
  std::vector<glm::vec3> reversed(quad.rbegin(), quad.rend());
  std::vector<uint32_t> triangles;
  EXPECT_TRUE(triangulator.triangulateFace(reversed, triangles));
  EXPECT_EQ(triangles, fanOf(4));
}

TEST(CapTriangulatorFace, CollinearCornersAreKeptWithoutFlatTriangles) {
  // A square with an extra corner on two of its sides, one of them next to the corner the fan
  // starts from: the fan makes the flat triangle (0, 1, 2); ear clipping fans each collinear corner
  // from across the square instead.
  const std::vector<glm::vec3> face = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0},
                                       {2, 1, 0}, {2, 2, 0}, {0, 2, 0}};
  EXPECT_FALSE(unfolded(face, fanOf(6)));
  CapTriangulator triangulator;
  std::vector<uint32_t> triangles;
  EXPECT_TRUE(triangulator.triangulateFace(face, triangles));
  EXPECT_TRUE(unfolded(face, triangles));
}

TEST(CapTriangulatorFace, FacesThatCrossThemselvesOrHaveNoAreaGetTheFan) {
  CapTriangulator triangulator;
  const std::vector<glm::vec3> bowTie = {{0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<glm::vec3> flat = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  // A pentagram: every corner turns the same way but the outline winds twice.
  std::vector<glm::vec3> star;
  for (int k = 0; k < 5; ++k) {
    const double angle = 2.0 * 3.14159265358979323846 * (2 * k) / 5.0;
    star.emplace_back(float(std::cos(angle)), float(std::sin(angle)), 0.f);
  }
  const std::vector<glm::vec3>* faces[] = {&bowTie, &flat, &star};
  for (const std::vector<glm::vec3>* face : faces) {
    std::vector<uint32_t> triangles;
    EXPECT_FALSE(triangulator.triangulateFace(*face, triangles));
    EXPECT_EQ(triangles, fanOf(static_cast<uint32_t>(face->size())));
  }
}

}  // namespace
}  // namespace cleave::geometry
