// SPDX-License-Identifier: MIT
// JointDef: the checked description of a constraint between two bodies, given to
// PhysicsWorld::createJoint.
//
// Frames. A joint has one frame on each body, given in that body's local frame (origin at its
// centre of mass, see body_def.h): `frameA` in body A, `frameB` in body B. The constraint keeps the
// two frame origins together (the pivot: a ball joint) and limits how the frames may turn against
// each other. Build both frames from one world frame F at creation, frameX = inverse(bodyX) * F, so
// the joint starts at rest (zero swing, twist and hinge angle).
//
// Limits, radians, relative to that rest:
//  - ConeTwist: the twist axis is the frame's local x axis. The x axis of B may swing away from the
//    x axis of A inside an elliptic cone of half-angles swingSpan1 (about the frame's z axis, i.e.
//    swinging towards y) and swingSpan2 (about y, swinging towards z); B may twist about its x axis
//    by at most twistSpan either way. Spans in [0, pi]; a hip, a shoulder, a neck.
//  - Hinge: one rotation axis, the frame's local z axis; the angle of B about it stays within
//    [lowerLimit, upperLimit] (lower <= upper, both in [-pi, pi]); a knee, an elbow.
//
// Ownership and lifetime: the world owns the constraint. A joint disappears when either of its
// bodies is destroyed (its handle then reports stale), or with destroyJoint. Joints never break.
#pragma once

#include <cstdint>

#include "cleave/physics/physics_events.h"
#include "cleave/physics/physics_ids.h"

namespace cleave::physics {

enum class JointType : uint8_t {
  ConeTwist,  // ball joint with a swing cone and a twist limit
  Hinge,      // one rotation axis with an angle range
};
const char* toString(JointType type);

struct JointDef {
  JointType type = JointType::ConeTwist;
  BodyId bodyA;  // dynamic, kinematic or static; A and B must differ and not both be immovable
  BodyId bodyB;
  BodyTransform frameA;  // joint frame in A's local frame (metres, unit quaternion)
  BodyTransform frameB;  // joint frame in B's local frame
  float swingSpan1 = 0.7f;  // ConeTwist, radians
  float swingSpan2 = 0.7f;  // ConeTwist, radians
  float twistSpan = 0.5f;   // ConeTwist, radians
  float lowerLimit = -1.5f;  // Hinge, radians
  float upperLimit = 1.5f;   // Hinge, radians
  bool collideConnected = false;  // false: A and B do not collide with each other
};

// Where a joint's two frames are now, world space: pivotA (from body A) and pivotB (from body B)
// coincide when the joint holds; `separation` is their distance, metres.
struct JointState {
  glm::vec3 pivotA{0.0f};
  glm::vec3 pivotB{0.0f};
  float separation = 0.0f;
  float hingeAngle = 0.0f;   // Hinge: current angle about the axis, radians (0 for cone-twist)
  float swingAngle = 0.0f;   // ConeTwist: angle between the x axes of the two frames, radians
  float twistAngle = 0.0f;   // ConeTwist: twist of B about the twist axis, radians
};

}  // namespace cleave::physics
