// SPDX-License-Identifier: MIT
// Frozen bodies (PhysicsWorld::setFrozen): a frozen body leaves the simulation where it is, stays a
// collider that awake bodies rest on, keeps its mass and inertia for its return, is seen by
// triggers, never pairs with static or frozen bodies; and the two queries the piece budget uses
// with it: extentAlong (a body's interval along a direction) and bodiesInBox.
#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/quaternion.hpp>

#include "cleave/physics/physics_world.h"
#include "tests/physics/physics_test_helpers.h"

namespace cleave::physics {
namespace {

using testing::addBody;
using testing::addGround;
using testing::kDt;
using testing::stepFor;

const ShapeDef kCube = ShapeDef::box(glm::vec3(0.5f));

bool touching(const PhysicsWorld& world, BodyId a, BodyId b) {
  for (const ContactEvent& ev : world.contactEvents())
    if ((ev.bodyA == a && ev.bodyB == b) || (ev.bodyA == b && ev.bodyB == a)) return true;
  return false;
}

TEST(BodyFreeze, FrozenBodyStaysWhereItIsWithZeroVelocityAndKeepsItsMass) {
  PhysicsWorld world;
  BodyDef moving;
  moving.linearVelocity = glm::vec3(1.0f, 2.0f, 0.0f);
  moving.angularVelocity = glm::vec3(0.0f, 3.0f, 0.0f);
  const BodyId frozen = addBody(world, kCube, 2.0f, glm::vec3(0, 5, 0), moving);
  const BodyId twin = addBody(world, kCube, 2.0f, glm::vec3(3, 5, 0), moving);  // not frozen: falls
  const BodyTransform at = *world.bodyTransform(frozen);
  ASSERT_TRUE(world.setFrozen(frozen, true));
  EXPECT_TRUE(world.isFrozen(frozen));
  EXPECT_FALSE(world.isFrozen(twin));
  EXPECT_EQ(world.frozenBodyCount(), 1u);
  stepFor(world, 60);
  // Exactly where it was: a frozen body is never integrated.
  const BodyTransform now = *world.bodyTransform(frozen);
  EXPECT_EQ(now.position, at.position);
  EXPECT_EQ(now.rotation, at.rotation);
  EXPECT_EQ(*world.linearVelocity(frozen), glm::vec3(0.0f));
  EXPECT_EQ(*world.angularVelocity(frozen), glm::vec3(0.0f));
  EXPECT_FALSE(world.isAwake(frozen));
  EXPECT_EQ(*world.bodyMass(frozen), 2.0f);  // kept for its return (a static body reports 0)
  EXPECT_LT(world.bodyTransform(twin)->position.y, 4.0f);  // the same body unfrozen fell
}

TEST(BodyFreeze, DynamicBodyDroppedOnAFrozenOneRestsOnIt) {
  PhysicsWorld world;
  addGround(world);
  // Frozen in mid-air, 2 m above the ground: only the frozen body can hold the falling one up.
  const BodyId shelf = addBody(world, ShapeDef::box(glm::vec3(1.0f, 0.25f, 1.0f)), 5.0f, glm::vec3(0, 2, 0));
  ASSERT_TRUE(world.setFrozen(shelf, true));
  const BodyId box = addBody(world, kCube, 1.0f, glm::vec3(0, 4, 0));
  stepFor(world, 180);
  EXPECT_NEAR(world.bodyTransform(box)->position.y, 2.25f + 0.5f, 0.01f);
  EXPECT_EQ(world.bodyTransform(shelf)->position, glm::vec3(0, 2, 0));  // not pushed down
  EXPECT_TRUE(world.isFrozen(shelf));
}

TEST(BodyFreeze, ThawRestoresMassAndInertiaAndTheBodyFallsAgain) {
  PhysicsWorld world(WorldDef{glm::vec3(0.0f, -9.81f, 0.0f)});
  BodyDef def;
  def.localInertia = glm::vec3(0.1f, 0.2f, 0.3f);  // not Bullet's box inertia: must survive as given
  const BodyId body = addBody(world, kCube, 3.0f, glm::vec3(0, 5, 0), def);
  const BodyId twin = addBody(world, kCube, 3.0f, glm::vec3(4, 5, 0), def);  // never frozen
  const glm::vec3 inertia = *world.bodyLocalInertia(body);
  ASSERT_TRUE(world.setFrozen(body, true));
  stepFor(world, 10);
  ASSERT_TRUE(world.setFrozen(body, false));
  EXPECT_FALSE(world.isFrozen(body));
  EXPECT_EQ(world.frozenBodyCount(), 0u);
  EXPECT_TRUE(world.isAwake(body));
  EXPECT_EQ(*world.linearVelocity(body), glm::vec3(0.0f));  // back at rest
  EXPECT_EQ(*world.bodyMass(body), 3.0f);
  const glm::vec3 after = *world.bodyLocalInertia(body);
  for (int k = 0; k < 3; ++k) EXPECT_FLOAT_EQ(after[k], inertia[k]) << k;
  // The solver really uses them: the same off-centre impulse spins it as it spins the twin.
  const glm::vec3 impulse(0.0f, 0.0f, 1.0f), arm(0.3f, 0.2f, 0.0f);
  ASSERT_TRUE(world.applyImpulse(body, impulse, world.bodyTransform(body)->position + arm));
  ASSERT_TRUE(world.setVelocity(twin, glm::vec3(0.0f), glm::vec3(0.0f)));
  ASSERT_TRUE(world.applyImpulse(twin, impulse, world.bodyTransform(twin)->position + arm));
  const glm::vec3 spin = *world.angularVelocity(body), twinSpin = *world.angularVelocity(twin);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(spin[k], twinSpin[k], 1e-5f * glm::length(twinSpin)) << k;
  EXPECT_NEAR(glm::length(*world.linearVelocity(body)), 1.0f / 3.0f, 1e-5f);  // J / m
  // And gravity pulls it again.
  const float y = world.bodyTransform(body)->position.y;
  stepFor(world, 30);
  EXPECT_LT(world.bodyTransform(body)->position.y, y - 1.0f);
}

TEST(BodyFreeze, ImpulseVelocityAndActivateThawAFrozenBody) {
  PhysicsWorld world(WorldDef{glm::vec3(0.0f)});
  const BodyId pushed = addBody(world, kCube, 2.0f, glm::vec3(0, 0, 0));
  const BodyId thrown = addBody(world, kCube, 2.0f, glm::vec3(3, 0, 0));
  const BodyId woken = addBody(world, kCube, 2.0f, glm::vec3(6, 0, 0));
  for (BodyId b : {pushed, thrown, woken}) ASSERT_TRUE(world.setFrozen(b, true));
  ASSERT_EQ(world.frozenBodyCount(), 3u);

  ASSERT_TRUE(world.applyImpulse(pushed, glm::vec3(4, 0, 0), world.bodyTransform(pushed)->position));
  EXPECT_FALSE(world.isFrozen(pushed));
  EXPECT_NEAR(world.linearVelocity(pushed)->x, 2.0f, 1e-6f);  // J / m: the impulse is not lost

  ASSERT_TRUE(world.setVelocity(thrown, glm::vec3(0, 0, 1), glm::vec3(0.0f)));
  EXPECT_FALSE(world.isFrozen(thrown));

  ASSERT_TRUE(world.activate(woken));
  EXPECT_FALSE(world.isFrozen(woken));
  EXPECT_TRUE(world.isAwake(woken));
  EXPECT_EQ(world.frozenBodyCount(), 0u);

  const glm::vec3 before = world.bodyTransform(thrown)->position;
  stepFor(world, 6);
  EXPECT_NEAR(world.bodyTransform(thrown)->position.z - before.z, 6.0f * float(kDt), 1e-4f);  // it moves again
  EXPECT_GT(world.bodyTransform(pushed)->position.x, 0.1f);
}

TEST(BodyFreeze, RefusesStaticKinematicJointedAndStaleBodies) {
  PhysicsWorld world;
  const BodyId ground = addGround(world);
  BodyDef kinematicDef;
  kinematicDef.kinematic = true;
  const BodyId kinematic = addBody(world, kCube, 0.0f, glm::vec3(5, 1, 0), kinematicDef);
  const BodyId a = addBody(world, kCube, 1.0f, glm::vec3(0, 3, 0));
  const BodyId b = addBody(world, kCube, 1.0f, glm::vec3(1.2f, 3, 0));
  JointDef joint;
  joint.bodyA = a;
  joint.bodyB = b;
  joint.frameA.position = glm::vec3(0.6f, 0, 0);
  joint.frameB.position = glm::vec3(-0.6f, 0, 0);
  ASSERT_TRUE(world.createJoint(joint).ok());
  const BodyId gone = addBody(world, kCube, 1.0f, glm::vec3(-5, 3, 0));
  ASSERT_TRUE(world.destroyBody(gone));

  EXPECT_FALSE(world.setFrozen(ground, true));
  EXPECT_FALSE(world.setFrozen(kinematic, true));
  EXPECT_FALSE(world.setFrozen(a, true));  // a joint needs both of its bodies simulated
  EXPECT_FALSE(world.setFrozen(b, true));
  EXPECT_FALSE(world.setFrozen(gone, true));
  EXPECT_FALSE(world.setFrozen(BodyId{}, true));
  for (BodyId body : {ground, kinematic, a, b, gone}) EXPECT_FALSE(world.isFrozen(body));
  EXPECT_EQ(world.frozenBodyCount(), 0u);
  // The refused jointed bodies are still simulated: they fall.
  stepFor(world, 30);
  EXPECT_LT(world.bodyTransform(a)->position.y, 2.5f);
}

TEST(BodyFreeze, FreezingTwiceChangesNothingAndAJointThawsItsBodies) {
  PhysicsWorld world;
  const BodyId a = addBody(world, kCube, 1.0f, glm::vec3(0, 3, 0));
  const BodyId b = addBody(world, kCube, 1.0f, glm::vec3(1.2f, 3, 0));
  ASSERT_TRUE(world.setFrozen(a, true));
  EXPECT_TRUE(world.setFrozen(a, true));
  EXPECT_TRUE(world.setFrozen(b, false));  // thawing a body that is not frozen
  EXPECT_EQ(world.frozenBodyCount(), 1u);
  JointDef joint;
  joint.bodyA = a;
  joint.bodyB = b;
  joint.frameA.position = glm::vec3(0.6f, 0, 0);
  joint.frameB.position = glm::vec3(-0.6f, 0, 0);
  ASSERT_TRUE(world.createJoint(joint).ok());
  EXPECT_FALSE(world.isFrozen(a));
  EXPECT_EQ(world.frozenBodyCount(), 0u);
}

TEST(BodyFreeze, TriggersStillReportAFrozenBody) {
  PhysicsWorld world(WorldDef{glm::vec3(0.0f)});
  const BodyId body = addBody(world, kCube, 1.0f, glm::vec3(0.0f));
  ASSERT_TRUE(world.setFrozen(body, true));
  // detectStatic off: the trigger skips static bodies, and a frozen body must not look like one.
  const ShapeId shape = world.createShape(ShapeDef::box(glm::vec3(0.3f))).value();
  TriggerDef def;
  def.shape = shape;
  def.position = glm::vec3(0.5f, 0.0f, 0.0f);
  const TriggerId trigger = world.createTrigger(def).value();
  world.destroyShape(shape);
  stepFor(world, 1);
  ASSERT_EQ(world.triggerEvents().size(), 1u);
  EXPECT_EQ(world.triggerEvents()[0].trigger, trigger);
  EXPECT_EQ(world.triggerEvents()[0].body, body);
  EXPECT_EQ(world.triggerEvents()[0].kind, TriggerEventKind::Begin);
  stepFor(world, 1);
  ASSERT_EQ(world.triggerEvents().size(), 1u);
  EXPECT_EQ(world.triggerEvents()[0].kind, TriggerEventKind::Stay);
}

TEST(BodyFreeze, FrozenBodiesPairWithNeitherEachOtherNorTheGround) {
  PhysicsWorld world;
  addGround(world);
  // Two boxes 0.2 m into each other, the lower one 0.1 m into the ground: any pairing would give a
  // contact (and the solver would push them apart).
  const BodyId low = addBody(world, kCube, 1.0f, glm::vec3(0, 0.4f, 0));
  const BodyId high = addBody(world, kCube, 1.0f, glm::vec3(0.1f, 1.2f, 0));
  ASSERT_TRUE(world.setFrozen(low, true));
  ASSERT_TRUE(world.setFrozen(high, true));
  stepFor(world, 5);
  EXPECT_TRUE(world.contactEvents().empty());
  // An awake body dropped on them does pair with a frozen one.
  const BodyId box = addBody(world, ShapeDef::box(glm::vec3(0.2f)), 1.0f, glm::vec3(0.1f, 2.0f, 0));
  bool touched = false;
  for (int i = 0; i < 60 && !touched; ++i) {
    stepFor(world, 1);
    touched = touching(world, box, high);
    for (const ContactEvent& ev : world.contactEvents()) {
      EXPECT_FALSE((ev.bodyA == low && ev.bodyB == high) || (ev.bodyA == high && ev.bodyB == low));
    }
  }
  EXPECT_TRUE(touched);
}

// The analytic interval of a box (half extents h, rotation r, centre c) along d:
// dot(d, c) -+ sum_i |dot(d, r e_i)| h_i.
glm::vec2 boxInterval(glm::vec3 half, const glm::quat& r, glm::vec3 centre, glm::vec3 d) {
  float reach = 0.0f;
  for (int i = 0; i < 3; ++i) {
    glm::vec3 axis(0.0f);
    axis[i] = 1.0f;
    reach += std::abs(glm::dot(d, r * axis)) * half[i];
  }
  const float mid = glm::dot(d, centre);
  return {mid - reach, mid + reach};
}

TEST(BodyFreeze, ExtentAlongOfABoxIsItsAnalyticInterval) {
  PhysicsWorld world(WorldDef{glm::vec3(0.0f)});
  const glm::vec3 half(0.5f, 0.25f, 1.0f);
  const glm::vec3 centre(1.0f, 2.0f, -3.0f);
  BodyDef turned;
  turned.rotation = glm::angleAxis(0.7f, glm::normalize(glm::vec3(1.0f, 2.0f, 0.5f)));
  const BodyId straight = addBody(world, ShapeDef::box(half), 1.0f, centre);
  const BodyId rotated = addBody(world, ShapeDef::box(half), 1.0f, centre, turned);
  const glm::quat rotation = world.bodyTransform(rotated)->rotation;
  // Unit and non-unit directions (the interval is then in units of the direction's length).
  const glm::vec3 directions[] = {{0, 1, 0}, {1, 0, 0}, glm::normalize(glm::vec3(1, 1, 1)), {0.3f, -2.0f, 0.7f}};
  for (const glm::vec3& d : directions) {
    const glm::vec2 expectStraight = boxInterval(half, glm::quat(1, 0, 0, 0), centre, d);
    const glm::vec2 expectRotated = boxInterval(half, rotation, centre, d);
    const glm::vec2 gotStraight = *world.extentAlong(straight, d);
    const glm::vec2 gotRotated = *world.extentAlong(rotated, d);
    const float tolerance = 1e-5f * 10.0f * glm::length(d);
    EXPECT_NEAR(gotStraight.x, expectStraight.x, tolerance) << d.x << " " << d.y << " " << d.z;
    EXPECT_NEAR(gotStraight.y, expectStraight.y, tolerance) << d.x << " " << d.y << " " << d.z;
    EXPECT_NEAR(gotRotated.x, expectRotated.x, tolerance) << d.x << " " << d.y << " " << d.z;
    EXPECT_NEAR(gotRotated.y, expectRotated.y, tolerance) << d.x << " " << d.y << " " << d.z;
  }
  // The rotated box really reaches further along y than the straight one (the case is not trivial).
  EXPECT_GT(world.extentAlong(rotated, glm::vec3(0, 1, 0))->y, world.extentAlong(straight, glm::vec3(0, 1, 0))->y + 0.1f);
  EXPECT_FALSE(world.extentAlong(straight, glm::vec3(0.0f)).has_value());
  EXPECT_FALSE(world.extentAlong(straight, glm::vec3(NAN, 0, 0)).has_value());
  EXPECT_FALSE(world.extentAlong(BodyId{}, glm::vec3(0, 1, 0)).has_value());
}

TEST(BodyFreeze, ExtentAlongOfACompoundCoversItsParts) {
  PhysicsWorld world(WorldDef{glm::vec3(0.0f)});
  // Two 0.4 m cubes 1 m apart along x (a dumbbell without its bar), the body turned 90 degrees
  // about z so the parts lie along y.
  std::vector<ConvexPart> parts(2);
  parts[0].points = testing::boxCorners(glm::vec3(0.2f));
  parts[0].position = glm::vec3(-0.5f, 0, 0);
  parts[1].points = testing::boxCorners(glm::vec3(0.2f));
  parts[1].position = glm::vec3(0.5f, 0, 0);
  BodyDef turned;
  turned.rotation = glm::angleAxis(glm::half_pi<float>(), glm::vec3(0, 0, 1));
  const BodyId body = addBody(world, ShapeDef::compound(parts), 1.0f, glm::vec3(0, 3, 0), turned);
  const glm::vec2 alongY = *world.extentAlong(body, glm::vec3(0, 1, 0));
  const glm::vec2 alongX = *world.extentAlong(body, glm::vec3(1, 0, 0));
  // Hulls keep their size (their margin is taken inside): [3 - 0.7, 3 + 0.7] and [-0.2, 0.2].
  EXPECT_NEAR(alongY.x, 2.3f, 2e-3f);
  EXPECT_NEAR(alongY.y, 3.7f, 2e-3f);
  EXPECT_NEAR(alongX.x, -0.2f, 2e-3f);
  EXPECT_NEAR(alongX.y, 0.2f, 2e-3f);
}

TEST(BodyFreeze, BodiesInBoxFindsBodiesByTheirBoundsInIndexOrder) {
  PhysicsWorld world(WorldDef{glm::vec3(0.0f)});
  const BodyId first = addBody(world, kCube, 1.0f, glm::vec3(0, 0, 0));
  const BodyId frozen = addBody(world, kCube, 1.0f, glm::vec3(5, 0, 0));
  const BodyId outside = addBody(world, kCube, 1.0f, glm::vec3(30, 0, 0));
  const BodyId fixed = addBody(world, kCube, 0.0f, glm::vec3(10, 0, 0));  // static
  ASSERT_TRUE(world.setFrozen(frozen, true));
  // A body in a reused slot: its index is lower than those made before it, so index order is not
  // creation order.
  ASSERT_TRUE(world.destroyBody(first));
  const BodyId reused = addBody(world, kCube, 1.0f, glm::vec3(15, 0, 0));
  // A trigger inside the box is not a body.
  const ShapeId shape = world.createShape(kCube).value();
  TriggerDef trigger;
  trigger.shape = shape;
  trigger.position = glm::vec3(12, 0, 0);
  ASSERT_TRUE(world.createTrigger(trigger).ok());
  world.destroyShape(shape);

  std::vector<BodyId> expected = {frozen, fixed, reused};
  std::sort(expected.begin(), expected.end(), [](BodyId a, BodyId b) { return a.index < b.index; });
  ASSERT_NE(expected.back(), reused) << "the slot was not reused: the order case is not tested";
  EXPECT_EQ(world.bodiesInBox(glm::vec3(4.6f, -1, -1), glm::vec3(15.0f, 1, 1)), expected);
  // By bounds: a box that only grazes the frozen body's face finds it, one 1 cm short does not.
  const auto bounds = *world.bodyBounds(frozen);
  EXPECT_LE(bounds.first.x, 4.5f);
  EXPECT_GE(bounds.second.x, 5.5f);
  EXPECT_EQ(world.bodiesInBox(glm::vec3(bounds.second.x, -1, -1), glm::vec3(bounds.second.x + 1, 1, 1)),
            std::vector<BodyId>{frozen});
  EXPECT_TRUE(world.bodiesInBox(glm::vec3(bounds.second.x + 0.01f, -1, -1), glm::vec3(9.0f, 1, 1)).empty());
  EXPECT_TRUE(world.bodiesInBox(glm::vec3(100, 100, 100), glm::vec3(101, 101, 101)).empty());
  (void)outside;
}

// A small scene with freezing in the middle of it: a stack whose middle box is frozen, a box
// dropped on it, a thaw by impulse and one by setFrozen.
std::vector<uint64_t> runWithFreezing() {
  PhysicsWorld world;
  addGround(world);
  std::vector<BodyId> stack;
  for (int i = 0; i < 4; ++i)
    stack.push_back(addBody(world, kCube, 1.0f, glm::vec3(0.03f * float(i), 0.5f + 1.02f * float(i), 0)));
  std::vector<uint64_t> hashes;
  for (int step = 0; step < 240; ++step) {
    if (step == 30) world.setFrozen(stack[1], true);
    if (step == 40) addBody(world, ShapeDef::sphere(0.3f), 2.0f, glm::vec3(0.2f, 6.0f, 0.1f));
    if (step == 120) world.applyImpulse(stack[1], glm::vec3(2, 0, 0), glm::vec3(0, 1.6f, 0.2f));
    if (step == 150) world.setFrozen(stack[3], true);
    if (step == 200) world.setFrozen(stack[3], false);
    EXPECT_EQ(world.step(kDt), PhysicsStatus::Ok);
    hashes.push_back(world.stateHash());
  }
  return hashes;
}

TEST(BodyFreeze, StateHashIsTheSameInTwoRunsWithFreezing) {
  const std::vector<uint64_t> a = runWithFreezing(), b = runWithFreezing();
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 0; k < a.size(); ++k) ASSERT_EQ(a[k], b[k]) << "step " << k;
  EXPECT_NE(a[29], a[239]);  // the scene moves
}

// A body that must never sleep (BodyDef::allowSleep = false) keeps that after a freeze and a thaw
// (setFrozen(body, false) "returns it to the simulation awake and at rest").
//
// Bullet keeps "never sleep" as an activation state, which freezing (a static object sleeps)
// overwrites: the body record keeps allowSleep for the thaw.
TEST(BodyFreeze, ThawedBodyStillNeverSleepsWhenItWasMadeSo) {
  PhysicsWorld world;
  addGround(world);
  BodyDef insomniac;
  insomniac.allowSleep = false;
  const BodyId body = addBody(world, kCube, 1.0f, glm::vec3(0, 0.5f, 0), insomniac);
  stepFor(world, 300);
  ASSERT_TRUE(world.isAwake(body));  // as made
  ASSERT_TRUE(world.setFrozen(body, true));
  ASSERT_TRUE(world.setFrozen(body, false));
  stepFor(world, 300);
  EXPECT_TRUE(world.isAwake(body));
}

}  // namespace
}  // namespace cleave::physics
