// SPDX-License-Identifier: MIT
// Ragdoll pieces: a skinned piece on capsule bones joined by joints, planned in compute for the
// joints the piece still uses (skinned.h, planRagdoll), made at commit; the entity's frame is the
// anchor bone's body frame and the piece's joint matrices are relative to it. A piece too small
// for any bone keeps animating on one body instead.
#include "cleave/components/piece_kind.h"

#include <algorithm>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "cleave/components/skinned.h"
#include "cleave/components/split_system.h"

namespace cleave::components {

namespace {

class RagdollPieces final : public PieceKindStrategy {
 public:
  const char* name() const override { return "ragdoll"; }
  bool keepsSkin() const override { return true; }
  bool hasCollider() const override { return false; }  // its bones are its colliders
  bool skinnedByBones() const override { return true; }

  void plan(const PiecePlan& p, PieceSpec& spec) const override {
    const SplitJob& job = p.job;
    const std::vector<glm::vec3> world = transformedPoints(p.posed, job.model);
    if (!planRagdoll(p.piece.mesh, world, p.piece.joints, job.skin->skeleton, p.jointGlobals,
                     std::max(spec.mass, 1e-6), spec.ragdoll)
             .ok()) {
      spec.kind = PieceKind::KeepAnimating;  // too few vertices for any bone
      return;
    }
    const RagdollBoneSpec& anchor = spec.ragdoll.bones[spec.ragdoll.anchor];
    const glm::dmat4 toAnchor =
        glm::inverse(glm::translate(glm::dmat4(1.0), anchor.centre) * glm::mat4_cast(anchor.rotation)) * job.model;
    spec.ragdoll.jointMatrices.reserve(job.jointMatrices.size());
    for (const glm::mat4& m : job.jointMatrices) spec.ragdoll.jointMatrices.push_back(glm::mat4(toAnchor * glm::dmat4(m)));
  }

  bool attach(PieceCommit& c, const PieceSpec& spec, ecs::Entity e, ecs::Transform& transform, MeshRenderer& renderer,
              RigidBody& rb, const glm::dvec3&) const override {
    RagdollDef def;
    def.motion = c.m.motion;
    def.velocity = c.m.now.velocity;
    def.angularVelocity = c.m.now.angularVelocity;
    def.parentCentre = c.m.now.centre;
    def.userData = toUserData(e);
    def.collisionGroup = toUserData(e) | (1ull << 63);
    Ragdoll ragdoll;
    if (!createRagdoll(c.w.physics, spec.ragdoll, def, ragdoll)) return false;
    const RagdollBone& anchor = ragdoll.bones[ragdoll.anchor];
    const physics::BodyTransform at = *c.w.physics.bodyTransform(anchor.body);
    transform.position = at.position;
    transform.rotation = at.rotation;
    renderer.meshOffset = glm::mat4(1.f);
    rb = RigidBody{anchor.body, anchor.shape};
    SkinnedMesh pieceSkin = *c.skin;
    pieceSkin.jointMatrices = spec.ragdoll.jointMatrices;
    c.commands.add<SkinnedMesh>(e, std::move(pieceSkin));
    c.commands.add<Ragdoll>(e, std::move(ragdoll));
    return true;
  }
};

}  // namespace

const PieceKindStrategy& ragdollPieces() {
  static const RagdollPieces kind;
  return kind;
}

}  // namespace cleave::components
