// SPDX-License-Identifier: MIT
// Cutting an animated skinned character in its current pose, through the split system: the three
// piece modes (keep animating, ragdoll, bake), mass kept per cut, and the pose (not the bind pose)
// being what is cut.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <set>

#include <glm/gtc/matrix_transform.hpp>

#include "cleave/components/skinned.h"
#include "cleave/components/splitable.h"
#include "cleave/assets/procedural_character.h"
#include "cleave/geometry/mass_properties.h"
#include "tests/components/sim_harness.h"

namespace cleave::components {
namespace {

using testing::kDt;
using testing::Sim;

const assets::ProceduralCharacter& character() {
  static const assets::ProceduralCharacter made = assets::makeProceduralCharacter();
  return made;
}

std::shared_ptr<const SkinnedAsset> characterAsset() {
  static const std::shared_ptr<const SkinnedAsset> asset = [] {
    auto a = std::make_shared<SkinnedAsset>();
    a->skeleton = character().skeleton;
    a->clips = {character().idle, character().walk};
    return a;
  }();
  return asset;
}

void addFloor(Sim& sim) {
  auto shape = sim.physics.createShape(physics::ShapeDef::box(glm::vec3(20.f, 0.5f, 20.f)));
  ASSERT_TRUE(shape.ok());
  physics::BodyDef def;
  def.shape = shape.value();
  def.position = glm::vec3(0.f, -0.5f, 0.f);  // top face at y = 0
  ASSERT_TRUE(sim.physics.createBody(def).ok());
}

constexpr float kStartTime = 0.3f;  // into the walk: legs apart, arms swinging

// The generated character walking in place, feet on y = 0, on a kinematic body.
ecs::Entity spawnCharacter(Sim& sim, SkinnedPieceMode mode, glm::vec3 at = glm::vec3(0.f)) {
  const ecs::Entity e = sim.world.create();
  sim.world.add<ecs::Name>(e, ecs::Name{"character"});
  ecs::Transform t;
  t.position = at;
  sim.world.add<ecs::Transform>(e, t);
  sim.world.add<ecs::WorldTransform>(e, ecs::WorldTransform{ecs::localMatrix(t)});
  MeshRenderer mr;
  mr.source = std::make_shared<geometry::MeshData>(character().mesh);
  mr.materials.resize(5);
  sim.world.add<MeshRenderer>(e, std::move(mr));
  sim.world.add<SkinnedMesh>(e, makeSkinnedMesh(characterAsset(), "walk", kStartTime));
  Splitable sp;
  sp.skinnedPieces = mode;
  sp.density = 1000.0;
  sim.world.add<Splitable>(e, sp);
  SplitWorld w = sim.sw();
  EXPECT_EQ(makeSkinnedBody(w, e, 1000.0, /*kinematic=*/true).message, "");
  ecs::updateWorldTransforms(sim.world);
  return e;
}

// Metres above the feet: through the hips, just below the hands that hang at the sides (any
// horizontal cut between 0.87 m and the shoulders also cuts both arms, giving four pieces).
constexpr double kWaist = 0.82;

SplitRequest waistCut(ecs::Entity target, double height = kWaist) {
  SplitRequest r;
  r.target = target;
  r.planeNormal = glm::dvec3(0.0, 1.0, 0.0);
  r.planeOffset = height;
  r.playerCaused = true;
  return r;
}

// Runs ticks until the split system has executed the request (queued now, run next tick).
SplitEvent cutNextTick(Sim& sim, const SplitRequest& r) {
  sim.splits.request(r);
  for (int i = 0; i < 3; ++i) {
    sim.step();
    for (const SplitEvent& ev : sim.splits.lastEvents())
      if (ev.original == r.target) return ev;
  }
  ADD_FAILURE() << "the split never ran";
  return {};
}

glm::dmat4 modelOf(Sim& sim, ecs::Entity e) {
  return glm::dmat4(sim.world.get<ecs::WorldTransform>(e).matrix) * glm::dmat4(sim.world.get<MeshRenderer>(e).meshOffset);
}

std::set<uint16_t> jointsUsed(const geometry::MeshData& mesh) {
  std::set<uint16_t> used;
  for (size_t i = 0; i < mesh.joints.size(); ++i)
    for (int k = 0; k < 4; ++k)
      if (mesh.weights[i][k] > 0.f) used.insert(mesh.joints[i][k]);
  return used;
}

bool isUpperJoint(const std::string& name) {
  return name.find("head") != std::string::npos || name.find("neck") != std::string::npos ||
         name.find("chest") != std::string::npos || name.find("arm") != std::string::npos ||
         name.find("hand") != std::string::npos;
}

// A character whose skin is taken away while its cut computes on a worker is refused at commit: it
// stays whole, with its body, mass and motion, and nothing is made.
TEST(SkinnedSplit, ACharacterThatLostItsSkinBeforeTheCommitStaysWhole) {
  Sim sim;
  addFloor(sim);
  SplitBudgetSettings settings = sim.splits.budget().settings();
  settings.threads = 1;
  settings.commitDelayTicks = 2;
  sim.splits.budget().setSettings(settings);
  const ecs::Entity e = spawnCharacter(sim, SkinnedPieceMode::Bake);
  const physics::BodyId body = sim.world.get<RigidBody>(e).body;
  sim.splits.request(waistCut(e));
  while (sim.splits.jobsInFlight() == 0 && sim.tick < 10) sim.step();
  ASSERT_EQ(sim.splits.jobsInFlight(), 1u);
  ASSERT_TRUE(sim.world.remove<SkinnedMesh>(e));
  const auto before = sim.physics.bodyState(body);
  ASSERT_TRUE(before);
  const testing::InFlightTarget held = testing::inFlightTarget(sim, e);
  testing::expectRefusedAtCommit(sim, held, sim.runUntil(sim.tick + 4), "lost its skin");
  const auto after = sim.physics.bodyState(body);
  ASSERT_TRUE(after);
  EXPECT_EQ(after->linearVelocity, before->linearVelocity);  // kinematic: it stands as it stood
  EXPECT_EQ(after->transform.position, before->transform.position);
}

TEST(SkinnedSplit, KeepAnimatingPiecesPlayOnInSyncWithAnUncutAnimator) {
  Sim sim;
  addFloor(sim);
  const ecs::Entity c = spawnCharacter(sim, SkinnedPieceMode::KeepAnimating);
  SkinnedMesh reference = sim.world.get<SkinnedMesh>(c);  // an uncut copy, advanced alongside
  const double parentMass = sim.world.get<MassInfo>(c).mass;
  sim.splits.request(waistCut(c));
  SplitEvent ev;
  for (int tick = 0; tick < 90; ++tick) {
    sim.step();
    reference.animator.advance(float(kDt));
    for (const SplitEvent& e : sim.splits.lastEvents()) ev = e;
  }
  reference.animator.evaluateJointMatrices(reference.jointMatrices);
  ASSERT_EQ(ev.status, geometry::SplitStatus::Ok) << ev.message;
  ASSERT_EQ(ev.pieces.size(), 2u);
  EXPECT_NEAR(ev.piecesMass / parentMass, 1.0, 1e-9);
  EXPECT_FALSE(sim.world.alive(c));
  for (ecs::Entity piece : ev.pieces) {
    ASSERT_TRUE(sim.world.alive(piece));
    const auto* skin = sim.world.tryGet<SkinnedMesh>(piece);
    ASSERT_NE(skin, nullptr);
    EXPECT_EQ(sim.world.tryGet<Ragdoll>(piece), nullptr);
    EXPECT_EQ(skin->animator.clip(), characterAsset()->clip("walk"));
    EXPECT_FLOAT_EQ(skin->animator.time(), reference.animator.time());
    EXPECT_NEAR(skin->animator.time(), kStartTime + 90.f * float(kDt), 1e-4);
    ASSERT_EQ(skin->jointMatrices.size(), reference.jointMatrices.size());
    for (size_t j = 0; j < reference.jointMatrices.size(); ++j)
      EXPECT_EQ(skin->jointMatrices[j], reference.jointMatrices[j]) << "joint " << j;
    // Still a skinned mesh, with a body of its own that keeps it on the floor.
    EXPECT_FALSE(sim.world.get<MeshRenderer>(piece).source->joints.empty());
    const auto* rb = sim.world.tryGet<RigidBody>(piece);
    ASSERT_NE(rb, nullptr);
    EXPECT_GT(*sim.physics.bodyMass(rb->body), 0.f);
    EXPECT_GT(sim.physics.bodyTransform(rb->body)->position.y, 0.0f);
  }
}

TEST(SkinnedSplit, RagdollPiecesHaveBonesOnlyForTheirJointsAndHoldTogether) {
  Sim sim;
  addFloor(sim);
  const ecs::Entity c = spawnCharacter(sim, SkinnedPieceMode::Ragdoll);
  const double parentMass = sim.world.get<MassInfo>(c).mass;
  // The pose the cut is made in (see BakedPiecesAreClosedAndKeepThePosedVolume) and the posed
  // volume, computed here: each piece's mass must be its own posed volume's share of the parent's.
  sim.step();
  const glm::dmat4 model = modelOf(sim, c);
  const std::vector<glm::mat4> joints = sim.world.get<SkinnedMesh>(c).jointMatrices;
  auto posedVolume = [&](const geometry::MeshData& bindSpace) {
    geometry::MeshData posed;
    bakeSkin(bindSpace, joints, posed);
    return geometry::computeMassProperties(posed, model).volume;
  };
  const double wholeVolume = posedVolume(character().mesh);
  const SplitEvent ev = cutNextTick(sim, waistCut(c));
  ASSERT_EQ(ev.status, geometry::SplitStatus::Ok) << ev.message;
  ASSERT_EQ(ev.pieces.size(), 2u);
  for (ecs::Entity piece : ev.pieces) {
    const double share = posedVolume(*sim.world.get<MeshRenderer>(piece).source) / wholeVolume;
    // (the split poses in double, bakeSkin in float: shares agree to about 1e-5)
    EXPECT_NEAR(sim.world.get<MassInfo>(piece).mass / parentMass, share, 1e-4);
  }
  const anim::Skeleton& skeleton = characterAsset()->skeleton;
  for (ecs::Entity piece : ev.pieces) {
    const auto* ragdoll = sim.world.tryGet<Ragdoll>(piece);
    ASSERT_NE(ragdoll, nullptr);
    const std::set<uint16_t> used = jointsUsed(*sim.world.get<MeshRenderer>(piece).source);
    const bool upper = sim.physics.bodyTransform(ragdoll->bones[ragdoll->anchor].body)->position.y > kWaist;
    ASSERT_GE(ragdoll->bones.size(), 3u);
    EXPECT_EQ(ragdoll->joints.size() + 1, ragdoll->bones.size()) << "one tree of bones per piece";
    double boneMass = 0.0;
    for (const RagdollBone& bone : ragdoll->bones) {
      EXPECT_TRUE(used.count(bone.joint)) << skeleton.joints[bone.joint].name << " is not used by the piece";
      const std::string& name = skeleton.joints[bone.joint].name;
      if (upper) {
        // The tops of the thighs reach above the cut; shins and feet do not.
        EXPECT_TRUE(name.find("shin") == std::string::npos && name.find("foot") == std::string::npos)
            << name << " on the upper piece";
      } else {
        EXPECT_FALSE(isUpperJoint(name)) << name << " on the lower piece";
      }
      boneMass += bone.mass;
    }
    EXPECT_NEAR(boneMass / sim.world.get<MassInfo>(piece).mass, 1.0, 1e-5);
    if (!upper) {
      bool hinge = false;
      for (const RagdollJoint& j : ragdoll->joints) hinge |= j.type == physics::JointType::Hinge;
      EXPECT_TRUE(hinge) << "knees are hinges";
    }
  }
  // Two seconds later: every joint holds, nothing went through the floor, the skin follows.
  float worstSeparation = 0.f, lowest = 10.f, lowestCentre = 10.f;
  for (int tick = 0; tick < 120; ++tick) {
    sim.step();
    for (ecs::Entity piece : ev.pieces) {
      const Ragdoll& ragdoll = sim.world.get<Ragdoll>(piece);
      for (const RagdollBone& bone : ragdoll.bones) {
        const physics::BodyTransform t = *sim.physics.bodyTransform(bone.body);
        const glm::vec3 axis = t.rotation * glm::vec3(0, 1, 0);
        const float low = std::min((t.position + axis * bone.halfHeight).y,
                                           (t.position - axis * bone.halfHeight).y) - bone.radius;
        lowestCentre = std::min(lowestCentre, t.position.y);
        if (tick == 119) lowest = std::min(lowest, low);
      }
      if (tick == 119)
        for (const RagdollJoint& j : ragdoll.joints)
          worstSeparation = std::max(worstSeparation, sim.physics.jointState(j.joint)->separation);
    }
  }
  // Joints hold to within 3 cm (a bone pressed between the floor and a heavy torso stretches its
  // joint a little). Capsules of a few centimetres' radius dip into the floor on impact for a few
  // ticks (the contact solver pushes them out over several steps), but no bone centre goes more
  // than 2 cm below the floor's top, and at rest none is sunk more than 2 cm.
  EXPECT_LT(worstSeparation, 0.03f) << "adjacent bones drifted apart at their joint";
  EXPECT_GT(lowestCentre, -0.02f) << "a bone fell through the floor";
  EXPECT_GT(lowest, -0.02f) << "a bone rests sunk into the floor";
  std::printf("ragdoll: worst joint separation %.4f m after 2 s, lowest bone centre %.4f m, lowest resting surface %.4f m\n",
              worstSeparation, lowestCentre, lowest);
  for (ecs::Entity piece : ev.pieces) {
    // The skin follows the anchor: the entity sits where its anchor body is.
    const Ragdoll& ragdoll = sim.world.get<Ragdoll>(piece);
    const glm::vec3 anchor = sim.physics.bodyTransform(ragdoll.bones[ragdoll.anchor].body)->position;
    EXPECT_LT(glm::length(sim.world.get<ecs::Transform>(piece).position - anchor), 1e-5f);
    for (const glm::mat4& m : sim.world.get<SkinnedMesh>(piece).jointMatrices)
      for (int k = 0; k < 4; ++k) EXPECT_TRUE(std::isfinite(m[3][k]));
  }
  // Destroying a piece frees its bones, their shapes and their joints (its destroy hooks).
  const uint32_t bodiesBefore = sim.physics.bodyCount();
  const uint32_t shapesBefore = sim.physics.liveShapeCount();
  const size_t bones = sim.world.get<Ragdoll>(ev.pieces[0]).bones.size();
  ASSERT_GT(bones, 1u);
  EXPECT_TRUE(sim.world.destroy(ev.pieces[0]));
  EXPECT_EQ(sim.physics.bodyCount(), bodiesBefore - bones);
  EXPECT_EQ(sim.physics.liveShapeCount(), shapesBefore - bones);
  EXPECT_EQ(sim.physics.jointCount(), sim.world.get<Ragdoll>(ev.pieces[1]).joints.size());
}

TEST(SkinnedSplit, BakedPiecesAreClosedAndKeepThePosedVolume) {
  Sim sim;
  addFloor(sim);
  const ecs::Entity c = spawnCharacter(sim, SkinnedPieceMode::Bake, glm::vec3(0.5f, 0.f, -0.25f));
  const double parentMass = sim.world.get<MassInfo>(c).mass;
  // The posed and the bind-pose character in the world, as they are when the cut runs (the pose
  // does not change between this tick's Animation phase and the next tick's Split phase).
  sim.step();
  const glm::dmat4 model = modelOf(sim, c);
  geometry::MeshData posed;
  bakeSkin(character().mesh, sim.world.get<SkinnedMesh>(c).jointMatrices, posed);
  const geometry::MassProperties whole = geometry::computeMassProperties(posed, model);
  ASSERT_TRUE(whole.closed);
  const SplitEvent ev = cutNextTick(sim, waistCut(c));
  ASSERT_EQ(ev.status, geometry::SplitStatus::Ok) << ev.message;
  ASSERT_EQ(ev.pieces.size(), 2u);
  double volume = 0.0;
  glm::dvec3 lowerMin(1e9), lowerMax(-1e9);
  for (ecs::Entity piece : ev.pieces) {
    EXPECT_EQ(sim.world.tryGet<SkinnedMesh>(piece), nullptr);
    const geometry::MeshData& mesh = *sim.world.get<MeshRenderer>(piece).source;
    EXPECT_TRUE(mesh.joints.empty());
    // The piece's mesh in the world at its creation: its body has not moved yet in this tick.
    const auto& rb = sim.world.get<RigidBody>(piece);
    (void)rb;
    const geometry::MassProperties props = geometry::computeMassProperties(mesh, modelOf(sim, piece));
    EXPECT_TRUE(props.closed);
    volume += props.volume;
    // Its mass is its share of the parent's by the volume recomputed here, not by the split's figure.
    EXPECT_NEAR(sim.world.get<MassInfo>(piece).mass / parentMass, props.volume / whole.volume, 1e-4);
    const glm::dmat4 m = modelOf(sim, piece);
    glm::dvec3 lo(1e9), hi(-1e9);
    for (const glm::vec3& p : mesh.positions) {
      const glm::dvec3 q(m * glm::dvec4(glm::dvec3(p), 1.0));
      lo = glm::min(lo, q);
      hi = glm::max(hi, q);
    }
    if (hi.y < kWaist + 0.05) {
      lowerMin = lo;
      lowerMax = hi;
    }
  }
  EXPECT_NEAR(volume / whole.volume, 1.0, 1e-4);
  // Cut in the pose: the lower piece spans what the posed legs span (strides apart along z), not
  // what the bind-pose legs span.
  glm::dvec3 posedMin(1e9), posedMax(-1e9), bindMin(1e9), bindMax(-1e9);
  for (size_t i = 0; i < posed.positions.size(); ++i) {
    const glm::dvec3 p(model * glm::dvec4(glm::dvec3(posed.positions[i]), 1.0));
    const glm::dvec3 b(model * glm::dvec4(glm::dvec3(character().mesh.positions[i]), 1.0));
    if (p.y < kWaist) {
      posedMin = glm::min(posedMin, p);
      posedMax = glm::max(posedMax, p);
    }
    if (b.y < kWaist) {
      bindMin = glm::min(bindMin, b);
      bindMax = glm::max(bindMax, b);
    }
  }
  ASSERT_LT(lowerMax.y, 2.0) << "no lower piece found";
  // The lower piece moved a little during the one physics step since its creation: compare with
  // a tolerance of 1 cm; the bind pose differs by far more along the stride.
  for (int k : {0, 2}) {
    EXPECT_NEAR(lowerMin[k], posedMin[k], 0.01) << "axis " << k;
    EXPECT_NEAR(lowerMax[k], posedMax[k], 0.01) << "axis " << k;
  }
  const double strideDifference = std::max(std::abs(posedMin.z - bindMin.z), std::abs(posedMax.z - bindMax.z));
  EXPECT_GT(strideDifference, 0.08) << "the walk pose should differ from the bind pose along the stride";
  const double lowerDifference = std::max(std::abs(lowerMin.z - bindMin.z), std::abs(lowerMax.z - bindMax.z));
  EXPECT_GT(lowerDifference, 0.08) << "the lower piece looks like a bind-pose cut";
}

TEST(SkinnedSplit, PiecesOfPiecesKeepMassAndSkin) {
  // A ragdoll piece cut again: the cut uses the ragdoll's pose; mass stays.
  Sim sim;
  addFloor(sim);
  const ecs::Entity c = spawnCharacter(sim, SkinnedPieceMode::Ragdoll);
  const SplitEvent first = cutNextTick(sim, waistCut(c));
  ASSERT_EQ(first.pieces.size(), 2u);
  for (int i = 0; i < 10; ++i) sim.step();
  ecs::Entity upper;
  for (ecs::Entity piece : first.pieces)
    if (sim.world.get<ecs::Transform>(piece).position.y > kWaist) upper = piece;
  ASSERT_TRUE(sim.world.alive(upper));
  const double upperMass = sim.world.get<MassInfo>(upper).mass;
  // A vertical cut through the middle of the upper body (left from right).
  SplitRequest r;
  r.target = upper;
  r.planeNormal = glm::dvec3(1.0, 0.0, 0.0);
  r.planeOffset = sim.world.get<ecs::Transform>(upper).position.x;
  const SplitEvent second = cutNextTick(sim, r);
  ASSERT_EQ(second.status, geometry::SplitStatus::Ok) << second.message;
  ASSERT_GE(second.pieces.size(), 2u);
  EXPECT_NEAR(second.piecesMass / upperMass, 1.0, 1e-9);
  for (ecs::Entity piece : second.pieces) {
    const bool skinned = sim.world.has<Ragdoll>(piece) || sim.world.has<SkinnedMesh>(piece);
    EXPECT_TRUE(skinned || sim.world.get<MeshRenderer>(piece).source->joints.empty());
  }
}

}  // namespace
}  // namespace cleave::components
