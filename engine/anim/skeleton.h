// SPDX-License-Identifier: MIT
// Skeleton and pose: joints with a parent, a rest transform and an inverse bind matrix; local poses
// to global transforms; global transforms to the joint matrices that skin a mesh.
//
// Spaces. A joint's local transform is relative to its parent joint (or, for a root joint, to the
// model origin), after the joint's fixed `offset` (the transforms of non-joint nodes that sit
// between two joints in a file; identity for skeletons built in code). Globals are in model space.
// The joint matrix of joint j is global[j] * inverseBind[j]: it maps a bind-space vertex to model
// space, so a skinned vertex is model * sum_k w_k * jointMatrix[j_k] * p (see
// geometry::MeshContainer).
//
// Units: metres and radians; quaternions are unit length (w, x, y, z as in GLM).
// Ownership: everything is plain values. No function allocates unless an output vector must grow.
// Failure: validateSkeleton() reports a broken skeleton with a reason; the pose functions require a
// valid skeleton and a pose of the skeleton's size (asserted).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <span>
#include <string>
#include <vector>

#include "cleave/base/status.h"

namespace cleave::anim {

// Translation, rotation, scale: matrix = T * R * S.
struct Transform {
  glm::vec3 translation{0.f};
  glm::quat rotation{1.f, 0.f, 0.f, 0.f};
  glm::vec3 scale{1.f};

  glm::mat4 matrix() const;
};

struct Joint {
  std::string name;
  int32_t parent = -1;         // index of the parent joint, -1 for a root
  Transform rest;              // local transform in the rest (bind) pose
  glm::mat4 offset{1.f};       // fixed transform applied before `rest`/the animated local one
  glm::mat4 inverseBind{1.f};  // model space -> joint space in the bind pose
};

struct Skeleton {
  std::vector<Joint> joints;  // any order; a parent may come after its child

  size_t size() const { return joints.size(); }
  // Index of the first joint with this name, or -1.
  int32_t find(const std::string& name) const;
};

// A local transform per joint, indexed like Skeleton::joints.
using Pose = std::vector<Transform>;

// Ok when every parent index is in range and the parent chains have no cycle; otherwise
// InvalidArgument with a reason naming the joint.
base::Status validateSkeleton(const Skeleton& skeleton);

// The rest pose (each joint's `rest`).
void restPose(const Skeleton& skeleton, Pose& out);

// Per joint: lerp of translation and scale, shortest-path slerp of rotation; t in [0, 1]
// (0 gives a, 1 gives b). `a` and `b` must have the same size; `out` may alias either.
void blendPoses(const Pose& a, const Pose& b, float t, Pose& out);

// Global (model-space) transform of every joint: global = global[parent] * offset * local.
void localToGlobal(const Skeleton& skeleton, const Pose& local, std::vector<glm::mat4>& global);

// Joint matrices: global[j] * inverseBind[j].
void jointMatrices(const Skeleton& skeleton, std::span<const glm::mat4> global,
                   std::vector<glm::mat4>& out);

// Convenience: local pose -> joint matrices in one call.
void poseToJointMatrices(const Skeleton& skeleton, const Pose& local, std::vector<glm::mat4>& out);

// Inverse bind matrices that make `local` the bind pose: inverseBind[j] = inverse(global[j]).
void setBindPose(Skeleton& skeleton, const Pose& local);

}  // namespace cleave::anim
