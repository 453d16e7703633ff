// SPDX-License-Identifier: MIT
// Cutting skinned meshes in their pose: merged and renormalised weights on new vertices, cap
// vertices weighted like the cut edges, the joints each piece keeps, and cuts placed in pose space.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "cleave/geometry/mesh_splitter.h"
#include "cleave/geometry/primitives.h"

namespace cleave::geometry {
namespace {

constexpr uint16_t kLower = 3, kUpper = 7;

// A capsule along y (y in [-1.1, 1.1]) skinned to joint 3 below y = -0.3, joint 7 above y = 0.3 and
// a blend of both in between. Joint matrices are given for 8 joints.
MeshData skinnedCapsule() {
  MeshData mesh = primitives::capsule(0.3f, 1.6f, 16, 8);
  mesh.joints.clear();
  mesh.weights.clear();
  for (const glm::vec3& p : mesh.positions) {
    const float s = glm::clamp((p.y + 0.3f) / 0.6f, 0.f, 1.f);
    if (s <= 0.f) {
      mesh.joints.emplace_back(kLower, 0, 0, 0);
      mesh.weights.emplace_back(1.f, 0.f, 0.f, 0.f);
    } else if (s >= 1.f) {
      mesh.joints.emplace_back(kUpper, 0, 0, 0);
      mesh.weights.emplace_back(1.f, 0.f, 0.f, 0.f);
    } else {
      mesh.joints.emplace_back(kLower, kUpper, 0, 0);
      mesh.weights.emplace_back(1.f - s, s, 0.f, 0.f);
    }
  }
  return mesh;
}

// Joint 7 bends the upper half by 40 degrees about z around the point (0, 0.3, 0).
std::vector<glm::mat4> bentPose() {
  std::vector<glm::mat4> joints(8, glm::mat4(1.f));
  const glm::vec3 pivot(0.f, 0.3f, 0.f);
  joints[kUpper] = glm::translate(glm::mat4(1.f), pivot) *
                   glm::rotate(glm::mat4(1.f), glm::radians(40.f), glm::vec3(0, 0, 1)) *
                   glm::translate(glm::mat4(1.f), -pivot);
  return joints;
}

glm::vec3 skin(const MeshData& mesh, size_t v, std::span<const glm::mat4> joints) {
  glm::mat4 blend(0.f);
  for (int k = 0; k < 4; ++k) blend += mesh.weights[v][k] * joints[mesh.joints[v][k]];
  return glm::vec3(blend * glm::vec4(mesh.positions[v], 1.f));
}

struct Cut {
  SplitStatus status;
  SplitResult result;
};

Cut cutInPose(const MeshData& mesh, std::span<const glm::mat4> joints, const Plane& plane) {
  MeshContainer container;
  EXPECT_EQ(container.setMesh(mesh).message, "");
  EXPECT_EQ(container.setSkinningPose(joints, glm::mat4(1.f)).message, "");
  Cut cut;
  cut.status = makeConcaveSplitter()->split(container, plane, SplitOptions{}, cut.result);
  return cut;
}

void expectValidSkin(const MeshData& mesh) {
  ASSERT_EQ(mesh.joints.size(), mesh.positions.size());
  ASSERT_EQ(mesh.weights.size(), mesh.positions.size());
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const glm::vec4 w = mesh.weights[v];
    EXPECT_NEAR(w.x + w.y + w.z + w.w, 1.f, 1e-5f) << "vertex " << v;
    for (int k = 0; k < 4; ++k) {
      EXPECT_GE(w[k], 0.f);
      if (w[k] == 0.f) {
        EXPECT_EQ(mesh.joints[v][k], 0) << "an empty slot names no joint";
      }
    }
    for (int k = 0; k < 3; ++k) EXPECT_GE(w[k], w[k + 1]) << "weights sorted, largest first";
  }
}

TEST(SkinnedSplit, PiecesKeepOnlyTheJointsTheyUse) {
  const MeshData mesh = skinnedCapsule();
  const std::vector<glm::mat4> identity(8, glm::mat4(1.f));
  Cut cut = cutInPose(mesh, identity, Plane{{0, 1, 0}, 0.85});  // in the upper hemisphere
  ASSERT_EQ(cut.status, SplitStatus::Ok) << cut.result.message;
  ASSERT_EQ(cut.result.pieces.size(), 2u);
  const SplitPiece& above = cut.result.pieces[0];
  const SplitPiece& below = cut.result.pieces[1];
  EXPECT_EQ(above.joints, std::vector<uint16_t>({kUpper}));
  EXPECT_EQ(below.joints, std::vector<uint16_t>({kLower, kUpper}));
  // A cut through the lower half leaves the lower joint only on the small piece.
  Cut low = cutInPose(mesh, identity, Plane{{0, 1, 0}, -0.8});
  ASSERT_EQ(low.status, SplitStatus::Ok);
  EXPECT_EQ(low.result.pieces[1].joints, std::vector<uint16_t>({kLower}));
  // Static meshes report no joints.
  MeshContainer plain;
  ASSERT_EQ(plain.setMesh(primitives::box(glm::vec3(1.f))).code, SplitStatus::Ok);
  SplitResult boxResult;
  ASSERT_EQ(makeConcaveSplitter()->split(plain, Plane{{0, 1, 0}, 0.0}, SplitOptions{}, boxResult),
            SplitStatus::Ok);
  EXPECT_TRUE(boxResult.pieces[0].joints.empty());
}

TEST(SkinnedSplit, WeightsStayNormalisedAndCapVerticesFollowTheCutEdges) {
  const MeshData mesh = skinnedCapsule();
  Cut cut = cutInPose(mesh, bentPose(), Plane{{1, 1, 0}, 0.05});  // through the blended middle
  ASSERT_EQ(cut.status, SplitStatus::Ok) << cut.result.message;
  const uint32_t capMaterial = SplitOptions{}.capMaterialId;
  for (const SplitPiece& piece : cut.result.pieces) {
    expectValidSkin(piece.mesh);
    // Every cap vertex has the same influences as the side-wall vertex at the same place.
    size_t capVertices = 0;
    for (const SubMesh& run : piece.mesh.submeshes) {
      if (run.materialId != capMaterial) continue;
      for (uint32_t i = run.firstIndex; i < run.firstIndex + run.indexCount; ++i) {
        const uint32_t v = piece.mesh.indices[i];
        ++capVertices;
        bool matched = false;
        for (size_t u = 0; u < piece.mesh.positions.size() && !matched; ++u) {
          if (u == v || glm::distance(piece.mesh.positions[u], piece.mesh.positions[v]) > 1e-6f)
            continue;
          if (piece.mesh.normals[u] == piece.mesh.normals[v]) continue;  // another cap vertex
          matched = piece.mesh.joints[u] == piece.mesh.joints[v] &&
                    piece.mesh.weights[u] == piece.mesh.weights[v];
        }
        EXPECT_TRUE(matched) << "cap vertex " << v;
      }
    }
    EXPECT_GT(capVertices, 0u);
  }
}

TEST(SkinnedSplit, TheCutIsPlacedInThePose) {
  const MeshData mesh = skinnedCapsule();
  const std::vector<glm::mat4> pose = bentPose();
  // A plane across the bent upper half, perpendicular to its bent axis, 0.55 m from the pivot.
  const glm::vec3 axis = glm::vec3(pose[kUpper] * glm::vec4(0, 1, 0, 0));
  const glm::vec3 pivot(0.f, 0.3f, 0.f);
  const Plane plane{glm::dvec3(axis), glm::dot(glm::dvec3(axis), glm::dvec3(pivot + 0.55f * axis))};
  Cut cut = cutInPose(mesh, pose, plane);
  ASSERT_EQ(cut.status, SplitStatus::Ok) << cut.result.message;
  ASSERT_EQ(cut.result.pieces.size(), 2u);
  const SplitPiece& above = cut.result.pieces[0];
  EXPECT_EQ(above.joints, std::vector<uint16_t>({kUpper}));
  // The upper joint is rigid there: re-posing the piece puts every vertex above the plane and the
  // cut ones on it. In bind space the cut lies 0.55 above the pivot (y = 0.85); in the pose it is
  // tilted by 40 degrees, so a bind-space cut at y = 0.85 would have missed it.
  size_t onPlane = 0;
  float lowestWorld = 10.f, highestWorld = -10.f;
  for (size_t v = 0; v < above.mesh.positions.size(); ++v) {
    const glm::vec3 posed = skin(above.mesh, v, pose);
    const double d = glm::dot(glm::dvec3(posed), plane.normal) / glm::length(plane.normal) -
                     plane.offset / glm::length(plane.normal);
    EXPECT_GT(d, -1e-5) << "vertex " << v;
    if (std::abs(d) < 1e-5) {
      ++onPlane;
      EXPECT_NEAR(above.mesh.positions[v].y, 0.85f, 1e-4f);
      lowestWorld = std::min(lowestWorld, posed.y);
      highestWorld = std::max(highestWorld, posed.y);
    }
  }
  EXPECT_GT(onPlane, 16u);
  EXPECT_GT(highestWorld - lowestWorld, 0.3f);
}

}  // namespace
}  // namespace cleave::geometry
