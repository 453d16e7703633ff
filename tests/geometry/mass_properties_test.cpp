// SPDX-License-Identifier: MIT
// Mass properties against exact and analytic values, principal axes, and the procedural primitives
// (closed, outward, exact seams, analytic volumes) they are measured on.
#include "cleave/geometry/mass_properties.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "cleave/geometry/primitives.h"
#include "tests/geometry/test_meshes.h"

namespace cleave::geometry {
namespace {

namespace prim = primitives;
constexpr double kPi = std::numbers::pi;

void expectMatNear(const glm::dmat3& a, const glm::dmat3& b, double tol) {
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) EXPECT_NEAR(a[c][r], b[c][r], tol) << "element [" << c << "][" << r << "]";
  }
}

glm::dmat3 boxInertia(const glm::dvec3& full) {  // about the centre, density 1
  const double v = full.x * full.y * full.z;
  return glm::dmat3(glm::dvec3(v * (full.y * full.y + full.z * full.z) / 12.0, 0, 0),
                    glm::dvec3(0, v * (full.x * full.x + full.z * full.z) / 12.0, 0),
                    glm::dvec3(0, 0, v * (full.x * full.x + full.y * full.y) / 12.0));
}

TEST(MassProperties, UnitCubeHasUnitVolumeAndKnownInertia) {
  MassProperties m = computeMassProperties(prim::box(glm::vec3(0.5f)));
  EXPECT_TRUE(m.closed);
  EXPECT_FALSE(m.fromConvexHull);
  EXPECT_NEAR(m.volume, 1.0, 1e-14);
  EXPECT_NEAR(glm::length(m.centerOfMass), 0.0, 1e-14);
  expectMatNear(m.inertia, glm::dmat3(1.0 / 6.0), 1e-14);
}

TEST(MassProperties, TranslatedBoxKeepsInertiaAboutItsCentre) {
  MeshData mesh = prim::box(glm::vec3(0.5f, 1.f, 1.5f));
  prim::transform(mesh, glm::translate(glm::mat4(1.f), glm::vec3(3.f, -2.f, 5.f)));
  MassProperties m = computeMassProperties(mesh);
  EXPECT_NEAR(m.volume, 6.0, 1e-12);
  EXPECT_NEAR(m.centerOfMass.x, 3.0, 1e-12);
  EXPECT_NEAR(m.centerOfMass.y, -2.0, 1e-12);
  EXPECT_NEAR(m.centerOfMass.z, 5.0, 1e-12);
  expectMatNear(m.inertia, boxInertia({1, 2, 3}), 1e-11);
}

TEST(MassProperties, TwoBoxesFollowTheParallelAxisTheorem) {
  MeshData a = prim::box(glm::vec3(0.5f));
  MeshData b = prim::box(glm::vec3(1.f, 0.5f, 0.25f));
  prim::transform(a, glm::translate(glm::mat4(1.f), glm::vec3(-2.f, 1.f, 0.f)));
  prim::transform(b, glm::translate(glm::mat4(1.f), glm::vec3(3.f, 0.f, 1.f)));
  MassProperties m = computeMassProperties(prim::merge(a, b));
  const double va = 1.0, vb = 2.0 * 1.0 * 0.5;
  const glm::dvec3 ca(-2, 1, 0), cb(3, 0, 1);
  const glm::dvec3 c = (va * ca + vb * cb) / (va + vb);
  auto shift = [&](double v, const glm::dvec3& d) {
    return v * (glm::dot(d, d) * glm::dmat3(1.0) - glm::outerProduct(d, d));
  };
  const glm::dmat3 expected = boxInertia({1, 1, 1}) + shift(va, ca - c) + boxInertia({2, 1, 0.5}) + shift(vb, cb - c);
  EXPECT_TRUE(m.closed);
  EXPECT_NEAR(m.volume, va + vb, 1e-12);
  EXPECT_NEAR(glm::length(m.centerOfMass - c), 0.0, 1e-12);
  expectMatNear(m.inertia, expected, 1e-11);
}

TEST(MassProperties, SphereMatchesAnalyticWithinTessellationError) {
  const double r = 2.0;
  MassProperties m = computeMassProperties(prim::uvSphere(float(r), 256, 128));
  const double volume = 4.0 / 3.0 * kPi * r * r * r;
  EXPECT_TRUE(m.closed);
  EXPECT_NEAR(m.volume / volume, 1.0, 1e-3);
  EXPECT_LT(m.volume, volume);  // an inscribed polyhedron
  EXPECT_NEAR(glm::length(m.centerOfMass), 0.0, 1e-9);
  const double moment = 0.4 * volume * r * r;
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(m.inertia[k][k] / moment, 1.0, 2e-3);
  EXPECT_NEAR(m.inertia[0][1], 0.0, 1e-9);
}

TEST(MassProperties, ScaledTransformScalesVolumeAndInertia) {
  const glm::dmat4 scale = glm::scale(glm::dmat4(1.0), glm::dvec3(2.0, 3.0, 4.0));
  MassProperties m = computeMassProperties(prim::box(glm::vec3(0.5f)), scale);
  EXPECT_NEAR(m.volume, 24.0, 1e-12);
  expectMatNear(m.inertia, boxInertia({2, 3, 4}), 1e-11);
}

TEST(MassProperties, MirroringTransformKeepsVolumePositive) {
  MeshData mesh = prim::uvSphere(1.f, 24, 12);
  prim::transform(mesh, glm::translate(glm::mat4(1.f), glm::vec3(0.5f, 0.25f, 0.f)));
  const glm::dmat4 plain = glm::scale(glm::dmat4(1.0), glm::dvec3(2.0, 1.0, 0.5));
  const glm::dmat4 mirror = glm::scale(glm::dmat4(1.0), glm::dvec3(-2.0, 1.0, 0.5));
  MassProperties a = computeMassProperties(mesh, plain);
  MassProperties b = computeMassProperties(mesh, mirror);
  EXPECT_TRUE(b.closed);
  EXPECT_GT(b.volume, 0.0);
  EXPECT_NEAR(b.volume, a.volume, 1e-12 * a.volume);
  EXPECT_NEAR(b.centerOfMass.x, -a.centerOfMass.x, 1e-12);
  EXPECT_NEAR(b.centerOfMass.y, a.centerOfMass.y, 1e-12);
  // Mirroring x flips the sign of the xy and xz products and keeps the moments.
  EXPECT_NEAR(b.inertia[0][0], a.inertia[0][0], 1e-12);
  EXPECT_NEAR(b.inertia[2][2], a.inertia[2][2], 1e-12);
  EXPECT_NEAR(b.inertia[0][1], -a.inertia[0][1], 1e-12);
}

TEST(MassProperties, InsideOutMeshHasNegativeVolume) {
  MeshData mesh = prim::box(glm::vec3(0.5f));
  for (size_t k = 0; k < mesh.indices.size(); k += 3) std::swap(mesh.indices[k + 1], mesh.indices[k + 2]);
  MassProperties m = computeMassProperties(mesh);
  EXPECT_TRUE(m.closed);
  EXPECT_NEAR(m.volume, -1.0, 1e-14);
}

TEST(MassProperties, OpenMeshIsFlaggedAndUsesItsConvexHull) {
  MeshData mesh = prim::box(glm::vec3(0.5f));
  mesh.indices.resize(mesh.indices.size() - 3);  // drop one triangle: a hole
  EXPECT_FALSE(isClosedAndOriented(mesh.positions, mesh.indices));
  MassProperties m = computeMassProperties(mesh);
  EXPECT_FALSE(m.closed);
  EXPECT_TRUE(m.fromConvexHull);
  EXPECT_NEAR(m.volume, 1.0, 1e-12);
  expectMatNear(m.inertia, glm::dmat3(1.0 / 6.0), 1e-12);
}

TEST(MassProperties, FlatOpenMeshGivesZeroVolume) {
  std::vector<glm::vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  std::vector<uint32_t> idx = {0, 1, 2, 2, 1, 3};
  MassProperties m = computeMassProperties(p, idx);
  EXPECT_FALSE(m.closed);
  EXPECT_TRUE(m.fromConvexHull);
  EXPECT_EQ(m.volume, 0.0);
  EXPECT_TRUE(std::isfinite(m.centerOfMass.x));
}

TEST(MassProperties, InvalidInputGivesZeroProperties) {
  MeshData mesh = prim::box(glm::vec3(0.5f));
  MeshData badIndex = mesh;
  badIndex.indices[4] = 1000;
  MassProperties a = computeMassProperties(badIndex);
  EXPECT_EQ(a.volume, 0.0);
  EXPECT_FALSE(a.closed);
  EXPECT_FALSE(a.fromConvexHull);
  MeshData nan = mesh;
  nan.positions[3].y = std::nanf("");
  EXPECT_EQ(computeMassProperties(nan).volume, 0.0);
  MeshData ragged = mesh;
  ragged.indices.pop_back();
  EXPECT_EQ(computeMassProperties(ragged).volume, 0.0);
  EXPECT_EQ(computeMassProperties(MeshData{}).volume, 0.0);
}

TEST(MassProperties, DoublePositionsMatchFloatPositions) {
  MeshData mesh = prim::torus(1.f, 0.3f, 32, 16);
  std::vector<glm::dvec3> p(mesh.positions.begin(), mesh.positions.end());
  const glm::dmat4 t = glm::rotate(glm::dmat4(1.0), 0.7, glm::dvec3(1, 2, 3));
  MassProperties a = computeMassProperties(mesh, t);
  MassProperties b = computeMassProperties(p, mesh.indices, t);
  EXPECT_EQ(a.volume, b.volume);
  EXPECT_EQ(a.centerOfMass, b.centerOfMass);
  EXPECT_TRUE(b.closed);
}

TEST(MassProperties, ClosedSurfaceIntegrationMatchesTheCheckedPath) {
  MeshData mesh = prim::capsule(0.5f, 1.f, 16, 8);
  std::vector<glm::dvec3> p(mesh.positions.begin(), mesh.positions.end());
  MassProperties checked = computeMassProperties(mesh);
  MassProperties fast = integrateClosedSurface(p, mesh.indices);
  EXPECT_TRUE(fast.closed);
  EXPECT_EQ(fast.volume, checked.volume);
  EXPECT_EQ(fast.centerOfMass, checked.centerOfMass);
  EXPECT_NEAR(integrateClosedSurface(p, mesh.indices, true).volume, -checked.volume, 1e-15);
  std::vector<uint32_t> bad = {0, 1, 99999};
  EXPECT_FALSE(integrateClosedSurface(p, bad).closed);
}

TEST(MassProperties, ClosednessRejectsAFlippedTriangle) {
  MeshData mesh = prim::uvSphere(1.f, 16, 8);
  EXPECT_TRUE(isClosedAndOriented(mesh.positions, mesh.indices));
  std::swap(mesh.indices[7], mesh.indices[8]);
  EXPECT_FALSE(isClosedAndOriented(mesh.positions, mesh.indices));
}

// Every edge in both directions is not enough: a surface listed twice uses each directed edge twice.
// Its open parts (tiles of a sphere, one triangle each) and a mesh whose lone edges pair up only by
// chance of their ids are open too; a large closed mesh (many probes of the edge set) is closed.
TEST(MassProperties, ClosednessWantsEachDirectedEdgeOnceAndItsReverseOnce) {
  MeshData sphere = prim::uvSphere(1.f, 64, 32);
  EXPECT_TRUE(isClosedAndOriented(sphere.positions, sphere.indices));
  MeshData twice = sphere;
  twice.indices.insert(twice.indices.end(), sphere.indices.begin(), sphere.indices.end());
  EXPECT_FALSE(isClosedAndOriented(twice.positions, twice.indices)) << "each directed edge used twice";
  MeshData both = sphere;  // the surface and its reverse: every edge once in each direction, twice
  for (size_t t = 0; t + 2 < sphere.indices.size(); t += 3) {
    both.indices.insert(both.indices.end(), {sphere.indices[t], sphere.indices[t + 2], sphere.indices[t + 1]});
  }
  EXPECT_FALSE(isClosedAndOriented(both.positions, both.indices));
  const std::vector<uint32_t> lone = {sphere.indices.begin(), sphere.indices.begin() + 3};
  EXPECT_FALSE(isClosedAndOriented(sphere.positions, lone));
  MeshData big = prim::uvSphere(1.f, 512, 256);
  EXPECT_TRUE(isClosedAndOriented(big.positions, big.indices));
  big.indices.resize(big.indices.size() - 3);
  EXPECT_FALSE(isClosedAndOriented(big.positions, big.indices));
}

TEST(PrincipalInertia, DiagonalTensorIsSortedAscendingWithProperRotation) {
  PrincipalInertia p = principalInertia(glm::dmat3(glm::dvec3(3, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 2)));
  EXPECT_EQ(p.moments, glm::dvec3(1, 2, 3));
  EXPECT_NEAR(glm::determinant(p.axes), 1.0, 1e-15);
  EXPECT_NEAR(std::abs(p.axes[0].y), 1.0, 1e-15);
  EXPECT_NEAR(std::abs(p.axes[1].z), 1.0, 1e-15);
}

TEST(PrincipalInertia, RotatedBoxRecoversMomentsAndReconstructs) {
  const glm::dmat3 rotation(glm::rotate(glm::dmat4(1.0), 0.9, glm::normalize(glm::dvec3(1, -2, 0.5))));
  const glm::dmat3 tensor = rotation * boxInertia({1, 2, 3}) * glm::transpose(rotation);
  PrincipalInertia p = principalInertia(tensor);
  const glm::dmat3 local = boxInertia({1, 2, 3});
  EXPECT_NEAR(p.moments[0], local[2][2], 1e-12);
  EXPECT_NEAR(p.moments[1], local[1][1], 1e-12);
  EXPECT_NEAR(p.moments[2], local[0][0], 1e-12);
  EXPECT_NEAR(glm::determinant(p.axes), 1.0, 1e-12);
  expectMatNear(glm::transpose(p.axes) * p.axes, glm::dmat3(1.0), 1e-12);
  glm::dmat3 diag(0.0);
  for (int k = 0; k < 3; ++k) diag[k][k] = p.moments[k];
  expectMatNear(p.axes * diag * glm::transpose(p.axes), tensor, 1e-12);
}

TEST(PrincipalInertia, RepeatedMomentsStillGiveARotation) {
  MassProperties m = computeMassProperties(prim::box(glm::vec3(1.f, 1.f, 2.f)),
                                           glm::dmat4(glm::rotate(glm::dmat4(1.0), 0.4, glm::dvec3(0, 1, 1))));
  PrincipalInertia p = principalInertia(m.inertia);
  EXPECT_NEAR(glm::determinant(p.axes), 1.0, 1e-12);
  EXPECT_LE(p.moments[0], p.moments[1]);
  EXPECT_LE(p.moments[1], p.moments[2]);
  EXPECT_NEAR(p.moments[1], p.moments[2], 1e-9 * p.moments[2]);  // x and y moments of a 2x2x4 box
  EXPECT_LT(p.moments[0], p.moments[1] * 0.5);
}

// ---- Primitives: the shapes every other geometry test is built on. ----

struct NamedMesh {
  std::string name;
  MeshData mesh;
};

std::vector<NamedMesh> allPrimitives() {
  return {
      {"box", prim::box(glm::vec3(0.5f, 1.f, 0.25f))},
      {"uvSphere", prim::uvSphere(1.f, 24, 12)},
      {"ellipsoid", prim::ellipsoid(glm::vec3(1.f, 0.5f, 2.f), 20, 11)},
      {"cylinder", prim::cylinder(0.5f, 2.f, 20)},
      {"torus", prim::torus(1.f, 0.25f, 32, 12)},
      {"capsule", prim::capsule(0.5f, 1.f, 16, 8)},
      {"capsuleNoBand", prim::capsule(0.5f, 0.f, 16, 8)},
      {"hollowSphere", prim::hollowSphere(1.f, 0.6f, 24, 12)},
      {"nestedShells", prim::nestedShells(3, 1.f, 24, 12)},
      {"combPrism", prim::combPrism(8)},
      {"starPrism", prim::starPrism(5)},
      {"tetrahedron", prim::tetrahedron(1.f)},
      {"twoDisjointSpheres", prim::twoDisjointSpheres(0.5f, 0.2f, 16, 8)},
  };
}

TEST(Primitives, EveryShapeIsClosedOutwardAndComplete) {
  for (const NamedMesh& named : allPrimitives()) {
    SCOPED_TRACE(named.name);
    const MeshData& m = named.mesh;
    ASSERT_FALSE(m.empty());
    EXPECT_EQ(m.normals.size(), m.positions.size());
    EXPECT_EQ(m.tangents.size(), m.positions.size());
    EXPECT_EQ(m.uv0.size(), m.positions.size());
    EXPECT_TRUE(isClosedAndOriented(m.positions, m.indices)) << "exact-position weld";
    testing::expectClosedAndOriented(m);
    EXPECT_GT(computeMassProperties(m).volume, 0.0);
    for (size_t i = 0; i < m.positions.size(); ++i) {
      EXPECT_NEAR(glm::length(m.normals[i]), 1.f, 1e-5f);
      EXPECT_NEAR(glm::length(glm::vec3(m.tangents[i])), 1.f, 1e-5f);
      EXPECT_NEAR(glm::dot(m.normals[i], glm::vec3(m.tangents[i])), 0.f, 1e-5f);
      EXPECT_EQ(std::abs(m.tangents[i].w), 1.f);
    }
    for (size_t t = 0; t < m.indices.size(); t += 3) {
      const glm::dvec3 a(m.positions[m.indices[t]]), b(m.positions[m.indices[t + 1]]), c(m.positions[m.indices[t + 2]]);
      const glm::dvec3 n = glm::cross(b - a, c - a);
      ASSERT_GT(glm::length(n), 0.0) << "zero-area triangle " << t / 3;
      const glm::dvec3 shading = glm::dvec3(m.normals[m.indices[t]] + m.normals[m.indices[t + 1]] + m.normals[m.indices[t + 2]]);
      ASSERT_GT(glm::dot(n, shading), 0.0) << "winding disagrees with normals at triangle " << t / 3;
    }
  }
}

TEST(Primitives, BoxHasTwentyFourVerticesAndTwelveTriangles) {
  MeshData m = prim::box(glm::vec3(1.f));
  EXPECT_EQ(m.vertexCount(), 24u);
  EXPECT_EQ(m.triangleCount(), 12u);
}

TEST(Primitives, SphereTriangleCountFollowsTessellation) {
  EXPECT_EQ(prim::uvSphere(1.f, 32, 16).triangleCount(), 2u * 32u * 15u);
  EXPECT_EQ(prim::torus(1.f, 0.2f, 30, 10).triangleCount(), 2u * 30u * 10u);
}

TEST(Primitives, ExactShapesHaveExactVolumes) {
  const double d = 0.3, p = 0.2, len = 0.6, s = 0.2;
  const uint32_t teeth = 7;
  EXPECT_NEAR(computeMassProperties(prim::combPrism(teeth, float(p), float(len), float(s), float(d))).volume,
              (teeth * p * s + teeth * 0.5 * p * len) * d, 1e-6);
  // Star: 2n triangles of the outline fan, each 1/2 R r sin(pi / n).
  const uint32_t points = 6;
  const double outer = 1.0, inner = 0.4, h = 0.5;
  EXPECT_NEAR(computeMassProperties(prim::starPrism(points, float(outer), float(inner), float(h))).volume,
              2.0 * points * 0.5 * outer * inner * std::sin(kPi / points) * h, 1e-6);
  const double sTet = 1.0 / std::sqrt(3.0);
  EXPECT_NEAR(computeMassProperties(prim::tetrahedron(1.f)).volume, 8.0 / 3.0 * sTet * sTet * sTet, 1e-6);
}

TEST(Primitives, CurvedShapesApproachAnalyticVolumes) {
  EXPECT_NEAR(computeMassProperties(prim::cylinder(0.5f, 2.f, 256)).volume / (kPi * 0.25 * 2.0), 1.0, 1e-3);
  EXPECT_NEAR(computeMassProperties(prim::torus(1.f, 0.25f, 256, 128)).volume / (2.0 * kPi * kPi * 0.0625), 1.0, 1e-3);
  const double capsule = kPi * 0.25 * 1.0 + 4.0 / 3.0 * kPi * 0.125;
  EXPECT_NEAR(computeMassProperties(prim::capsule(0.5f, 1.f, 256, 128)).volume / capsule, 1.0, 1e-3);
  EXPECT_NEAR(computeMassProperties(prim::ellipsoid(glm::vec3(1.f, 0.5f, 2.f), 256, 128)).volume / (4.0 / 3.0 * kPi),
              1.0, 1e-3);
}

TEST(Primitives, ShellsAddUpWithAlternatingSigns) {
  auto volume = [](const MeshData& m) { return computeMassProperties(m).volume; };
  const double v1 = volume(prim::uvSphere(1.f, 24, 12));
  const double v2 = volume(prim::uvSphere(2.f / 3.f, 24, 12));
  const double v3 = volume(prim::uvSphere(1.f / 3.f, 24, 12));
  // Radii differ by float rounding between the two constructions, hence 1e-6.
  EXPECT_NEAR(volume(prim::nestedShells(3, 1.f, 24, 12)), v1 - v2 + v3, 1e-6);
  EXPECT_NEAR(volume(prim::hollowSphere(1.f, 2.f / 3.f, 24, 12)), v1 - v2, 1e-6);
}

TEST(Primitives, MirroringTransformKeepsOutwardWinding) {
  MeshData m = prim::torus(1.f, 0.3f, 24, 12);
  const double before = computeMassProperties(m).volume;
  prim::transform(m, glm::scale(glm::mat4(1.f), glm::vec3(-1.f, 2.f, 1.f)));
  EXPECT_TRUE(isClosedAndOriented(m.positions, m.indices));
  EXPECT_NEAR(computeMassProperties(m).volume, 2.0 * before, 1e-5 * before);
  for (size_t t = 0; t < m.indices.size(); t += 3) {
    const glm::vec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]], c = m.positions[m.indices[t + 2]];
    ASSERT_GT(glm::dot(glm::cross(b - a, c - a), m.normals[m.indices[t]] + m.normals[m.indices[t + 1]] + m.normals[m.indices[t + 2]]), 0.f);
  }
}

TEST(Primitives, MergeOffsetsIndicesAndKeepsMaterialRuns) {
  MeshData a = prim::box(glm::vec3(1.f));
  MeshData b = prim::tetrahedron(1.f);
  b.submeshes = {{0, 6, 4}, {6, static_cast<uint32_t>(b.indices.size() - 6), 5}};
  b.colors.assign(b.positions.size(), glm::vec4(0.5f));
  MeshData m = prim::merge(a, b);
  EXPECT_EQ(m.vertexCount(), a.vertexCount() + b.vertexCount());
  EXPECT_EQ(m.indices[a.indices.size()], b.indices[0] + a.vertexCount());
  ASSERT_EQ(m.submeshes.size(), 3u);
  EXPECT_EQ(m.submeshes[0].materialId, 0u);
  EXPECT_EQ(m.submeshes[0].indexCount, a.indices.size());
  EXPECT_EQ(m.submeshes[1].firstIndex, a.indices.size());
  EXPECT_EQ(m.submeshes[2].materialId, 5u);
  ASSERT_EQ(m.colors.size(), m.positions.size());
  EXPECT_EQ(m.colors.front(), glm::vec4(1.f));
  EXPECT_EQ(m.colors.back(), glm::vec4(0.5f));
}

TEST(Primitives, BadArgumentsGiveEmptyOrClampedMeshes) {
  EXPECT_TRUE(prim::uvSphere(0.f, 16, 8).empty());
  EXPECT_TRUE(prim::torus(0.2f, 0.5f, 16, 8).empty());  // tube wider than the ring
  EXPECT_TRUE(prim::hollowSphere(0.5f, 1.f, 16, 8).empty());
  MeshData clamped = prim::uvSphere(1.f, 0, 0);
  EXPECT_FALSE(clamped.empty());
  EXPECT_TRUE(isClosedAndOriented(clamped.positions, clamped.indices));
}

}  // namespace
}  // namespace cleave::geometry
