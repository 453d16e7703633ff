// SPDX-License-Identifier: MIT
// Fracture (engine/geometry/fracture.h): Voronoi cells that tile their box, and meshes broken into
// cells with the split invariants kept: every piece closed and manifold on its float positions,
// inside its cell, volumes summing to the input's, the caps two neighbouring cells leave on their
// shared plane covering the same area, and the same bytes from the same seed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "cleave/geometry/fracture.h"
#include "cleave/geometry/mesh_container.h"
#include "cleave/geometry/mesh_splitter.h"
#include "cleave/geometry/primitives.h"
#include "tests/geometry/test_meshes.h"

namespace cleave::geometry {
namespace {

// The volume a mesh encloses by this test's own arithmetic (signed tetrahedra about the centre of
// its bounds), not the library's mass integration: the pieces' volumes are checked against it.
double ownVolume(const MeshData& mesh) {
  std::vector<glm::dvec3> p(mesh.positions.begin(), mesh.positions.end());
  return testing::signedVolume(p, mesh.indices);
}

struct Fractured {
  FractureResult result;
  std::vector<ConvexCell> cells;
  double volume = 0.0;  // of the input
  glm::dvec3 boundsSize{0.0};
};

Fractured fractureMesh(const MeshData& mesh, uint32_t cellCount, uint64_t seed,
                       FractureMethod method = FractureMethod::Clipper) {
  Fractured f;
  MeshContainer container;
  EXPECT_EQ(container.setMesh(mesh).code, SplitStatus::Ok);
  glm::dvec3 lo, hi;
  testing::bounds(container.cutPositions(), lo, hi);
  const glm::dvec3 margin = (hi - lo) * 0.01;
  f.boundsSize = hi - lo;
  f.cells = voronoiCells(fractureSeeds(cellCount, seed, lo, hi), lo - margin, hi + margin);
  f.result = fracture(container, f.cells, SplitOptions{}, method);
  f.volume = ownVolume(mesh);
  return f;
}

// Area of the cap triangles of `piece` on its cell's plane k (model: identity).
double capAreaOnPlane(const FracturePiece& piece, uint32_t k) {
  double area = 0.0;
  for (size_t t = 0; t < piece.sourceTriangles.size(); ++t) {
    if (piece.sourceTriangles[t] != (kFromCap | k)) continue;
    const uint32_t* v = &piece.mesh.indices[3 * t];
    area += testing::triangleArea(glm::dvec3(piece.mesh.positions[v[0]]), glm::dvec3(piece.mesh.positions[v[1]]),
                                  glm::dvec3(piece.mesh.positions[v[2]]));
  }
  return area;
}

void expectFractureInvariants(const char* name, const MeshData& mesh, uint32_t cellCount) {
  SCOPED_TRACE(name);
  const Fractured f = fractureMesh(mesh, cellCount, 7);
  ASSERT_EQ(f.result.status, SplitStatus::Ok) << f.result.message;
  ASSERT_GE(f.result.pieces.size(), cellCount / 2) << "most cells should hold a part";
  double sum = 0.0;
  std::map<uint32_t, int> perCell;
  for (const FracturePiece& piece : f.result.pieces) {
    EXPECT_TRUE(testing::manifoldOnFloats(piece.mesh)) << "cell " << piece.cell;
    EXPECT_GT(piece.mass.volume, 0.0);
    EXPECT_TRUE(piece.mass.closed);
    ASSERT_EQ(piece.sourceTriangles.size(), piece.mesh.indices.size() / 3);
    // The piece's mass volume is what its mesh encloses, and the meshes add up to the input.
    const double own = ownVolume(piece.mesh);
    EXPECT_NEAR(piece.mass.volume, own, 1e-6 * f.volume) << "cell " << piece.cell;
    sum += own;
    ++perCell[piece.cell];
    // Inside its cell: no vertex above any of the cell's planes (beyond float rounding).
    const ConvexCell& cell = f.cells[piece.cell];
    for (const glm::vec3& p : piece.mesh.positions)
      for (const Plane& plane : cell.planes) ASSERT_LE(glm::dot(plane.normal, glm::dvec3(p)) - plane.offset, 1e-5);
  }
  EXPECT_NEAR(sum, f.volume, 1e-6 * f.volume) << "the cells' volumes do not add up to the mesh's";
  std::printf("[ fracture] %s: %u cells, %zu pieces, %u cuts, %u cells carved by splits, volume %.9f of %.9f\n",
              name, cellCount, f.result.pieces.size(), f.result.cuts, f.result.carvedBySplits, sum, f.volume);
  // Neighbouring cells' caps on their shared plane: the same area from both sides.
  size_t sharedPlanes = 0;
  double largest = 0.0;
  for (uint32_t i = 0; i < f.cells.size(); ++i) {
    for (uint32_t k = 0; k < f.cells[i].planes.size(); ++k) {
      const Plane& p = f.cells[i].planes[k];
      for (uint32_t j = i + 1; j < f.cells.size(); ++j) {
        for (uint32_t m = 0; m < f.cells[j].planes.size(); ++m) {
          const Plane& q = f.cells[j].planes[m];
          if (glm::dot(p.normal, q.normal) > -1.0 + 1e-12 || std::abs(p.offset + q.offset) > 1e-9) continue;
          double a = 0.0, b = 0.0;
          for (const FracturePiece& piece : f.result.pieces) {
            if (piece.cell == i) a += capAreaOnPlane(piece, k);
            if (piece.cell == j) b += capAreaOnPlane(piece, m);
          }
          if (a == 0.0 && b == 0.0) continue;
          ++sharedPlanes;
          // Each side's cap is made from its own cut points, and a point within the on-plane
          // tolerance of a plane counts as on it and is not moved: each edge of the cap may lie up to
          // that tolerance off, so the areas may differ by the perimeter (about 4 sqrt(area)) times
          // twice the tolerance, plus float rounding.
          const double area = std::max(a, b);
          const double onPlane = SplitOptions{}.relativeTolerance * glm::length(glm::dvec3(f.boundsSize));
          largest = std::max(largest, std::abs(a - b) / area);
          EXPECT_NEAR(a, b, 1e-5 * area + 8.0 * onPlane * std::sqrt(area)) << "cells " << i << " and " << j;
        }
      }
    }
  }
  EXPECT_GT(sharedPlanes, 0u) << "no two cells share a capped plane: the check saw nothing";
  std::printf("[ fracture] %s: %zu shared capped planes, largest relative cap area difference %.2g\n", name,
              sharedPlanes, largest);
}

TEST(Fracture, GeneratedMeshesBreakIntoClosedCellsThatAddUp) {
  expectFractureInvariants("sphere", primitives::uvSphere(1.f, 32, 16), 16);
  expectFractureInvariants("torus", primitives::torus(1.f, 0.35f, 48, 24), 16);
  expectFractureInvariants("hollow sphere", primitives::hollowSphere(1.f, 0.7f, 32, 16), 16);
  expectFractureInvariants("comb", primitives::combPrism(16), 16);
  expectFractureInvariants("sphere, 32 cells", primitives::uvSphere(1.f, 32, 16), 32);
  expectFractureInvariants("sphere, 64 cells", primitives::uvSphere(1.f, 32, 16), 64);
}

// The cell clipper (the default) against one split per plane: the same cells hold a part, with the
// same volume to float rounding, and the clipper carves every cell of these meshes itself.
TEST(Fracture, TheClipperCarvesTheCellsTheSplitsCarve) {
  struct Case {
    const char* name;
    MeshData mesh;
    uint32_t cells;
  };
  const Case cases[] = {{"sphere", primitives::uvSphere(1.f, 32, 16), 16},
                        {"sphere, 64 cells (some wholly inside)", primitives::uvSphere(1.f, 32, 16), 64},
                        {"torus", primitives::torus(1.f, 0.35f, 48, 24), 16},
                        {"hollow sphere", primitives::hollowSphere(1.f, 0.7f, 32, 16), 16},
                        {"comb", primitives::combPrism(16), 16}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const Fractured clipped = fractureMesh(c.mesh, c.cells, 7, FractureMethod::Clipper);
    const Fractured split = fractureMesh(c.mesh, c.cells, 7, FractureMethod::Splits);
    ASSERT_EQ(clipped.result.status, SplitStatus::Ok) << clipped.result.message;
    ASSERT_EQ(split.result.status, SplitStatus::Ok) << split.result.message;
    EXPECT_EQ(split.result.carvedBySplits, c.cells);
    std::map<uint32_t, double> a, b;
    for (const FracturePiece& piece : clipped.result.pieces) a[piece.cell] += piece.mass.volume;
    for (const FracturePiece& piece : split.result.pieces) b[piece.cell] += piece.mass.volume;
    ASSERT_EQ(a.size(), b.size());
    for (const auto& [cell, volume] : b) {
      ASSERT_TRUE(a.count(cell)) << "cell " << cell << " lost";
      EXPECT_NEAR(a[cell], volume, 1e-6 * clipped.volume) << "cell " << cell;
    }
    std::printf("[ fracture] %s: %u of %u cells by the clipper\n", c.name, c.cells - clipped.result.carvedBySplits,
                c.cells);
    // Concave cells that fall apart into islands go to the splits; the convex ones never do.
    if (std::string(c.name).rfind("sphere", 0) == 0) {
      EXPECT_EQ(clipped.result.carvedBySplits, 0u);
    }
  }
}

// Cells of many planes: up to 32 the clipper ranks the planes in bit masks, past that in 16-bit
// ranks; a polyhedral ball of 24 and of 40 tangent planes, crossing the sphere's surface, carved by
// the clipper gives the part the splits carve (volumes within the float positions' 1e-7).
TEST(Fracture, CellsOfManyPlanesAreCarvedByTheClipperAsByTheSplits) {
  const MeshData sphere = primitives::uvSphere(1.f, 32, 16);
  MeshContainer container;
  ASSERT_EQ(container.setMesh(sphere).code, SplitStatus::Ok);
  for (const uint32_t planes : {24u, 40u}) {
    SCOPED_TRACE(planes);
    ConvexCell ball;
    const glm::dvec3 centre(0.6, 0.1, -0.05);
    for (uint32_t k = 0; k < planes; ++k) {  // normals spread on the sphere (golden angle)
      const double z = 1.0 - 2.0 * (k + 0.5) / planes, r = std::sqrt(1.0 - z * z), a = 2.399963229728653 * k;
      const glm::dvec3 n(r * std::cos(a), r * std::sin(a), z);
      ball.planes.push_back(Plane{n, glm::dot(n, centre) + 0.55});
    }
    const FractureResult clipped = fracture(container, std::span<const ConvexCell>(&ball, 1));
    const FractureResult split =
        fracture(container, std::span<const ConvexCell>(&ball, 1), SplitOptions{}, FractureMethod::Splits);
    ASSERT_EQ(clipped.status, SplitStatus::Ok) << clipped.message;
    ASSERT_EQ(split.status, SplitStatus::Ok) << split.message;
    EXPECT_EQ(clipped.carvedBySplits, 0u);
    ASSERT_EQ(clipped.pieces.size(), 1u);
    ASSERT_EQ(split.pieces.size(), 1u);
    EXPECT_GT(clipped.pieces[0].capTriangles, 0u);
    EXPECT_LT(clipped.pieces[0].capTriangles, clipped.pieces[0].sourceTriangles.size()) << "no mesh surface kept";
    EXPECT_NEAR(clipped.pieces[0].mass.volume, split.pieces[0].mass.volume, 1e-7 * split.pieces[0].mass.volume);
    EXPECT_TRUE(testing::manifoldOnFloats(clipped.pieces[0].mesh));
  }
}

// A cell wholly inside the solid: the part is the cell itself, all caps (two triangles per face of
// a cube), with its exact volume; and a cell whose plane holds a face of the mesh is left to the
// splits, which give the same part.
TEST(Fracture, ACellInsideTheSolidIsAllCapsAndAFaceInACellPlaneGoesToTheSplits) {
  const MeshData box = primitives::box(glm::vec3(1.f));
  MeshContainer container;
  ASSERT_EQ(container.setMesh(box).code, SplitStatus::Ok);
  ConvexCell cube;
  for (int axis = 0; axis < 3; ++axis) {
    for (double sign : {1.0, -1.0}) {
      glm::dvec3 n(0.0);
      n[axis] = sign;
      cube.planes.push_back(Plane{n, 0.25});
    }
  }
  const FractureResult inside = fracture(container, std::span<const ConvexCell>(&cube, 1));
  ASSERT_EQ(inside.status, SplitStatus::Ok) << inside.message;
  ASSERT_EQ(inside.pieces.size(), 1u);
  EXPECT_EQ(inside.carvedBySplits, 0u);
  const FracturePiece& piece = inside.pieces[0];
  EXPECT_EQ(piece.mesh.indices.size(), 36u);
  EXPECT_EQ(piece.capTriangles, 12u);
  for (uint32_t source : piece.sourceTriangles) EXPECT_TRUE(source & kFromCap);
  EXPECT_NEAR(piece.mass.volume, 0.125, 1e-12);
  EXPECT_TRUE(testing::manifoldOnFloats(piece.mesh));

  ConvexCell onFace;  // x <= 1 holds the box's +x face; y <= 0 cuts it in half
  onFace.planes = {Plane{glm::dvec3(1.0, 0.0, 0.0), 1.0}, Plane{glm::dvec3(0.0, 1.0, 0.0), 0.0}};
  const FractureResult half = fracture(container, std::span<const ConvexCell>(&onFace, 1));
  ASSERT_EQ(half.status, SplitStatus::Ok) << half.message;
  EXPECT_EQ(half.carvedBySplits, 1u);
  ASSERT_EQ(half.pieces.size(), 1u);
  EXPECT_NEAR(half.pieces[0].mass.volume, 4.0, 1e-9);
}

// SplitOptions::keepSide, the clip fracture cuts with: the pieces of one side, the same bytes as
// that side of a split that keeps both.
TEST(Fracture, KeepSideGivesTheSameBytesAsThatSideOfAFullSplit) {
  const MeshData torus = primitives::torus(1.f, 0.35f, 48, 24);
  MeshContainer container;
  ASSERT_EQ(container.setMesh(torus).code, SplitStatus::Ok);
  auto splitter = makeConcaveSplitter();
  const Plane plane{glm::normalize(glm::dvec3(0.3, 1.0, 0.2)), 0.1};
  SplitResult both, below, above;
  SplitOptions options;
  ASSERT_EQ(splitter->split(container, plane, options, both), SplitStatus::Ok);
  options.keepSide = -1;
  ASSERT_EQ(splitter->split(container, plane, options, below), SplitStatus::Ok);
  options.keepSide = 1;
  ASSERT_EQ(splitter->split(container, plane, options, above), SplitStatus::Ok);
  size_t a = 0, b = 0;
  for (const SplitPiece& piece : both.pieces) {
    const SplitResult& one = piece.side > 0 ? above : below;
    size_t& k = piece.side > 0 ? a : b;
    ASSERT_LT(k, one.pieces.size());
    const SplitPiece& same = one.pieces[k++];
    EXPECT_EQ(same.side, piece.side);
    EXPECT_EQ(same.mesh.indices, piece.mesh.indices);
    ASSERT_EQ(same.mesh.positions.size(), piece.mesh.positions.size());
    EXPECT_EQ(std::memcmp(same.mesh.positions.data(), piece.mesh.positions.data(),
                          piece.mesh.positions.size() * sizeof(glm::vec3)), 0);
    EXPECT_EQ(same.mass.volume, piece.mass.volume);
    EXPECT_EQ(same.capLoops, piece.capLoops);
  }
  EXPECT_EQ(a, above.pieces.size());
  EXPECT_EQ(b, below.pieces.size());
  EXPECT_GT(a, 0u);
  EXPECT_GT(b, 0u);
}

TEST(Fracture, SameSeedGivesTheSameBytesAndAnotherSeedOtherCells) {
  const MeshData torus = primitives::torus(1.f, 0.35f, 48, 24);
  const Fractured a = fractureMesh(torus, 16, 3), b = fractureMesh(torus, 16, 3), c = fractureMesh(torus, 16, 4);
  ASSERT_EQ(a.result.pieces.size(), b.result.pieces.size());
  for (size_t k = 0; k < a.result.pieces.size(); ++k) {
    const MeshData& x = a.result.pieces[k].mesh;
    const MeshData& y = b.result.pieces[k].mesh;
    ASSERT_EQ(x.positions.size(), y.positions.size());
    EXPECT_EQ(std::memcmp(x.positions.data(), y.positions.data(), x.positions.size() * sizeof(glm::vec3)), 0);
    EXPECT_EQ(x.indices, y.indices);
  }
  ASSERT_EQ(a.cells.size(), c.cells.size());
  for (size_t k = 0; k < a.cells.size(); ++k) EXPECT_NE(a.cells[k].seed, c.cells[k].seed) << "cell " << k;
  // Another seed breaks the torus otherwise: other pieces, adding up to the same volume.
  auto volumes = [](const Fractured& f) {
    std::vector<double> v;
    for (const FracturePiece& piece : f.result.pieces) v.push_back(ownVolume(piece.mesh));
    std::sort(v.begin(), v.end());
    return v;
  };
  const std::vector<double> va = volumes(a), vc = volumes(c);
  EXPECT_NE(va, vc);
  size_t shared = 0;  // pieces of one volume (to 1e-9 of the torus's) in both
  for (double v : vc)
    shared += std::any_of(va.begin(), va.end(), [&](double w) { return std::abs(v - w) < 1e-9 * a.volume; });
  EXPECT_LT(shared, vc.size() / 2) << "most pieces of seed 4 are pieces of seed 3";
  EXPECT_NEAR(std::accumulate(vc.begin(), vc.end(), 0.0), c.volume, 1e-6 * c.volume);
}

TEST(Fracture, OneCellIsTheWholeMeshAndAnEmptyCellGivesNothing) {
  const MeshData sphere = primitives::uvSphere(1.f, 16, 8);
  MeshContainer container;
  ASSERT_EQ(container.setMesh(sphere).code, SplitStatus::Ok);
  std::vector<ConvexCell> cells(2);
  cells[1].empty = true;
  const FractureResult r = fracture(container, cells);
  ASSERT_EQ(r.status, SplitStatus::Ok);
  ASSERT_EQ(r.pieces.size(), 1u);
  EXPECT_EQ(r.pieces[0].mesh.indices, sphere.indices);
  EXPECT_NEAR(r.pieces[0].mass.volume, computeMassProperties(sphere).volume, 1e-12);
  EXPECT_EQ(r.cuts, 0u);
}

TEST(Fracture, VoronoiCellsTileTheBoxByNearestSeed) {
  const glm::dvec3 lo(-1.0), hi(1.0);
  std::vector<glm::dvec3> seeds = fractureSeeds(24, 11, lo, hi);
  seeds.push_back(seeds[5]);  // a repeated seed gets an empty cell
  const std::vector<ConvexCell> cells = voronoiCells(seeds, lo, hi);
  ASSERT_EQ(cells.size(), seeds.size());
  EXPECT_TRUE(cells.back().empty);
  size_t pruned = 0;
  for (const ConvexCell& cell : cells) pruned += seeds.size() - 1 - cell.planes.size();
  EXPECT_GT(pruned, 0u) << "no bisector was pruned";
  // Every sample point is inside exactly the cell of its nearest seed.
  std::mt19937_64 rng(5);
  auto unit = [&] { return double(rng() >> 11) * 0x1.0p-53; };
  for (int n = 0; n < 2000; ++n) {
    const glm::dvec3 x = lo + glm::dvec3(unit(), unit(), unit()) * (hi - lo);
    size_t nearest = 0;
    for (size_t i = 1; i + 1 < seeds.size(); ++i)
      if (glm::length(seeds[i] - x) < glm::length(seeds[nearest] - x)) nearest = i;
    int inside = 0;
    for (size_t i = 0; i < cells.size(); ++i) {
      if (cells[i].empty) continue;
      bool in = true;
      for (const Plane& p : cells[i].planes) in = in && glm::dot(p.normal, x) <= p.offset + 1e-12;
      if (in) {
        ++inside;
        EXPECT_EQ(i, nearest);
      }
    }
    EXPECT_EQ(inside, 1);
  }
}

TEST(Fracture, AVoronoiCellKeepsAFarBisectorBehindNearOnesThatMiss) {
  // Seed 0 at the origin, a row of seeds along +x from 3 to 4.9 (only the first one's bisector
  // bounds cell 0: the others' lie beyond it) and one at (0, 5, 0), farther than all but the row's
  // end: more than a batch of near bisectors that miss comes before the one that bounds the cell
  // at y = 2.5.
  std::vector<glm::dvec3> seeds = {glm::dvec3(0.0)};
  for (int k = 0; k < 20; ++k) seeds.emplace_back(3.0 + 0.1 * k, 0.0, 0.0);
  seeds.emplace_back(0.0, 5.0, 0.0);
  const std::vector<ConvexCell> cells = voronoiCells(seeds, glm::dvec3(-10.0), glm::dvec3(10.0));
  ASSERT_FALSE(cells[0].empty);
  auto inside = [&](const glm::dvec3& x) {
    for (const Plane& p : cells[0].planes)
      if (glm::dot(p.normal, x) > p.offset + 1e-12) return false;
    return true;
  };
  EXPECT_EQ(cells[0].planes.size(), 2u);
  EXPECT_TRUE(inside(glm::dvec3(-1.0, 2.0, 0.0)));
  EXPECT_FALSE(inside(glm::dvec3(0.0, 3.0, 0.0))) << "nearer (0, 5, 0) than the origin";
  EXPECT_FALSE(inside(glm::dvec3(2.0, 0.0, 0.0))) << "nearer (3, 0, 0) than the origin";
}

TEST(Fracture, SeedsGatherAroundTheImpactPoint) {
  const glm::dvec3 lo(-1.0), hi(1.0), impact(0.6, 0.0, 0.0);
  const std::vector<glm::dvec3> seeds = fractureSeeds(40, 9, lo, hi, impact, 0.3, 0.5);
  int near = 0;
  for (const glm::dvec3& s : seeds) {
    EXPECT_TRUE(s.x >= lo.x && s.x <= hi.x && s.y >= lo.y && s.y <= hi.y && s.z >= lo.z && s.z <= hi.z);
    near += glm::length(s - impact) <= 0.3 ? 1 : 0;
  }
  EXPECT_GE(near, 20);
  EXPECT_EQ(fractureSeeds(40, 9, lo, hi, impact, 0.3, 0.5), seeds);
}

}  // namespace
}  // namespace cleave::geometry
