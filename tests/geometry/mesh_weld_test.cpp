// SPDX-License-Identifier: MIT
// MeshContainer's weld, closedness and connectivity against plain reference implementations: ids
// by a sweep along x (the lowest earlier vertex within the tolerance, chains merged), closedness by
// a map of directed edges, parts by a union-find over every triangle. The meshes are chosen to meet
// every path of the container: flat grids that crowd a bounds-sized cell, jittered copies around
// the tolerance, a table that must grow, vertices of high valence, defects of every kind.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <tuple>
#include <utility>
#include <vector>

#include "cleave/geometry/index_range.h"
#include "cleave/geometry/mesh_splitter.h"
#include "cleave/geometry/primitives.h"
#include "test_meshes.h"

namespace cleave::geometry {
namespace {

using testing::SeededRandom;

// Ids as MeshContainer defines them: vertex v joins the id of the lowest-index earlier vertex
// within 1e-6 of the bounds diagonal, else starts the next id.
std::vector<uint32_t> referenceIds(const std::vector<glm::vec3>& positions) {
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (const glm::vec3& p : positions) {
    lo = glm::min(lo, glm::dvec3(p));
    hi = glm::max(hi, glm::dvec3(p));
  }
  const double tolerance = 1e-6 * glm::length(hi - lo);
  std::vector<uint32_t> byX(positions.size());
  std::iota(byX.begin(), byX.end(), 0u);
  std::sort(byX.begin(), byX.end(), [&](uint32_t a, uint32_t b) {
    return positions[a].x != positions[b].x ? positions[a].x < positions[b].x : a < b;
  });
  std::vector<uint32_t> ids(positions.size());
  uint32_t count = 0;
  for (uint32_t v = 0; v < positions.size(); ++v) {
    const glm::dvec3 p(positions[v]);
    auto first = std::lower_bound(byX.begin(), byX.end(), p.x - 2 * tolerance,
                                  [&](uint32_t i, double x) { return double(positions[i].x) < x; });
    uint32_t best = UINT32_MAX;
    for (auto it = first; it != byX.end() && double(positions[*it].x) <= p.x + 2 * tolerance; ++it) {
      const glm::dvec3 d = glm::dvec3(positions[*it]) - p;
      if (*it < v && *it < best && glm::dot(d, d) <= tolerance * tolerance) best = *it;
    }
    ids[v] = best == UINT32_MAX ? count++ : ids[best];
  }
  return ids;
}

// Closed on the ids: every directed edge of a triangle with three distinct ids once, its reverse once.
bool referenceClosed(const std::vector<uint32_t>& ids, const std::vector<uint32_t>& indices) {
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    const uint32_t c[3] = {ids[indices[t]], ids[indices[t + 1]], ids[indices[t + 2]]};
    if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0]) continue;
    for (int e = 0; e < 3; ++e) ++directed[{c[e], c[(e + 1) % 3]}];
  }
  for (const auto& [edge, count] : directed) {
    const auto reverse = directed.find({edge.second, edge.first});
    if (count != 1 || reverse == directed.end() || reverse->second != 1) return false;
  }
  return !directed.empty();
}

// One part: every triangle (degenerate ones too) joins its corners' ids; ids no triangle uses are
// in no part.
bool referenceConnected(const std::vector<uint32_t>& ids, const std::vector<uint32_t>& indices) {
  const uint32_t count = ids.empty() ? 0 : *std::max_element(ids.begin(), ids.end()) + 1;
  std::vector<uint32_t> parent(count);
  std::iota(parent.begin(), parent.end(), 0u);
  std::vector<bool> used(count, false);
  auto find = [&](uint32_t x) {
    while (parent[x] != x) x = parent[x];
    return x;
  };
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    for (int k = 0; k < 3; ++k) used[ids[indices[t + k]]] = true;
    for (int k = 1; k < 3; ++k) parent[find(ids[indices[t + k]])] = find(ids[indices[t]]);
  }
  uint32_t parts = 0;
  for (uint32_t id = 0; id < count; ++id) parts += used[id] && parent[id] == id;
  return parts == 1;
}

// The container against the references; `what` names the mesh in a failure. Where the processor
// runs AVX2, also against the container's plain loops (allowAvx2): the same closedness, parts and
// winding.
void expectLikeReference(const MeshData& mesh, const char* what) {
  SCOPED_TRACE(what);
  MeshContainer container;
  ASSERT_TRUE(container.setMesh(mesh).ok());
  const std::vector<uint32_t> ids = referenceIds(mesh.positions);
  ASSERT_TRUE(std::equal(ids.begin(), ids.end(), container.positionIds().begin(), container.positionIds().end()));
  const bool closed = referenceClosed(ids, mesh.indices);
  EXPECT_EQ(container.closed(), closed);
  EXPECT_EQ(container.connected(), closed && referenceConnected(ids, mesh.indices));
  detail::allowAvx2(false);
  MeshContainer plain;
  const bool set = plain.setMesh(mesh).ok();
  detail::allowAvx2(true);
  ASSERT_TRUE(set);
  EXPECT_EQ(plain.closed(), container.closed());
  EXPECT_EQ(plain.connected(), container.connected());
  EXPECT_EQ(plain.inverted(), container.inverted());
}

// A closed slab over a grid of filled unit cells (like the benchmark's comb): top and bottom faces
// two triangles a cell, walls `layers` rows high, every vertex shared. Flat and wide, so that cells
// sized by the bounds alone would hold hundreds of vertices.
MeshData gridSlab(const std::vector<std::vector<bool>>& filled, float cell, float depth, int layers) {
  MeshData m;
  std::map<std::tuple<int, int, int>, uint32_t> index;
  auto vertex = [&](int x, int y, int z) {
    const auto [it, fresh] = index.try_emplace({x, y, z}, static_cast<uint32_t>(m.positions.size()));
    if (fresh) m.positions.push_back(glm::vec3(x * cell, y * cell, z * depth / float(layers)));
    return it->second;
  };
  const int w = static_cast<int>(filled.size()), h = static_cast<int>(filled[0].size());
  auto full = [&](int x, int y) { return x >= 0 && y >= 0 && x < w && y < h && filled[x][y]; };
  auto quad = [&](uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
    m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
  };
  for (int x = 0; x < w; ++x) {
    for (int y = 0; y < h; ++y) {
      if (!full(x, y)) continue;
      quad(vertex(x, y, layers), vertex(x + 1, y, layers), vertex(x + 1, y + 1, layers), vertex(x, y + 1, layers));
      quad(vertex(x, y, 0), vertex(x, y + 1, 0), vertex(x + 1, y + 1, 0), vertex(x + 1, y, 0));
      // Walls where the neighbour is empty: the cell's edge walked counter-clockwise seen from +z
      // (neighbour offset, then the edge's two ends relative to the cell).
      const int walls[4][6] = {{0, -1, 0, 0, 1, 0}, {1, 0, 1, 0, 1, 1}, {0, 1, 1, 1, 0, 1}, {-1, 0, 0, 1, 0, 0}};
      for (const auto& wall : walls) {
        if (full(x + wall[0], y + wall[1])) continue;
        const int px = x + wall[2], py = y + wall[3], qx = x + wall[4], qy = y + wall[5];
        for (int k = 0; k < layers; ++k) quad(vertex(px, py, k), vertex(qx, qy, k), vertex(qx, qy, k + 1), vertex(px, py, k + 1));
      }
    }
  }
  return m;
}

std::vector<std::vector<bool>> combCells(int teeth) {
  std::vector<std::vector<bool>> filled(size_t(teeth * 8 - 4), std::vector<bool>(48, false));
  for (size_t x = 0; x < filled.size(); ++x) {
    for (size_t y = 0; y < 48; ++y) filled[x][y] = y < 8 || (x % 8) < 4;
  }
  return filled;
}

TEST(MeshWeld, FlatCombGridIsClosedOnePartAndWeldedLikeTheReference) {
  const MeshData comb = gridSlab(combCells(6), 0.01f, 0.12f, 6);
  ASSERT_GT(comb.positions.size(), 3000u);
  expectLikeReference(comb, "comb slab");
  MeshContainer container;
  ASSERT_TRUE(container.setMesh(comb).ok());
  EXPECT_TRUE(container.closed());
  EXPECT_TRUE(container.connected());
  EXPECT_EQ(container.positionIdCount(), comb.positions.size());
}

// Every vertex of a mesh copied several times with offsets of a fraction of the tolerance to a few
// tolerances, the triangles spread over the copies: chains of near points must merge as the
// reference merges them, whatever cell they fall in.
TEST(MeshWeld, JitteredCopiesAroundTheToleranceWeldLikeTheReference) {
  for (const MeshData& base : {primitives::uvSphere(1.f, 40, 20), primitives::torus(1.f, 0.3f, 36, 18),
                               gridSlab(combCells(3), 0.05f, 0.3f, 3)}) {
    glm::dvec3 lo(INFINITY), hi(-INFINITY);
    for (const glm::vec3& p : base.positions) {
      lo = glm::min(lo, glm::dvec3(p));
      hi = glm::max(hi, glm::dvec3(p));
    }
    const double tolerance = 1e-6 * glm::length(hi - lo);
    SeededRandom random(7);
    MeshData m;
    const uint32_t copies = 4;
    for (uint32_t c = 0; c < copies; ++c) {
      for (const glm::vec3& p : base.positions) {
        const double reach = (c == 0 ? 0.0 : (c == 1 ? 0.4 : (c == 2 ? 0.9 : 3.0))) * tolerance;
        const glm::dvec3 offset(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1));
        m.positions.push_back(glm::vec3(glm::dvec3(p) + reach * offset / std::sqrt(3.0)));
      }
    }
    const uint32_t n = static_cast<uint32_t>(base.positions.size());
    for (size_t k = 0; k < base.indices.size(); ++k) {
      m.indices.push_back(base.indices[k] + n * static_cast<uint32_t>(random.next() % copies));
    }
    expectLikeReference(m, "jittered copies");
  }
}

// Tiny triangles and many vertices no triangle uses, scattered: the cells (twice the tiny edges)
// hold one vertex each and the table must grow past its first size.
TEST(MeshWeld, ScatteredVerticesGrowTheTableAndWeldLikeTheReference) {
  SeededRandom random(11);
  MeshData m;
  for (int k = 0; k < 40000; ++k) {
    m.positions.push_back(glm::vec3(random.uniform(), random.uniform(), random.uniform()));
  }
  for (int k = 0; k < 3000; ++k) {
    const glm::vec3 p(random.uniform(), random.uniform(), random.uniform());
    const uint32_t first = static_cast<uint32_t>(m.positions.size());
    m.positions.insert(m.positions.end(), {p, p + glm::vec3(1e-3f, 0, 0), p + glm::vec3(0, 1e-3f, 0)});
    m.indices.insert(m.indices.end(), {first, first + 1, first + 2});
  }
  m.positions.push_back(m.positions[5]);  // and one exact repeat
  expectLikeReference(m, "scattered");
}

// Two cones base to base around a rim of 40,000 vertices, the apexes first: each apex's edge list
// (80,000 entries filed under it) takes the sorted check, the rim's the tallied one.
TEST(MeshWeld, AVertexOfVeryHighValenceIsCheckedToo) {
  MeshData m;
  const uint32_t rim = 40000;
  m.positions = {glm::vec3(0, 0, 1), glm::vec3(0, 0, -1)};
  for (uint32_t k = 0; k < rim; ++k) {
    const double angle = 2.0 * 3.141592653589793 * k / rim;
    m.positions.push_back(glm::vec3(float(std::cos(angle)), float(std::sin(angle)), 0.f));
  }
  for (uint32_t k = 0; k < rim; ++k) {
    const uint32_t a = 2 + k, b = 2 + (k + 1) % rim;
    m.indices.insert(m.indices.end(), {0, a, b, 1, b, a});
  }
  expectLikeReference(m, "bipyramid");
  MeshContainer container;
  ASSERT_TRUE(container.setMesh(m).ok());
  EXPECT_TRUE(container.closed());
  EXPECT_TRUE(container.connected());
  std::swap(m.indices[1], m.indices[2]);
  expectLikeReference(m, "bipyramid with a flipped triangle");
}

// Vertices of high valence (cones with 40 and 2000 sides), defects of every kind: a flipped, a
// missing and a doubled triangle, two cubes sharing an edge, degenerate triangles joining parts.
TEST(MeshWeld, ClosednessAndPartsMatchTheReferenceOnDefects) {
  expectLikeReference(primitives::cylinder(0.5f, 1.f, 40), "cylinder 40");
  const MeshData cylinder = primitives::cylinder(0.5f, 1.f, 2000);
  expectLikeReference(cylinder, "cylinder 2000");
  // A triangle at the vertex of highest valence flipped: its long edge list must see it.
  const std::vector<uint32_t> cylinderIds = referenceIds(cylinder.positions);
  std::vector<uint32_t> valence(cylinder.positions.size(), 0);
  for (uint32_t v : cylinder.indices) ++valence[cylinderIds[v]];
  const uint32_t hub = static_cast<uint32_t>(std::max_element(valence.begin(), valence.end()) - valence.begin());
  ASSERT_GT(valence[hub], 1000u);
  MeshData flippedAtHub = cylinder;
  for (size_t t = 0; t < flippedAtHub.indices.size(); t += 3) {
    if (cylinderIds[flippedAtHub.indices[t]] != hub) continue;
    std::swap(flippedAtHub.indices[t + 1], flippedAtHub.indices[t + 2]);
    break;
  }
  expectLikeReference(flippedAtHub, "cylinder 2000 with a triangle at its hub flipped");
  const MeshData sphere = primitives::uvSphere(1.f, 24, 12);
  expectLikeReference(sphere, "sphere");
  MeshData flipped = sphere;
  std::swap(flipped.indices[31], flipped.indices[32]);
  expectLikeReference(flipped, "flipped triangle");
  MeshData missing = sphere;
  missing.indices.erase(missing.indices.begin() + 30, missing.indices.begin() + 33);
  expectLikeReference(missing, "missing triangle");
  MeshData doubled = sphere;
  doubled.indices.insert(doubled.indices.end(), sphere.indices.begin() + 30, sphere.indices.begin() + 33);
  expectLikeReference(doubled, "doubled triangle");
  MeshData doubledBothWays = doubled;  // the doubled one and its reverse: edges used four times
  doubledBothWays.indices.insert(doubledBothWays.indices.end(), {sphere.indices[30], sphere.indices[32], sphere.indices[31]});
  expectLikeReference(doubledBothWays, "doubled both ways");
  MeshData cubes = primitives::merge(primitives::box(glm::vec3(0.5f)), primitives::box(glm::vec3(0.5f)));
  for (size_t v = cubes.positions.size() / 2; v < cubes.positions.size(); ++v) cubes.positions[v] += glm::vec3(1, 1, 0);
  expectLikeReference(cubes, "cubes sharing an edge");
  MeshData spheres = primitives::twoDisjointSpheres(0.5f, 0.3f, 12, 6);
  expectLikeReference(spheres, "two spheres");
  MeshData joined = spheres;  // a degenerate triangle from one sphere to the other joins them
  const uint32_t a = joined.indices[0], b = joined.indices[joined.indices.size() - 1];
  joined.indices.insert(joined.indices.end(), {a, a, b});
  expectLikeReference(joined, "two spheres and a degenerate triangle");
  MeshData joinedFirst = spheres;  // the same triangle first, among the first eight
  joinedFirst.indices.insert(joinedFirst.indices.begin(), {a, a, b});
  expectLikeReference(joinedFirst, "two spheres and a degenerate triangle first");
  MeshData degenerateInside = sphere;  // a closed sphere with a degenerate triangle in its list
  degenerateInside.indices.insert(degenerateInside.indices.begin() + 12, {sphere.indices[0], sphere.indices[0], sphere.indices[1]});
  expectLikeReference(degenerateInside, "sphere with a degenerate triangle");
}

// Vertices of low valence: the tetrahedron's ids file at most eight edges each (pairedRows then
// checks a row in one vector rather than with the tally), with the same defects as above; the
// doubled tetrahedron and the box also overflow a row at their lowest id.
TEST(MeshWeld, ClosednessOfShortEdgeListsMatchesTheReference) {
  MeshData tetrahedron;
  tetrahedron.positions = {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)};
  tetrahedron.indices = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  expectLikeReference(tetrahedron, "tetrahedron");
  MeshContainer container;
  ASSERT_TRUE(container.setMesh(tetrahedron).ok());
  EXPECT_TRUE(container.closed());
  const std::vector<uint32_t> face = {1, 2, 3}, reversed = {1, 3, 2};
  MeshData flipped = tetrahedron;
  flipped.indices.resize(9);
  flipped.indices.insert(flipped.indices.end(), reversed.begin(), reversed.end());
  expectLikeReference(flipped, "tetrahedron with a flipped face");
  MeshData missing = tetrahedron;
  missing.indices.resize(9);
  expectLikeReference(missing, "tetrahedron with a missing face");
  MeshData doubled = tetrahedron;
  doubled.indices.insert(doubled.indices.end(), face.begin(), face.end());
  expectLikeReference(doubled, "tetrahedron with a doubled face");
  MeshData doubledBothWays = doubled;  // the face's edges used twice each way: four times in all
  doubledBothWays.indices.insert(doubledBothWays.indices.end(), reversed.begin(), reversed.end());
  expectLikeReference(doubledBothWays, "tetrahedron with a face doubled both ways");
  MeshData inwards = tetrahedron;  // every face turned: closed, wound inwards
  for (size_t t = 0; t < inwards.indices.size(); t += 3) std::swap(inwards.indices[t + 1], inwards.indices[t + 2]);
  expectLikeReference(inwards, "tetrahedron wound inwards");
  MeshData inwardSphere = primitives::uvSphere(1.f, 24, 12);  // past the first blocks of eight
  for (size_t t = 0; t < inwardSphere.indices.size(); t += 3) std::swap(inwardSphere.indices[t + 1], inwardSphere.indices[t + 2]);
  expectLikeReference(inwardSphere, "sphere wound inwards");
  ASSERT_TRUE(container.setMesh(inwardSphere).ok());
  EXPECT_TRUE(container.inverted());
  MeshData twice = primitives::merge(tetrahedron, tetrahedron);  // two closed copies at one place
  expectLikeReference(twice, "tetrahedron twice");
  expectLikeReference(primitives::box(glm::vec3(0.5f)), "box");
}

}  // namespace
}  // namespace cleave::geometry
