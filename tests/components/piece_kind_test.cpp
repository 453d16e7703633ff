// SPDX-License-Identifier: MIT
// Piece kinds (piece_kind.h): a kind of the test's own, "static props" (pieces that stay where the
// cut left them, on a static body with the collider the compute planned), is one class and one
// registration; the split stages need no change for it.
#include <gtest/gtest.h>

#include <string>

#include "cleave/components/piece_kind.h"
#include "tests/components/sim_harness.h"

namespace cleave::components {
namespace {

using testing::scenePath;
using testing::Sim;

class StaticProps final : public PieceKindStrategy {
 public:
  const char* name() const override { return "static-prop"; }
  bool attach(PieceCommit& c, const PieceSpec& spec, ecs::Entity e, ecs::Transform& transform, MeshRenderer&,
              RigidBody& rb, const glm::dvec3&) const override {
    const physics::ShapeId shape =
        createPlannedShape(c.w.physics, spec.hulls, spec.concavePositions, spec.concaveIndices).valueOr({});
    if (shape.isNull()) return false;
    physics::BodyDef def;
    def.shape = shape;  // mass 0: static
    def.position = transform.position;
    def.rotation = transform.rotation;
    def.userData = toUserData(e);
    auto body = c.w.physics.createBody(def);
    if (!body.ok()) {
      c.w.physics.destroyShape(shape);
      return false;
    }
    rb = RigidBody{body.value(), shape};
    return true;
  }
};

PieceKind staticProps() {
  static const StaticProps kind;
  static const PieceKind registered = registerPieceKind(kind);
  return registered;
}

TEST(PieceKind, AKindOfAGamesOwnIsOneClassAndOneRegistration) {
  const PieceKind props = staticProps();
  EXPECT_GT(size_t(props), size_t(PieceKind::Baked));
  EXPECT_STREQ(toString(props), "static-prop");
  EXPECT_EQ(&pieceKind(props), &pieceKind(staticProps())) << "registered once";
  Sim sim;
  ASSERT_TRUE(sim.load(scenePath("torus_cut.json"))) << sim.scene.message;
  const ecs::Entity torus = sim.scene.find("torus");
  sim.world.get<Splitable>(torus).rigidPieces = props;
  const std::vector<SplitEvent> events = sim.runUntil(40);
  ASSERT_EQ(events.size(), 1u);
  const SplitEvent& ev = events[0];
  ASSERT_EQ(ev.status, geometry::SplitStatus::Ok) << ev.message;
  ASSERT_EQ(ev.pieces.size(), 2u);
  EXPECT_NEAR(ev.piecesMass, ev.parentMass, 1e-6 * ev.parentMass);
  std::vector<glm::vec3> placed;
  for (size_t k = 0; k < ev.pieces.size(); ++k) {
    EXPECT_EQ(ev.kinds[k], props);
    const ecs::Entity piece = ev.pieces[k];
    ASSERT_TRUE(sim.world.has<RigidBody>(piece));
    EXPECT_EQ(sim.physics.bodyMass(sim.world.get<RigidBody>(piece).body).value_or(-1.f), 0.f) << "a static body";
    EXPECT_TRUE(sim.world.has<Splitable>(piece)) << "a body of its own: cut again like any piece";
    EXPECT_GT(ev.colliderFit[k], 0.8);
    placed.push_back(sim.world.get<ecs::Transform>(piece).position);
  }
  // Props stay where the cut left them.
  sim.runUntil(sim.tick + 60);
  for (size_t k = 0; k < ev.pieces.size(); ++k)
    EXPECT_EQ(sim.world.get<ecs::Transform>(ev.pieces[k]).position, placed[k]) << "piece " << k;
}

}  // namespace
}  // namespace cleave::components
