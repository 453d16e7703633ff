// SPDX-License-Identifier: MIT
// Debris: a piece too small for the solver (or one no collider could hold) is drawn only; it falls
// under gravity, comes to rest on what is at rest, and fades (world_systems.h, updateDebris).
#include "cleave/components/piece_kind.h"

#include "cleave/components/world_systems.h"

namespace cleave::components {

namespace {

class DebrisPieces final : public PieceKindStrategy {
 public:
  const char* name() const override { return "debris"; }
  bool hasCollider() const override { return false; }
  bool hasBody() const override { return false; }
  bool attach(PieceCommit&, const PieceSpec&, ecs::Entity, ecs::Transform&, MeshRenderer&, RigidBody&,
              const glm::dvec3&) const override {
    return true;  // nothing to make
  }
  void addComponents(PieceCommit& c, const PieceSpec& spec, ecs::Entity e, const glm::dvec3& velocity) const override {
    Debris d;
    d.velocity = glm::vec3(velocity);
    d.angularVelocity = glm::vec3(c.m.now.angularVelocity);
    d.radius = float(ballRadius(spec.volume));
    c.commands.add<Debris>(e, d);
  }
};

}  // namespace

const PieceKindStrategy& debrisPieces() {
  static const DebrisPieces kind;
  return kind;
}

}  // namespace cleave::components
