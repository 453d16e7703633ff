// SPDX-License-Identifier: MIT
// Skeleton poses. Joints may be stored in any order, so localToGlobal resolves parents first: the
// common case (every parent before its child) is one forward pass; otherwise joints are resolved in
// repeated passes, each finishing at least one more level of the tree.
#include "cleave/anim/skeleton.h"

#include <cassert>
#include <glm/gtc/matrix_transform.hpp>

namespace cleave::anim {

glm::mat4 Transform::matrix() const {
  glm::mat4 m = glm::mat4_cast(rotation);
  m[0] *= scale.x;
  m[1] *= scale.y;
  m[2] *= scale.z;
  m[3] = glm::vec4(translation, 1.f);
  return m;
}

int32_t Skeleton::find(const std::string& name) const {
  for (size_t j = 0; j < joints.size(); ++j) {
    if (joints[j].name == name) return static_cast<int32_t>(j);
  }
  return -1;
}

base::Status validateSkeleton(const Skeleton& skeleton) {
  auto fail = [](std::string reason) {
    return base::Status::failure(base::StatusCode::InvalidArgument, std::move(reason));
  };
  const size_t n = skeleton.joints.size();
  for (size_t j = 0; j < n; ++j) {
    const int32_t parent = skeleton.joints[j].parent;
    if (parent < -1 || parent >= static_cast<int32_t>(n) || parent == static_cast<int32_t>(j)) {
      return fail("joint " + std::to_string(j) + " has an invalid parent " + std::to_string(parent));
    }
  }
  // A chain longer than n steps must revisit a joint.
  for (size_t j = 0; j < n; ++j) {
    int32_t at = static_cast<int32_t>(j);
    size_t steps = 0;
    while (at >= 0 && steps <= n) {
      at = skeleton.joints[static_cast<size_t>(at)].parent;
      ++steps;
    }
    if (at >= 0) {
      return fail("joint " + std::to_string(j) + " ('" + skeleton.joints[j].name + "') is in a parent cycle");
    }
  }
  return {};
}

void restPose(const Skeleton& skeleton, Pose& out) {
  out.resize(skeleton.joints.size());
  for (size_t j = 0; j < out.size(); ++j) out[j] = skeleton.joints[j].rest;
}

void blendPoses(const Pose& a, const Pose& b, float t, Pose& out) {
  assert(a.size() == b.size());
  out.resize(a.size());
  for (size_t j = 0; j < a.size(); ++j) {
    Transform r;
    r.translation = glm::mix(a[j].translation, b[j].translation, t);
    r.scale = glm::mix(a[j].scale, b[j].scale, t);
    glm::quat qb = b[j].rotation;
    if (glm::dot(a[j].rotation, qb) < 0.f) qb = -qb;  // shortest path
    r.rotation = glm::normalize(glm::slerp(a[j].rotation, qb, t));
    out[j] = r;
  }
}

void localToGlobal(const Skeleton& skeleton, const Pose& local, std::vector<glm::mat4>& global) {
  const size_t n = skeleton.joints.size();
  assert(local.size() == n);
  global.resize(n);
  bool ordered = true;
  for (size_t j = 0; j < n && ordered; ++j)
    ordered = skeleton.joints[j].parent < static_cast<int32_t>(j);
  auto compute = [&](size_t j) {
    const Joint& joint = skeleton.joints[j];
    const glm::mat4 own = joint.offset * local[j].matrix();
    global[j] = joint.parent < 0 ? own : global[static_cast<size_t>(joint.parent)] * own;
  };
  if (ordered) {
    for (size_t j = 0; j < n; ++j) compute(j);
    return;
  }
  std::vector<uint8_t> done(n, 0);
  size_t remaining = n;
  while (remaining > 0) {
    size_t progress = 0;
    for (size_t j = 0; j < n; ++j) {
      if (done[j]) continue;
      const int32_t parent = skeleton.joints[j].parent;
      if (parent >= 0 && !done[static_cast<size_t>(parent)]) continue;
      compute(j);
      done[j] = 1;
      ++progress;
    }
    if (progress == 0) break;  // a cycle (precondition violated): leave the rest as they are
    remaining -= progress;
  }
}

void jointMatrices(const Skeleton& skeleton, std::span<const glm::mat4> global,
                   std::vector<glm::mat4>& out) {
  assert(global.size() == skeleton.joints.size());
  out.resize(global.size());
  for (size_t j = 0; j < global.size(); ++j) out[j] = global[j] * skeleton.joints[j].inverseBind;
}

void poseToJointMatrices(const Skeleton& skeleton, const Pose& local, std::vector<glm::mat4>& out) {
  localToGlobal(skeleton, local, out);
  for (size_t j = 0; j < out.size(); ++j) out[j] = out[j] * skeleton.joints[j].inverseBind;
}

void setBindPose(Skeleton& skeleton, const Pose& local) {
  std::vector<glm::mat4> global;
  localToGlobal(skeleton, local, global);
  for (size_t j = 0; j < global.size(); ++j)
    skeleton.joints[j].inverseBind = glm::inverse(global[j]);
}

}  // namespace cleave::anim
