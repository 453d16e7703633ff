// SPDX-License-Identifier: MIT
// The piece kinds' registry and what their commits share (piece_kind.h).
#include "cleave/components/piece_kind.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>

#include <glm/gtc/constants.hpp>

#include "cleave/components/activation_throttle.h"
#include "cleave/components/split_system.h"
#include "cleave/log/log.h"

namespace cleave::components {

namespace {

constexpr size_t kBuiltIn = 5;
constexpr size_t kMaxKinds = kBuiltIn + 32;

// Built-in kinds first, in PieceKind order; registered ones after. Written on the main thread,
// read by workers: each slot is an atomic pointer, filled before its number is handed out.
struct KindTable {
  std::array<std::atomic<const PieceKindStrategy*>, kMaxKinds> slots{};
  KindTable() {
    for (auto& slot : slots) slot.store(nullptr);
    slots[size_t(PieceKind::Rigid)].store(&rigidPieces());
    slots[size_t(PieceKind::Debris)].store(&debrisPieces());
    slots[size_t(PieceKind::KeepAnimating)].store(&keepAnimatingPieces());
    slots[size_t(PieceKind::Ragdoll)].store(&ragdollPieces());
    slots[size_t(PieceKind::Baked)].store(&bakedPieces());
  }
};

std::array<std::atomic<const PieceKindStrategy*>, kMaxKinds>& kinds() {
  static KindTable table;
  return table.slots;
}

std::atomic<size_t> registered{kBuiltIn};

// Continuous collision for small pieces (shatter cells, chips): a piece under 15 cm across is swept
// as a sphere of a third of its smallest extent, so that it does not pass through the floor.
float smallPieceCcdRadius(const PieceSpec& spec) {
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const HullSpec& hull : spec.hulls)
    for (const glm::vec3& p : hull.points) lo = glm::min(lo, p), hi = glm::max(hi, p);
  if (!(lo.x <= hi.x)) return 0.f;
  const glm::vec3 size = hi - lo;
  const float largest = std::max({size.x, size.y, size.z});
  const float smallest = std::min({size.x, size.y, size.z});
  return largest < 0.15f ? smallest / 3.f : 0.f;
}

}  // namespace

const PieceKindStrategy& pieceKind(PieceKind kind) {
  const size_t k = size_t(kind);
  const PieceKindStrategy* s = k < kMaxKinds ? kinds()[k].load(std::memory_order_acquire) : nullptr;
  return s ? *s : rigidPieces();
}

PieceKind registerPieceKind(const PieceKindStrategy& strategy) {
  const size_t k = registered.load();
  if (k >= kMaxKinds) {  // a game registering kinds in a loop: said, and its pieces stay rigid
    log::error("cleave", "piece kind '%s' not registered: %zu kinds of a game's own at most; its pieces are rigid",
               strategy.name(), kMaxKinds - kBuiltIn);
    return PieceKind::Rigid;
  }
  kinds()[k].store(&strategy, std::memory_order_release);
  registered.store(k + 1);
  return PieceKind(k);
}

const char* toString(PieceKind kind) { return pieceKind(kind).name(); }

double ballRadius(double volume) { return std::cbrt(3.0 * std::max(volume, 0.0) / (4.0 * glm::pi<double>())); }

RigidBody createPieceBody(PieceCommit& c, const PieceSpec& spec, ecs::Entity e, const ecs::Transform& transform,
                          const glm::dvec3& velocity, const glm::dvec3& angularVelocity) {
  const physics::ShapeId shape =
      createPlannedShape(c.w.physics, spec.hulls, spec.concavePositions, spec.concaveIndices).valueOr({});
  if (shape.isNull()) return {};  // a flat sliver: no hull can hold it
  physics::BodyDef def;
  def.shape = shape;
  def.mass = float(std::max(spec.mass, 1e-6));
  def.position = transform.position;
  def.rotation = transform.rotation;
  def.linearVelocity = glm::vec3(velocity);
  def.angularVelocity = glm::vec3(angularVelocity);
  def.localInertia = glm::vec3(spec.frame.moments);
  def.userData = toUserData(e);
  def.ccdRadius = smallPieceCcdRadius(spec);
  // Small pieces: sleep when their surface barely moves (a 1 cm chip turning at 5 rad/s looks still),
  // and a little damping of the spin the solver gives slivers at contacts.
  const double radius = ballRadius(std::max(spec.volume, 1e-12));
  def.sleepAngularSpeed = float(std::max(1.0, 0.08 / radius));
  if (radius < 0.05) def.angularDamping = 0.2f;
  const bool awakeNow = c.activations.admitAwake(c.maxActivationsPerTick);
  def.startAwake = awakeNow;
  auto created = c.w.physics.createBody(def);
  if (!created.ok()) {
    c.w.physics.destroyShape(shape);
    return {};
  }
  const physics::BodyId body = created.value();
  if (!awakeNow) c.activations.queue(body);
  return RigidBody{body, shape};
}

bool PieceKindStrategy::attach(PieceCommit& c, const PieceSpec& spec, ecs::Entity e, ecs::Transform& transform,
                               MeshRenderer&, RigidBody& rb, const glm::dvec3& velocity) const {
  rb = createPieceBody(c, spec, e, transform, velocity, c.m.now.angularVelocity);
  return !rb.body.isNull();
}

}  // namespace cleave::components
