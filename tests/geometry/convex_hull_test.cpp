// SPDX-License-Identifier: MIT
// Convex hulls: exact small cases, containment and convexity on random clouds, degenerate inputs,
// determinism; and the convexity test the physics layer uses to pick a collider.
#include "cleave/geometry/convex_hull.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "cleave/geometry/mass_properties.h"
#include "cleave/geometry/primitives.h"
#include "tests/geometry/test_meshes.h"

namespace cleave::geometry {
namespace {

namespace prim = primitives;

double hullVolume(const ConvexHull& h) { return testing::signedVolume(h.positions, h.indices); }

// Every point at most `tol` above every hull face, and every hull edge convex.
void expectContainsAndConvex(const ConvexHull& h, std::span<const glm::dvec3> points, double tol) {
  ASSERT_EQ(h.status, HullStatus::Ok) << h.message;
  EXPECT_TRUE(testing::closedAndOriented(h.positions, h.indices, 0.0));
  for (size_t t = 0; t < h.indices.size(); t += 3) {
    const glm::dvec3 a = h.positions[h.indices[t]];
    const glm::dvec3 n = glm::normalize(glm::cross(h.positions[h.indices[t + 1]] - a, h.positions[h.indices[t + 2]] - a));
    double worst = -INFINITY;
    for (const glm::dvec3& p : points) worst = std::max(worst, glm::dot(n, p - a));
    ASSERT_LE(worst, tol) << "a point lies above hull face " << t / 3;
    for (const glm::dvec3& p : h.positions) ASSERT_LE(glm::dot(n, p - a), tol) << "reflex hull at face " << t / 3;
  }
}

TEST(ConvexHull, CubeWithInteriorFaceAndDuplicatePointsIsTheCube) {
  std::vector<glm::dvec3> pts;
  testing::SeededRandom rng(7);
  for (int k = 0; k < 200; ++k) pts.push_back({rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)});
  for (int x = -1; x <= 1; x += 2) {
    for (int y = -1; y <= 1; y += 2) {
      for (int z = -1; z <= 1; z += 2) {
        pts.push_back({x, y, z});
        pts.push_back({x, y, z});  // duplicate
      }
    }
  }
  for (int k = 0; k < 50; ++k) pts.push_back({1.0, rng.uniform(-1, 1), rng.uniform(-1, 1)});  // on a face
  for (int k = 0; k < 20; ++k) pts.push_back({rng.uniform(-1, 1), -1.0, -1.0});             // on an edge
  ConvexHull h = computeConvexHull(std::span<const glm::dvec3>(pts));
  ASSERT_EQ(h.status, HullStatus::Ok) << h.message;
  EXPECT_EQ(h.positions.size(), 8u);
  EXPECT_EQ(h.indices.size(), 36u);
  EXPECT_NEAR(hullVolume(h), 8.0, 1e-12);
  for (size_t i = 0; i < h.positions.size(); ++i) EXPECT_EQ(pts[h.sourceIndices[i]], h.positions[i]);
  expectContainsAndConvex(h, pts, 1e-12);
}

TEST(ConvexHull, SphereVerticesAreAllHullVertices) {
  MeshData sphere = prim::uvSphere(1.f, 32, 16);
  ConvexHull h = computeConvexHull(std::span<const glm::vec3>(sphere.positions));
  ASSERT_EQ(h.status, HullStatus::Ok) << h.message;
  EXPECT_EQ(h.positions.size(), 32u * 15u + 2u);  // distinct positions: rings plus two poles
  EXPECT_NEAR(hullVolume(h), computeMassProperties(sphere).volume, 1e-6);
  // Float positions are convex only up to rounding; the hull is convex within a few tolerances.
  std::vector<glm::dvec3> pts(sphere.positions.begin(), sphere.positions.end());
  expectContainsAndConvex(h, pts, 1e-8);
}

TEST(ConvexHull, RandomCloudIsContainedAndConvex) {
  testing::SeededRandom rng(12345);
  std::vector<glm::dvec3> pts;
  for (int k = 0; k < 3000; ++k) pts.push_back(rng.unitVector() * std::cbrt(rng.uniform()) * 5.0 + glm::dvec3(100, -40, 7));
  ConvexHull h = computeConvexHull(std::span<const glm::dvec3>(pts));
  EXPECT_GT(hullVolume(h), 0.0);
  expectContainsAndConvex(h, pts, 1e-9);
}

TEST(ConvexHull, PointsOnASphereSurfaceAllSurvive) {
  testing::SeededRandom rng(99);
  std::vector<glm::dvec3> pts;
  for (int k = 0; k < 1000; ++k) pts.push_back(rng.unitVector());
  ConvexHull h = computeConvexHull(std::span<const glm::dvec3>(pts));
  ASSERT_EQ(h.status, HullStatus::Ok);
  EXPECT_EQ(h.positions.size(), 1000u);
  EXPECT_EQ(h.indices.size(), 3u * (2u * 1000u - 4u));  // Euler: F = 2V - 4 for a triangulated sphere
  expectContainsAndConvex(h, pts, 1e-12);
}

TEST(ConvexHull, GridOnCubeFacesKeepsOnlyCorners) {
  std::vector<glm::dvec3> pts;
  for (int a = 0; a <= 6; ++a) {
    for (int b = 0; b <= 6; ++b) {
      const double u = a / 3.0 - 1.0, v = b / 3.0 - 1.0;
      for (double s : {-1.0, 1.0}) {
        pts.push_back({s, u, v});
        pts.push_back({u, s, v});
        pts.push_back({u, v, s});
      }
    }
  }
  ConvexHull h = computeConvexHull(std::span<const glm::dvec3>(pts));
  ASSERT_EQ(h.status, HullStatus::Ok) << h.message;
  EXPECT_EQ(h.positions.size(), 8u);
  EXPECT_NEAR(hullVolume(h), 8.0, 1e-12);
}

TEST(ConvexHull, DegenerateInputsReturnAStatus) {
  std::vector<glm::dvec3> three = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_EQ(computeConvexHull(std::span<const glm::dvec3>(three)).status, HullStatus::TooFewPoints);
  std::vector<glm::dvec3> same(10, glm::dvec3(1, 2, 3));
  EXPECT_EQ(computeConvexHull(std::span<const glm::dvec3>(same)).status, HullStatus::TooFewPoints);
  std::vector<glm::dvec3> line;
  for (int k = 0; k < 10; ++k) line.push_back(glm::dvec3(1, 2, 3) * double(k));
  ConvexHull l = computeConvexHull(std::span<const glm::dvec3>(line));
  EXPECT_EQ(l.status, HullStatus::Collinear);
  EXPECT_FALSE(l.message.empty());
  EXPECT_TRUE(l.indices.empty());
  std::vector<glm::dvec3> flat;
  for (int a = 0; a < 5; ++a) {
    for (int b = 0; b < 5; ++b) flat.push_back({a, b, 0.5 * a - 0.25 * b});
  }
  EXPECT_EQ(computeConvexHull(std::span<const glm::dvec3>(flat)).status, HullStatus::Coplanar);
  std::vector<glm::dvec3> nan = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, NAN}};
  EXPECT_EQ(computeConvexHull(std::span<const glm::dvec3>(nan)).status, HullStatus::InvalidInput);
  EXPECT_STREQ(toString(HullStatus::Coplanar), "Coplanar");
}

TEST(ConvexHull, OutputIsDeterministic) {
  MeshData torus = prim::torus(1.f, 0.4f, 40, 20);
  ConvexHull a = computeConvexHull(std::span<const glm::vec3>(torus.positions));
  ConvexHull b = computeConvexHull(std::span<const glm::vec3>(torus.positions));
  ASSERT_EQ(a.status, HullStatus::Ok);
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.indices, b.indices);
  MeshData mesh = toMeshData(a);
  EXPECT_EQ(mesh.positions.size(), a.positions.size());
  EXPECT_TRUE(isClosedAndOriented(mesh.positions, mesh.indices));
}

TEST(IsConvex, ConvexPrimitivesAreConvex) {
  EXPECT_TRUE(isConvex(prim::uvSphere(1.f, 32, 16)));
  EXPECT_TRUE(isConvex(prim::box(glm::vec3(1.f, 2.f, 3.f))));
  EXPECT_TRUE(isConvex(prim::ellipsoid(glm::vec3(1.f, 0.3f, 2.f), 24, 12)));
  EXPECT_TRUE(isConvex(prim::cylinder(0.5f, 2.f, 24)));
  EXPECT_TRUE(isConvex(prim::capsule(0.5f, 1.f, 24, 12)));
  EXPECT_TRUE(isConvex(prim::tetrahedron(1.f)));
  MeshData mirrored = prim::box(glm::vec3(1.f));
  prim::transform(mirrored, glm::scale(glm::mat4(1.f), glm::vec3(-1.f, 0.5f, 2.f)));
  EXPECT_TRUE(isConvex(mirrored));
}

TEST(IsConvex, ConcaveAndCompoundShapesAreNot) {
  EXPECT_FALSE(isConvex(prim::torus(1.f, 0.25f, 32, 12)));
  EXPECT_FALSE(isConvex(prim::combPrism(4)));
  EXPECT_FALSE(isConvex(prim::starPrism(5)));
  EXPECT_FALSE(isConvex(prim::twoDisjointSpheres(0.5f, 0.1f, 16, 8)));
  EXPECT_FALSE(isConvex(prim::hollowSphere(1.f, 0.5f, 16, 8)));
}

TEST(IsConvex, OneDentedVertexMakesASphereConcave) {
  MeshData sphere = prim::uvSphere(1.f, 32, 16);
  const uint32_t vertex = 8 * 33 + 5;  // ring 8 (the equator), away from the seam
  sphere.positions[vertex] *= 0.9f;
  EXPECT_FALSE(isConvex(sphere));
}

TEST(IsConvex, OpenOrEmptyMeshesAreNot) {
  MeshData box = prim::box(glm::vec3(1.f));
  box.indices.resize(box.indices.size() - 3);
  EXPECT_FALSE(isConvex(box));
  EXPECT_FALSE(isConvex(MeshData{}));
}

}  // namespace
}  // namespace cleave::geometry
