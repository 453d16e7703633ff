// SPDX-License-Identifier: MIT
// Island contacts (island_contacts.h) and IslandMode::Touching in the splitter: multi-part art stays
// one piece per side unless the cut really separates it. Exact small cases: parts that pass into
// one another, lie flush, hold one another, or stand apart, cut in both island modes.
#include <gtest/gtest.h>

#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "cleave/geometry/island_contacts.h"
#include "cleave/geometry/mesh_splitter.h"
#include "cleave/geometry/primitives.h"
#include "tests/geometry/test_meshes.h"

namespace cleave::geometry {
namespace {

namespace prim = primitives;

TEST(IslandContactPredicates, SegmentsCrossTrianglesExactly) {
  const glm::dvec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_TRUE(segmentCrossesTriangle({0.2, 0.2, -1}, {0.2, 0.2, 1}, a, b, c));
  EXPECT_TRUE(segmentCrossesTriangle({0.2, 0.2, 0}, {0.2, 0.2, 1}, a, b, c));  // touching at an end
  EXPECT_FALSE(segmentCrossesTriangle({0.2, 0.2, 0.1}, {0.2, 0.2, 1}, a, b, c));  // above it
  EXPECT_FALSE(segmentCrossesTriangle({0.8, 0.8, -1}, {0.8, 0.8, 1}, a, b, c));   // beside it
  EXPECT_FALSE(segmentCrossesTriangle({-1, 0.2, 0}, {2, 0.2, 0}, a, b, c));      // in its plane: not here
}

TEST(IslandContactPredicates, PointTriangleDistanceInEveryRegion) {
  const glm::dvec3 a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  EXPECT_DOUBLE_EQ(pointTriangleDistance2({0.5, 0.5, 3}, a, b, c), 9.0);    // over the face
  EXPECT_DOUBLE_EQ(pointTriangleDistance2({-1, -1, 0}, a, b, c), 2.0);      // corner a
  EXPECT_DOUBLE_EQ(pointTriangleDistance2({3, -1, 0}, a, b, c), 2.0);       // corner b
  EXPECT_DOUBLE_EQ(pointTriangleDistance2({1, -2, 0}, a, b, c), 4.0);       // edge ab
  EXPECT_DOUBLE_EQ(pointTriangleDistance2({2, 2, 0}, a, b, c), 2.0);        // edge bc
  EXPECT_DOUBLE_EQ(pointTriangleDistance2({0.5, 0.5, 0}, a, b, c), 0.0);    // on it
}

MeshData boxAt(const glm::vec3& half, const glm::vec3& centre) {
  MeshData m = prim::box(half);
  prim::transform(m, glm::translate(glm::mat4(1.f), centre));
  return m;
}

struct Counts {
  int above = 0, below = 0;
  double volume = 0.0;
};

Counts cut(const MeshData& mesh, const Plane& plane, IslandMode mode, SplitResult* out = nullptr) {
  SplitOptions options;
  options.islands = mode;
  SplitResult result = splitMesh(mesh, glm::mat4(1.f), plane, options);
  EXPECT_EQ(result.status, SplitStatus::Ok) << result.message;
  Counts counts;
  for (const SplitPiece& piece : result.pieces) {
    ++(piece.side > 0 ? counts.above : counts.below);
    counts.volume += piece.mass.volume;
    EXPECT_TRUE(piece.reached || mode == IslandMode::Connected);
  }
  if (out) *out = std::move(result);
  return counts;
}

const Plane kMiddle{{0.0, 1.0, 0.0}, 0.05};

TEST(IslandsTouching, PartsThatPassIntoOneAnotherStayOnePiecePerSide) {
  const MeshData mesh = prim::merge(boxAt({0.5f, 0.5f, 0.5f}, {0, 0, 0}), boxAt({0.3f, 0.3f, 0.3f}, {0.6f, 0.1f, 0}));
  const Counts touching = cut(mesh, kMiddle, IslandMode::Touching);
  EXPECT_EQ(touching.above, 1);
  EXPECT_EQ(touching.below, 1);
  const Counts connected = cut(mesh, kMiddle, IslandMode::Connected);
  EXPECT_EQ(connected.above, 2);
  EXPECT_EQ(connected.below, 2);
  // Mass is the parts' sum in either mode (their common volume counts twice, as in the whole).
  EXPECT_NEAR(touching.volume, 1.0 + 0.216, 1e-6);  // float corners
  EXPECT_NEAR(connected.volume, touching.volume, 1e-12);
}

// A unit box at the origin and a second box; the pieces per side a cut through both gives.
::testing::AssertionResult piecesOfTwoBoxes(const glm::vec3& half, const glm::vec3& centre, IslandMode mode,
                                            int above, int below) {
  const MeshData mesh = prim::merge(boxAt({0.5f, 0.5f, 0.5f}, {0, 0, 0}), boxAt(half, centre));
  const Counts counts = cut(mesh, kMiddle, mode);
  if (counts.above == above && counts.below == below) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << counts.above << " above and " << counts.below << " below";
}

TEST(IslandsTouching, PartsLyingFlushAreOnePiece) {
  // Side by side on the plane x = 0.5, their vertices not shared.
  EXPECT_TRUE(piecesOfTwoBoxes({0.5f, 0.5f, 0.25f}, {1.0f, 0, 0}, IslandMode::Touching, 1, 1));
}

TEST(IslandsTouching, APartHeldInsideAnotherGoesWithIt) {
  // A small box inside the unit one, no triangle of either touching the other.
  EXPECT_TRUE(piecesOfTwoBoxes({0.1f, 0.2f, 0.1f}, {0.2f, 0, 0}, IslandMode::Touching, 1, 1));
  EXPECT_TRUE(piecesOfTwoBoxes({0.1f, 0.2f, 0.1f}, {0.2f, 0, 0}, IslandMode::Connected, 2, 2));
}

TEST(IslandsTouching, PartsApartThatTheCutReachesStayApart) {
  // A gap of 0.1 (far above the tolerance) between two cut boxes: the side really falls apart.
  EXPECT_TRUE(piecesOfTwoBoxes({0.5f, 0.5f, 0.5f}, {1.1f, 0, 0}, IslandMode::Touching, 2, 2));
}

TEST(IslandsTouching, APartTheCutDoesNotReachGoesWithTheNearestCutPieceOfItsSide) {
  // Two boxes cut, and a small one above, apart from both, nearer the second.
  MeshData mesh = prim::merge(boxAt({0.5f, 0.5f, 0.5f}, {0, 0, 0}), boxAt({0.5f, 0.5f, 0.5f}, {1.5f, 0, 0}));
  mesh = prim::merge(mesh, boxAt({0.1f, 0.1f, 0.1f}, {1.5f, 0.9f, 0}));
  SplitResult result;
  const Counts touching = cut(mesh, kMiddle, IslandMode::Touching, &result);
  ASSERT_EQ(touching.above, 2);
  EXPECT_EQ(touching.below, 2);
  double withSmall = 0.0;  // the above piece holding the small box: volume 0.45 + 0.008
  for (const SplitPiece& piece : result.pieces) {
    if (piece.side > 0 && piece.mass.centerOfMass.x > 1.0) withSmall = piece.mass.volume;
  }
  EXPECT_NEAR(withSmall, 0.45 + 0.008, 1e-6);
  // Connected: the small box is a piece of its own, which the plane did not reach.
  const Counts connected = cut(mesh, kMiddle, IslandMode::Connected, &result);
  EXPECT_EQ(connected.above, 3);
  int unreached = 0;
  for (const SplitPiece& piece : result.pieces) unreached += piece.reached ? 0 : 1;
  EXPECT_EQ(unreached, 1);
}

TEST(IslandsTouching, JoinsAreTransitiveAndNumberedByFirstTriangle) {
  // Three boxes in a row, each passing into the next, plus one far apart; triangles of 0, 1, 2, 3.
  std::vector<glm::dvec3> corners;
  std::vector<uint32_t> component;
  auto addBox = [&](const glm::vec3& centre, uint32_t label) {
    const MeshData b = boxAt({0.5f, 0.5f, 0.5f}, centre);
    for (uint32_t index : b.indices) corners.push_back(glm::dvec3(b.positions[index]));
    component.insert(component.end(), b.indices.size() / 3, label);
  };
  addBox({0, 0, 0}, 0);
  addBox({5, 0, 0}, 1);
  addBox({0.8f, 0, 0}, 2);
  addBox({1.6f, 0, 0}, 3);
  std::vector<uint32_t> root;
  ContactScratch scratch;
  EXPECT_EQ(joinTouchingComponents(corners, component, 4, 1e-6, root, scratch), 2u);
  EXPECT_EQ(root, (std::vector<uint32_t>{0, 1, 0, 0}));
}

}  // namespace
}  // namespace cleave::geometry
