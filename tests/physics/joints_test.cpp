// SPDX-License-Identifier: MIT
// Joints (cone-twist and hinge constraints): a pendulum chain holds together and swings, limits are
// respected, destroying a body drops its joints, bad defs are refused, runs are deterministic; and
// the two body options ragdolls need: collision groups and kinematic bodies.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "cleave/physics/physics_world.h"
#include "tests/physics/physics_test_helpers.h"

namespace cleave::physics {
namespace {

using testing::addBody;
using testing::addGround;
using testing::kDt;

// A joint between two bodies at a world pivot with a world frame rotation (frames built so the
// joint starts at rest).
JointDef jointAt(PhysicsWorld& world, JointType type, BodyId a, BodyId b, glm::vec3 pivot,
                 glm::quat rotation = glm::quat(1, 0, 0, 0)) {
  JointDef def;
  def.type = type;
  def.bodyA = a;
  def.bodyB = b;
  auto local = [&](BodyId body) {
    const BodyTransform t = *world.bodyTransform(body);
    const glm::quat inv = glm::inverse(t.rotation);
    return BodyTransform{inv * (pivot - t.position), inv * rotation};
  };
  def.frameA = local(a);
  def.frameB = local(b);
  return def;
}

struct Chain {
  BodyId anchor;
  std::vector<BodyId> links;
  std::vector<JointId> joints;
};

// A static anchor at (0, 5, 0) and `n` capsule links of 0.4 m hanging sideways along +x from it
// (horizontal at the start, so gravity swings the chain down).
Chain makeChain(PhysicsWorld& world, int n, JointType type) {
  Chain chain;
  chain.anchor = addBody(world, ShapeDef::sphere(0.05f), 0.0f, glm::vec3(0.0f, 5.0f, 0.0f));
  // Capsule axis is local y: turn it onto +x.
  const glm::quat toX = glm::angleAxis(-glm::half_pi<float>(), glm::vec3(0, 0, 1));
  BodyId previous = chain.anchor;
  for (int i = 0; i < n; ++i) {
    BodyDef def;
    def.rotation = toX;
    def.allowSleep = false;
    const BodyId link = addBody(world, ShapeDef::capsule(0.05f, 0.15f), 1.0f,
                                glm::vec3(0.2f + 0.4f * float(i), 5.0f, 0.0f), def);
    // Hinge axis (frame z) = world z: the chain swings in the x-y plane.
    const JointDef j = jointAt(world, type, previous, link, glm::vec3(0.4f * float(i), 5.0f, 0.0f));
    const Result<JointId> id = world.createJoint(j);
    EXPECT_TRUE(id.ok()) << id.message();
    chain.links.push_back(link);
    chain.joints.push_back(id.value());
    previous = link;
  }
  return chain;
}

TEST(Joints, PendulumChainHoldsTogetherAndSwings) {
  for (JointType type : {JointType::ConeTwist, JointType::Hinge}) {
    PhysicsWorld world;
        Chain chain = makeChain(world, 5, type);
    ASSERT_EQ(world.jointCount(), 5u);
    float maxSeparation = 0.0f, sumSeparation = 0.0f;
    int samples = 0;
    float lowestTip = 5.0f;
    for (int step = 0; step < 180; ++step) {
      ASSERT_EQ(world.step(kDt), PhysicsStatus::Ok);
      for (JointId j : chain.joints) {
        const auto state = world.jointState(j);
        ASSERT_TRUE(state);
        maxSeparation = std::max(maxSeparation, state->separation);
        sumSeparation += state->separation;
        ++samples;
      }
      lowestTip = std::min(lowestTip, world.bodyTransform(chain.links.back())->position.y);
    }
    // Held: every pivot pair stays within 5 cm of its partner at the fastest whip of the 2 m chain
    // (the solver's error correction lags a little) and within 1 cm on average. Swung: the tip fell
    // well below the anchor line.
    EXPECT_LT(maxSeparation, 0.05f) << toString(type);
    EXPECT_LT(sumSeparation / float(samples), 0.01f) << toString(type);
    EXPECT_LT(lowestTip, 4.0f) << toString(type);
    // The first link hangs from the anchor: its centre stays 0.2 m from the anchor point.
    const glm::vec3 first = world.bodyTransform(chain.links.front())->position;
    EXPECT_NEAR(glm::length(first - glm::vec3(0.0f, 5.0f, 0.0f)), 0.2f, 0.02f) << toString(type);
  }
}

TEST(Joints, HingeLimitsAreRespected) {
  PhysicsWorld world;
  const BodyId anchor = addBody(world, ShapeDef::sphere(0.05f), 0.0f, glm::vec3(0.0f, 5.0f, 0.0f));
  const glm::quat toX = glm::angleAxis(-glm::half_pi<float>(), glm::vec3(0, 0, 1));
  BodyDef def;
  def.rotation = toX;
  def.allowSleep = false;
  const BodyId arm = addBody(world, ShapeDef::capsule(0.05f, 0.3f), 1.0f, glm::vec3(0.4f, 5.0f, 0.0f), def);
  JointDef j = jointAt(world, JointType::Hinge, anchor, arm, glm::vec3(0.0f, 5.0f, 0.0f));
  j.lowerLimit = -0.5f;  // gravity turns the arm by -pi/2 about z: the limit stops it at -0.5
  j.upperLimit = 1.0f;
  const Result<JointId> joint = world.createJoint(j);
  ASSERT_TRUE(joint.ok()) << joint.message();
  float minAngle = 0.0f, maxAngle = 0.0f;
  for (int step = 0; step < 240; ++step) {
    world.step(kDt);
    const float angle = world.jointState(joint.value())->hingeAngle;
    minAngle = std::min(minAngle, angle);
    maxAngle = std::max(maxAngle, angle);
  }
  EXPECT_LT(minAngle, -0.4f) << "the arm never reached its limit";
  EXPECT_GT(minAngle, -0.5f - 0.08f) << "the arm went past its lower limit";
  EXPECT_LT(maxAngle, 0.08f) << "it only ever fell (negative angles)";
  // Resting on the limit: the arm points 0.5 rad below the horizontal.
  const glm::vec3 centre = world.bodyTransform(arm)->position;
  const float below = std::atan2(5.0f - centre.y, centre.x);
  EXPECT_NEAR(below, 0.5f, 0.08f);
}

TEST(Joints, ConeSwingLimitIsRespected) {
  PhysicsWorld world;
  const BodyId anchor = addBody(world, ShapeDef::sphere(0.05f), 0.0f, glm::vec3(0.0f, 5.0f, 0.0f));
  const glm::quat toX = glm::angleAxis(-glm::half_pi<float>(), glm::vec3(0, 0, 1));
  BodyDef def;
  def.rotation = toX;
  def.allowSleep = false;
  const BodyId arm = addBody(world, ShapeDef::capsule(0.05f, 0.3f), 1.0f, glm::vec3(0.4f, 5.0f, 0.0f), def);
  JointDef j = jointAt(world, JointType::ConeTwist, anchor, arm, glm::vec3(0.0f, 5.0f, 0.0f));
  j.swingSpan1 = 0.4f;
  j.swingSpan2 = 0.4f;
  j.twistSpan = 0.2f;
  const Result<JointId> joint = world.createJoint(j);
  ASSERT_TRUE(joint.ok()) << joint.message();
  float maxSwing = 0.0f;
  for (int step = 0; step < 240; ++step) {
    world.step(kDt);
    maxSwing = std::max(maxSwing, world.jointState(joint.value())->swingAngle);
  }
  EXPECT_GT(maxSwing, 0.3f) << "gravity should have swung the arm to its cone";
  EXPECT_LT(maxSwing, 0.4f + 0.08f) << "the arm swung past its cone";
}

TEST(Joints, DestroyingABodyDropsItsJoints) {
  PhysicsWorld world;
  Chain chain = makeChain(world, 4, JointType::ConeTwist);
  ASSERT_EQ(world.jointCount(), 4u);
  // Link 1 has two joints: to link 0 (joint 1) and to link 2 (joint 2).
  ASSERT_TRUE(world.destroyBody(chain.links[1]));
  EXPECT_EQ(world.jointCount(), 2u);
  EXPECT_TRUE(world.isValid(chain.joints[0]));
  EXPECT_FALSE(world.isValid(chain.joints[1]));
  EXPECT_FALSE(world.isValid(chain.joints[2]));
  EXPECT_TRUE(world.isValid(chain.joints[3]));
  EXPECT_FALSE(world.jointState(chain.joints[1]));
  EXPECT_FALSE(world.destroyJoint(chain.joints[2]));
  // The rest of the chain (links 2 and 3) now falls freely; link 0 still hangs from the anchor.
  for (int step = 0; step < 60; ++step) ASSERT_EQ(world.step(kDt), PhysicsStatus::Ok);
  EXPECT_LT(world.bodyTransform(chain.links[3])->position.y, 3.5f);
  EXPECT_NEAR(glm::length(world.bodyTransform(chain.links[0])->position - glm::vec3(0, 5, 0)), 0.2f, 0.02f);
  ASSERT_TRUE(world.destroyJoint(chain.joints[0]));
  EXPECT_FALSE(world.isValid(chain.joints[0]));
  EXPECT_EQ(world.jointCount(), 1u);
  // The slot is reused with a new generation: the old handle stays stale.
  const Result<JointId> again = world.createJoint(
      jointAt(world, JointType::Hinge, chain.anchor, chain.links[0], glm::vec3(0, 5, 0)));
  ASSERT_TRUE(again.ok());
  EXPECT_FALSE(world.isValid(chain.joints[0]));
  EXPECT_TRUE(world.isValid(again.value()));
}

TEST(Joints, BadDefsAreRefusedWithAReason) {
  PhysicsWorld world;
  const BodyId ground = addGround(world);
  const BodyId a = addBody(world, ShapeDef::sphere(0.1f), 1.0f, glm::vec3(0, 1, 0));
  const BodyId still = addBody(world, ShapeDef::sphere(0.1f), 0.0f, glm::vec3(0, 2, 0));
  JointDef def = jointAt(world, JointType::ConeTwist, a, a, glm::vec3(0, 1, 0));
  EXPECT_EQ(world.createJoint(def).code(), PhysicsStatus::InvalidArgument);
  def = jointAt(world, JointType::ConeTwist, ground, still, glm::vec3(0, 1, 0));
  EXPECT_EQ(world.createJoint(def).code(), PhysicsStatus::InvalidArgument);
  def = jointAt(world, JointType::Hinge, ground, a, glm::vec3(0, 1, 0));
  def.lowerLimit = 1.0f;
  def.upperLimit = -1.0f;
  const Result<JointId> r = world.createJoint(def);
  EXPECT_EQ(r.code(), PhysicsStatus::InvalidArgument);
  EXPECT_FALSE(r.message().empty());
  def = jointAt(world, JointType::ConeTwist, ground, a, glm::vec3(0, 1, 0));
  def.frameB.rotation = glm::quat(0, 0, 0, 0);
  EXPECT_EQ(world.createJoint(def).code(), PhysicsStatus::InvalidArgument);
  def = jointAt(world, JointType::ConeTwist, ground, a, glm::vec3(0, 1, 0));
  def.swingSpan1 = NAN;
  EXPECT_EQ(world.createJoint(def).code(), PhysicsStatus::InvalidArgument);
  EXPECT_EQ(world.createJoint(JointDef{}).code(), PhysicsStatus::StaleHandle);
  EXPECT_EQ(world.jointCount(), 0u);
}

uint64_t chainRun(JointType type) {
  PhysicsWorld world;
  addGround(world);
  Chain chain = makeChain(world, 6, type);
  for (int step = 0; step < 300; ++step) {
    world.step(kDt);
    if (step == 100) world.destroyBody(chain.links[3]);
  }
  return world.stateHash();
}

TEST(Joints, ChainRunsAreDeterministic) {
  EXPECT_EQ(chainRun(JointType::ConeTwist), chainRun(JointType::ConeTwist));
  EXPECT_EQ(chainRun(JointType::Hinge), chainRun(JointType::Hinge));
  EXPECT_NE(chainRun(JointType::ConeTwist), chainRun(JointType::Hinge));
}

TEST(BodyOptions, SameCollisionGroupPassesThroughOtherGroupsCollide) {
  // Two boxes dropped onto a third resting on the ground: the one in the resting box's group falls
  // through it, the other one lands on top.
  for (bool sameGroup : {true, false}) {
    PhysicsWorld world;
    addGround(world);
    BodyDef base;
    base.collisionGroup = 7;
    addBody(world, ShapeDef::box(glm::vec3(0.5f)), 1.0f, glm::vec3(0, 0.5f, 0), base);
    BodyDef top;
    top.collisionGroup = sameGroup ? 7 : 8;
    const BodyId falling = addBody(world, ShapeDef::box(glm::vec3(0.2f)), 1.0f, glm::vec3(0, 2.0f, 0), top);
    for (int step = 0; step < 120; ++step) world.step(kDt);
    const float y = world.bodyTransform(falling)->position.y;
    if (sameGroup) {
      EXPECT_LT(y, 0.5f) << "same group: should pass through the base box and rest on the ground";
    } else {
      EXPECT_GT(y, 1.1f) << "different groups: should land on the base box";
    }
  }
}

TEST(BodyOptions, KinematicBodyIsMovedPushesAndReportsItsVelocity) {
  PhysicsWorld world;
  addGround(world);
  BodyDef def;
  def.kinematic = true;
  const BodyId pusher = addBody(world, ShapeDef::box(glm::vec3(0.5f)), 0.0f, glm::vec3(-2.0f, 0.5f, 0), def);
  EXPECT_TRUE(world.isKinematic(pusher));
  const BodyId box = addBody(world, ShapeDef::box(glm::vec3(0.25f)), 1.0f, glm::vec3(0.0f, 0.25f, 0));
  EXPECT_FALSE(world.isKinematic(box));
  BodyDef bad = def;
  const Result<ShapeId> sphere = world.createShape(ShapeDef::sphere(0.1f));
  ASSERT_TRUE(sphere.ok());
  bad.shape = sphere.value();
  bad.mass = 1.0f;
  EXPECT_EQ(world.createBody(bad).code(), PhysicsStatus::InvalidArgument) << "kinematic with mass";
  float x = -2.0f;
  for (int step = 0; step < 120; ++step) {
    x += 2.0f * float(kDt);  // 2 m/s along +x
    ASSERT_TRUE(world.setBodyTransform(pusher, BodyTransform{glm::vec3(x, 0.5f, 0.0f), glm::quat(1, 0, 0, 0)}));
    world.step(kDt);
  }
  EXPECT_NEAR(world.bodyTransform(pusher)->position.x, x, 1e-5f);
  EXPECT_NEAR(world.bodyTransform(pusher)->position.y, 0.5f, 1e-5f) << "gravity must not move it";
  EXPECT_NEAR(world.linearVelocity(pusher)->x, 2.0f, 0.05f);
  EXPECT_GT(world.bodyTransform(box)->position.x, x + 0.5f) << "the box was not pushed ahead";
}

}  // namespace
}  // namespace cleave::physics
