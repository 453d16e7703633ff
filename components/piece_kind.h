// SPDX-License-Identifier: MIT
// Piece kinds: what a piece of a split becomes (PieceKind, splitable.h). Each kind is a strategy
// with its part of both stages that make a piece:
//
//   plan    (compute, any thread)  completes the piece's PieceSpec with what the kind needs (a
//                                  ragdoll's bones), and says which mesh it draws and whether it
//                                  gets a collider, planned from which mesh;
//   commit  (main thread)          puts the piece on its body (or bones, or nothing) and adds the
//                                  components of its kind.
//
// The split compute (split_compute.cpp) and commit (split_system.cpp) do what every piece needs and
// ask the kind for the rest; they never test for a kind. The built-in kinds each have a file:
// piece_rigid.cpp, piece_debris.cpp, piece_skinned.cpp (keep animating, baked), piece_ragdoll.cpp.
// A game adds a kind by deriving PieceKindStrategy in a file of its own and registering it once
// (registerPieceKind); Splitable::rigidPieces, or a split handler (SplitSystem::registerHandler)
// setting PieceSpec::kind, chooses it.
//
// Threads: plan runs on the split workers and must touch nothing but its arguments; the registry
// is written on the main thread before the splits that use a kind, and read from any thread.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "cleave/components/scene_components.h"
#include "cleave/components/split_job.h"
#include "cleave/ecs/command_buffer.h"
#include "cleave/ecs/hierarchy.h"

namespace cleave::components {

class ActivationThrottle;
struct SkinnedMesh;
struct SplitEvent;
struct SplitWorld;

// What the compute knows of one piece when its kind plans it.
struct PiecePlan {
  const SplitJob& job;
  const geometry::SplitPiece& piece;            // as cut (bind space for skinned jobs)
  const geometry::MeshData& posed;              // skinned jobs: the piece in its pose; empty otherwise
  const std::vector<glm::dmat4>& jointGlobals;  // ragdoll jobs: joint world transforms in the cut pose
};

// The parent's motion from prepare to commit, applied to the specs' prepare-tick poses.
struct ParentMoved {
  ParentMotion now;
  glm::dmat4 motion{1.0};
  glm::dmat3 turn{1.0};
  bool moved = false;

  glm::dvec3 position(const glm::dvec3& p) const { return moved ? glm::dvec3(motion * glm::dvec4(p, 1.0)) : p; }
  glm::dquat rotation(const glm::dquat& q) const { return moved ? glm::normalize(glm::quat_cast(turn) * q) : q; }
  // The parent's velocity now at the piece, plus its impulse (both turned with the parent).
  glm::dvec3 velocity(const PieceSpec& spec) const {
    return now.velocity + glm::cross(now.angularVelocity, turn * spec.offsetFromParent) + turn * spec.impulse;
  }
};

// What the pieces of one commit share.
struct PieceCommit {
  SplitWorld& w;
  const SplitJob& job;
  ecs::CommandBuffer& commands;
  ParentMoved m;
  const SkinnedMesh* skin = nullptr;  // the target's, for skinned jobs
  SplitEvent& ev;
  ActivationThrottle& activations;    // bodies beyond the tick's wakings start asleep, queued
  uint32_t maxActivationsPerTick = 0;
};

class PieceKindStrategy {
 public:
  virtual ~PieceKindStrategy() = default;
  virtual const char* name() const = 0;

  // Compute. Completes the spec (its kind, mass, frame, mesh and name are set); may turn it into
  // another kind (a ragdoll piece too small for any bone keeps animating instead).
  virtual void plan(const PiecePlan&, PieceSpec&) const {}
  // The piece draws its bind-space mesh with a skin (else the piece as cut, posed when skinned).
  virtual bool keepsSkin() const { return false; }
  // It gets a collider planned in compute: from its pose (else from the mesh it draws).
  virtual bool hasCollider() const { return true; }
  virtual bool colliderFromPose() const { return false; }
  // Its collider parts stay with it for its own cuts (they are in the space of the mesh it draws).
  virtual bool keepsParts(bool hierarchy) const { return !hierarchy; }

  // Commit. It has a body (RigidBody; it is cut again, it counts as a body in the piece budget).
  virtual bool hasBody() const { return true; }
  // Puts the piece on its body: fills `rb` and, when the body decides them, `transform` and
  // `renderer`. False when nothing could be made (the piece then falls as debris).
  virtual bool attach(PieceCommit& c, const PieceSpec& spec, ecs::Entity e, ecs::Transform& transform,
                      MeshRenderer& renderer, RigidBody& rb, const glm::dvec3& velocity) const;
  // Components of its kind, after those every piece gets.
  virtual void addComponents(PieceCommit&, const PieceSpec&, ecs::Entity, const glm::dvec3& /*velocity*/) const {}
  // Its skin follows bones of its own (no copy of the parent's animator).
  virtual bool skinnedByBones() const { return false; }
};

// The strategy of a kind (Rigid's for a kind never registered).
const PieceKindStrategy& pieceKind(PieceKind kind);
// Adds a kind; returns its PieceKind (after the built-in ones). The strategy must outlive every
// split that uses it. Main thread, before those splits. At most 32 kinds of a game's own: past that
// the call logs an error and returns Rigid.
PieceKind registerPieceKind(const PieceKindStrategy& strategy);

// For kinds' commits: a dynamic body with the spec's planned collider, woken now or queued by the
// activation throttle; null (and no shape left behind) when the bridge refuses it.
RigidBody createPieceBody(PieceCommit& c, const PieceSpec& spec, ecs::Entity e, const ecs::Transform& transform,
                          const glm::dvec3& velocity, const glm::dvec3& angularVelocity);
// The radius of a ball of `volume` (m^3): a piece's size for its sleep threshold and where debris rests.
double ballRadius(double volume);

// The built-in kinds (one file each).
const PieceKindStrategy& rigidPieces();
const PieceKindStrategy& debrisPieces();
const PieceKindStrategy& keepAnimatingPieces();
const PieceKindStrategy& bakedPieces();
const PieceKindStrategy& ragdollPieces();

}  // namespace cleave::components
