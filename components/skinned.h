// SPDX-License-Identifier: MIT
// Skinned meshes as components: an animated character (SkinnedMesh), the Animation-phase system that
// plays it, CPU skinning for baking a pose, and the ragdolls that skinned split pieces can become.
//
// Spaces. A skinned entity's MeshRenderer::source is in bind space with joints and weights; its
// SkinnedMesh::jointMatrices take bind space to mesh space (the pose), and the entity draws at
// WorldTransform x meshOffset x jointMatrix, exactly as geometry::MeshContainer::setSkinningPose
// poses it for a cut: the cut happens in the pose the player sees.
//
// What a cut does to a skinned entity is chosen per Splitable (SkinnedPieceMode, splitable.h); see
// split_system.h for the piece rules and docs in each mode below.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cleave/components/split_job.h"
#include "cleave/components/split_system.h"
#include "cleave/anim/animation_clip.h"
#include "cleave/anim/skeleton.h"
#include "cleave/ecs/entity.h"
#include "cleave/geometry/mesh_data.h"
#include "cleave/physics/joint_def.h"
#include "cleave/physics/physics_ids.h"
#include "cleave/physics/physics_world.h"

namespace cleave::components {

// A skeleton with its clips, shared (immutable) by a character and every piece cut from it.
struct SkinnedAsset {
  anim::Skeleton skeleton;
  std::vector<anim::AnimationClip> clips;

  // The clip with this name, or null.
  const anim::AnimationClip* clip(const std::string& name) const;
};

// An animated skinned mesh. The animator points into *asset (kept alive by the shared pointer), so
// copying a SkinnedMesh copies the whole playing state (clip, time, crossfade): a copy keeps playing
// in sync with the original.
struct SkinnedMesh {
  std::shared_ptr<const SkinnedAsset> asset;
  anim::Animator animator;
  std::vector<glm::mat4> jointMatrices;  // bind space -> mesh space, one per skeleton joint
  float speed = 1.f;                     // playback rate (0 freezes the pose)
};

// A SkinnedMesh playing `clip` (looping) from `startTime`, with its joint matrices evaluated. An
// unknown clip name shows the rest pose.
SkinnedMesh makeSkinnedMesh(std::shared_ptr<const SkinnedAsset> asset, const std::string& clip,
                            float startTime = 0.f);

// One bone of a ragdoll: a capsule body carrying a skeleton joint.
struct RagdollBone {
  uint16_t joint = 0;
  physics::BodyId body;
  physics::ShapeId shape;
  float radius = 0.f;      // metres
  float halfHeight = 0.f;  // metres, of the cylindrical part
  float mass = 0.f;        // kg
};

// A constraint between two bones (indices into Ragdoll::bones) at a skeleton joint.
struct RagdollJoint {
  physics::JointId joint;
  uint16_t parentBone = 0;
  uint16_t childBone = 0;
  uint16_t skeletonJoint = 0;  // the joint whose origin is the pivot
  physics::JointType type = physics::JointType::ConeTwist;
};

// A skinned piece driven by physics: capsules for the bones whose joints the piece keeps, joined by
// cone-twist joints (hinges at elbows and knees, the forearm and shin joints). Every skeleton joint
// is carried by one bone body (its own, or the nearest ancestor's, or the anchor's) at a fixed
// transform, so the joint matrices follow the bodies. The entity's RigidBody is the anchor (the
// heaviest bone) and its Transform follows the anchor; joint matrices are relative to it.
struct Ragdoll {
  std::vector<RagdollBone> bones;
  std::vector<RagdollJoint> joints;
  size_t anchor = 0;                   // index into bones
  std::vector<uint16_t> carrier;       // per skeleton joint: the bone that carries it
  std::vector<glm::mat4> carried;      // per skeleton joint: its global transform in that body's frame
};

// CPU linear blend skinning: positions, normals and tangents of a bind-space mesh in the pose
// (weights renormalised as MeshContainer does); joints and weights are dropped from `out`. A mesh
// without skin is copied. Every joint id used with weight > 0 must be < jointMatrices.size().
void bakeSkin(const geometry::MeshData& mesh, std::span<const glm::mat4> jointMatrices,
              geometry::MeshData& out);

// World-space global transforms of every joint of a posed skeleton: model x jointMatrix x bind.
void posedJointGlobals(const anim::Skeleton& skeleton, std::span<const glm::mat4> jointMatrices,
                       const glm::dmat4& model, std::vector<glm::dmat4>& out);

// Creates the body of an authored skinned entity (MeshRenderer, SkinnedMesh, Transform): exact mass
// from the posed mesh's volume times `density`, a convex-hull collider of the posed mesh, the body
// origin at the posed centre of mass (meshOffset shifted to match). Kinematic: the body keeps the
// entity's rotation and is moved by the game (setBodyTransform each tick), pushing what it walks
// into; its MassInfo still holds the mass that its pieces share. InvalidArgument with a reason when
// the entity has no skinned mesh, the pose no volume, or the bridge refuses the hull or the body.
base::Status makeSkinnedBody(SplitWorld& w, ecs::Entity e, double density, bool kinematic);

// Plans the ragdoll of one skinned piece (pure: no physics). `bindPiece` is the piece in bind space
// with skin, `posed` the same vertices in world space (the pose at the cut), `keptJoints` the joints
// it uses (SplitPiece::joints), `globals` the world transforms of every skeleton joint in that pose.
// Bones get capsules fitted to the vertices each joint dominates and a share of `mass` by vertex
// influence (shares sum to `mass`); joints join each bone to its nearest ancestor bone (hinges at
// elbows and knees). InvalidArgument if no bone has enough vertices for a capsule.
base::Status planRagdoll(const geometry::MeshData& bindPiece, std::span<const glm::vec3> posed,
                         std::span<const uint16_t> keptJoints, const anim::Skeleton& skeleton,
                         std::span<const glm::dmat4> globals, double mass, RagdollSpec& out);

// Where and how a planned ragdoll (RagdollSpec) is made at commit. Units: metres, seconds, radians.
struct RagdollDef {
  // The rigid motion of the parent since the plan (identity if it did not move): the bones are made
  // at motion x their planned poses.
  glm::dmat4 motion{1.0};
  // The parent's motion now: each bone gets the velocity of the point it occupies,
  // velocity + angularVelocity x (centre - parentCentre), and the angular velocity.
  glm::dvec3 velocity{0.0};         // m/s, world
  glm::dvec3 angularVelocity{0.0};  // rad/s, world
  glm::dvec3 parentCentre{0.0};     // m, world
  uint64_t userData = 0;            // on every bone body (the entity id)
  uint64_t collisionGroup = 0;      // shared by the bones, which then never collide with each other
  // Jointed capsules jitter against the floor and each other: more angular damping and higher
  // sleep thresholds than a plain body (the values of Bullet's ragdoll demo) let a fallen ragdoll
  // come to rest. See physics::BodyDef for the ranges.
  float linearDamping = 0.05f;
  float angularDamping = 0.85f;
  float sleepLinearSpeed = 1.6f;   // m/s
  float sleepAngularSpeed = 2.5f;  // rad/s
  float friction = 0.8f;
};

// Creates the ragdoll `spec` plans as `def` says: the bone bodies, then the joints between the
// bones that were made. Returns false (and creates nothing) if the anchor bone cannot be created;
// a bone the bridge refuses is left out and its joints with it.
bool createRagdoll(physics::PhysicsWorld& physics, const RagdollSpec& spec, const RagdollDef& def, Ragdoll& out);

// Joint matrices of a ragdoll now, relative to its anchor body's frame (the entity frame).
void ragdollJointMatrices(const physics::PhysicsWorld& physics, const Ragdoll& ragdoll,
                          const anim::Skeleton& skeleton, std::vector<glm::mat4>& out);

// Animation phase: advances every SkinnedMesh without a Ragdoll by dt x speed and evaluates its
// joint matrices; ragdoll pieces take their joint matrices from their bone bodies.
void updateAnimations(SplitWorld& w, float dt);

// Destroys a ragdoll's bodies (its joints go with them) and shapes.
void releaseRagdoll(physics::PhysicsWorld& physics, Ragdoll& ragdoll);

}  // namespace cleave::components
