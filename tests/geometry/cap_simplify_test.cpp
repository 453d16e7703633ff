// SPDX-License-Identifier: MIT
// Cap simplification (engine/geometry/cap_simplify.h): a box cut by two planes in turn keeps a point
// on the planes' common line that only the caps use; made again, the caps drop it and the piece stays
// closed and manifold on its float positions with its volume. Over fractures, no point of a piece is
// used by the caps of only one or two planes and nothing else.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <vector>

#include "cleave/geometry/cap_simplify.h"
#include "cleave/geometry/fracture.h"
#include "cleave/geometry/mesh_container.h"
#include "cleave/geometry/mesh_splitter.h"
#include "cleave/geometry/primitives.h"
#include "tests/geometry/test_meshes.h"

namespace cleave::geometry {
namespace {

Plane planeOf(glm::dvec3 normal, double offset) {
  Plane p;
  p.normal = glm::normalize(normal);
  p.offset = offset / glm::length(normal);
  return p;
}

// The piece below `plane` of a cut of `mesh` (with its weld), its caps marked kFromCap | k.
SplitPiece below(const MeshData& mesh, const MeshWeld* weld, const Plane& plane, uint32_t k,
                 std::vector<uint32_t>& source) {
  MeshContainer container;
  EXPECT_EQ(weld ? container.setMesh(mesh, *weld).code : container.setMesh(mesh).code, SplitStatus::Ok);
  SplitOptions options;
  options.keepSide = -1;
  SplitResult result;
  EXPECT_EQ(makeConcaveSplitter()->split(container, plane, options, result), SplitStatus::Ok);
  EXPECT_EQ(result.pieces.size(), 1u);
  SplitPiece piece = std::move(result.pieces.at(0));
  std::vector<uint32_t> next(piece.sourceTriangles.size());
  for (size_t t = 0; t < next.size(); ++t) {
    const uint32_t s = piece.sourceTriangles[t];
    next[t] = (s & kFromCap) ? (kFromCap | k) : (source.empty() ? s : source[s]);
  }
  source = std::move(next);
  return piece;
}

size_t capTriangles(const std::vector<uint32_t>& source) {
  size_t n = 0;
  for (uint32_t s : source) n += (s & kFromCap) != 0;
  return n;
}

TEST(CapSimplifier, DropsThePointOnTwoCapsCommonLineAndKeepsThePieceClosed) {
  const MeshData box = primitives::box(glm::vec3(0.5f));
  const Plane planes[2] = {planeOf({1, 0.3, 0.2}, 0.1), planeOf({-0.2, 1, 0.4}, 0.05)};
  std::vector<uint32_t> source;
  SplitPiece first = below(box, nullptr, planes[0], 0, source);
  SplitPiece piece = below(first.mesh, &first.weld, planes[1], 1, source);
  const double volume = computeMassProperties(piece.mesh).volume;  // of the float positions
  const size_t trianglesBefore = piece.mesh.indices.size() / 3, capsBefore = capTriangles(source);
  ASSERT_TRUE(testing::manifoldOnFloats(piece.mesh));

  CapSimplifier simplifier;
  const CapSimplifyStats stats = simplifier.simplify(piece.mesh, piece.weld, source, planes, glm::dmat4(1.0));
  EXPECT_EQ(stats.keptRegions, 0u);
  EXPECT_GE(stats.regions, 1u);
  EXPECT_GE(stats.droppedPoints, 1u) << "the second cut crosses the first cap's inner edge";
  EXPECT_LT(piece.mesh.indices.size() / 3, trianglesBefore);
  EXPECT_LT(capTriangles(source), capsBefore);
  EXPECT_EQ(source.size(), piece.mesh.indices.size() / 3);
  EXPECT_TRUE(testing::manifoldOnFloats(piece.mesh));
  EXPECT_NEAR(computeMassProperties(piece.mesh).volume, volume, 1e-9 * volume);
  // The weld still fits the mesh: the container takes it.
  MeshContainer again;
  EXPECT_EQ(again.setMesh(piece.mesh, piece.weld).code, SplitStatus::Ok);
  EXPECT_TRUE(again.closed());
  // Nothing more to drop: a second call changes nothing.
  const MeshData kept = piece.mesh;
  EXPECT_EQ(simplifier.simplify(piece.mesh, piece.weld, source, planes, glm::dmat4(1.0)).regions, 0u);
  EXPECT_EQ(piece.mesh.indices, kept.indices);
}

// Per float position of a piece: whether a surface triangle uses it, and the cap planes that do.
void expectNoCapOnlyPointsOffCorners(const FracturePiece& piece) {
  struct Use {
    bool surface = false;
    std::set<uint32_t> planes;
  };
  std::map<std::tuple<float, float, float>, Use> uses;
  for (size_t t = 0; t < piece.sourceTriangles.size(); ++t) {
    for (int c = 0; c < 3; ++c) {
      const glm::vec3 p = piece.mesh.positions[piece.mesh.indices[3 * t + c]];
      Use& u = uses[{p.x, p.y, p.z}];
      if (piece.sourceTriangles[t] & kFromCap) {
        u.planes.insert(piece.sourceTriangles[t] & ~kFromCap);
      } else {
        u.surface = true;
      }
    }
  }
  size_t capOnly = 0;
  for (const auto& [p, u] : uses) capOnly += !u.surface && u.planes.size() < 3;
  EXPECT_EQ(capOnly, 0u) << "cell " << piece.cell << ": points only one or two caps use";
}

TEST(CapSimplifier, FracturePiecesKeepOnlyTheCapPointsTheirBordersNeed) {
  struct Case {
    const char* name;
    MeshData mesh;
    size_t capBound;  // cap triangles over all pieces, at most (before simplification: 2,227 / 4,305)
  };
  const Case cases[] = {{"box", primitives::box(glm::vec3(0.5f)), 700},
                        {"sphere", primitives::uvSphere(0.5f, 32, 16), 1500}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    MeshContainer container;
    ASSERT_EQ(container.setMesh(c.mesh).code, SplitStatus::Ok);
    const glm::dvec3 lo = container.boundsMin(), hi = container.boundsMax();
    const std::vector<ConvexCell> cells =
        voronoiCells(fractureSeeds(16, 1, lo, hi), lo - 0.01 * (hi - lo), hi + 0.01 * (hi - lo));
    const FractureResult r = fracture(container, cells);
    ASSERT_EQ(r.status, SplitStatus::Ok) << r.message;
    size_t caps = 0;
    double volume = 0.0;
    for (const FracturePiece& piece : r.pieces) {
      caps += piece.capTriangles;
      volume += piece.mass.volume;
      EXPECT_TRUE(testing::manifoldOnFloats(piece.mesh)) << "cell " << piece.cell;
      EXPECT_EQ(piece.capTriangles, capTriangles(piece.sourceTriangles)) << "cell " << piece.cell;
      expectNoCapOnlyPointsOffCorners(piece);
    }
    EXPECT_LE(caps, c.capBound);
    EXPECT_NEAR(volume, computeMassProperties(c.mesh).volume, 1e-6 * volume);
  }
}

}  // namespace
}  // namespace cleave::geometry
