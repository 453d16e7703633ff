// SPDX-License-Identifier: MIT
// Carried collider parts: the decomposition of concave meshes, the clip of parts into the pieces of
// a split (each part in the island that holds it, every piece with parts), and the fit of the
// clipped parts to the pieces they stand for.
#include "cleave/geometry/collider_parts.h"

#include <gtest/gtest.h>

#include <cstdio>

#include <glm/gtc/matrix_transform.hpp>

#include "cleave/geometry/mass_properties.h"
#include "cleave/geometry/primitives.h"

namespace cleave::geometry {
namespace {

struct Cut {
  SplitResult result;
  std::vector<ColliderPartSet> parts;
};

// The decomposition of `mesh` with a splitter of its own.
ColliderPartSet partsOf(const MeshData& mesh) {
  auto splitter = makeConcaveSplitter();
  return decomposeConvex(mesh, *splitter);
}

Cut cutWithParts(const MeshData& mesh, const ColliderPartSet& parts, const Plane& plane) {
  Cut c;
  MeshContainer container;
  EXPECT_EQ(container.setMesh(mesh).code, SplitStatus::Ok);
  auto splitter = makeConcaveSplitter();
  EXPECT_EQ(splitter->split(container, plane, SplitOptions{}, c.result), SplitStatus::Ok) << c.result.message;
  clipPartsToPieces(parts, plane, c.result, {}, c.parts);
  return c;
}

TEST(ColliderParts, ConvexMeshIsOnePartAndTorusSeveral) {
  auto splitter = makeConcaveSplitter();
  const MeshData ball = primitives::uvSphere(0.5f, 24, 12);
  EXPECT_TRUE(isConvex(ball, kPartConvexTolerance));
  EXPECT_EQ(decomposeConvex(ball, *splitter).size(), 1u);
  const MeshData ring = primitives::torus(0.5f, 0.15f, 48, 24);
  EXPECT_FALSE(isConvex(ring, kPartConvexTolerance));
  const ColliderPartSet parts = decomposeConvex(ring, *splitter);
  EXPECT_GE(parts.size(), 8u);
  for (const ConvexPolytope& p : parts) EXPECT_LE(p.vertices.size(), kMaxPartVertices);
  const double volume = computeMassProperties(ring).volume;
  const double fit = partsVolume(parts) / volume;
  std::printf("[parts] torus: %zu parts, collider volume / mesh volume %.3f\n", parts.size(), fit);
  EXPECT_GT(fit, 0.9);
  EXPECT_LT(fit, 1.5);
}

TEST(ColliderParts, BoxPartsClipToExactlyThePieces) {
  const MeshData box = primitives::box(glm::vec3(0.5f, 0.3f, 0.2f));
  const ColliderPartSet parts = partsOf(box);
  ASSERT_EQ(parts.size(), 1u);
  const Cut c = cutWithParts(box, parts, Plane{glm::dvec3(1, 0.2, 0), 0.1});
  ASSERT_EQ(c.result.pieces.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    ASSERT_EQ(c.parts[i].size(), 1u);
    EXPECT_NEAR(partsVolume(c.parts[i]), c.result.pieces[i].mass.volume, 1e-9) << "piece " << i;
  }
}

TEST(ColliderParts, TorusHalvesKeepTheirPartsAndFitWithinOneAndAHalf) {
  const MeshData ring = primitives::torus(0.5f, 0.15f, 48, 24);
  const ColliderPartSet parts = partsOf(ring);
  for (const Plane& plane : {Plane{glm::dvec3(1, 0, 0), 0.0}, Plane{glm::dvec3(0, 1, 0), 0.02},
                             Plane{glm::dvec3(0.3, 0.2, 1), 0.1}}) {
    const Cut c = cutWithParts(ring, parts, plane);
    ASSERT_GE(c.result.pieces.size(), 2u);
    for (size_t i = 0; i < c.result.pieces.size(); ++i) {
      ASSERT_FALSE(c.parts[i].empty()) << "piece " << i << " got no part";
      const double fit = partsVolume(c.parts[i]) / c.result.pieces[i].mass.volume;
      EXPECT_GT(fit, 0.85) << "piece " << i;
      EXPECT_LT(fit, 1.5) << "piece " << i;
      // Each part lies on its piece's side of the plane.
      const double side = double(c.result.pieces[i].side);
      for (const ConvexPolytope& part : c.parts[i])
        for (const glm::dvec3& v : part.vertices)
          ASSERT_GE(side * (glm::dot(glm::normalize(plane.normal), v) - plane.offset / glm::length(plane.normal)), -1e-9);
    }
  }
}

TEST(ColliderParts, IslandsOfOneSideEachGetTheirOwnParts) {
  // Two spheres side by side: decomposed into one part each, cut across both, four islands.
  const MeshData pair = primitives::twoDisjointSpheres(0.4f, 0.3f, 24, 12);
  const ColliderPartSet parts = partsOf(pair);
  ASSERT_EQ(parts.size(), 2u);
  const Cut c = cutWithParts(pair, parts, Plane{glm::dvec3(0.1, 1, 0.05), 0.1});
  ASSERT_EQ(c.result.pieces.size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    ASSERT_EQ(c.parts[i].size(), 1u) << "piece " << i;
    const double fit = partsVolume(c.parts[i]) / c.result.pieces[i].mass.volume;
    // Parts keep at most kMaxPartVertices of a sphere's hull: they lie inside it, about 10% smaller.
    EXPECT_GT(fit, 0.85) << "piece " << i;
    EXPECT_LT(fit, 1.0) << "piece " << i;
    // The part sits in its own island: its centroid is nearer that piece's centre than any other's.
    const glm::dvec3 centre = polytopeCentroid(c.parts[i][0]);
    for (size_t j = 0; j < 4; ++j) {
      if (j == i) continue;
      EXPECT_LT(glm::length(centre - c.result.pieces[i].mass.centerOfMass),
                glm::length(centre - c.result.pieces[j].mass.centerOfMass));
    }
  }
}

}  // namespace
}  // namespace cleave::geometry
