// SPDX-License-Identifier: MIT
// The generated humanoid: closed, about 4,000 triangles, weights summing to 1, a valid skeleton and
// clips, and cuttable with caps in a walking pose.
#include "cleave/assets/procedural_character.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "cleave/anim/animation_clip.h"
#include "cleave/geometry/mesh_splitter.h"

namespace cleave::assets {
namespace {

const ProceduralCharacter& character() {
  static const ProceduralCharacter c = makeProceduralCharacter();
  return c;
}

TEST(ProceduralCharacter, IsClosedAfterWeldingAndHasAbout4000Triangles) {
  const geometry::MeshData& mesh = character().mesh;
  EXPECT_GE(mesh.triangleCount(), 3500u);
  EXPECT_LE(mesh.triangleCount(), 4500u);
  geometry::MeshContainer container;
  ASSERT_EQ(container.setMesh(mesh).message, "");
  EXPECT_TRUE(container.closed());
  // Each position once: welding merges nothing.
  EXPECT_EQ(container.positionIdCount(), mesh.vertexCount());
  // Outward winding: the signed volume is positive and plausible for a person (tens of litres).
  double volume = 0.0;
  for (size_t t = 0; t < mesh.indices.size(); t += 3) {
    const glm::dvec3 a(mesh.positions[mesh.indices[t]]), b(mesh.positions[mesh.indices[t + 1]]),
        c(mesh.positions[mesh.indices[t + 2]]);
    volume += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  EXPECT_GT(volume, 0.03);
  EXPECT_LT(volume, 0.12);
}

TEST(ProceduralCharacter, WeightsSumToOneOverAtMostFourJoints) {
  const ProceduralCharacter& c = character();
  ASSERT_EQ(c.mesh.joints.size(), c.mesh.vertexCount());
  ASSERT_EQ(c.mesh.weights.size(), c.mesh.vertexCount());
  ASSERT_EQ(c.mesh.normals.size(), c.mesh.vertexCount());
  for (size_t v = 0; v < c.mesh.vertexCount(); ++v) {
    const glm::vec4 w = c.mesh.weights[v];
    ASSERT_NEAR(w.x + w.y + w.z + w.w, 1.f, 1e-6f) << "vertex " << v;
    for (int k = 0; k < 4; ++k) {
      ASSERT_GE(w[k], 0.f);
      ASSERT_LT(c.mesh.joints[v][k], c.skeleton.size());
      if (w[k] == 0.f) {
        ASSERT_EQ(c.mesh.joints[v][k], 0);
      }
    }
    ASSERT_NEAR(glm::length(c.mesh.normals[v]), 1.f, 1e-4f);
  }
  // Hands follow the hand joints, feet the foot joints.
  const int32_t leftHand = c.skeleton.find("left_hand");
  size_t handVertices = 0;
  for (size_t v = 0; v < c.mesh.vertexCount(); ++v) {
    if (c.mesh.positions[v].x > 0.52f) {
      ++handVertices;
      EXPECT_EQ(c.mesh.joints[v][0], leftHand) << "vertex " << v;
    }
  }
  EXPECT_GT(handVertices, 5u);
}

TEST(ProceduralCharacter, SkeletonAndClipsAreValid) {
  const ProceduralCharacter& c = character();
  EXPECT_EQ(c.skeleton.size(), 17u);
  EXPECT_EQ(anim::validateSkeleton(c.skeleton).message, "");
  EXPECT_EQ(anim::validateClip(c.idle, c.skeleton.size()).message, "");
  EXPECT_EQ(anim::validateClip(c.walk, c.skeleton.size()).message, "");
  EXPECT_FLOAT_EQ(c.walk.duration, 1.f);
  EXPECT_FLOAT_EQ(c.idle.duration, 2.f);
  // The walk loops seamlessly: the pose at the end equals the pose at the start.
  anim::Pose start, end;
  anim::sampleClip(c.skeleton, c.walk, 0.f, false, start);
  anim::sampleClip(c.skeleton, c.walk, c.walk.duration, false, end);
  for (size_t j = 0; j < start.size(); ++j) {
    EXPECT_NEAR(glm::dot(start[j].rotation, end[j].rotation), 1.f, 1e-6f);
    EXPECT_NEAR(glm::distance(start[j].translation, end[j].translation), 0.f, 1e-6f);
  }
  // Mid-stride the feet are apart front to back.
  anim::Pose pose;
  anim::sampleClip(c.skeleton, c.walk, 0.25f, true, pose);
  std::vector<glm::mat4> global;
  anim::localToGlobal(c.skeleton, pose, global);
  const float leftZ = global[size_t(c.skeleton.find("left_foot"))][3].z;
  const float rightZ = global[size_t(c.skeleton.find("right_foot"))][3].z;
  EXPECT_GT(std::abs(leftZ - rightZ), 0.3f);
  // Deterministic: a second build is identical.
  const ProceduralCharacter again = makeProceduralCharacter();
  EXPECT_EQ(again.mesh.positions, c.mesh.positions);
  EXPECT_EQ(again.mesh.indices, c.mesh.indices);
  EXPECT_EQ(again.mesh.weights, c.mesh.weights);
}

TEST(ProceduralCharacter, CutsWithCapsInAWalkingPose) {
  const ProceduralCharacter& c = character();
  anim::Pose pose;
  anim::sampleClip(c.skeleton, c.walk, 0.3f, true, pose);
  std::vector<glm::mat4> joints;
  anim::poseToJointMatrices(c.skeleton, pose, joints);
  geometry::MeshContainer container;
  ASSERT_EQ(container.setMesh(c.mesh).code, geometry::SplitStatus::Ok);
  ASSERT_EQ(container.setSkinningPose(joints, glm::mat4(1.f)).code, geometry::SplitStatus::Ok);
  auto splitter = geometry::makeConcaveSplitter();
  const geometry::Plane planes[] = {{{0, 1, 0}, 1.0},     {{0, 1, 0}, 0.6},   {{1, 0, 0}, 0.0},
                                    {{0.3, 1, 0.2}, 1.3}, {{1, 0.2, 0}, 0.3}, {{0, 0, 1}, 0.02}};
  for (const geometry::Plane& plane : planes) {
    geometry::SplitResult result;
    ASSERT_EQ(splitter->split(container, plane, geometry::SplitOptions{}, result),
              geometry::SplitStatus::Ok)
        << result.message;
    EXPECT_GE(result.pieces.size(), 2u);
    for (const geometry::SplitPiece& piece : result.pieces) {
      EXPECT_GT(piece.capTriangles, 0u);
      EXPECT_GT(piece.mass.volume, 0.0);
      EXPECT_FALSE(piece.joints.empty());
      geometry::MeshContainer check;
      ASSERT_EQ(check.setMesh(piece.mesh).code, geometry::SplitStatus::Ok);
      EXPECT_TRUE(check.closed());
    }
  }
}

// The convex multi-part variant: one closed convex box per bone, rigidly bound, no two touching,
// and cuttable in a pose like the smooth character (the sections of separate parts never overlap).
TEST(ProceduralCharacter, MultiPartVariantIsRigidConvexPartsThatNeverTouch) {
  const ProceduralCharacter& c = character();
  const geometry::MeshData parts = makeCharacterParts(c);
  ASSERT_EQ(parts.joints.size(), parts.positions.size());
  ASSERT_EQ(parts.weights.size(), parts.positions.size());
  // Boxes of 24 vertices and 12 triangles, one joint each with weight 1.
  ASSERT_EQ(parts.positions.size() % 24, 0u);
  const size_t boxes = parts.positions.size() / 24;
  EXPECT_GE(boxes, 14u);
  std::vector<glm::vec3> lo(boxes, glm::vec3(1e9f)), hi(boxes, glm::vec3(-1e9f));
  for (size_t v = 0; v < parts.positions.size(); ++v) {
    EXPECT_EQ(parts.weights[v], glm::vec4(1.f, 0.f, 0.f, 0.f));
    EXPECT_EQ(parts.joints[v].x, parts.joints[v / 24 * 24].x) << "a box spans two joints";
    lo[v / 24] = glm::min(lo[v / 24], parts.positions[v]);
    hi[v / 24] = glm::max(hi[v / 24], parts.positions[v]);
  }
  geometry::MeshContainer container;
  ASSERT_EQ(container.setMesh(parts).code, geometry::SplitStatus::Ok);
  EXPECT_TRUE(container.closed());
  // Every box is convex and the parts are apart: the smallest gap between vertices of different
  // boxes is positive (a conservative check against touching parts).
  double nearest = 1e9;
  for (size_t a = 0; a < boxes; ++a)
    for (size_t b = a + 1; b < boxes; ++b)
      for (size_t i = 0; i < 24; ++i)
        for (size_t k = 0; k < 24; ++k)
          nearest = std::min(nearest, double(glm::distance(parts.positions[a * 24 + i], parts.positions[b * 24 + k])));
  EXPECT_GT(nearest, 0.01);
  anim::Pose pose;
  anim::sampleClip(c.skeleton, c.idle, 0.7f, true, pose);
  std::vector<glm::mat4> joints;
  anim::poseToJointMatrices(c.skeleton, pose, joints);
  ASSERT_EQ(container.setSkinningPose(joints, glm::mat4(1.f)).code, geometry::SplitStatus::Ok);
  auto splitter = geometry::makeConcaveSplitter();
  for (const geometry::Plane& plane : {geometry::Plane{{0, 1, 0}, 1.1}, geometry::Plane{{0, 1, 0}, 0.5},
                                       geometry::Plane{{1, 0, 0.3}, 0.05}, geometry::Plane{{0.2, 1, 0.1}, 1.4}}) {
    geometry::SplitResult result;
    ASSERT_EQ(splitter->split(container, plane, geometry::SplitOptions{}, result), geometry::SplitStatus::Ok)
        << result.message;
    for (const geometry::SplitPiece& piece : result.pieces) {
      geometry::MeshContainer check;
      ASSERT_EQ(check.setMesh(piece.mesh).code, geometry::SplitStatus::Ok);
      EXPECT_TRUE(check.closed());
    }
  }
}

}  // namespace
}  // namespace cleave::assets
