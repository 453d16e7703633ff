// SPDX-License-Identifier: MIT
// MeshContainer: validation, welding, cut space (transform, mirroring, skinning), extraction.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "cleave/geometry/mesh_splitter.h"
#include "cleave/geometry/primitives.h"

namespace cleave::geometry {
namespace {

// Unit cube [0,1]^3 with 4 vertices per face (split seams), uv per face, normals, one run.
MeshData seamCube() {
  MeshData m;
  const glm::vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const glm::vec3& n : normals) {
    // Two axes spanning the face so that (a, b, n) is right-handed.
    glm::vec3 a = std::abs(n.x) > 0.5f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    glm::vec3 b = glm::cross(n, a);
    const glm::vec3 centre = glm::vec3(0.5f) + 0.5f * n;
    const uint32_t base = static_cast<uint32_t>(m.positions.size());
    const glm::vec2 corners[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (const glm::vec2& c : corners) {
      m.positions.push_back(centre + 0.5f * c.x * a + 0.5f * c.y * b);
      m.normals.push_back(n);
      m.uv0.push_back(0.5f * (c + 1.f));
    }
    for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) m.indices.push_back(base + i);
  }
  return m;
}

TEST(MeshContainer, AcceptsAValidMeshAndWeldsItsSeams) {
  MeshContainer c;
  MeshStatus set = c.setMesh(seamCube());
  ASSERT_EQ(set.code, SplitStatus::Ok) << set.message;
  EXPECT_EQ(c.mesh().vertexCount(), 24u);
  EXPECT_EQ(c.positionIdCount(), 8u);
  EXPECT_TRUE(c.closed());
  EXPECT_FALSE(c.mirrored());
  EXPECT_NEAR(c.boundsDiagonal(), std::sqrt(3.0), 1e-12);
  // Ids are numbered by first vertex, and the first vertex of each id is its representative.
  std::span<const uint32_t> ids = c.positionIds();
  EXPECT_EQ(ids[0], 0u);
  uint32_t next = 0;
  for (size_t v = 0; v < ids.size(); ++v) {
    if (ids[v] == next) {
      EXPECT_EQ(c.positionRepresentatives()[next], v);
      ++next;
    }
    EXPECT_LT(ids[v], next);
    EXPECT_EQ(c.mesh().positions[v], c.mesh().positions[c.positionRepresentatives()[ids[v]]]);
  }
}

TEST(MeshContainer, TakesAWeldWorkedOutBefore) {
  MeshContainer welded;
  ASSERT_EQ(welded.setMesh(seamCube()).code, SplitStatus::Ok);
  MeshWeld weld;
  welded.copyWeld(weld);
  EXPECT_EQ(weld.positionIds.size(), 24u);
  EXPECT_EQ(weld.representatives.size(), 8u);
  EXPECT_TRUE(weld.closed);
  MeshContainer c;
  MeshStatus set = c.setMesh(seamCube(), weld);
  ASSERT_EQ(set.code, SplitStatus::Ok) << set.message;
  EXPECT_EQ(c.positionIdCount(), 8u);
  EXPECT_TRUE(c.closed());
  EXPECT_NEAR(c.boundsDiagonal(), welded.boundsDiagonal(), 0.0);
  EXPECT_TRUE(std::equal(c.positionIds().begin(), c.positionIds().end(), welded.positionIds().begin()));
  // The same split either way.
  auto splitter = makeConcaveSplitter();
  SplitResult a, b;
  const Plane plane{glm::dvec3(0.2, 1.0, 0.1), 0.55};
  ASSERT_EQ(splitter->split(welded, plane, SplitOptions{}, a), SplitStatus::Ok);
  ASSERT_EQ(splitter->split(c, plane, SplitOptions{}, b), SplitStatus::Ok);
  ASSERT_EQ(a.pieces.size(), b.pieces.size());
  for (size_t k = 0; k < a.pieces.size(); ++k) {
    EXPECT_EQ(a.pieces[k].mesh.indices, b.pieces[k].mesh.indices);
    EXPECT_EQ(a.pieces[k].weld.positionIds, b.pieces[k].weld.positionIds);
  }
}

TEST(MeshContainer, SharesAMeshWithoutCopyingIt) {
  auto shared = std::make_shared<const MeshData>(seamCube());
  MeshContainer c;
  MeshStatus set;
  set = c.setMesh(shared, nullptr);
  ASSERT_EQ(set.code, SplitStatus::Ok) << set.message;
  EXPECT_EQ(&c.mesh(), shared.get());
  EXPECT_EQ(c.positionIdCount(), 8u);
  EXPECT_TRUE(c.closed());
  MeshWeld weld;
  c.copyWeld(weld);
  MeshContainer d;
  set = d.setMesh(shared, &weld);
  ASSERT_EQ(set.code, SplitStatus::Ok) << set.message;
  EXPECT_EQ(d.positionIdCount(), 8u);
  // Taking a copy afterwards (even of the shared mesh itself) stops sharing.
  set = d.setMesh(*shared);
  ASSERT_EQ(set.code, SplitStatus::Ok) << set.message;
  EXPECT_NE(&d.mesh(), shared.get());
  EXPECT_EQ(d.mesh().positions, shared->positions);
  set = c.setMesh(std::shared_ptr<const MeshData>(), nullptr);
  EXPECT_EQ(set.code, SplitStatus::InvalidInput) << set.message;
  EXPECT_FALSE(set.message.empty());
}

TEST(MeshContainer, RejectsAWeldOfAnotherMesh) {
  MeshWeld weld;
  MeshContainer welded;
  ASSERT_EQ(welded.setMesh(seamCube()).code, SplitStatus::Ok);
  welded.copyWeld(weld);
  MeshContainer c;
  MeshStatus set;
  MeshWeld shorter = weld;
  shorter.positionIds.pop_back();
  set = c.setMesh(seamCube(), shorter);
  EXPECT_EQ(set.code, SplitStatus::InvalidInput) << set.message;
  EXPECT_NE(set.message.find("weld"), std::string::npos) << set.message;
  MeshWeld outOfRange = weld;
  outOfRange.positionIds[5] = 8;
  set = c.setMesh(seamCube(), outOfRange);
  EXPECT_EQ(set.code, SplitStatus::InvalidInput) << set.message;
  // One past the ids on a vertex no representative names: only the range check sees it.
  const uint32_t last = static_cast<uint32_t>(weld.positionIds.size() - 1);
  ASSERT_EQ(std::count(weld.representatives.begin(), weld.representatives.end(), last), 0);
  outOfRange = weld;
  outOfRange.positionIds[last] = static_cast<uint32_t>(weld.representatives.size());
  set = c.setMesh(seamCube(), outOfRange);
  EXPECT_EQ(set.code, SplitStatus::InvalidInput) << set.message;
  MeshWeld wrongRepresentative = weld;
  std::swap(wrongRepresentative.representatives[1], wrongRepresentative.representatives[2]);
  set = c.setMesh(seamCube(), wrongRepresentative);
  EXPECT_EQ(set.code, SplitStatus::InvalidInput) << set.message;
  MeshWeld notItsOwn = weld;  // representative 3 carries id 2: ids in range, representatives ascending
  notItsOwn.positionIds[notItsOwn.representatives[3]] = 2;
  set = c.setMesh(seamCube(), notItsOwn);
  EXPECT_EQ(set.code, SplitStatus::InvalidInput) << set.message;
  MeshWeld pastTheEnd = weld;  // ascending still, the last one past the vertices
  pastTheEnd.representatives.back() = static_cast<uint32_t>(pastTheEnd.positionIds.size());
  set = c.setMesh(seamCube(), pastTheEnd);
  EXPECT_EQ(set.code, SplitStatus::InvalidInput) << set.message;
  MeshWeld none = weld;
  none.representatives.clear();
  set = c.setMesh(seamCube(), none);
  EXPECT_EQ(set.code, SplitStatus::InvalidInput) << set.message;
  ASSERT_EQ(c.setMesh(seamCube(), weld).code, SplitStatus::Ok);  // the weld itself is taken
  EXPECT_EQ(c.positionIdCount(), 8u);
  set = c.setMesh(seamCube(), notItsOwn);
  EXPECT_EQ(c.positionIdCount(), 0u);  // nothing half set
  EXPECT_TRUE(c.cutPositions().empty());
}

TEST(MeshContainer, WeldsWithinTheToleranceScaledToTheMesh) {
  MeshData m = seamCube();
  m.positions[5] += glm::vec3(2e-7f, 0.f, 0.f);  // 2e-7 < 1e-6 * sqrt(3): same point
  MeshContainer c;
  ASSERT_EQ(c.setMesh(m).code, SplitStatus::Ok);
  EXPECT_EQ(c.positionIdCount(), 8u);
  EXPECT_TRUE(c.closed());
  m.positions[5] += glm::vec3(1e-4f, 0.f, 0.f);  // far beyond the tolerance: a new point, an open mesh
  ASSERT_EQ(c.setMesh(m).code, SplitStatus::Ok);
  EXPECT_EQ(c.positionIdCount(), 9u);
  EXPECT_FALSE(c.closed());
}

TEST(MeshContainer, ScaledMeshWeldsWithAScaledTolerance) {
  MeshData m = seamCube();
  for (glm::vec3& p : m.positions) p *= 1000.f;
  m.positions[5] += glm::vec3(1e-4f, 0.f, 0.f);  // 1e-4 < 1e-6 * 1732
  MeshContainer c;
  ASSERT_EQ(c.setMesh(m).code, SplitStatus::Ok);
  EXPECT_EQ(c.positionIdCount(), 8u);
}

// connected(): one part on position ids, worked out for a closed mesh, carried by its weld.
TEST(MeshContainer, KnowsWhetherAClosedMeshIsOnePart) {
  MeshContainer c;
  ASSERT_TRUE(c.setMesh(seamCube()).ok());
  EXPECT_TRUE(c.connected());
  MeshWeld weld;
  c.copyWeld(weld);
  EXPECT_TRUE(weld.connected);
  MeshContainer taken;
  ASSERT_TRUE(taken.setMesh(seamCube(), weld).ok());
  EXPECT_TRUE(taken.connected());
  weld.connected = false;  // a weld that does not know: nor does the container
  ASSERT_TRUE(taken.setMesh(seamCube(), weld).ok());
  EXPECT_FALSE(taken.connected());
  ASSERT_TRUE(c.setMesh(primitives::twoDisjointSpheres(0.5f, 0.3f, 12, 6)).ok());
  EXPECT_TRUE(c.closed());
  EXPECT_FALSE(c.connected());
  // A lone degenerate triangle away from the cube is a part of its own (the splitter's islands
  // count it), though the closedness check ignores it.
  MeshData cube = seamCube();
  const uint32_t first = static_cast<uint32_t>(cube.positions.size());
  cube.positions.insert(cube.positions.end(), {glm::vec3(5, 5, 5), glm::vec3(5, 5, 5), glm::vec3(6, 5, 5)});
  cube.indices.insert(cube.indices.end(), {first, first + 1, first + 2});
  if (!cube.normals.empty()) cube.normals.resize(cube.positions.size(), glm::vec3(0, 0, 1));
  if (!cube.uv0.empty()) cube.uv0.resize(cube.positions.size());
  if (!cube.tangents.empty()) cube.tangents.resize(cube.positions.size());
  ASSERT_TRUE(c.setMesh(cube).ok()) << c.setMesh(cube).message;
  EXPECT_TRUE(c.closed());
  EXPECT_FALSE(c.connected());
  // An open mesh: not worked out.
  MeshData open = seamCube();
  open.indices.resize(open.indices.size() - 3);
  ASSERT_TRUE(c.setMesh(open).ok());
  EXPECT_FALSE(c.closed());
  EXPECT_FALSE(c.connected());
  c.release();
  EXPECT_FALSE(c.connected());
}

TEST(MeshContainer, OpenMeshIsNotClosed) {
  MeshData m = seamCube();
  m.indices.resize(m.indices.size() - 3);
  MeshContainer c;
  ASSERT_EQ(c.setMesh(m).code, SplitStatus::Ok);
  EXPECT_FALSE(c.closed());
}

// Every edge used an even number of times, with both directions, is not enough: each must be used
// exactly once each way. A cube listed twice (each directed edge twice) and a cube with its mirror
// (each edge twice each way) are not closed surfaces.
TEST(MeshContainer, EdgesUsedTwiceEachWayAreNotClosed) {
  const MeshData cube = seamCube();
  MeshData twice = cube;
  twice.indices.insert(twice.indices.end(), cube.indices.begin(), cube.indices.end());
  MeshContainer c;
  ASSERT_TRUE(c.setMesh(twice).ok());
  EXPECT_FALSE(c.closed());
  MeshData mirrored = twice;
  for (size_t t = cube.indices.size(); t < mirrored.indices.size(); t += 3) {
    std::swap(mirrored.indices[t + 1], mirrored.indices[t + 2]);
  }
  ASSERT_TRUE(c.setMesh(mirrored).ok());
  EXPECT_FALSE(c.closed());
  ASSERT_TRUE(c.setMesh(cube).ok());
  EXPECT_TRUE(c.closed());
}

TEST(MeshContainer, RejectsNaNAndInfinitePositions) {
  MeshContainer c;
  MeshData m = seamCube();
  m.positions[3].y = std::numeric_limits<float>::quiet_NaN();
  MeshStatus set;
  set = c.setMesh(m);
  EXPECT_EQ(set.code, SplitStatus::InvalidInput) << set.message;
  EXPECT_NE(set.message.find("vertex 3"), std::string::npos) << set.message;
  m = seamCube();
  m.positions[7].z = std::numeric_limits<float>::infinity();
  set = c.setMesh(m);
  EXPECT_EQ(set.code, SplitStatus::InvalidInput) << set.message;
  EXPECT_NE(set.message.find("vertex 7"), std::string::npos) << set.message;
  EXPECT_TRUE(c.mesh().empty());  // a rejected mesh leaves nothing to split
}

// The check and the bounds read the positions four at a time with a scalar tail: a special value
// is found, and a vertex sets the bounds, wherever it is (in a block, in the tail, on any axis).
TEST(MeshContainer, EveryVertexIsCheckedAndBounded) {
  for (const int extra : {0, 1, 2, 3}) {  // 24 vertices (whole blocks of four), then a tail of 1-3
    MeshData base = seamCube();
    for (int k = 0; k < extra; ++k) {  // unused vertices
      base.positions.push_back(glm::vec3(0.5f));
      if (!base.normals.empty()) base.normals.push_back(glm::vec3(0, 0, 1));
      if (!base.uv0.empty()) base.uv0.push_back(glm::vec2(0.f));
    }
    MeshContainer c;
    for (size_t i = 0; i < base.positions.size(); ++i) {
      for (int axis = 0; axis < 3; ++axis) {
        for (const float special : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                                    -std::numeric_limits<float>::infinity()}) {
          MeshData m = base;
          m.positions[i][axis] = special;
          const MeshStatus set = c.setMesh(m);
          EXPECT_EQ(set.code, SplitStatus::InvalidInput) << extra << " " << i << " " << axis;
          EXPECT_NE(set.message.find("vertex " + std::to_string(i) + " "), std::string::npos) << set.message;
        }
        for (const float far : {-3.f, 4.f}) {
          MeshData m = base;
          m.positions[i][axis] = far;
          const MeshStatus set = c.setMesh(m);
          ASSERT_EQ(set.code, SplitStatus::Ok) << set.message;
          glm::dvec3 lo(INFINITY), hi(-INFINITY);
          for (const glm::vec3& p : m.positions) {
            lo = glm::min(lo, glm::dvec3(p));
            hi = glm::max(hi, glm::dvec3(p));
          }
          EXPECT_EQ(c.boundsMin(), lo) << extra << " " << i << " " << axis << " " << far;
          EXPECT_EQ(c.boundsMax(), hi) << extra << " " << i << " " << axis << " " << far;
          EXPECT_EQ(c.boundsDiagonal(), glm::length(hi - lo));
        }
      }
    }
  }
}

TEST(MeshContainer, RejectsBadIndices) {
  MeshContainer c;
  MeshStatus set;
  MeshData m = seamCube();
  m.indices[10] = 24;
  set = c.setMesh(m);
  EXPECT_EQ(set.code, SplitStatus::InvalidInput) << set.message;
  EXPECT_NE(set.message.find("out of range"), std::string::npos) << set.message;
  m = seamCube();
  m.indices.push_back(0);
  set = c.setMesh(m);
  EXPECT_EQ(set.code, SplitStatus::InvalidInput) << set.message;
  EXPECT_NE(set.message.find("multiple of 3"), std::string::npos) << set.message;
  m.indices.clear();
  set = c.setMesh(m);
  EXPECT_EQ(set.code, SplitStatus::InvalidInput) << set.message;
}

TEST(MeshContainer, RejectsMismatchedAttributesAndRuns) {
  MeshContainer c;
  MeshStatus set;
  MeshData m = seamCube();
  m.normals.pop_back();
  set = c.setMesh(m);
  EXPECT_EQ(set.code, SplitStatus::InvalidInput) << set.message;
  EXPECT_NE(set.message.find("normals"), std::string::npos) << set.message;
  m = seamCube();
  m.joints.assign(24, glm::u16vec4(0));
  set = c.setMesh(m);
  EXPECT_EQ(set.code, SplitStatus::InvalidInput) << set.message;  // joints without weights
  EXPECT_NE(set.message.find("weights"), std::string::npos) << set.message;
  m = seamCube();
  m.submeshes = {{0, 18, 0}, {21, 15, 1}};  // a gap
  set = c.setMesh(m);
  EXPECT_EQ(set.code, SplitStatus::InvalidInput) << set.message;
  m.submeshes = {{0, 18, 0}, {18, 12, 1}};  // short of the end
  set = c.setMesh(m);
  EXPECT_EQ(set.code, SplitStatus::InvalidInput) << set.message;
  m.submeshes = {{0, 18, 0}, {18, 18, 1}};
  set = c.setMesh(m);
  EXPECT_EQ(set.code, SplitStatus::Ok) << set.message;
}

TEST(MeshContainer, TransformMakesCutSpaceAndDetectsMirroring) {
  MeshContainer c;
  ASSERT_EQ(c.setMesh(seamCube()).code, SplitStatus::Ok);
  const glm::mat4 model = glm::translate(glm::mat4(1.f), glm::vec3(1, 2, 3)) *
                          glm::scale(glm::mat4(1.f), glm::vec3(2.f, 1.f, 1.f));
  c.setTransform(model);
  EXPECT_FALSE(c.mirrored());
  const glm::dvec3 p = c.cutPositions()[2];
  const glm::vec3 q = c.mesh().positions[2];
  EXPECT_DOUBLE_EQ(p.x, 2.0 * q.x + 1.0);
  EXPECT_DOUBLE_EQ(p.y, q.y + 2.0);
  EXPECT_NEAR(c.boundsDiagonal(), std::sqrt(6.0), 1e-12);
  c.setTransform(glm::scale(glm::mat4(1.f), glm::vec3(1.f, -1.f, 1.f)));
  EXPECT_TRUE(c.mirrored());
  c.setTransform(glm::scale(glm::mat4(1.f), glm::vec3(-1.f, -1.f, 1.f)));  // a rotation by pi
  EXPECT_FALSE(c.mirrored());
}

// While the cut space is the source space the cut positions are the source floats (no copy); a
// transform moves them into an array of doubles, and the identity brings back the source, with its
// bounds and winding, whatever came between (a mirroring transform, a skinning pose).
TEST(MeshContainer, CutPositionsAreTheSourceFloatsUntilATransform) {
  MeshData m = seamCube();
  for (glm::vec3& p : m.positions) p = 0.1f * p + glm::vec3(0.3f, -0.7f, 0.01f);  // values a float rounds
  for (size_t i = 0; i < m.positions.size(); ++i) {
    m.joints.emplace_back(0, 0, 0, 0);
    m.weights.emplace_back(1.f, 0.f, 0.f, 0.f);
  }
  MeshContainer c;
  ASSERT_EQ(c.setMesh(m).code, SplitStatus::Ok);
  auto expectSource = [&](const char* after) {
    const CutPositions cut = c.cutPositions();
    EXPECT_TRUE(cut.isSource()) << after;
    ASSERT_EQ(cut.size(), m.positions.size()) << after;
    EXPECT_EQ(cut.source().data(), c.mesh().positions.data()) << after;
    glm::dvec3 lo(INFINITY), hi(-INFINITY);
    size_t read = 0;
    for (const glm::dvec3 p : cut) {
      EXPECT_EQ(p, glm::dvec3(m.positions[read])) << after << " " << read;
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
      ++read;
    }
    EXPECT_EQ(read, m.positions.size()) << after;
    EXPECT_EQ(c.boundsMin(), lo) << after;
    EXPECT_EQ(c.boundsMax(), hi) << after;
    EXPECT_FALSE(c.mirrored()) << after;
    std::vector<glm::dvec3> scratch;
    const std::span<const glm::dvec3> copied = cut.doubles(scratch);
    EXPECT_EQ(copied.data(), scratch.data()) << after;
    EXPECT_TRUE(std::equal(copied.begin(), copied.end(), cut.begin())) << after;
  };
  expectSource("setMesh");
  c.setTransform(glm::scale(glm::mat4(1.f), glm::vec3(2.f, -1.f, 1.f)));
  {
    const CutPositions cut = c.cutPositions();
    EXPECT_FALSE(cut.isSource());
    EXPECT_TRUE(cut.source().empty());
    ASSERT_EQ(cut.size(), m.positions.size());
    EXPECT_EQ(cut[3], glm::dvec3(2.0 * m.positions[3].x, -double(m.positions[3].y), m.positions[3].z));
    EXPECT_TRUE(c.mirrored());
    std::vector<glm::dvec3> scratch;
    EXPECT_TRUE(cut.doubles(scratch).data() != scratch.data()) << "the held doubles, not a copy";
    EXPECT_TRUE(scratch.empty());
  }
  c.setTransform(glm::mat4(1.f));
  expectSource("identity after a mirroring transform");
  const std::vector<glm::mat4> joints = {glm::translate(glm::mat4(1.f), glm::vec3(0, 5, 0))};
  ASSERT_EQ(c.setSkinningPose(joints, glm::mat4(1.f)).code, SplitStatus::Ok);
  EXPECT_FALSE(c.cutPositions().isSource());
  EXPECT_NEAR(c.cutPositions()[0].y, double(m.positions[0].y) + 5.0, 1e-6);
  c.setTransform(glm::mat4(1.f));
  expectSource("identity after a skinning pose");
  EXPECT_TRUE(c.jointMatrices().empty());
}

TEST(MeshContainer, SkinningPoseBlendsJointMatrices) {
  MeshData m = seamCube();
  for (const glm::vec3& p : m.positions) {
    m.joints.emplace_back(0, 1, 0, 0);
    m.weights.emplace_back(1.f - p.x, p.x, 0.f, 0.f);
  }
  MeshContainer c;
  ASSERT_EQ(c.setMesh(m).code, SplitStatus::Ok);
  const std::vector<glm::mat4> joints = {glm::mat4(1.f), glm::translate(glm::mat4(1.f), glm::vec3(0, 1, 0))};
  const glm::mat4 model = glm::translate(glm::mat4(1.f), glm::vec3(10, 0, 0));
  ASSERT_EQ(c.setSkinningPose(joints, model).code, SplitStatus::Ok);
  for (size_t i = 0; i < m.positions.size(); ++i) {
    const glm::dvec3 expected = glm::dvec3(m.positions[i]) + glm::dvec3(10.0, m.positions[i].x, 0.0);
    EXPECT_NEAR(glm::length(c.cutPositions()[i] - expected), 0.0, 1e-6) << i;
  }
  EXPECT_EQ(c.jointMatrices().size(), 2u);
  MeshStatus set;
  set = c.setSkinningPose(std::span<const glm::mat4>(joints.data(), 1), model);
  EXPECT_EQ(set.code, SplitStatus::InvalidInput) << set.message;
  EXPECT_NE(set.message.find("joint 1"), std::string::npos) << set.message;
  ASSERT_EQ(c.setMesh(seamCube()).code, SplitStatus::Ok);
  set = c.setSkinningPose(joints, model);
  EXPECT_EQ(set.code, SplitStatus::InvalidInput) << set.message;  // no skin data
}

TEST(MeshContainer, ExtractTrianglesRemapsVerticesAndKeepsRuns) {
  MeshData m = seamCube();
  for (size_t i = 0; i < m.positions.size(); ++i) m.colors.emplace_back(float(i), 0.f, 0.f, 1.f);
  m.submeshes = {{0, 12, 4}, {12, 24, 7}};  // faces 0-1 material 4, faces 2-5 material 7
  MeshContainer c;
  ASSERT_EQ(c.setMesh(m).code, SplitStatus::Ok);
  MeshData out;
  const std::vector<uint32_t> triangles = {5, 0, 1};  // face 2's second triangle, face 0
  c.extractTriangles(triangles, out);
  ASSERT_EQ(out.triangleCount(), 3u);
  ASSERT_EQ(out.submeshes.size(), 2u);  // runs in source order: material 4 first
  EXPECT_EQ(out.submeshes[0].materialId, 4u);
  EXPECT_EQ(out.submeshes[0].firstIndex, 0u);
  EXPECT_EQ(out.submeshes[0].indexCount, 6u);
  EXPECT_EQ(out.submeshes[1].materialId, 7u);
  EXPECT_EQ(out.submeshes[1].indexCount, 3u);
  EXPECT_EQ(out.vertexCount(), 7u);  // 4 of face 0, 3 of face 2's second triangle
  EXPECT_EQ(out.normals.size(), 7u);
  EXPECT_EQ(out.uv0.size(), 7u);
  EXPECT_EQ(out.colors.size(), 7u);
  EXPECT_TRUE(out.tangents.empty());
  for (size_t k = 0; k < out.indices.size(); ++k) {
    const size_t t = k < 6 ? k / 3 : 5;  // source triangle of this corner
    const uint32_t source = m.indices[3 * t + k % 3];
    EXPECT_EQ(out.positions[out.indices[k]], m.positions[source]);
    EXPECT_EQ(out.colors[out.indices[k]], m.colors[source]);
  }
}

}  // namespace
}  // namespace cleave::geometry

namespace cleave::geometry {
namespace {

// The cut-space bounds the container keeps with its diagonal: after setMesh (welded or with a
// weld), after a transform, after a pose change back to none, and infinite once released.
TEST(MeshContainer, KeepsTheCutSpaceBoundsOfItsPositions) {
  const MeshData box = primitives::box(glm::vec3(0.5f, 1.f, 2.f));
  MeshContainer c;
  ASSERT_EQ(c.setMesh(box).code, SplitStatus::Ok);
  EXPECT_EQ(c.boundsMin(), glm::dvec3(-0.5, -1.0, -2.0));
  EXPECT_EQ(c.boundsMax(), glm::dvec3(0.5, 1.0, 2.0));
  c.setTransform(glm::translate(glm::mat4(1.f), glm::vec3(10.f, 0.f, 0.f)));
  EXPECT_EQ(c.boundsMin(), glm::dvec3(9.5, -1.0, -2.0));
  EXPECT_EQ(c.boundsMax(), glm::dvec3(10.5, 1.0, 2.0));
  EXPECT_DOUBLE_EQ(c.boundsDiagonal(), glm::length(c.boundsMax() - c.boundsMin()));
  MeshWeld weld;
  c.copyWeld(weld);
  MeshContainer d;
  ASSERT_EQ(d.setMesh(box, weld).code, SplitStatus::Ok);
  EXPECT_EQ(d.boundsMax(), glm::dvec3(0.5, 1.0, 2.0));
  d.release();
  EXPECT_GT(d.boundsMin().x, d.boundsMax().x);
}

}  // namespace
}  // namespace cleave::geometry
