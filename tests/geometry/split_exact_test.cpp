// SPDX-License-Identifier: MIT
// Small, hand-checkable splits: exact volumes, cap areas, normals, UVs, islands, failure cases, the
// thesis's two failure cases, submesh reuse, determinism and the no-allocation guarantee.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <new>
#include <limits>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "cleave/geometry/mesh_splitter.h"
#include "cleave/geometry/pass_threads.h"
#include "cleave/geometry/primitives.h"
#include "cleave/geometry/whole_blocks.h"
#include "tests/geometry/test_meshes.h"

// ---- Allocation counting (tests/support/counting_allocator.h): only while gCountAllocations is
// set (by the no-allocation tests below).
#include "tests/support/counting_allocator.h"
using cleave::testing::gAllocations;
using cleave::testing::gCountAllocations;

namespace cleave::geometry {
namespace {

using testing::capArea;
using testing::closedAndOriented;
using testing::toCutSpace;

Plane planeOf(glm::dvec3 normal, double offset) {
  Plane p;
  p.normal = normal;
  p.offset = offset;
  return p;
}

// Unit cube [0,1]^3, 24 vertices (4 per face: UV and normal seams), CCW from outside, one run.
MeshData seamCube() {
  MeshData m;
  const glm::vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const glm::vec3& n : normals) {
    const glm::vec3 a = std::abs(n.x) > 0.5f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 b = glm::cross(n, a);
    const glm::vec3 centre = glm::vec3(0.5f) + 0.5f * n;
    const uint32_t base = static_cast<uint32_t>(m.positions.size());
    const glm::vec2 corners[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (const glm::vec2& c : corners) {
      m.positions.push_back(centre + 0.5f * c.x * a + 0.5f * c.y * b);
      m.normals.push_back(n);
      m.tangents.emplace_back(a, 1.f);
      m.uv0.push_back(0.5f * (c + 1.f));
    }
    for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) m.indices.push_back(base + i);
  }
  return m;
}

// Adds the quad a-b-c-d (a cycle, either orientation) as two triangles facing `outward`; `other`
// picks the diagonal b-d instead of a-c.
void addQuad(MeshData& m, uint32_t a, uint32_t b, uint32_t c, uint32_t d, const glm::vec3& outward,
             bool other = false) {
  const glm::vec3 n = glm::cross(m.positions[b] - m.positions[a], m.positions[c] - m.positions[a]);
  if (glm::dot(n, outward) < 0.f) std::swap(b, d);
  if (!other) {
    for (uint32_t i : {a, b, c, a, c, d}) m.indices.push_back(i);
  } else {
    for (uint32_t i : {a, b, d, b, c, d}) m.indices.push_back(i);
  }
}

// Box [lo, hi] with 8 shared vertices; `otherDiagonal` flips the diagonal of the y faces.
MeshData box8(const glm::vec3& lo, const glm::vec3& hi, bool otherDiagonal = false) {
  MeshData m;
  for (int i = 0; i < 8; ++i) {
    m.positions.emplace_back(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
  }
  addQuad(m, 0, 2, 6, 4, {-1, 0, 0});
  addQuad(m, 1, 3, 7, 5, {1, 0, 0});
  addQuad(m, 0, 1, 5, 4, {0, -1, 0}, otherDiagonal);
  addQuad(m, 2, 3, 7, 6, {0, 1, 0}, otherDiagonal);
  addQuad(m, 0, 1, 3, 2, {0, 0, -1});
  addQuad(m, 4, 5, 7, 6, {0, 0, 1});
  return m;
}

void append(MeshData& a, const MeshData& b) {
  const uint32_t base = static_cast<uint32_t>(a.positions.size());
  a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
  for (uint32_t i : b.indices) a.indices.push_back(base + i);
}

// A square ring prism: outer square [-R, R]^2 and hole [-r, r]^2 in xz, y in [0, h]; 16 vertices.
MeshData squareRing(float R, float r, float h) {
  MeshData m;
  const glm::vec2 corners[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  for (float y : {0.f, h}) {
    for (const glm::vec2& c : corners) m.positions.emplace_back(R * c.x, y, R * c.y);  // outer: 0-3, 8-11
    for (const glm::vec2& c : corners) m.positions.emplace_back(r * c.x, y, r * c.y);  // inner: 4-7, 12-15
  }
  for (uint32_t i = 0; i < 4; ++i) {
    const uint32_t j = (i + 1) % 4;
    const glm::vec2 mid = 0.5f * (corners[i] + corners[j]);
    const glm::vec3 away(mid.x, 0.f, mid.y);
    addQuad(m, i, j, 8 + j, 8 + i, away);                  // outer wall, facing out
    addQuad(m, 4 + i, 4 + j, 12 + j, 12 + i, -away);       // hole wall, facing into the hole
    addQuad(m, 8 + i, 8 + j, 12 + j, 12 + i, {0, 1, 0});   // top
    addQuad(m, i, j, 4 + j, 4 + i, {0, -1, 0});            // bottom
  }
  return m;
}

struct Split {
  SplitStatus status;
  SplitResult result;
};

Split run(const MeshData& mesh, const Plane& plane, SplitOptions options = {}, const glm::mat4& model = glm::mat4(1.f),
          bool convex = false) {
  MeshContainer container;
  EXPECT_EQ(container.setMesh(mesh).message, "");
  container.setTransform(model);
  auto splitter = convex ? makeConvexSplitter() : makeConcaveSplitter();
  Split s;
  s.status = splitter->split(container, plane, options, s.result);
  EXPECT_EQ(s.status, s.result.status);
  return s;
}

double pieceVolumeInSource(const MeshData& m) {
  return testing::signedVolume(toCutSpace(m, glm::dmat4(1.0)), m.indices);
}

void expectClosed(const MeshData& m) {
  const std::vector<glm::dvec3> p = toCutSpace(m, glm::dmat4(1.0));
  EXPECT_TRUE(closedAndOriented(p, m.indices, 1e-9));  // exact positions: tolerance only for rounding
}

double minTriangleArea(const MeshData& m) {
  double smallest = INFINITY;
  for (size_t t = 0; t < m.indices.size(); t += 3) {
    smallest = std::min(smallest, testing::triangleArea(glm::dvec3(m.positions[m.indices[t]]),
                                                        glm::dvec3(m.positions[m.indices[t + 1]]),
                                                        glm::dvec3(m.positions[m.indices[t + 2]])));
  }
  return smallest;
}

// Every vertex of the cap run of `m`: calls f(vertex index).
template <typename F>
void forCapVertices(const MeshData& m, uint32_t capMaterial, F f) {
  for (const SubMesh& run : m.submeshes) {
    if (run.materialId != capMaterial) continue;
    for (uint32_t k = run.firstIndex; k < run.firstIndex + run.indexCount; ++k) f(m.indices[k]);
  }
}

// ---------------------------------------------------------------------------------------------

TEST(ConcaveSplitter, UnitCubeCutAtHalfGivesTwoBoxes) {
  Split s = run(seamCube(), planeOf({1, 0, 0}, 0.5));
  ASSERT_EQ(s.status, SplitStatus::Ok) << s.result.message;
  EXPECT_TRUE(s.result.message.empty());
  EXPECT_EQ(s.result.sectionLoops, 1u);
  ASSERT_EQ(s.result.pieces.size(), 2u);
  for (const SplitPiece& piece : s.result.pieces) {
    const double sign = piece.side;  // above first: x > 0.5
    EXPECT_NEAR(piece.mass.volume, 0.5, 1e-12);
    EXPECT_TRUE(piece.mass.closed);
    EXPECT_NEAR(piece.mass.centerOfMass.x, 0.5 + 0.25 * sign, 1e-12);
    EXPECT_NEAR(piece.mass.centerOfMass.y, 0.5, 1e-12);
    EXPECT_NEAR(pieceVolumeInSource(piece.mesh), 0.5, 1e-7);
    EXPECT_EQ(piece.capLoops, 1u);
    // The square's 4 corners and, where each side face's diagonal crosses the plane, 4 collinear
    // points that must stay (no T-junction): 8 points, 6 triangles.
    EXPECT_EQ(piece.capTriangles, 6u);
    uint32_t capTriangles = 0;
    EXPECT_NEAR(capArea(piece.mesh, 1, glm::dmat4(1.0), &capTriangles), 1.0, 1e-7);
    EXPECT_EQ(capTriangles, 6u);
    expectClosed(piece.mesh);
    ASSERT_EQ(piece.mesh.submeshes.size(), 2u);  // the cube's run, then the cap run
    EXPECT_EQ(piece.mesh.submeshes[0].materialId, 0u);
    EXPECT_EQ(piece.mesh.submeshes[1].materialId, 1u);
    // Cap vertices: on the plane, normal out of the piece (opposite per side), tangent w = +1.
    forCapVertices(piece.mesh, 1, [&](uint32_t v) {
      EXPECT_FLOAT_EQ(piece.mesh.positions[v].x, 0.5f);
      EXPECT_EQ(piece.mesh.normals[v], glm::vec3(-float(sign), 0.f, 0.f));
      EXPECT_NEAR(glm::dot(glm::vec3(piece.mesh.tangents[v]), piece.mesh.normals[v]), 0.f, 1e-6f);
      EXPECT_EQ(piece.mesh.tangents[v].w, 1.f);
    });
    // Side vertices stay on their side.
    for (const glm::vec3& p : piece.mesh.positions) EXPECT_GE(sign * (p.x - 0.5f), 0.f);
  }
  EXPECT_EQ(s.result.pieces[0].side, 1);
  EXPECT_EQ(s.result.pieces[1].side, -1);
}

TEST(ConcaveSplitter, CapUvsAreWorldPlanarOrNormalisedAndMappedIntoTheAtlas) {
  SplitOptions options;
  options.uvPerMetre = 2.0;
  options.atlasRect = {0.5f, 0.f, 0.5f, 0.5f};
  Split s = run(seamCube(), planeOf({1, 0, 0}, 0.5), options);
  ASSERT_EQ(s.status, SplitStatus::Ok);
  // For the normal +x the basis is u = +z, v = -y; the above cap mirrors u so that its tangent (-z)
  // keeps w = +1 seen from outside.
  for (const SplitPiece& piece : s.result.pieces) {
    forCapVertices(piece.mesh, 1, [&](uint32_t v) {
      const glm::vec3 p = piece.mesh.positions[v];
      const float u = piece.side < 0 ? p.z : -p.z;
      EXPECT_NEAR(piece.mesh.uv0[v].x, 0.5f + 0.5f * 2.f * u, 1e-6f);
      EXPECT_NEAR(piece.mesh.uv0[v].y, 0.5f * 2.f * -p.y, 1e-6f);
      EXPECT_NEAR(piece.mesh.tangents[v].z, piece.side < 0 ? 1.f : -1.f, 1e-6f);
    });
  }
  options.uvMode = CapUvMode::NormalizedBounds;
  options.atlasRect = {0.f, 0.f, 1.f, 1.f};
  s = run(seamCube(), planeOf({1, 0, 0}, 0.5), options);
  ASSERT_EQ(s.status, SplitStatus::Ok);
  for (const SplitPiece& piece : s.result.pieces) {
    forCapVertices(piece.mesh, 1, [&](uint32_t v) {
      const glm::vec3 p = piece.mesh.positions[v];
      EXPECT_NEAR(piece.mesh.uv0[v].x, piece.side < 0 ? p.z : 1.f - p.z, 1e-6f);
      EXPECT_NEAR(piece.mesh.uv0[v].y, 1.f - p.y, 1e-6f);
    });
  }
}

// Thesis failure case 1: the plane z = x passes through cube vertices and, on the y faces, through a
// vertex of each triangle and its opposite edge. Each such triangle must split into exactly two
// proper triangles through the vertex, never a zero-area sliver.
TEST(ConcaveSplitter, CubeCutThroughAVertexAndTheOppositeEdge) {
  for (bool otherDiagonal : {false, true}) {
    SCOPED_TRACE(otherDiagonal ? "y faces split along the crossing diagonal" : "y faces split along the plane");
    const MeshData cube = box8(glm::vec3(0.f), glm::vec3(1.f), otherDiagonal);
    Split s = run(cube, planeOf({-1, 0, 1}, 0.0));
    ASSERT_EQ(s.status, SplitStatus::Ok) << s.result.message;
    ASSERT_EQ(s.result.pieces.size(), 2u);
    EXPECT_EQ(s.result.sectionLoops, 1u);
    for (const SplitPiece& piece : s.result.pieces) {
      EXPECT_NEAR(piece.mass.volume, 0.5, 1e-12);
      EXPECT_NEAR(capArea(piece.mesh, 1, glm::dmat4(1.0)), std::sqrt(2.0), 1e-6);
      EXPECT_GT(minTriangleArea(piece.mesh), 0.1) << "a sliver triangle";
      expectClosed(piece.mesh);
      // A triangular prism and its cap corners; the crossing diagonals add a cut point on each y face,
      // which is also a (collinear) cap point.
      EXPECT_EQ(piece.mesh.vertexCount(), otherDiagonal ? 6u + 2u + 6u : 6u + 4u);
    }
  }
}

// Thesis failure case 2: the first vertex of a triangle lies on the plane.
TEST(ConcaveSplitter, FirstTriangleVertexOnThePlane) {
  const MeshData tetra = testing::cornerTetrahedron();
  Split s = run(tetra, planeOf({1, -1, 0}, 0.0));  // x = y: through (0,0,0) and (0,0,1)
  ASSERT_EQ(s.status, SplitStatus::Ok) << s.result.message;
  ASSERT_EQ(s.result.pieces.size(), 2u);
  const double cap = 0.5 * glm::length(glm::cross(glm::dvec3(0, 0, 1), glm::dvec3(0.5, 0.5, 0)));
  for (const SplitPiece& piece : s.result.pieces) {
    EXPECT_NEAR(piece.mass.volume, 1.0 / 12.0, 1e-12);
    EXPECT_NEAR(capArea(piece.mesh, 1, glm::dmat4(1.0)), cap, 1e-7);
    EXPECT_EQ(piece.capTriangles, 1u);
    EXPECT_GT(minTriangleArea(piece.mesh), 0.05);
    expectClosed(piece.mesh);
  }
}

TEST(ConcaveSplitter, PlaneThroughAFaceLeavesOneSideEmptyAndMisses) {
  const MeshData cube = box8(glm::vec3(0.f), glm::vec3(1.f));
  SplitResult result;
  auto splitter = makeConcaveSplitter();
  MeshContainer container;
  ASSERT_EQ(container.setMesh(cube).code, SplitStatus::Ok);
  ASSERT_EQ(splitter->split(container, planeOf({1, 0, 0}, 0.5), {}, result), SplitStatus::Ok);
  ASSERT_EQ(result.pieces.size(), 2u);
  for (const Plane& plane : {planeOf({1, 0, 0}, 0.0), planeOf({-1, 0, 0}, 0.0), planeOf({0, 1, 0}, 1.0),
                             planeOf({0, 0, -2}, -2.0)}) {
    EXPECT_EQ(splitter->split(container, plane, {}, result), SplitStatus::PlaneMissesMesh);
    EXPECT_EQ(result.status, SplitStatus::PlaneMissesMesh);
    EXPECT_TRUE(result.pieces.empty()) << "no partial output";
    EXPECT_FALSE(result.message.empty());
  }
}

TEST(ConcaveSplitter, PlaneMissingTheMesh) {
  Split s = run(seamCube(), planeOf({0, 1, 0}, 5.0));
  EXPECT_EQ(s.status, SplitStatus::PlaneMissesMesh);
  EXPECT_TRUE(s.result.pieces.empty());
  s = run(seamCube(), planeOf({1, 1, 1}, -0.01));
  EXPECT_EQ(s.status, SplitStatus::PlaneMissesMesh);
}

TEST(ConcaveSplitter, TetrahedronCutAcross) {
  Split s = run(testing::cornerTetrahedron(), planeOf({0, 0, 1}, 0.5));
  ASSERT_EQ(s.status, SplitStatus::Ok) << s.result.message;
  ASSERT_EQ(s.result.pieces.size(), 2u);
  EXPECT_NEAR(s.result.pieces[0].mass.volume, 1.0 / 48.0, 1e-12);
  EXPECT_NEAR(s.result.pieces[1].mass.volume, 7.0 / 48.0, 1e-12);
  for (const SplitPiece& piece : s.result.pieces) {
    EXPECT_NEAR(capArea(piece.mesh, 1, glm::dmat4(1.0)), 0.125, 1e-7);
    expectClosed(piece.mesh);
  }
}

TEST(ConcaveSplitter, SeamCubeCutObliquelyIsWatertight) {
  const MeshData cube = seamCube();
  for (const Plane& plane : {planeOf({1, 2, 3}, 3.0), planeOf({0.3, -1, 0.2}, -0.3), planeOf({1, 1, 0}, 1.0)}) {
    Split s = run(cube, plane);
    ASSERT_EQ(s.status, SplitStatus::Ok) << s.result.message;
    double volume = 0.0;
    for (const SplitPiece& piece : s.result.pieces) {
      expectClosed(piece.mesh);  // every edge shared by exactly two triangles, in opposite directions
      volume += piece.mass.volume;
      // Seam vertices keep their own UVs: every vertex's normal is one of the six face normals or,
      // for a cap vertex, the cap normal.
      const glm::vec3 capNormal = glm::normalize(glm::vec3(plane.normal)) * float(-piece.side);
      for (const glm::vec3& n : piece.mesh.normals) {
        const float largest = std::max({std::abs(n.x), std::abs(n.y), std::abs(n.z)});
        EXPECT_TRUE(std::abs(largest - 1.f) < 1e-6f || glm::length(n - capNormal) < 1e-6f);
      }
    }
    EXPECT_NEAR(volume, 1.0, 1e-12);
  }
}

TEST(ConcaveSplitter, MirroredTransformKeepsVolumesPositiveAndWindingOutward) {
  const glm::mat4 model = glm::translate(glm::mat4(1.f), glm::vec3(3, 0, 0)) *
                          glm::scale(glm::mat4(1.f), glm::vec3(-2.f, 1.f, 1.f));  // x' = 3 - 2x
  Split s = run(seamCube(), planeOf({1, 0, 0}, 2.0), {}, model);  // x' = 2 <=> x = 0.5
  ASSERT_EQ(s.status, SplitStatus::Ok) << s.result.message;
  ASSERT_EQ(s.result.pieces.size(), 2u);
  for (const SplitPiece& piece : s.result.pieces) {
    EXPECT_NEAR(piece.mass.volume, 1.0, 1e-12);  // half of the doubled cube
    EXPECT_NEAR(pieceVolumeInSource(piece.mesh), 0.5, 1e-7);  // outward in source space
    expectClosed(piece.mesh);
    // Above (x' > 2) is source x < 0.5: the cap normal there points to +x in source space.
    forCapVertices(piece.mesh, 1, [&](uint32_t v) {
      EXPECT_NEAR(piece.mesh.normals[v].x, piece.side > 0 ? 1.f : -1.f, 1e-6f);
    });
  }
  EXPECT_NEAR(s.result.pieces[0].mass.centerOfMass.x, 2.5, 1e-12);
}

TEST(ConcaveSplitter, InvalidInputGivesNoPieces) {
  MeshData bad = seamCube();
  bad.positions[0].x = std::numeric_limits<float>::quiet_NaN();
  MeshContainer container;
  MeshStatus set = container.setMesh(bad);
  EXPECT_EQ(set.code, SplitStatus::InvalidInput);
  EXPECT_FALSE(set.message.empty());
  auto splitter = makeConcaveSplitter();
  SplitResult result;
  MeshContainer good;
  ASSERT_EQ(good.setMesh(seamCube()).code, SplitStatus::Ok);
  ASSERT_EQ(splitter->split(good, planeOf({1, 0, 0}, 0.5), {}, result), SplitStatus::Ok);
  EXPECT_EQ(splitter->split(container, planeOf({1, 0, 0}, 0.5), {}, result), SplitStatus::InvalidInput);
  EXPECT_TRUE(result.pieces.empty());
  EXPECT_FALSE(result.message.empty());

  bad = seamCube();
  bad.indices[4] = 99;
  set = container.setMesh(bad);
  EXPECT_EQ(set.code, SplitStatus::InvalidInput);
  EXPECT_NE(set.message.find("99"), std::string::npos) << set.message;
  EXPECT_EQ(splitter->split(container, planeOf({1, 0, 0}, 0.5), {}, result), SplitStatus::InvalidInput);
  EXPECT_TRUE(result.pieces.empty());

  EXPECT_EQ(splitter->split(good, planeOf({0, 0, 0}, 0.5), {}, result), SplitStatus::InvalidInput);
  EXPECT_EQ(splitter->split(good, planeOf({1, 0, 0}, NAN), {}, result), SplitStatus::InvalidInput);
}

TEST(ConcaveSplitter, TwoDisjointBoxesGiveFourPiecesOrTwoWithoutIslands) {
  MeshData boxes = box8(glm::vec3(0.f), glm::vec3(1.f));
  append(boxes, box8(glm::vec3(2.f, 0.f, 0.f), glm::vec3(3.f, 2.f, 1.f)));
  Split s = run(boxes, planeOf({0, 1, 0}, 0.5));
  ASSERT_EQ(s.status, SplitStatus::Ok) << s.result.message;
  ASSERT_EQ(s.result.pieces.size(), 4u);
  EXPECT_EQ(s.result.sectionLoops, 2u);
  const double volumes[4] = {0.5, 1.5, 0.5, 0.5};  // above: first box, second box; then below
  const int sides[4] = {1, 1, -1, -1};
  for (size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(s.result.pieces[k].side, sides[k]);
    EXPECT_NEAR(s.result.pieces[k].mass.volume, volumes[k], 1e-12) << k;
    EXPECT_EQ(s.result.pieces[k].capLoops, 1u);
    expectClosed(s.result.pieces[k].mesh);
  }
  EXPECT_LT(s.result.pieces[0].mass.centerOfMass.x, 1.0);  // ordered by smallest source triangle

  SplitOptions whole;
  whole.separateIslands = false;
  s = run(boxes, planeOf({0, 1, 0}, 0.5), whole);
  ASSERT_EQ(s.status, SplitStatus::Ok);
  ASSERT_EQ(s.result.pieces.size(), 2u);
  EXPECT_NEAR(s.result.pieces[0].mass.volume, 2.0, 1e-12);
  EXPECT_NEAR(s.result.pieces[1].mass.volume, 1.0, 1e-12);
  EXPECT_EQ(s.result.pieces[0].capLoops, 2u);
  EXPECT_EQ(s.result.pieces[0].capTriangles, 2u * 6u);  // 4 corners + 4 diagonal crossings per loop
}

TEST(ConcaveSplitter, PlaneBetweenTwoBoxesSeparatesThemWithoutCaps) {
  MeshData boxes = box8(glm::vec3(0.f), glm::vec3(1.f));
  append(boxes, box8(glm::vec3(2.f, 0.f, 0.f), glm::vec3(3.f, 1.f, 1.f)));
  Split s = run(boxes, planeOf({1, 0, 0}, 1.5));
  ASSERT_EQ(s.status, SplitStatus::Ok) << s.result.message;
  ASSERT_EQ(s.result.pieces.size(), 2u);
  EXPECT_EQ(s.result.sectionLoops, 0u);
  for (const SplitPiece& piece : s.result.pieces) {
    EXPECT_EQ(piece.capTriangles, 0u);
    EXPECT_NEAR(piece.mass.volume, 1.0, 1e-12);
  }
}

TEST(ConcaveSplitter, SquareRingCutHorizontallyGivesAnAnnulus) {
  const MeshData ring = squareRing(1.5f, 0.5f, 1.f);  // outer 3 x 3, hole 1 x 1
  for (bool convex : {false, true}) {  // the convex splitter falls back to the general path
    Split s = run(ring, planeOf({0, 1, 0}, 0.5), {}, glm::mat4(1.f), convex);
    ASSERT_EQ(s.status, SplitStatus::Ok) << s.result.message;
    EXPECT_EQ(s.result.sectionLoops, 2u);
    ASSERT_EQ(s.result.pieces.size(), 2u);
    for (const SplitPiece& piece : s.result.pieces) {
      EXPECT_EQ(piece.capLoops, 2u);
      EXPECT_NEAR(piece.mass.volume, 4.0, 1e-12);
      EXPECT_NEAR(capArea(piece.mesh, 1, glm::dmat4(1.0)), 9.0 - 1.0, 1e-6);
      expectClosed(piece.mesh);
    }
  }
}

TEST(ConcaveSplitter, IslandInAHoleInAnIsland) {
  MeshData scene = squareRing(2.5f, 1.5f, 1.f);                          // area 25 - 9
  append(scene, box8(glm::vec3(-0.5f, 0.f, -0.5f), glm::vec3(0.5f, 1.f, 0.5f)));  // area 1, in the hole
  Split s = run(scene, planeOf({0, 1, 0}, 0.25));
  ASSERT_EQ(s.status, SplitStatus::Ok) << s.result.message;
  EXPECT_EQ(s.result.sectionLoops, 3u);
  ASSERT_EQ(s.result.pieces.size(), 4u);
  const double areas[4] = {16.0, 1.0, 16.0, 1.0};
  const uint32_t loops[4] = {2, 1, 2, 1};
  for (size_t k = 0; k < 4; ++k) {
    const SplitPiece& piece = s.result.pieces[k];
    EXPECT_NEAR(capArea(piece.mesh, 1, glm::dmat4(1.0)), areas[k], 1e-6) << k;
    EXPECT_EQ(piece.capLoops, loops[k]) << k;
    EXPECT_NEAR(piece.mass.volume, areas[k] * (piece.side > 0 ? 0.75 : 0.25), 1e-12) << k;
    expectClosed(piece.mesh);
  }
}

TEST(ConcaveSplitter, HollowSphereCavityStaysWithItsShell) {
  // The plane only grazes the outer sphere: the inner (inward) sphere lies whole on one side and is a
  // cavity of that side's piece, not a piece of its own.
  const MeshData shell = primitives::hollowSphere(1.f, 0.5f, 24, 12);
  Split s = run(shell, planeOf({0, 1, 0}, 0.7));
  ASSERT_EQ(s.status, SplitStatus::Ok) << s.result.message;
  ASSERT_EQ(s.result.pieces.size(), 2u);
  for (const SplitPiece& piece : s.result.pieces) EXPECT_GT(piece.mass.volume, 0.0);
}

TEST(ConcaveSplitter, CavityGoesWithTheSmallestPartAroundIt) {
  // Three spheres about one centre: radius 3 facing out (cut near its top), 2 facing out (whole,
  // below the plane) and 1 facing in (whole, inside both). The cavity belongs to the smaller of the
  // two outward parts around it; with strict connectivity the two stay apart.
  auto sphere = [](float radius, bool inward) {
    MeshData m = primitives::uvSphere(radius, 48, 24);
    if (inward) {
      for (size_t t = 0; t + 2 < m.indices.size(); t += 3) std::swap(m.indices[t + 1], m.indices[t + 2]);
      for (glm::vec3& n : m.normals) n = -n;
    }
    return m;
  };
  MeshData all;
  for (const MeshData& part : {sphere(3.f, false), sphere(2.f, false), sphere(1.f, true)}) {
    const uint32_t base = static_cast<uint32_t>(all.positions.size());
    all.positions.insert(all.positions.end(), part.positions.begin(), part.positions.end());
    all.normals.insert(all.normals.end(), part.normals.begin(), part.normals.end());
    all.uv0.insert(all.uv0.end(), part.uv0.begin(), part.uv0.end());
    for (uint32_t i : part.indices) all.indices.push_back(base + i);
  }
  const double middle = computeMassProperties(sphere(2.f, false)).volume;
  const double cavity = -computeMassProperties(sphere(1.f, true)).volume;
  ASSERT_GT(middle, 0.0);
  ASSERT_GT(cavity, 0.0);
  SplitOptions options;
  options.islands = IslandMode::Connected;
  Split s = run(all, planeOf({0, 1, 0}, 2.5), options);
  ASSERT_EQ(s.status, SplitStatus::Ok) << s.result.message;
  ASSERT_EQ(s.result.pieces.size(), 3u);  // the cap above; below, the big part and the middle one
  int found = 0;
  for (const SplitPiece& piece : s.result.pieces) {
    EXPECT_GT(piece.mass.volume, 0.0);
    if (std::abs(piece.mass.volume - (middle - cavity)) < 1e-9 * middle) ++found;
  }
  EXPECT_EQ(found, 1) << "the middle sphere with the cavity in it, as one piece";
}

TEST(ConcaveSplitter, CapSubmeshIsReusedWhenAPieceIsCutAgain) {
  SplitOptions options;
  options.capMaterialId = 3;
  Split first = run(seamCube(), planeOf({1, 0, 0}, 0.5), options);
  ASSERT_EQ(first.status, SplitStatus::Ok);
  const MeshData piece = first.result.pieces[1].mesh;  // x < 0.5: runs {0, 3}
  ASSERT_EQ(piece.submeshes.size(), 2u);
  Split second = run(piece, planeOf({0, 0, 1}, 0.5), options);
  ASSERT_EQ(second.status, SplitStatus::Ok) << second.result.message;
  ASSERT_EQ(second.result.pieces.size(), 2u);
  for (const SplitPiece& p : second.result.pieces) {
    ASSERT_EQ(p.mesh.submeshes.size(), 2u) << "no growth in submesh count";
    EXPECT_EQ(p.mesh.submeshes[0].materialId, 0u);
    EXPECT_EQ(p.mesh.submeshes[1].materialId, 3u);
    EXPECT_EQ(p.capTriangles, p.mesh.submeshes[1].indexCount / 3);
    EXPECT_NEAR(capArea(p.mesh, 3, glm::dmat4(1.0)), 0.5 + 0.5, 1e-7);
    EXPECT_NEAR(p.mass.volume, 0.25, 1e-12);
    expectClosed(p.mesh);
  }
}

TEST(ConcaveSplitter, HollowModeMakesNoCapsAndAllowsOpenSections) {
  SplitOptions hollow;
  hollow.cap = false;
  Split s = run(seamCube(), planeOf({1, 0, 0}, 0.5), hollow);
  ASSERT_EQ(s.status, SplitStatus::Ok);
  ASSERT_EQ(s.result.pieces.size(), 2u);
  for (const SplitPiece& piece : s.result.pieces) {
    EXPECT_EQ(piece.capTriangles, 0u);
    EXPECT_EQ(piece.mesh.triangleCount(), 2u + 4u * 3u);  // one whole face; 3 triangles of each cut face
  }
  MeshData open = seamCube();
  open.indices.resize(open.indices.size() - 6);  // drop the z = 0 face
  SplitOptions refuse;
  refuse.openSections = OpenSectionMode::Refuse;
  s = run(open, planeOf({1, 0, 0}, 0.5), refuse);
  EXPECT_EQ(s.status, SplitStatus::OpenSection);
  EXPECT_TRUE(s.result.pieces.empty());
  EXPECT_FALSE(s.result.message.empty());
  s = run(open, planeOf({1, 0, 0}, 0.5), hollow);
  EXPECT_EQ(s.status, SplitStatus::Ok);
  EXPECT_EQ(s.result.pieces.size(), 2u);
}

// Art that is not watertight is cut anyway (the default, OpenSectionMode::CapClosedLoops): the
// closed loops of the section are capped, the open chains are left open and counted, and pieces
// along an open chain are open (weld not closed, mass from the hull).
TEST(ConcaveSplitter, OpenArtIsCutWithItsClosedLoopsCappedAndItsOpenChainsReported) {
  MeshData open = seamCube();
  open.indices.resize(open.indices.size() - 6);  // drop the z = 0 face
  Split s = run(open, planeOf({1, 0, 0}, 0.5));
  ASSERT_EQ(s.status, SplitStatus::Ok) << s.result.message;
  ASSERT_EQ(s.result.pieces.size(), 2u);
  EXPECT_EQ(s.result.openChains, 1u);
  EXPECT_EQ(s.result.sectionLoops, 0u);
  for (const SplitPiece& piece : s.result.pieces) {
    EXPECT_EQ(piece.capTriangles, 0u);
    EXPECT_FALSE(piece.weld.closed);
    EXPECT_TRUE(piece.mass.fromConvexHull);
    EXPECT_NEAR(piece.mass.volume, 0.5, 1e-12);  // the hull of half a cube
  }
  // Parallel to the missing face: the section is a closed loop and is capped.
  s = run(open, planeOf({0, 0, 1}, 0.25));
  ASSERT_EQ(s.status, SplitStatus::Ok) << s.result.message;
  EXPECT_EQ(s.result.openChains, 0u);
  EXPECT_EQ(s.result.sectionLoops, 1u);
  for (const SplitPiece& piece : s.result.pieces) EXPECT_EQ(piece.capLoops, 1u);

  // A closed sphere and an open one cut together: the closed one's loop is capped, the other's chain
  // reported.
  MeshData closedBall = primitives::uvSphere(0.5f, 16, 8);
  MeshData openBall = primitives::uvSphere(0.5f, 16, 8);
  primitives::transform(openBall, glm::translate(glm::mat4(1.f), glm::vec3(2.f, 0.f, 0.f)));
  std::vector<uint32_t> kept;
  for (size_t t = 0; t + 2 < openBall.indices.size(); t += 3) {
    const glm::vec3 c = (openBall.positions[openBall.indices[t]] + openBall.positions[openBall.indices[t + 1]] +
                         openBall.positions[openBall.indices[t + 2]]) / 3.f;
    if (c.z > 0.3f && std::abs(c.y) < 0.2f) continue;  // a window across the equator
    kept.insert(kept.end(), {openBall.indices[t], openBall.indices[t + 1], openBall.indices[t + 2]});
  }
  ASSERT_LT(kept.size(), openBall.indices.size());
  openBall.indices = kept;
  s = run(primitives::merge(closedBall, openBall), planeOf({0, 1, 0}, 0.01));
  ASSERT_EQ(s.status, SplitStatus::Ok) << s.result.message;
  EXPECT_EQ(s.result.openChains, 1u);
  EXPECT_EQ(s.result.sectionLoops, 1u);
  size_t capped = 0;
  for (const SplitPiece& piece : s.result.pieces) capped += piece.capLoops;
  EXPECT_EQ(capped, 2u);  // the closed sphere's loop, on both of its halves
  SplitOptions refuse;
  refuse.openSections = OpenSectionMode::Refuse;
  s = run(primitives::merge(closedBall, openBall), planeOf({0, 1, 0}, 0.01), refuse);
  EXPECT_EQ(s.status, SplitStatus::OpenSection);
  EXPECT_TRUE(s.result.pieces.empty());
}

// Open art whose shells are wound both ways: a loop that cannot be capped (it would be a hole outside
// every border) is left open and counted, the others are capped; the strict mode refuses the cut.
// A sphere with a window across its equator, cut through the window: the section is an arc.
MeshData ballWithWindow(uint32_t segments, uint32_t rings) {
  MeshData ball = primitives::uvSphere(0.5f, segments, rings);
  std::vector<uint32_t> kept;
  for (size_t t = 0; t + 2 < ball.indices.size(); t += 3) {
    const glm::vec3 c = (ball.positions[ball.indices[t]] + ball.positions[ball.indices[t + 1]] +
                         ball.positions[ball.indices[t + 2]]) / 3.f;
    if (c.z > 0.3f && std::abs(c.y) < 0.2f) continue;
    kept.insert(kept.end(), {ball.indices[t], ball.indices[t + 1], ball.indices[t + 2]});
  }
  ball.indices = kept;
  return ball;
}

TEST(ConcaveSplitter, BridgeClosesAnOpenChainByItsChordAndCapsIt) {
  SplitOptions bridge;
  bridge.openSections = OpenSectionMode::Bridge;
  // The cube without its z = 0 face, cut by x = 0.5: the section is three sides of a square.
  MeshData open = seamCube();
  open.indices.resize(open.indices.size() - 6);
  Split s = run(open, planeOf({1, 0, 0}, 0.5), bridge);
  ASSERT_EQ(s.status, SplitStatus::Ok) << s.result.message;
  EXPECT_EQ(s.result.openChains, 0u);
  EXPECT_EQ(s.result.bridgedChains, 1u);
  ASSERT_EQ(s.result.pieces.size(), 2u);
  for (const SplitPiece& piece : s.result.pieces) {
    EXPECT_EQ(piece.capLoops, 1u);
    EXPECT_NEAR(capArea(piece.mesh, bridge.capMaterialId, glm::dmat4(1.0)), 1.0, 1e-12);  // the whole square
    EXPECT_FALSE(piece.weld.closed);  // open along the chord, where the missing face was
    EXPECT_TRUE(piece.mass.fromConvexHull);
  }
  // The arc of the windowed ball is closed by its chord across the window.
  s = run(ballWithWindow(32, 16), planeOf({0, 1, 0}, 0.01), bridge);
  ASSERT_EQ(s.status, SplitStatus::Ok) << s.result.message;
  EXPECT_EQ(s.result.bridgedChains, 1u);
  EXPECT_EQ(s.result.openChains, 0u);
  for (const SplitPiece& piece : s.result.pieces) EXPECT_EQ(piece.capLoops, 1u);
  // Cap-closed leaves the same chain open.
  s = run(ballWithWindow(32, 16), planeOf({0, 1, 0}, 0.01));
  EXPECT_EQ(s.result.bridgedChains, 0u);
  EXPECT_EQ(s.result.openChains, 1u);
}

TEST(ConcaveSplitter, BridgeLeavesAChainOpenWhenItsChordWouldOverlapAnotherCap) {
  SplitOptions bridge;
  bridge.openSections = OpenSectionMode::Bridge;
  // A small closed ball across the window's chord: the chord crosses its loop.
  MeshData small = primitives::uvSphere(0.05f, 16, 8);
  primitives::transform(small, glm::translate(glm::mat4(1.f), glm::vec3(0.f, 0.f, 0.25f)));
  Split s = run(primitives::merge(ballWithWindow(32, 16), small), planeOf({0, 1, 0}, 0.01), bridge);
  ASSERT_EQ(s.status, SplitStatus::Ok) << s.result.message;
  EXPECT_EQ(s.result.bridgedChains, 0u);
  EXPECT_EQ(s.result.openChains, 1u);
  EXPECT_EQ(s.result.sectionLoops, 1u);  // the small ball's loop, capped
  // The open cube with a cavity inside: closed by its chord the chain would hold the cavity's loop,
  // so it is not a cap of its own and stays open; with its ends within the gap, it is closed as a
  // seam and capped with the cavity as its hole.
  MeshData cavity = primitives::box(glm::vec3(0.2f));
  for (size_t t = 0; t + 2 < cavity.indices.size(); t += 3) std::swap(cavity.indices[t + 1], cavity.indices[t + 2]);
  primitives::transform(cavity, glm::translate(glm::mat4(1.f), glm::vec3(0.5f)));
  MeshData open = seamCube();
  open.indices.resize(open.indices.size() - 6);
  const MeshData hollow = primitives::merge(open, cavity);
  s = run(hollow, planeOf({1, 0, 0}, 0.5), bridge);
  ASSERT_EQ(s.status, SplitStatus::Ok) << s.result.message;
  EXPECT_EQ(s.result.bridgedChains, 0u);
  EXPECT_EQ(s.result.openChains, 1u);
  bridge.bridgeGap = 1.0;  // of the bounds diagonal: the chain's ends, 1 apart, are within it
  s = run(hollow, planeOf({1, 0, 0}, 0.5), bridge);
  ASSERT_EQ(s.status, SplitStatus::Ok) << s.result.message;
  EXPECT_EQ(s.result.bridgedChains, 1u);
  for (const SplitPiece& piece : s.result.pieces) {
    EXPECT_NEAR(capArea(piece.mesh, bridge.capMaterialId, glm::dmat4(1.0)), 1.0 - 0.16, 1e-6);  // square less hole
  }
}

TEST(ConcaveSplitter, OpenArtLeavesALoopThatCannotBeCappedOpen) {
  MeshData windowed = primitives::uvSphere(0.5f, 16, 8);
  std::vector<uint32_t> kept;
  for (size_t t = 0; t + 2 < windowed.indices.size(); t += 3) {
    const glm::vec3 c = (windowed.positions[windowed.indices[t]] + windowed.positions[windowed.indices[t + 1]] +
                         windowed.positions[windowed.indices[t + 2]]) / 3.f;
    if (c.y > 0.4f) continue;  // open at the top, far from the cut
    kept.insert(kept.end(), {windowed.indices[t], windowed.indices[t + 1], windowed.indices[t + 2]});
  }
  windowed.indices = kept;
  MeshData inward = primitives::uvSphere(0.5f, 16, 8);
  primitives::transform(inward, glm::translate(glm::mat4(1.f), glm::vec3(2.f, 0.f, 0.f)));
  for (size_t t = 0; t + 2 < inward.indices.size(); t += 3) std::swap(inward.indices[t + 1], inward.indices[t + 2]);
  const MeshData art = primitives::merge(windowed, inward);
  Split s = run(art, planeOf({0, 1, 0}, 0.01));
  ASSERT_EQ(s.status, SplitStatus::Ok) << s.result.message;
  EXPECT_EQ(s.result.sectionLoops, 2u);
  EXPECT_EQ(s.result.uncappedLoops, 1u);
  EXPECT_EQ(s.result.openChains, 0u);
  size_t capped = 0;
  for (const SplitPiece& piece : s.result.pieces) capped += piece.capLoops;
  EXPECT_EQ(capped, 2u);  // the outward sphere's loop, on both halves
  SplitOptions refuse;
  refuse.openSections = OpenSectionMode::Refuse;
  s = run(art, planeOf({0, 1, 0}, 0.01), refuse);
  EXPECT_EQ(s.status, SplitStatus::TriangulationFailed);
  EXPECT_TRUE(s.result.pieces.empty());
}

// The one-call API gives what a container and a splitter give.
// A tip that pokes through the plane by one float step, far from the origin, with its three other
// corners placed so that the three cut points are distinct in double but round to one float: what
// lies above would be written as triangles of zero area. The cut leaves the mesh whole.
MeshData tipOneUlpAbove(float third) {
  const float up = std::nextafter(60.f, 100.f);
  MeshData m;
  m.positions = {{60.f, up, 60.f}, {59.7f, 59.f, 60.2f}, {60.3f, 59.f, 59.8f}, {60.f, 59.f, third}};
  m.indices = {0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2};
  if (testing::signedVolume(toCutSpace(m, glm::dmat4(1.0)), m.indices) < 0.0) {
    for (size_t t = 0; t < m.indices.size(); t += 3) std::swap(m.indices[t + 1], m.indices[t + 2]);
  }
  return m;
}

TEST(ConcaveSplitter, ATipWhoseCutPointsRoundToOneFloatIsNotCutOff) {
  const MeshData tip = tipOneUlpAbove(60.35f);
  SplitResult result = splitMesh(tip, glm::mat4(1.f), Plane{{0, 1, 0}, 60.0}, SplitOptions{});
  EXPECT_EQ(result.status, SplitStatus::PlaneMissesMesh) << result.message;
  EXPECT_TRUE(result.pieces.empty());
}

TEST(ConcaveSplitter, CutPointsThatRoundToOneFloatAreOnePointOfAClosedPiece) {
  // The fourth corner farther out: two of the three cut points still round to one float.
  const MeshData tip = tipOneUlpAbove(61.5f);
  SplitResult result = splitMesh(tip, glm::mat4(1.f), Plane{{0, 1, 0}, 60.0}, SplitOptions{});
  ASSERT_EQ(result.status, SplitStatus::Ok) << result.message;
  ASSERT_EQ(result.pieces.size(), 2u);
  for (const SplitPiece& piece : result.pieces) {
    EXPECT_TRUE(testing::manifoldOnFloats(piece.mesh)) << "side " << piece.side;
    // The coinciding cut points share one position id in the piece's weld.
    MeshContainer again;
    ASSERT_EQ(again.setMesh(piece.mesh, piece.weld).code, SplitStatus::Ok);
    EXPECT_TRUE(again.closed());
  }
}

TEST(SplitMesh, OneCallCutsLikeAContainerAndASplitter) {
  const glm::mat4 model = glm::translate(glm::mat4(1.f), glm::vec3(1.f, 2.f, 3.f));
  const SplitResult one = splitMesh(seamCube(), model, planeOf({1, 0, 0}, 1.3));
  ASSERT_EQ(one.status, SplitStatus::Ok) << one.message;
  const Split two = run(seamCube(), planeOf({1, 0, 0}, 1.3), {}, model);
  ASSERT_EQ(one.pieces.size(), two.result.pieces.size());
  for (size_t i = 0; i < one.pieces.size(); ++i) {
    EXPECT_EQ(one.pieces[i].mesh.positions, two.result.pieces[i].mesh.positions);
    EXPECT_EQ(one.pieces[i].mesh.indices, two.result.pieces[i].mesh.indices);
    EXPECT_EQ(one.pieces[i].mass.volume, two.result.pieces[i].mass.volume);
  }
  EXPECT_NEAR(one.pieces[0].mass.volume + one.pieces[1].mass.volume, 1.0, 1e-12);
  MeshData bad = seamCube();
  bad.indices.push_back(999);
  const SplitResult refused = splitMesh(bad, model, planeOf({1, 0, 0}, 1.3));
  EXPECT_EQ(refused.status, SplitStatus::InvalidInput);
  EXPECT_FALSE(refused.message.empty());
  EXPECT_TRUE(refused.pieces.empty());
}

// Islands of an open sheet (hollow mode): triangles joined only at a vertex are one island. The
// first triangle lists its corners with ids 2, 0, 1, so its union links 2 to 0 and then 2 to 1; the
// second shares only vertex 0 with it. Linking a vertex that is no longer a root would drop the link
// 2 -> 0 and part the two triangles.
TEST(ConcaveSplitter, HollowSheetJoinedAtOneVertexStaysOneIsland) {
  MeshData m;
  m.positions = {{0, 1, 0}, {-1, 2, 0}, {-1, 1.5f, 0}, {1, 0.5f, 0}, {1, 2, 0}, {0.5f, -1, 0}, {1.5f, -1, 0}};
  m.indices = {2, 0, 1, /**/ 0, 3, 4, /**/ 3, 5, 6};
  SplitOptions options;
  options.cap = false;
  const Split s = run(m, planeOf({0, 1, 0}, 0.0), options);
  ASSERT_EQ(s.status, SplitStatus::Ok) << s.result.message;
  int above = 0, below = 0;
  for (const SplitPiece& piece : s.result.pieces) (piece.side > 0 ? above : below)++;
  EXPECT_EQ(above, 1);
  EXPECT_EQ(below, 1);
}

TEST(ConcaveSplitter, NewVerticesInterpolateAttributesAndMergeSkinWeights) {
  MeshData cube = seamCube();
  for (const glm::vec3& p : cube.positions) {
    const bool right = p.x > 0.5f;
    cube.joints.emplace_back(right ? 4 : 2, 9, 0, 0);
    cube.weights.emplace_back(0.75f, 0.25f, 0.f, 0.f);
    cube.colors.emplace_back(p.x, 0.f, 0.f, 1.f);
  }
  Split s = run(cube, planeOf({1, 0, 0}, 0.25));
  ASSERT_EQ(s.status, SplitStatus::Ok);
  const MeshData& below = s.result.pieces[1].mesh;
  bool sawCut = false;
  for (size_t v = 0; v < below.positions.size(); ++v) {
    if (std::abs(below.positions[v].x - 0.25f) > 1e-6f) continue;
    sawCut = true;
    // Joint 2 at 0.75 * 0.75, joint 4 at 0.25 * 0.75, joint 9 at 0.25: sorted by weight.
    EXPECT_EQ(below.joints[v], glm::u16vec4(2, 9, 4, 0));
    EXPECT_NEAR(below.weights[v].x, 0.5625f, 1e-6f);
    EXPECT_NEAR(below.weights[v].y, 0.25f, 1e-6f);
    EXPECT_NEAR(below.weights[v].z, 0.1875f, 1e-6f);
    EXPECT_EQ(below.weights[v].w, 0.f);
    EXPECT_NEAR(below.colors[v].x, 0.25f, 1e-6f);
    EXPECT_NEAR(glm::length(below.normals[v]), 1.f, 1e-6f);
    EXPECT_NEAR(glm::length(glm::vec3(below.tangents[v])), 1.f, 1e-6f);
  }
  EXPECT_TRUE(sawCut);
}

TEST(ConvexSplitter, GivesTheSameVolumesAndCapsAsTheConcavePath) {
  const MeshData sphere = primitives::uvSphere(1.f, 24, 12);
  const Plane plane = planeOf({0.3, 1, -0.2}, 0.2);
  Split concave = run(sphere, plane);
  Split convex = run(sphere, plane, {}, glm::mat4(1.f), true);
  ASSERT_EQ(concave.status, SplitStatus::Ok);
  ASSERT_EQ(convex.status, SplitStatus::Ok) << convex.result.message;
  ASSERT_EQ(convex.result.pieces.size(), 2u);
  for (size_t k = 0; k < 2; ++k) {
    const SplitPiece &a = concave.result.pieces[k], &b = convex.result.pieces[k];
    EXPECT_NEAR(a.mass.volume, b.mass.volume, 1e-12);
    EXPECT_NEAR(capArea(a.mesh, 1, glm::dmat4(1.0)), capArea(b.mesh, 1, glm::dmat4(1.0)), 1e-6);
    EXPECT_EQ(a.capTriangles, b.capTriangles);  // a fan and ear clipping both give n - 2 triangles
    expectClosed(b.mesh);
  }
  // A cut through cube edges makes collinear cap points: they stay in the fan (no T-junction).
  Split cube = run(seamCube(), planeOf({1, 1, 0}, 1.0), {}, glm::mat4(1.f), true);
  ASSERT_EQ(cube.status, SplitStatus::Ok);
  for (const SplitPiece& piece : cube.result.pieces) expectClosed(piece.mesh);
}

// Every field of a split's result, bit for bit. Each struct is taken apart with a structured binding
// of all its members, so a field added to SplitResult, SplitPiece, MeshData, MeshWeld or
// MassProperties stops this from compiling until it is compared here too.
template <typename T>
bool sameArray(const std::vector<T>& x, const std::vector<T>& y) {
  return x.size() == y.size() && (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof(T)) == 0);
}

template <typename T>
bool sameValue(const T& x, const T& y) {
  return std::memcmp(&x, &y, sizeof(T)) == 0;
}

bool sameBytes(const MeshData& a, const MeshData& b) {
  const auto& [positions, normals, tangents, uv0, uv1, colors, joints, weights, indices, submeshes] = a;
  return sameArray(positions, b.positions) && sameArray(normals, b.normals) && sameArray(tangents, b.tangents) &&
         sameArray(uv0, b.uv0) && sameArray(uv1, b.uv1) && sameArray(colors, b.colors) &&
         sameArray(joints, b.joints) && sameArray(weights, b.weights) && sameArray(indices, b.indices) &&
         sameArray(submeshes, b.submeshes);
}

bool sameBytes(const MassProperties& a, const MassProperties& b) {
  const auto& [volume, centerOfMass, inertia, closed, fromConvexHull] = a;
  return sameValue(volume, b.volume) && sameValue(centerOfMass, b.centerOfMass) && sameValue(inertia, b.inertia) &&
         closed == b.closed && fromConvexHull == b.fromConvexHull;
}

bool sameBytes(const MeshWeld& a, const MeshWeld& b) {
  const auto& [positionIds, representatives, closed, inverted, connected] = a;
  return sameArray(positionIds, b.positionIds) && sameArray(representatives, b.representatives) &&
         closed == b.closed && inverted == b.inverted && connected == b.connected;
}

bool sameBytes(const SplitPiece& a, const SplitPiece& b) {
  const auto& [mesh, weld, side, capTriangles, capLoops, mass, joints, reached, sourceTriangles] = a;
  return sameBytes(mesh, b.mesh) && sameBytes(weld, b.weld) && side == b.side && capTriangles == b.capTriangles &&
         capLoops == b.capLoops && sameBytes(mass, b.mass) && sameArray(joints, b.joints) && reached == b.reached &&
         sameArray(sourceTriangles, b.sourceTriangles);
}

bool sameBytes(const SplitResult& a, const SplitResult& b) {
  const auto& [status, message, pieces, sectionLoops, openChains, bridgedChains, uncappedLoops, sidesDisagree,
               islandsFromSection, islandFromLoops] = a;
  if (status != b.status || message != b.message || pieces.size() != b.pieces.size() ||
      sectionLoops != b.sectionLoops || openChains != b.openChains || bridgedChains != b.bridgedChains ||
      uncappedLoops != b.uncappedLoops || sidesDisagree != b.sidesDisagree ||
      islandsFromSection != b.islandsFromSection || islandFromLoops != b.islandFromLoops) {
    return false;
  }
  for (size_t k = 0; k < pieces.size(); ++k)
    if (!sameBytes(pieces[k], b.pieces[k])) return false;
  return true;
}

// sameBytes sees a change in any one field.
TEST(ConcaveSplitter, SameBytesSeesEveryField) {
  const Split base = run(primitives::torus(1.f, 0.3f, 16, 8), planeOf({0.1, 1, 0.05}, 0.02));
  ASSERT_EQ(base.status, SplitStatus::Ok);
  ASSERT_TRUE(sameBytes(base.result, base.result));
  const std::vector<void (*)(SplitResult&)> changes = {
      [](SplitResult& r) { r.message.push_back('x'); },
      [](SplitResult& r) { ++r.sectionLoops; },
      [](SplitResult& r) { ++r.openChains; },
      [](SplitResult& r) { ++r.bridgedChains; },
      [](SplitResult& r) { ++r.uncappedLoops; },
      [](SplitResult& r) { r.sidesDisagree = !r.sidesDisagree; },
      [](SplitResult& r) { r.islandsFromSection = !r.islandsFromSection; },
      [](SplitResult& r) { r.islandFromLoops = !r.islandFromLoops; },
      [](SplitResult& r) { r.pieces[1].mesh.uv0.at(0).x += 1.f; },
      [](SplitResult& r) { r.pieces[1].weld.connected = !r.pieces[1].weld.connected; },
      [](SplitResult& r) { r.pieces[1].weld.positionIds.at(0) += 1; },
      [](SplitResult& r) { r.pieces[1].mass.fromConvexHull = !r.pieces[1].mass.fromConvexHull; },
      [](SplitResult& r) { r.pieces[1].mass.inertia[2][1] += 1e-12; },
      [](SplitResult& r) { r.pieces[1].joints.push_back(3); },
      [](SplitResult& r) { r.pieces[1].reached = !r.pieces[1].reached; },
      [](SplitResult& r) { r.pieces[1].sourceTriangles.at(0) ^= 1u; },
      [](SplitResult& r) { ++r.pieces[1].capLoops; },
  };
  for (size_t k = 0; k < changes.size(); ++k) {
    SplitResult changed = base.result;
    changes[k](changed);
    EXPECT_FALSE(sameBytes(base.result, changed)) << "change " << k;
  }
}

TEST(ConcaveSplitter, SameInputGivesTheSameBytes) {
  const MeshData torus = primitives::torus(1.f, 0.3f, 32, 12);
  const Plane plane = planeOf({0.1, 1, 0.05}, 0.02);
  Split first = run(torus, plane);
  ASSERT_EQ(first.status, SplitStatus::Ok) << first.result.message;
  Split second = run(torus, plane);
  EXPECT_TRUE(sameBytes(first.result, second.result));
  // A reused splitter and result, dirty from another split, give the same bytes too.
  MeshContainer container;
  ASSERT_EQ(container.setMesh(seamCube()).code, SplitStatus::Ok);
  auto splitter = makeConcaveSplitter();
  SplitResult reused;
  ASSERT_EQ(splitter->split(container, planeOf({1, 1, 1}, 1.5), {}, reused), SplitStatus::Ok);
  ASSERT_EQ(container.setMesh(torus).code, SplitStatus::Ok);
  ASSERT_EQ(splitter->split(container, plane, {}, reused), SplitStatus::Ok);
  EXPECT_TRUE(sameBytes(first.result, reused));
}

// SplitOptions::threads: meshes past the threshold (50,000 triangles) are cut in chunks and have
// their two sides written at once; the output is the same bytes as on one thread, including the
// many-piece path (a comb of 3,200 teeth) and the island and cavity passes.
TEST(ConcaveSplitter, ThreadsGiveTheSameBytesAsOneThread) {
  struct Case {
    const char* name;
    MeshData mesh;
    Plane plane;
  };
  const Case cases[] = {
      {"sphere", primitives::uvSphere(1.f, 256, 128), planeOf({0.12, 0.07, 0.99}, 0.0137)},
      {"torus", primitives::torus(1.f, 0.3f, 256, 128), planeOf({1, 0, 0.001}, 0.0)},
      {"twoSpheres", primitives::twoDisjointSpheres(0.5f, 0.1f, 192, 96), planeOf({0.3, 0.2, 1}, 0.01)},
      {"shells", primitives::nestedShells(3, 1.f, 160, 80), planeOf({0.05, 1, 0.1}, 0.02)},
      {"comb", primitives::combPrism(3200), planeOf({0, 1, 0}, 0.4)},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    ASSERT_GE(c.mesh.indices.size() / 3, 50000u);
    const uint64_t parkedBeforeOne = detail::PassThreads::jobsRunOnParkedThreads();
    Split one = run(c.mesh, c.plane);
    ASSERT_EQ(one.status, SplitStatus::Ok) << one.result.message;
    ASSERT_GE(one.result.pieces.size(), 2u);
    EXPECT_EQ(detail::PassThreads::jobsRunOnParkedThreads(), parkedBeforeOne) << "one thread uses no other";
    for (uint32_t threads : {2u, 3u, 8u}) {
      SplitOptions options;
      options.threads = threads;
      const uint64_t parkedBefore = detail::PassThreads::jobsRunOnParkedThreads();
      Split many = run(c.mesh, c.plane, options);
      ASSERT_EQ(many.status, SplitStatus::Ok) << many.result.message;
      // islandFromLoops tells how the islands were found, not what they are: the threaded path labels
      // both sides at once and never takes that shortcut. Every other field is the same bytes.
      EXPECT_FALSE(many.result.islandFromLoops);
      many.result.islandFromLoops = one.result.islandFromLoops;
      EXPECT_TRUE(sameBytes(one.result, many.result)) << threads << " threads";
      // The threads took part: passes of this split ran on threads beside the caller's.
      EXPECT_GT(detail::PassThreads::jobsRunOnParkedThreads(), parkedBefore) << threads << " threads";
    }
  }
  // The comb: one piece per tooth above the plane, the spine below.
  EXPECT_EQ(run(cases[4].mesh, cases[4].plane).result.pieces.size(), 3201u);
}

// Where the processor runs AVX2 the set-up's closedness filing, the classification (side_lanes.h)
// and the cut pass (whole_blocks.h) take four or eight items at a time, leaving any block with a
// crossing triangle to the scalar loop: the output is the same bytes with the AVX2 loops off
// (allowAvx2). Planes through vertices (on-plane corners in many blocks), meshes wound inwards
// (their corners swapped), a part the plane does not reach (the islands' union, where the blocks
// stand aside), many pieces, the chunked passes on 1, 2 and 3 threads (chunk 0 of several files its
// triangles backwards; the big inward sphere with them, and the classification in chunks past
// 50,000 ids), and cut positions as the source's floats and as doubles moved by a transform.
TEST(ConcaveSplitter, WholeTriangleBlocksGiveTheSameBytesAsTheScalarLoop) {
  if (!detail::wholeBlocksRun(3, 3)) GTEST_SKIP() << "this processor has no AVX2";
  struct Case {
    const char* name;
    MeshData mesh;
    std::vector<Plane> planes;
  };
  auto inwardsOf = [](MeshData m) {
    for (size_t t = 0; t + 2 < m.indices.size(); t += 3) std::swap(m.indices[t + 1], m.indices[t + 2]);
    return m;
  };
  const Case cases[] = {
      {"sphere", primitives::uvSphere(1.f, 64, 33),
       {planeOf({0, 0, 1}, 0.0), planeOf({0.12, 0.07, 0.99}, 0.0137), planeOf({1, 0, 0}, 0.5)}},
      {"torus", primitives::torus(1.f, 0.3f, 64, 24), {planeOf({0, 0, 1}, 0.0), planeOf({1, 0.2, 0.1}, 0.3)}},
      {"inwards", inwardsOf(primitives::uvSphere(1.f, 48, 24)), {planeOf({0, 1, 0}, 0.0), planeOf({0.3, 1, 0.2}, 0.25)}},
      {"twoSpheres", primitives::twoDisjointSpheres(0.5f, 0.1f, 48, 24), {planeOf({1, 0, 0}, -0.55)}},
      {"comb", primitives::combPrism(64), {planeOf({0, 1, 0}, 0.4), planeOf({0, 1, 0}, 0.2)}},
      {"bigSphere", primitives::uvSphere(1.f, 256, 128), {planeOf({0.12, 0.07, 0.99}, 0.0137), planeOf({0, 0, 1}, 0.0)}},
      {"bigInwards", inwardsOf(primitives::uvSphere(1.f, 256, 128)), {planeOf({0.2, 1, 0.1}, 0.05)}},
      {"manyIds", primitives::uvSphere(1.f, 320, 160), {planeOf({1, 0.1, 0.05}, -0.2)}},
  };
  ASSERT_GT(cases[7].mesh.positions.size(), 50000u);
  const glm::mat4 moved = glm::rotate(glm::translate(glm::mat4(1.f), glm::vec3(0.3f, -0.2f, 0.1f)), 0.4f,
                                      glm::vec3(0.2f, 1.f, 0.1f));
  size_t compared = 0;
  const uint64_t blocksBefore = detail::wholeBlocksTaken().load();
  for (const Case& c : cases) {
    for (const Plane& plane : c.planes) {
      for (uint32_t threads : {1u, 2u, 3u}) {
        const glm::mat4 model = threads == 2 ? moved : glm::mat4(1.f);
        SCOPED_TRACE(std::string(c.name) + ", " + std::to_string(threads) + " threads, offset " +
                     std::to_string(plane.offset));
        SplitOptions options;
        options.threads = threads;
        detail::allowAvx2(false);
        const Split scalar = run(c.mesh, plane, options, model);
        detail::allowAvx2(true);
        const Split blocks = run(c.mesh, plane, options, model);
        ASSERT_EQ(scalar.status, SplitStatus::Ok) << scalar.result.message;
        ASSERT_GE(scalar.result.pieces.size(), 2u);
        EXPECT_TRUE(sameBytes(scalar.result, blocks.result));
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 42u);
  // The blocks ran: most triangles of these meshes lie in blocks of eight whole ones.
  EXPECT_GT(detail::wholeBlocksTaken().load() - blocksBefore, 20000u);
}

// A container whose cut space is the source space lends the splitter the source floats (no copy in
// doubles). The same positions held as doubles (a skinning pose of one identity joint: every blend
// is the identity) give the same bytes.
TEST(ConcaveSplitter, SourceFloatsInPlaceGiveTheSameBytesAsHeldDoubles) {
  struct Case {
    const char* name;
    MeshData mesh;
    Plane plane;
  };
  Case cases[] = {
      {"sphere", primitives::uvSphere(1.f, 64, 32), planeOf({0.12, 0.07, 0.99}, 0.0137)},
      {"torus", primitives::torus(1.f, 0.3f, 64, 24), planeOf({1, 0, 0.001}, 0.0)},
      {"comb", primitives::combPrism(16), planeOf({0, 1, 0}, 0.4)},
  };
  const std::vector<glm::mat4> joints = {glm::mat4(1.f)};
  for (Case& c : cases) {
    SCOPED_TRACE(c.name);
    c.mesh.joints.assign(c.mesh.positions.size(), glm::u16vec4(0));
    c.mesh.weights.assign(c.mesh.positions.size(), glm::vec4(1.f, 0.f, 0.f, 0.f));
    MeshContainer inPlace, held;
    ASSERT_EQ(inPlace.setMesh(c.mesh).code, SplitStatus::Ok);
    ASSERT_EQ(held.setMesh(c.mesh).code, SplitStatus::Ok);
    ASSERT_EQ(held.setSkinningPose(joints, glm::mat4(1.f)).code, SplitStatus::Ok);
    ASSERT_TRUE(inPlace.cutPositions().isSource());
    ASSERT_FALSE(held.cutPositions().isSource());
    auto splitter = makeConcaveSplitter();
    SplitResult a, b;
    ASSERT_EQ(splitter->split(inPlace, c.plane, SplitOptions{}, a), SplitStatus::Ok) << a.message;
    ASSERT_EQ(splitter->split(held, c.plane, SplitOptions{}, b), SplitStatus::Ok) << b.message;
    ASSERT_GE(a.pieces.size(), 2u);
    EXPECT_TRUE(sameBytes(a, b));
  }
}

TEST(ConcaveSplitter, WarmSplitOfASameSizeMeshDoesNotAllocate) {
  struct Case {
    MeshData mesh;
    Plane planes[2];
    bool convex;
  };
  Case cases[] = {
      {primitives::torus(1.f, 0.3f, 48, 16), {planeOf({0, 1, 0}, 0.05), planeOf({1, 0.2, 0}, 0.1)}, false},
      {primitives::uvSphere(1.f, 32, 16), {planeOf({0.2, 1, 0.1}, 0.1), planeOf({1, 0, 0}, -0.3)}, true},
      {primitives::combPrism(8), {planeOf({0, 1, 0}, 0.5), planeOf({0, 0, 1}, 0.02)}, false},
  };
  for (Case& c : cases) {
    MeshContainer container;
    ASSERT_EQ(container.setMesh(c.mesh).code, SplitStatus::Ok);
    container.setTransform(glm::rotate(glm::mat4(1.f), 0.3f, glm::vec3(0, 0, 1)));
    auto splitter = c.convex ? makeConvexSplitter() : makeConcaveSplitter();
    SplitResult result;
    SplitOptions options;
    for (int warm = 0; warm < 2; ++warm) {
      for (const Plane& plane : c.planes) ASSERT_EQ(splitter->split(container, plane, options, result), SplitStatus::Ok);
    }
    for (const Plane& plane : c.planes) {
      gAllocations = 0;
      gCountAllocations = true;
      const SplitStatus status = splitter->split(container, plane, options, result);
      gCountAllocations = false;
      EXPECT_EQ(status, SplitStatus::Ok);
      EXPECT_EQ(gAllocations.load(), 0u) << "heap allocations in a warm split";
    }
  }
}

// Another mesh of the same size (the same sphere, twice as large, in its own container) through a
// splitter and result warmed up on the first: still no allocation in split().
TEST(ConcaveSplitter, SplitOfAnotherSameSizeMeshDoesNotAllocate) {
  MeshContainer first, second;
  ASSERT_EQ(first.setMesh(primitives::uvSphere(1.f, 40, 21)).code, SplitStatus::Ok);
  ASSERT_EQ(second.setMesh(primitives::uvSphere(2.f, 40, 21)).code, SplitStatus::Ok);
  auto splitter = makeConcaveSplitter();
  SplitResult result;
  SplitOptions options;
  const Plane plane = planeOf({0.3, 1, 0.2}, 0.11);
  const Plane doubled{plane.normal, 2.0 * plane.offset};
  for (int warm = 0; warm < 2; ++warm) ASSERT_EQ(splitter->split(first, plane, options, result), SplitStatus::Ok);
  const size_t firstTriangles = result.pieces[0].mesh.indices.size() + result.pieces[1].mesh.indices.size();
  gAllocations = 0;
  gCountAllocations = true;
  const SplitStatus status = splitter->split(second, doubled, options, result);
  gCountAllocations = false;
  ASSERT_EQ(status, SplitStatus::Ok);
  EXPECT_EQ(result.pieces[0].mesh.indices.size() + result.pieces[1].mesh.indices.size(), firstTriangles);
  EXPECT_EQ(gAllocations.load(), 0u) << "heap allocations splitting a same-size mesh";
}

// The counter sees allocations (the two tests above would pass with a counter that never counts):
// a cold splitter and result allocate on their first split.
TEST(ConcaveSplitter, AllocationCounterSeesTheAllocationsOfAColdSplit) {
  MeshContainer container;
  ASSERT_EQ(container.setMesh(primitives::uvSphere(1.f, 24, 12)).code, SplitStatus::Ok);
  auto splitter = makeConcaveSplitter();
  SplitResult result;
  gAllocations = 0;
  gCountAllocations = true;
  const SplitStatus status = splitter->split(container, planeOf({0, 1, 0}, 0.1), SplitOptions{}, result);
  gCountAllocations = false;
  ASSERT_EQ(status, SplitStatus::Ok);
  EXPECT_GT(gAllocations.load(), 10u);
}

// Setting a warm container up again with a shared mesh and its known weld (as the engine does for
// every cut of a mesh it has seen) does not allocate either.
TEST(ConcaveSplitter, WarmSetMeshWithAKnownWeldDoesNotAllocate) {
  auto mesh = std::make_shared<const MeshData>(primitives::torus(1.f, 0.3f, 48, 16));
  MeshContainer container;
  ASSERT_EQ(container.setMesh(mesh, nullptr).code, SplitStatus::Ok);
  MeshWeld weld;
  container.copyWeld(weld);
  const glm::mat4 model = glm::rotate(glm::mat4(1.f), 0.4f, glm::vec3(0, 1, 0));
  for (int warm = 0; warm < 2; ++warm) {
    ASSERT_EQ(container.setMesh(mesh, &weld).code, SplitStatus::Ok);
    container.setTransform(model);
  }
  gAllocations = 0;
  gCountAllocations = true;
  const SplitStatus status = container.setMesh(mesh, &weld).code;
  container.setTransform(model);
  gCountAllocations = false;
  ASSERT_EQ(status, SplitStatus::Ok);
  EXPECT_EQ(gAllocations.load(), 0u) << "heap allocations setting up a warm container with a known weld";
}

}  // namespace
}  // namespace cleave::geometry
