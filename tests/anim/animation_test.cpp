// SPDX-License-Identifier: MIT
// engine/anim: skeleton poses, clip sampling (step, linear, cubic spline), looping, crossfades and
// joint matrices, on small cases with exact expected values.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "cleave/anim/animation_clip.h"
#include "cleave/anim/skeleton.h"

namespace cleave::anim {
namespace {

constexpr float kPi = 3.14159265358979f;

void expectNear(const glm::vec3& a, const glm::vec3& b, float eps = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

glm::vec4 quatValue(float angle, const glm::vec3& axis) {
  const glm::quat q = glm::angleAxis(angle, axis);
  return glm::vec4(q.x, q.y, q.z, q.w);
}

// Two joints: a root at the origin and a child one metre up the y axis.
Skeleton twoBoneArm() {
  Skeleton s;
  s.joints.resize(2);
  s.joints[0].name = "root";
  s.joints[1].name = "tip";
  s.joints[1].parent = 0;
  s.joints[1].rest.translation = glm::vec3(0.f, 1.f, 0.f);
  Pose rest;
  restPose(s, rest);
  setBindPose(s, rest);
  return s;
}

Channel channel(uint32_t joint, ChannelPath path, Interpolation interpolation,
                std::vector<float> times, std::vector<glm::vec4> values) {
  Channel c;
  c.joint = joint;
  c.path = path;
  c.interpolation = interpolation;
  c.times = std::move(times);
  c.values = std::move(values);
  return c;
}

TEST(Transform, MatrixIsTranslationRotationScale) {
  Transform t;
  t.translation = glm::vec3(1, 2, 3);
  t.rotation = glm::angleAxis(kPi / 2, glm::vec3(0, 0, 1));
  t.scale = glm::vec3(2, 1, 1);
  const glm::vec4 p = t.matrix() * glm::vec4(1, 0, 0, 1);  // scaled to (2,0,0), rotated to (0,2,0)
  expectNear(glm::vec3(p), glm::vec3(1, 4, 3));
}

TEST(Skeleton, ValidateRejectsCyclesAndBadParents) {
  Skeleton s = twoBoneArm();
  EXPECT_TRUE(validateSkeleton(s).ok());
  s.joints[0].parent = 1;
  std::string why;
  why = validateSkeleton(s).message;
  EXPECT_FALSE(why.empty());
  EXPECT_NE(why.find("cycle"), std::string::npos) << why;
  s.joints[0].parent = 7;
  why = validateSkeleton(s).message;
  EXPECT_FALSE(why.empty());
  EXPECT_NE(why.find("invalid parent"), std::string::npos) << why;
  EXPECT_EQ(twoBoneArm().find("tip"), 1);
  EXPECT_EQ(twoBoneArm().find("nose"), -1);
}

TEST(Skeleton, BindPoseGivesIdentityJointMatrices) {
  const Skeleton s = twoBoneArm();
  Pose rest;
  restPose(s, rest);
  std::vector<glm::mat4> joints;
  poseToJointMatrices(s, rest, joints);
  ASSERT_EQ(joints.size(), 2u);
  for (const glm::mat4& m : joints) {
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) EXPECT_NEAR(m[c][r], c == r ? 1.f : 0.f, 1e-6f);
  }
}

TEST(Skeleton, GlobalPoseChainsParentsInAnyOrder) {
  // The child is stored before its parent.
  Skeleton s;
  s.joints.resize(2);
  s.joints[0].parent = 1;
  s.joints[0].rest.translation = glm::vec3(0, 1, 0);
  s.joints[1].rest.rotation = glm::angleAxis(kPi / 2, glm::vec3(0, 0, 1));
  s.joints[1].offset = glm::translate(glm::mat4(1.f), glm::vec3(5, 0, 0));
  Pose rest;
  restPose(s, rest);
  std::vector<glm::mat4> global;
  localToGlobal(s, rest, global);
  // Root at (5,0,0) rotated 90 degrees about z: its child's +y offset points along -x.
  expectNear(glm::vec3(global[1][3]), glm::vec3(5, 0, 0));
  expectNear(glm::vec3(global[0][3]), glm::vec3(4, 0, 0));
}

TEST(Skeleton, JointMatrixMovesBindVertexWithItsBone) {
  const Skeleton s = twoBoneArm();
  Pose pose;
  restPose(s, pose);
  pose[0].rotation = glm::angleAxis(kPi / 2, glm::vec3(0, 0, 1));  // the whole arm turns to -x
  std::vector<glm::mat4> joints;
  poseToJointMatrices(s, pose, joints);
  // A bind-space vertex at the tip (0, 1.5, 0), bound to the tip joint, goes to (-1.5, 0, 0).
  expectNear(glm::vec3(joints[1] * glm::vec4(0, 1.5f, 0, 1)), glm::vec3(-1.5f, 0, 0));
}

TEST(AnimationClip, StepHoldsThePreviousKey) {
  const Skeleton s = twoBoneArm();
  AnimationClip clip;
  clip.channels.push_back(channel(1, ChannelPath::Translation, Interpolation::Step, {0.f, 1.f, 2.f},
                                  {{0, 1, 0, 0}, {0, 2, 0, 0}, {0, 3, 0, 0}}));
  clip.updateDuration();
  EXPECT_FLOAT_EQ(clip.duration, 2.f);
  Pose pose;
  sampleClip(s, clip, 0.99f, false, pose);
  EXPECT_FLOAT_EQ(pose[1].translation.y, 1.f);
  sampleClip(s, clip, 1.0f, false, pose);
  EXPECT_FLOAT_EQ(pose[1].translation.y, 2.f);
  sampleClip(s, clip, 7.f, false, pose);  // clamped past the end
  EXPECT_FLOAT_EQ(pose[1].translation.y, 3.f);
  // Joint 0 has no channel and keeps its rest transform.
  EXPECT_EQ(pose[0].translation, glm::vec3(0.f));
}

TEST(AnimationClip, LinearLerpsTranslationAndSlerpsRotation) {
  const Skeleton s = twoBoneArm();
  AnimationClip clip;
  clip.channels.push_back(channel(1, ChannelPath::Translation, Interpolation::Linear, {0.f, 2.f},
                                  {{0, 0, 0, 0}, {4, 0, 0, 0}}));
  clip.channels.push_back(channel(0, ChannelPath::Rotation, Interpolation::Linear, {0.f, 2.f},
                                  {quatValue(0.f, {0, 0, 1}), quatValue(kPi / 2, {0, 0, 1})}));
  clip.updateDuration();
  Pose pose;
  sampleClip(s, clip, 0.5f, false, pose);
  EXPECT_NEAR(pose[1].translation.x, 1.f, 1e-6f);
  // A quarter of the way: 22.5 degrees (slerp is uniform in angle, lerp of components would not
  // be).
  EXPECT_NEAR(glm::angle(pose[0].rotation), kPi / 8, 1e-5f);
  EXPECT_NEAR(glm::length(pose[0].rotation), 1.f, 1e-6f);
}

TEST(AnimationClip, LinearRotationTakesTheShortestPath) {
  const Skeleton s = twoBoneArm();
  AnimationClip clip;
  glm::vec4 b = quatValue(kPi / 2, {0, 0, 1});
  b = -b;  // the same rotation with the opposite sign
  clip.channels.push_back(channel(0, ChannelPath::Rotation, Interpolation::Linear, {0.f, 1.f},
                                  {quatValue(0.f, {0, 0, 1}), b}));
  clip.updateDuration();
  Pose pose;
  sampleClip(s, clip, 0.5f, false, pose);
  const glm::vec3 x = pose[0].rotation * glm::vec3(1, 0, 0);
  expectNear(x, glm::vec3(std::cos(kPi / 4), std::sin(kPi / 4), 0.f));
}

TEST(AnimationClip, CubicSplineFollowsTheHermiteFormula) {
  const Skeleton s = twoBoneArm();
  AnimationClip clip;
  // Keys at 0 and 2: values 0 and 1, out-tangent of key 0 = 1, in-tangent of key 1 = 0.5 (per
  // second).
  clip.channels.push_back(channel(1, ChannelPath::Scale, Interpolation::CubicSpline, {0.f, 2.f},
                                  {{9, 9, 9, 0},
                                   {0, 0, 0, 0},
                                   {1, 1, 1, 0},
                                   {0.5f, 0.5f, 0.5f, 0},
                                   {1, 1, 1, 0},
                                   {9, 9, 9, 0}}));
  clip.updateDuration();
  Pose pose;
  sampleClip(s, clip, 0.5f, false, pose);
  // s = 0.25, d = 2: h10 = s^3 - 2s^2 + s = 0.140625, h01 = 0.15625, h11 = s^3 - s^2 = -0.046875.
  const float expected = 0.140625f * 2.f * 1.f + 0.15625f * 1.f + -0.046875f * 2.f * 0.5f;
  EXPECT_NEAR(pose[1].scale.x, expected, 1e-6f);
  sampleClip(s, clip, 2.f, false, pose);
  EXPECT_FLOAT_EQ(pose[1].scale.y, 1.f);  // the value at the last key, not a tangent
}

TEST(AnimationClip, LoopingWrapsAndClampingHolds) {
  AnimationClip clip;
  clip.duration = 2.f;
  EXPECT_FLOAT_EQ(clipTime(clip, 5.f, true), 1.f);
  EXPECT_FLOAT_EQ(clipTime(clip, -0.5f, true), 1.5f);
  EXPECT_FLOAT_EQ(clipTime(clip, 5.f, false), 2.f);
  EXPECT_FLOAT_EQ(clipTime(clip, -1.f, false), 0.f);
  const Skeleton s = twoBoneArm();
  clip.channels.push_back(channel(1, ChannelPath::Translation, Interpolation::Linear, {0.f, 2.f},
                                  {{0, 0, 0, 0}, {2, 0, 0, 0}}));
  Pose a, b;
  sampleClip(s, clip, 0.25f, true, a);
  sampleClip(s, clip, 4.25f, true, b);
  EXPECT_EQ(a[1].translation, b[1].translation);
}

TEST(AnimationClip, ValidateNamesTheBrokenChannel) {
  AnimationClip clip;
  clip.name = "walk";
  clip.channels.push_back(channel(0, ChannelPath::Translation, Interpolation::Linear, {0.f, 1.f},
                                  {{0, 0, 0, 0}, {1, 0, 0, 0}}));
  EXPECT_TRUE(validateClip(clip, 2).ok());
  std::string why;
  why = validateClip(clip, 0).message;
  EXPECT_FALSE(why.empty());
  EXPECT_NE(why.find("walk"), std::string::npos);
  clip.channels[0].times = {1.f, 1.f};
  why = validateClip(clip, 2).message;
  EXPECT_FALSE(why.empty());
  EXPECT_NE(why.find("increasing"), std::string::npos) << why;
  clip.channels[0].times = {0.f, 1.f};
  clip.channels[0].interpolation = Interpolation::CubicSpline;  // needs 6 values
  why = validateClip(clip, 2).message;
  EXPECT_FALSE(why.empty());
  // A malformed channel is skipped, not read out of range.
  const Skeleton s = twoBoneArm();
  Pose pose;
  clip.updateDuration();
  sampleClip(s, clip, 0.5f, false, pose);
  EXPECT_EQ(pose[0].translation, glm::vec3(0.f));
}

TEST(Animator, CrossfadeBlendsFromTheOldClipToTheNew) {
  const Skeleton s = twoBoneArm();
  AnimationClip left, right;
  left.channels.push_back(
      channel(1, ChannelPath::Translation, Interpolation::Step, {0.f}, {{-1, 0, 0, 0}}));
  right.channels.push_back(
      channel(1, ChannelPath::Translation, Interpolation::Step, {0.f}, {{1, 0, 0, 0}}));
  left.duration = right.duration = 1.f;
  Animator animator(&s);
  animator.play(&left);
  Pose pose;
  animator.evaluate(pose);
  EXPECT_FLOAT_EQ(pose[1].translation.x, -1.f);
  animator.play(&right, 0.5f);
  animator.advance(0.125f);
  EXPECT_FLOAT_EQ(animator.blendWeight(), 0.25f);
  animator.evaluate(pose);
  EXPECT_FLOAT_EQ(pose[1].translation.x, -0.5f);  // 0.75 * -1 + 0.25 * 1
  animator.advance(0.5f);
  EXPECT_FLOAT_EQ(animator.blendWeight(), 1.f);
  animator.evaluate(pose);
  EXPECT_FLOAT_EQ(pose[1].translation.x, 1.f);
  EXPECT_EQ(animator.clip(), &right);
}

TEST(Animator, SamplingIsDeterministic) {
  const Skeleton s = twoBoneArm();
  AnimationClip clip;
  clip.channels.push_back(
      channel(0, ChannelPath::Rotation, Interpolation::Linear, {0.f, 0.7f, 1.3f},
              {quatValue(0.f, {0, 1, 0}), quatValue(1.f, {0, 1, 0}), quatValue(2.f, {1, 0, 0})}));
  clip.updateDuration();
  std::vector<glm::mat4> a, b;
  Animator first(&s), second(&s);
  first.play(&clip);
  second.play(&clip);
  for (int tick = 0; tick < 100; ++tick) {
    first.advance(1.f / 60.f);
    second.advance(1.f / 60.f);
  }
  first.evaluateJointMatrices(a);
  second.evaluateJointMatrices(b);
  ASSERT_EQ(a.size(), b.size());
  for (size_t j = 0; j < a.size(); ++j) EXPECT_EQ(a[j], b[j]);
}

}  // namespace
}  // namespace cleave::anim
