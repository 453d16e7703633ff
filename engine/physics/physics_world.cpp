// SPDX-License-Identifier: MIT
// PhysicsWorld over Bullet's btDiscreteDynamicsWorld.
//
// Pipeline of one step: Bullet's own stepSimulation with maxSubSteps = 0 (exactly one substep of
// dt, no accumulator, no motion-state interpolation; bodies have no motion state, transforms are
// read from the bodies), then one pass over the dispatcher's contact manifolds builds both event
// arrays: body-body manifolds become ContactEvents, trigger-body manifolds become trigger touches.
// A touch needs a narrowphase contact point no farther apart than kTouchDistance; broadphase (AABB)
// pairs alone never count, because the AABB of a large static ground overlaps everything on it.
//
// Back-references: every Bullet collision object carries its slot index in userIndex and its kind
// (body or trigger) in userIndex2; the generation is read from the slot table.
#include "cleave/physics/physics_world.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>
#include <vector>

#include <btBulletDynamicsCommon.h>
#include <BulletCollision/CollisionDispatch/btGhostObject.h>
#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>

#include "cleave/base/detail/slot_pool.h"
#include "cleave/physics/detail/bullet_convert.h"
#include "cleave/physics/detail/shape_builder.h"

namespace cleave::physics {
namespace {

using detail::toBt;
using detail::toGlm;

constexpr int kKindBody = 1;
constexpr int kKindTrigger = 2;
// Contact points farther apart than this (metres) are speculative and do not count as touching.
constexpr btScalar kTouchDistance = 0.001f;
constexpr double kMaxStep = 1.0;
constexpr int kJointSolverIterations = 40;
// Frozen bodies: a broadphase group of their own (Bullet's spare debris bit), paired with dynamic
// bodies and triggers only.
constexpr int kFrozenGroup = btBroadphaseProxy::DebrisFilter;
constexpr int kFrozenMask = btBroadphaseProxy::AllFilter & ~btBroadphaseProxy::StaticFilter &
                            ~btBroadphaseProxy::KinematicFilter & ~kFrozenGroup;

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool finite(const glm::quat& q) {
  return std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z) && std::isfinite(q.w);
}
// A usable rotation: finite and not (nearly) zero. Returns it normalised.
std::optional<glm::quat> normalisedRotation(const glm::quat& q) {
  if (!finite(q)) return std::nullopt;
  const float norm = glm::length(q);
  if (!(norm > 1e-6f)) return std::nullopt;
  return q / norm;
}

struct ShapeRecord {
  detail::BuiltShape built;
  uint32_t users = 0;           // bodies and triggers using the shape
  bool handleReleased = false;  // destroyShape was called; freed when users reaches 0
};

struct BodyRecord {
  std::unique_ptr<btRigidBody> body;
  uint32_t shapeIndex = 0;
  float mass = 0.0f;
  uint64_t userData = 0;
  uint64_t collisionGroup = 0;
  bool kinematic = false;
  bool frozen = false;
  bool allowSleep = true;            // BodyDef::allowSleep, restored when a frozen body thaws
  btVector3 frozenInertia{0, 0, 0};  // principal moments kept while frozen
};

struct JointRecord {
  std::unique_ptr<btTypedConstraint> constraint;
  JointType type = JointType::ConeTwist;
  BodyId bodyA;
  BodyId bodyB;
  btTransform frameA;
  btTransform frameB;
};

struct TriggerRecord {
  std::unique_ptr<btPairCachingGhostObject> ghost;
  uint32_t shapeIndex = 0;
  uint64_t userData = 0;
  bool persistent = true;
  bool spent = false;  // one-shot trigger after its step: out of the collision world
};

void hashBytes(uint64_t& hash, const void* data, size_t size) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < size; ++i) {
    hash ^= bytes[i];
    hash *= 0x100000001b3ull;
  }
}
void hashVector(uint64_t& hash, const btVector3& v) {
  const float xyz[3] = {v.x(), v.y(), v.z()};  // the 4th lane is padding
  hashBytes(hash, xyz, sizeof(xyz));
}

}  // namespace

// Broadphase filter: Bullet's group/mask test, plus "bodies of the same non-zero collision group
// never pair" (ragdoll bones). The group is looked up through the body's slot index.
struct GroupFilter : btOverlapFilterCallback {
  const base::detail::SlotPool<BodyRecord>* bodies = nullptr;
  bool needBroadphaseCollision(btBroadphaseProxy* p0, btBroadphaseProxy* p1) const override {
    const bool masks = (p0->m_collisionFilterGroup & p1->m_collisionFilterMask) != 0 &&
                       (p1->m_collisionFilterGroup & p0->m_collisionFilterMask) != 0;
    if (!masks) return false;
    const auto* a = static_cast<const btCollisionObject*>(p0->m_clientObject);
    const auto* b = static_cast<const btCollisionObject*>(p1->m_clientObject);
    if (a == nullptr || b == nullptr || a->getUserIndex2() != kKindBody || b->getUserIndex2() != kKindBody)
      return true;
    const BodyRecord* ra = bodies->atIndex(uint32_t(a->getUserIndex()));
    const BodyRecord* rb = bodies->atIndex(uint32_t(b->getUserIndex()));
    if (ra == nullptr || rb == nullptr) return true;
    return ra->collisionGroup == 0 || ra->collisionGroup != rb->collisionGroup;
  }
};

// Midphase for box triggers: a long blade turned about the vertical has bounds over most of a level,
// so the broadphase pairs it with every body there and each pair would run the narrowphase every
// step. A body whose bounds lie wholly outside the blade's box along one of the box's own axes
// cannot touch it: its pair skips the narrowphase, and the pair's contact points are dropped so no
// stale touch is reported. Other pairs take Bullet's own path.
bool separatedFromBox(const btCollisionObject& box, const btBroadphaseProxy& other) {
  const auto& shape = static_cast<const btBoxShape&>(*box.getCollisionShape());
  const btVector3 half = shape.getHalfExtentsWithMargin();
  const btVector3 centre = (other.m_aabbMin + other.m_aabbMax) * 0.5f;
  const btVector3 extent = (other.m_aabbMax - other.m_aabbMin) * 0.5f;
  const btTransform& t = box.getWorldTransform();
  const btVector3 offset = centre - t.getOrigin();
  for (int axis = 0; axis < 3; ++axis) {
    const btVector3 u = t.getBasis().getColumn(axis);
    const btScalar reach = std::fabs(u.x()) * extent.x() + std::fabs(u.y()) * extent.y() + std::fabs(u.z()) * extent.z();
    if (std::fabs(u.dot(offset)) > half[axis] + reach) return true;
  }
  return false;
}

void triggerNearCallback(btBroadphasePair& pair, btCollisionDispatcher& dispatcher, const btDispatcherInfo& info) {
  const auto* a = static_cast<const btCollisionObject*>(pair.m_pProxy0->m_clientObject);
  const auto* b = static_cast<const btCollisionObject*>(pair.m_pProxy1->m_clientObject);
  const bool aBox = a->getUserIndex2() == kKindTrigger && a->getCollisionShape()->getShapeType() == BOX_SHAPE_PROXYTYPE;
  const bool bBox = b->getUserIndex2() == kKindTrigger && b->getCollisionShape()->getShapeType() == BOX_SHAPE_PROXYTYPE;
  if ((aBox && separatedFromBox(*a, *pair.m_pProxy1)) || (bBox && separatedFromBox(*b, *pair.m_pProxy0))) {
    if (pair.m_algorithm != nullptr) {
      btManifoldArray manifolds;
      pair.m_algorithm->getAllContactManifolds(manifolds);
      for (int i = 0; i < manifolds.size(); ++i) manifolds[i]->clearManifold();
    }
    return;
  }
  btCollisionDispatcher::defaultNearCallback(pair, dispatcher, info);
}

struct PhysicsWorld::Impl {
  // Declaration order is construction order; ~Impl empties the world before members go.
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btGhostPairCallback ghostPairCallback;
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};

  base::detail::SlotPool<ShapeRecord> shapes;
  base::detail::SlotPool<BodyRecord> bodies;
  base::detail::SlotPool<TriggerRecord> triggers;
  base::detail::SlotPool<JointRecord> joints;  // declared after bodies: freed before them
  GroupFilter groupFilter;

  std::vector<TriggerEvent> triggerEvents;
  std::vector<ContactEvent> contactEvents;
  std::vector<std::pair<TriggerId, BodyId>> touching;  // sorted; touches of the last step
  uint64_t steps = 0;

  explicit Impl(const WorldDef& def) {
    btGImpactCollisionAlgorithm::registerAlgorithm(&dispatcher);
    dispatcher.setNearCallback(triggerNearCallback);
    broadphase.getOverlappingPairCache()->setInternalGhostPairCallback(&ghostPairCallback);
    groupFilter.bodies = &bodies;
    broadphase.getOverlappingPairCache()->setOverlapFilterCallback(&groupFilter);
    const glm::vec3 gravity = finite(def.gravity) ? def.gravity : WorldDef{}.gravity;
    world.setGravity(toBt(gravity));
    world.getSolverInfo().m_numIterations =
        def.solverIterations >= 1 ? def.solverIterations : WorldDef{}.solverIterations;
    // Only moving objects get new bounds each step: sleeping, static and frozen bodies keep theirs
    // (every teleport below updates the bounds it moves).
    world.setForceUpdateAllAabbs(false);
  }

  ~Impl() {
    joints.forEach([&](uint32_t, uint32_t, JointRecord& r) { world.removeConstraint(r.constraint.get()); });
    bodies.forEach([&](uint32_t, uint32_t, BodyRecord& r) { world.removeRigidBody(r.body.get()); });
    triggers.forEach([&](uint32_t, uint32_t, TriggerRecord& r) {
      if (!r.spent) world.removeCollisionObject(r.ghost.get());
    });
  }

  // Enters a new body in the Bullet world with its kind's filters and activation state.
  void addBody(btRigidBody& body, const BodyDef& def, bool dynamic) {
    if (def.kinematic) {
      body.setCollisionFlags(body.getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
      body.setActivationState(DISABLE_DEACTIVATION);
      // Not in the static group, so triggers (which skip static bodies) see it; it pairs with
      // dynamic bodies and triggers only.
      world.addRigidBody(&body, btBroadphaseProxy::KinematicFilter,
                         btBroadphaseProxy::AllFilter & ~btBroadphaseProxy::StaticFilter &
                             ~btBroadphaseProxy::KinematicFilter);
    } else {
      world.addRigidBody(&body);
    }
    if (dynamic && !def.allowSleep) {
      body.setActivationState(DISABLE_DEACTIVATION);
    } else if (dynamic && !def.startAwake) {
      body.setActivationState(ISLAND_SLEEPING);
    }
  }

  ShapeRecord* liveShape(ShapeId id) {
    ShapeRecord* record = shapes.get(id.index, id.generation);
    return record && !record->handleReleased ? record : nullptr;
  }
  BodyRecord* body(BodyId id) { return bodies.get(id.index, id.generation); }
  JointRecord* joint(JointId id) { return joints.get(id.index, id.generation); }
  void removeJoint(uint32_t index) {
    JointRecord* record = joints.atIndex(index);
    if (record == nullptr) return;
    world.removeConstraint(record->constraint.get());
    joints.erase(index);
  }
  TriggerRecord* trigger(TriggerId id) { return triggers.get(id.index, id.generation); }
  bool jointed(BodyId id) const {
    bool any = false;
    joints.forEach([&](uint32_t, uint32_t, const JointRecord& j) { any = any || j.bodyA == id || j.bodyB == id; });
    return any;
  }
  void freeze(BodyRecord& r);
  void thaw(BodyRecord& r);

  void releaseShapeUser(uint32_t index) {
    ShapeRecord* record = shapes.atIndex(index);
    if (record == nullptr) return;
    --record->users;
    if (record->users == 0 && record->handleReleased) shapes.erase(index);
  }

  BodyId bodyIdAt(uint32_t index) const { return BodyId{index, bodies.generationAt(index)}; }
  TriggerId triggerIdAt(uint32_t index) const {
    return TriggerId{index, triggers.generationAt(index)};
  }

  void forgetTouches(auto&& predicate) {
    std::erase_if(touching, predicate);
  }

  void collectEvents();
};

void PhysicsWorld::Impl::collectEvents() {
  contactEvents.clear();
  triggerEvents.clear();
  std::vector<std::pair<TriggerId, BodyId>> now;

  const int manifoldCount = dispatcher.getNumManifolds();
  for (int m = 0; m < manifoldCount; ++m) {
    const btPersistentManifold* manifold = dispatcher.getManifoldByIndexInternal(m);
    const btCollisionObject* a = manifold->getBody0();
    const btCollisionObject* b = manifold->getBody1();
    const int kindA = a->getUserIndex2();
    const int kindB = b->getUserIndex2();

    if (kindA == kKindBody && kindB == kKindBody) {
      ContactEvent event;
      float deepest = 0.0f;
      bool any = false;
      for (int p = 0; p < manifold->getNumContacts(); ++p) {
        const btManifoldPoint& point = manifold->getContactPoint(p);
        if (point.getDistance() > kTouchDistance) continue;
        event.impulse += point.getAppliedImpulse();
        ++event.pointCount;
        const float depth = std::max(0.0f, -point.getDistance());
        if (!any || depth > deepest) {
          deepest = depth;
          event.point = toGlm((point.getPositionWorldOnA() + point.getPositionWorldOnB()) * 0.5f);
          // Bullet's normal is on B, pointing from B towards A.
          event.normal = -toGlm(point.m_normalWorldOnB);
        }
        any = true;
      }
      if (!any) continue;
      event.depth = deepest;
      event.bodyA = bodyIdAt(uint32_t(a->getUserIndex()));
      event.bodyB = bodyIdAt(uint32_t(b->getUserIndex()));
      if (event.bodyB.index < event.bodyA.index) {
        std::swap(event.bodyA, event.bodyB);
        event.normal = -event.normal;
      }
      contactEvents.push_back(event);
    } else if ((kindA == kKindTrigger) != (kindB == kKindTrigger)) {
      const btCollisionObject* ghost = kindA == kKindTrigger ? a : b;
      const btCollisionObject* other = kindA == kKindTrigger ? b : a;
      if (other->getUserIndex2() != kKindBody) continue;
      bool touches = false;
      for (int p = 0; p < manifold->getNumContacts() && !touches; ++p) {
        touches = manifold->getContactPoint(p).getDistance() <= kTouchDistance;
      }
      if (touches) {
        now.emplace_back(triggerIdAt(uint32_t(ghost->getUserIndex())),
                         bodyIdAt(uint32_t(other->getUserIndex())));
      }
    }
  }

  // Compound and GImpact shapes give one manifold per child pair: merge them per body pair, keeping
  // the deepest point. Sorting by handle makes the order independent of Bullet's internals.
  std::stable_sort(contactEvents.begin(), contactEvents.end(),
                   [](const ContactEvent& x, const ContactEvent& y) {
                     return std::pair(x.bodyA, x.bodyB) < std::pair(y.bodyA, y.bodyB);
                   });
  size_t out = 0;
  for (size_t i = 0; i < contactEvents.size(); ++i) {
    if (out > 0 && contactEvents[out - 1].bodyA == contactEvents[i].bodyA &&
        contactEvents[out - 1].bodyB == contactEvents[i].bodyB) {
      ContactEvent& merged = contactEvents[out - 1];
      const ContactEvent& next = contactEvents[i];
      merged.impulse += next.impulse;
      merged.pointCount += next.pointCount;
      if (next.depth > merged.depth) {
        merged.depth = next.depth;
        merged.point = next.point;
        merged.normal = next.normal;
      }
    } else {
      contactEvents[out++] = contactEvents[i];
    }
  }
  contactEvents.resize(out);

  std::sort(now.begin(), now.end());
  now.erase(std::unique(now.begin(), now.end()), now.end());
  // Merge the sorted touch lists of the previous and this step into Begin / Stay / End.
  size_t i = 0, j = 0;
  while (i < touching.size() || j < now.size()) {
    if (j == now.size() || (i < touching.size() && touching[i] < now[j])) {
      triggerEvents.push_back({touching[i].first, touching[i].second, TriggerEventKind::End});
      ++i;
    } else if (i == touching.size() || now[j] < touching[i]) {
      triggerEvents.push_back({now[j].first, now[j].second, TriggerEventKind::Begin});
      ++j;
    } else {
      triggerEvents.push_back({now[j].first, now[j].second, TriggerEventKind::Stay});
      ++i;
      ++j;
    }
  }
  touching = std::move(now);
}

// Freezing re-enters the body in the world as a static object of the frozen group (Bullet keeps a
// static body's activation state asleep and never integrates it); thawing re-enters it dynamic with
// the mass and moments it had. Both drop the body's contact manifolds, which the next step rebuilds.
void PhysicsWorld::Impl::freeze(BodyRecord& r) {
  btRigidBody& b = *r.body;
  world.removeRigidBody(&b);
  const btVector3 inverse = b.getInvInertiaDiagLocal();
  auto invert = [](btScalar x) { return x > 0.0f ? 1.0f / x : 0.0f; };
  r.frozenInertia = btVector3(invert(inverse.x()), invert(inverse.y()), invert(inverse.z()));
  b.setLinearVelocity(btVector3(0, 0, 0));
  b.setAngularVelocity(btVector3(0, 0, 0));
  b.setMassProps(0.0f, btVector3(0, 0, 0));
  b.setCollisionFlags(b.getCollisionFlags() | btCollisionObject::CF_STATIC_OBJECT);
  b.updateInertiaTensor();
  world.addRigidBody(&b, kFrozenGroup, kFrozenMask);
  r.frozen = true;
}

void PhysicsWorld::Impl::thaw(BodyRecord& r) {
  btRigidBody& b = *r.body;
  world.removeRigidBody(&b);
  b.setCollisionFlags(b.getCollisionFlags() & ~btCollisionObject::CF_STATIC_OBJECT);
  b.setMassProps(r.mass, r.frozenInertia);
  b.updateInertiaTensor();
  b.setLinearVelocity(btVector3(0, 0, 0));
  b.setAngularVelocity(btVector3(0, 0, 0));
  world.addRigidBody(&b);
  b.setDeactivationTime(0.0f);
  b.forceActivationState(r.allowSleep ? ACTIVE_TAG : DISABLE_DEACTIVATION);
  r.frozen = false;
}

PhysicsWorld::PhysicsWorld(const WorldDef& def) : impl_(std::make_unique<Impl>(def)) {}
PhysicsWorld::~PhysicsWorld() = default;
PhysicsWorld::PhysicsWorld(PhysicsWorld&&) noexcept = default;
PhysicsWorld& PhysicsWorld::operator=(PhysicsWorld&&) noexcept = default;

// ---- world ----

PhysicsStatus PhysicsWorld::setGravity(glm::vec3 gravity) {
  if (!finite(gravity)) return PhysicsStatus::InvalidArgument;
  impl_->world.setGravity(toBt(gravity));
  return PhysicsStatus::Ok;
}

glm::vec3 PhysicsWorld::gravity() const { return toGlm(impl_->world.getGravity()); }

PhysicsStatus PhysicsWorld::step(double dt) {
  Impl& w = *impl_;
  if (!std::isfinite(dt) || dt <= 0.0 || dt > kMaxStep) {
    w.contactEvents.clear();
    w.triggerEvents.clear();
    return PhysicsStatus::InvalidArgument;
  }
  // maxSubSteps = 0: exactly one internal step of dt (Bullet's "variable timestep" path).
  w.world.stepSimulation(btScalar(dt), 0, btScalar(dt));
  w.collectEvents();
  // One-shot triggers have had their step: take them out of the collision world.
  w.triggers.forEach([&](uint32_t index, uint32_t, TriggerRecord& r) {
    if (r.persistent || r.spent) return;
    r.spent = true;
    w.world.removeCollisionObject(r.ghost.get());
    w.forgetTouches([&](const auto& touch) { return touch.first.index == index; });
  });
  ++w.steps;
  return PhysicsStatus::Ok;
}

uint64_t PhysicsWorld::stepCount() const { return impl_->steps; }

// ---- shapes ----

Result<ShapeId> PhysicsWorld::createShape(const ShapeDef& def) {
  detail::BuildOutcome outcome = detail::buildShape(def);
  if (outcome.status != PhysicsStatus::Ok) {
    return Result<ShapeId>::failure(outcome.status, std::move(outcome.reason));
  }
  ShapeRecord record;
  record.built = std::move(outcome.built);
  const auto key = impl_->shapes.insert(std::move(record));
  return Result<ShapeId>::success(ShapeId{key.index, key.generation});
}

bool PhysicsWorld::destroyShape(ShapeId shape) {
  ShapeRecord* record = impl_->liveShape(shape);
  if (record == nullptr) return false;
  record->handleReleased = true;
  if (record->users == 0) impl_->shapes.erase(shape.index);
  return true;
}

bool PhysicsWorld::isValid(ShapeId shape) const { return impl_->liveShape(shape) != nullptr; }

std::optional<ShapeType> PhysicsWorld::shapeType(ShapeId shape) const {
  const ShapeRecord* record = impl_->liveShape(shape);
  if (record == nullptr) return std::nullopt;
  return record->built.type;
}

std::optional<float> PhysicsWorld::shapeMargin(ShapeId shape) const {
  const ShapeRecord* record = impl_->liveShape(shape);
  if (record == nullptr) return std::nullopt;
  return record->built.margin;
}

std::optional<uint32_t> PhysicsWorld::hullVertexCount(ShapeId shape) const {
  const ShapeRecord* record = impl_->liveShape(shape);
  if (record == nullptr) return std::nullopt;
  return record->built.hullVertices;
}

uint32_t PhysicsWorld::liveShapeCount() const { return impl_->shapes.size(); }

// ---- bodies ----

// createBody in three steps: validate the def (every field, before anything is built), work out
// the inertia from the shape, build the Bullet body and enter it in the world.
namespace {

// What validation learnt about a def that building needs.
struct CheckedBody {
  bool dynamic = false;
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // normalised
};

// "createBody: BodyDef::<field> <reason>", as an InvalidArgument unless told otherwise.
Result<CheckedBody> refuse(const char* field, const std::string& reason,
                           PhysicsStatus status = PhysicsStatus::InvalidArgument) {
  return Result<CheckedBody>::failure(status, std::string("createBody: BodyDef::") + field + " " + reason);
}

bool finiteAtLeastZero(float v) { return std::isfinite(v) && v >= 0.0f; }
bool unitInterval(float v) { return v >= 0.0f && v <= 1.0f; }  // false for NaN

// Mass, kind and shape type together: what kind of body the def asks for.
Result<CheckedBody> checkKind(const BodyDef& def, ShapeType shapeType) {
  if (!finiteAtLeastZero(def.mass)) return refuse("mass", "must be finite and >= 0 (0 = static)");
  CheckedBody checked;
  checked.dynamic = def.mass > 0.0f;
  if (def.kinematic && checked.dynamic)
    return refuse("kinematic", "needs mass 0: a kinematic body is moved, not pushed");
  if (checked.dynamic && shapeType == ShapeType::StaticMesh) {
    return refuse("shape",
                  "is a static mesh, which cannot have mass; use a concave mesh (GImpact), a convex hull "
                  "or a compound for dynamic bodies",
                  PhysicsStatus::UnsupportedCombination);
  }
  if (def.localInertia) {
    const glm::vec3 i = *def.localInertia;
    if (!checked.dynamic) return refuse("localInertia", "needs mass > 0 (static and kinematic bodies have none)");
    if (!finite(i) || !(i.x > 0.0f && i.y > 0.0f && i.z > 0.0f))
      return refuse("localInertia", "moments must be finite and > 0");
  }
  return Result<CheckedBody>::success(checked);
}

// Pose, velocities, surface, damping, sleep and continuous collision values.
Result<CheckedBody> checkValues(const BodyDef& def, CheckedBody checked) {
  if (!finite(def.position)) return refuse("position", "must be finite");
  const std::optional<glm::quat> rotation = normalisedRotation(def.rotation);
  if (!rotation) return refuse("rotation", "must be a finite, non-zero quaternion");
  checked.rotation = *rotation;
  if (!finite(def.linearVelocity)) return refuse("linearVelocity", "must be finite");
  if (!finite(def.angularVelocity)) return refuse("angularVelocity", "must be finite");
  if (!finiteAtLeastZero(def.friction)) return refuse("friction", "must be finite and >= 0");
  if (!unitInterval(def.restitution)) return refuse("restitution", "must be in [0, 1]");
  if (!unitInterval(def.linearDamping)) return refuse("linearDamping", "must be in [0, 1]");
  if (!unitInterval(def.angularDamping)) return refuse("angularDamping", "must be in [0, 1]");
  if (!finiteAtLeastZero(def.ccdRadius)) return refuse("ccdRadius", "must be finite and >= 0");
  if (!finiteAtLeastZero(def.sleepLinearSpeed)) return refuse("sleepLinearSpeed", "must be finite and >= 0");
  if (!finiteAtLeastZero(def.sleepAngularSpeed)) return refuse("sleepAngularSpeed", "must be finite and >= 0");
  return Result<CheckedBody>::success(checked);
}

Result<CheckedBody> validateBodyDef(const BodyDef& def, ShapeType shapeType) {
  const Result<CheckedBody> kind = checkKind(def, shapeType);
  return kind.ok() ? checkValues(def, kind.value()) : kind;
}

// Principal moments: the def's, Bullet's for the shape, or none for a static body.
btVector3 bodyInertia(const BodyDef& def, bool dynamic, const btCollisionShape& shape) {
  btVector3 inertia(0, 0, 0);
  if (def.localInertia) return toBt(*def.localInertia);
  if (dynamic) shape.calculateLocalInertia(def.mass, inertia);
  return inertia;
}

std::unique_ptr<btRigidBody> makeRigidBody(const BodyDef& def, const CheckedBody& checked,
                                           btCollisionShape* shape, const btVector3& inertia) {
  btRigidBody::btRigidBodyConstructionInfo info(def.mass, nullptr, shape, inertia);
  info.m_startWorldTransform = detail::toBt(def.position, checked.rotation);
  info.m_friction = def.friction;
  info.m_restitution = def.restitution;
  info.m_linearDamping = def.linearDamping;
  info.m_angularDamping = def.angularDamping;
  info.m_linearSleepingThreshold = def.sleepLinearSpeed;
  info.m_angularSleepingThreshold = def.sleepAngularSpeed;
  auto body = std::make_unique<btRigidBody>(info);
  if (checked.dynamic && def.ccdRadius > 0.0f) {
    body->setCcdMotionThreshold(def.ccdRadius);
    body->setCcdSweptSphereRadius(def.ccdRadius);
  }
  if (checked.dynamic) {
    body->setLinearVelocity(toBt(def.linearVelocity));
    body->setAngularVelocity(toBt(def.angularVelocity));
  }
  return body;
}

}  // namespace

Result<BodyId> PhysicsWorld::createBody(const BodyDef& def) {
  Impl& w = *impl_;
  ShapeRecord* shape = w.liveShape(def.shape);
  if (shape == nullptr)
    return Result<BodyId>::failure(PhysicsStatus::StaleHandle, "createBody: BodyDef::shape is null or destroyed");
  const Result<CheckedBody> checked = validateBodyDef(def, shape->built.type);
  if (!checked.ok()) return Result<BodyId>::failure(checked.code(), checked.message());
  const bool dynamic = checked.value().dynamic;
  std::unique_ptr<btRigidBody> body = makeRigidBody(def, checked.value(), shape->built.shape.get(),
                                                    bodyInertia(def, dynamic, *shape->built.shape));
  btRigidBody* raw = body.get();
  BodyRecord record;
  record.body = std::move(body);
  record.shapeIndex = def.shape.index;
  record.mass = def.mass;
  record.userData = def.userData;
  record.collisionGroup = def.collisionGroup;
  record.kinematic = def.kinematic;
  record.allowSleep = def.allowSleep;
  const auto key = w.bodies.insert(std::move(record));
  raw->setUserIndex(int(key.index));
  raw->setUserIndex2(kKindBody);
  w.addBody(*raw, def, dynamic);
  ++shape->users;
  return Result<BodyId>::success(BodyId{key.index, key.generation});
}

bool PhysicsWorld::destroyBody(BodyId body) {
  Impl& w = *impl_;
  BodyRecord* record = w.body(body);
  if (record == nullptr) return false;
  // Its joints go first: a constraint must never outlive one of its bodies.
  std::vector<uint32_t> attached;
  w.joints.forEach([&](uint32_t index, uint32_t, const JointRecord& j) {
    if (j.bodyA == body || j.bodyB == body) attached.push_back(index);
  });
  for (uint32_t index : attached) w.removeJoint(index);
  w.world.removeRigidBody(record->body.get());
  const uint32_t shapeIndex = record->shapeIndex;
  w.bodies.erase(body.index);
  w.releaseShapeUser(shapeIndex);
  w.forgetTouches([&](const auto& touch) { return touch.second == body; });
  return true;
}

bool PhysicsWorld::isValid(BodyId body) const { return impl_->body(body) != nullptr; }

uint32_t PhysicsWorld::bodyCount() const { return impl_->bodies.size(); }

std::optional<BodyTransform> PhysicsWorld::bodyTransform(BodyId body) const {
  const BodyRecord* record = impl_->body(body);
  if (record == nullptr) return std::nullopt;
  const btTransform& t = record->body->getWorldTransform();
  return BodyTransform{toGlm(t.getOrigin()), toGlm(t.getRotation())};
}

std::optional<glm::vec3> PhysicsWorld::linearVelocity(BodyId body) const {
  const BodyRecord* record = impl_->body(body);
  if (record == nullptr) return std::nullopt;
  return toGlm(record->body->getLinearVelocity());
}

std::optional<glm::vec3> PhysicsWorld::angularVelocity(BodyId body) const {
  const BodyRecord* record = impl_->body(body);
  if (record == nullptr) return std::nullopt;
  return toGlm(record->body->getAngularVelocity());
}

std::optional<BodyState> PhysicsWorld::bodyState(BodyId body) const {
  const BodyRecord* record = impl_->body(body);
  if (record == nullptr) return std::nullopt;
  BodyState state;
  state.transform = *bodyTransform(body);
  state.linearVelocity = toGlm(record->body->getLinearVelocity());
  state.angularVelocity = toGlm(record->body->getAngularVelocity());
  state.mass = record->mass;
  state.awake = isAwake(body);
  state.userData = record->userData;
  return state;
}

std::optional<float> PhysicsWorld::bodyMass(BodyId body) const {
  const BodyRecord* record = impl_->body(body);
  if (record == nullptr) return std::nullopt;
  return record->mass;
}

std::optional<glm::vec3> PhysicsWorld::bodyLocalInertia(BodyId body) const {
  const BodyRecord* record = impl_->body(body);
  if (record == nullptr) return std::nullopt;
  const btVector3 inverse = record->body->getInvInertiaDiagLocal();
  auto invert = [](btScalar x) { return x > 0.0f ? 1.0f / x : 0.0f; };
  return glm::vec3(invert(inverse.x()), invert(inverse.y()), invert(inverse.z()));
}

std::optional<uint64_t> PhysicsWorld::bodyUserData(BodyId body) const {
  const BodyRecord* record = impl_->body(body);
  if (record == nullptr) return std::nullopt;
  return record->userData;
}

bool PhysicsWorld::isAwake(BodyId body) const {
  const BodyRecord* record = impl_->body(body);
  return record != nullptr && record->mass > 0.0f && record->body->isActive();
}

bool PhysicsWorld::isKinematic(BodyId body) const {
  const BodyRecord* record = impl_->body(body);
  return record != nullptr && record->kinematic;
}

bool PhysicsWorld::setBodyTransform(BodyId body, const BodyTransform& transform) {
  BodyRecord* record = impl_->body(body);
  const std::optional<glm::quat> rotation = normalisedRotation(transform.rotation);
  if (record == nullptr || !finite(transform.position) || !rotation) return false;
  record->body->setCenterOfMassTransform(detail::toBt(transform.position, *rotation));
  if (record->mass > 0.0f && !record->frozen) record->body->activate(true);
  impl_->world.updateSingleAabb(record->body.get());
  return true;
}

bool PhysicsWorld::setVelocity(BodyId body, glm::vec3 linear, glm::vec3 angular) {
  BodyRecord* record = impl_->body(body);
  if (record == nullptr || record->mass <= 0.0f || !finite(linear) || !finite(angular)) {
    return false;
  }
  if (record->frozen) impl_->thaw(*record);
  record->body->setLinearVelocity(toBt(linear));
  record->body->setAngularVelocity(toBt(angular));
  record->body->activate(true);
  return true;
}

bool PhysicsWorld::applyImpulse(BodyId body, glm::vec3 impulse, glm::vec3 worldPoint) {
  BodyRecord* record = impl_->body(body);
  if (record == nullptr || record->mass <= 0.0f || !finite(impulse) || !finite(worldPoint)) {
    return false;
  }
  if (record->frozen) impl_->thaw(*record);
  btRigidBody& rigid = *record->body;
  rigid.applyImpulse(toBt(impulse), toBt(worldPoint) - rigid.getCenterOfMassPosition());
  rigid.activate(true);
  return true;
}

bool PhysicsWorld::activate(BodyId body) {
  BodyRecord* record = impl_->body(body);
  if (record == nullptr || record->mass <= 0.0f) return false;
  if (record->frozen) impl_->thaw(*record);
  record->body->activate(true);
  return true;
}

bool PhysicsWorld::setFrozen(BodyId body, bool frozen) {
  BodyRecord* record = impl_->body(body);
  if (record == nullptr || record->mass <= 0.0f || record->kinematic) return false;
  if (record->frozen == frozen) return true;
  if (frozen && impl_->jointed(body)) return false;
  if (frozen) {
    impl_->freeze(*record);
  } else {
    impl_->thaw(*record);
  }
  return true;
}

bool PhysicsWorld::isFrozen(BodyId body) const {
  const BodyRecord* record = impl_->body(body);
  return record != nullptr && record->frozen;
}

uint32_t PhysicsWorld::frozenBodyCount() const {
  uint32_t count = 0;
  impl_->bodies.forEach([&](uint32_t, uint32_t, const BodyRecord& r) { count += r.frozen ? 1u : 0u; });
  return count;
}

namespace {

// Widens [lo, hi] by the shape's support points along `d` (in the shape's frame `toBody` inside
// the body frame); compounds recurse into their children, other shapes use their bounding box.
void projectShape(const btCollisionShape& shape, const btTransform& toBody, const btVector3& d, btScalar& lo,
                  btScalar& hi) {
  if (shape.isConvex()) {
    const auto& convex = static_cast<const btConvexShape&>(shape);
    const btVector3 local = toBody.getBasis().transpose() * d;
    hi = std::max(hi, d.dot(toBody(convex.localGetSupportingVertex(local))));
    lo = std::min(lo, d.dot(toBody(convex.localGetSupportingVertex(-local))));
    return;
  }
  if (shape.isCompound()) {
    const auto& compound = static_cast<const btCompoundShape&>(shape);
    for (int i = 0; i < compound.getNumChildShapes(); ++i)
      projectShape(*compound.getChildShape(i), toBody * compound.getChildTransform(i), d, lo, hi);
    return;
  }
  btVector3 min, max;
  shape.getAabb(toBody, min, max);
  const btVector3 centre = (min + max) * 0.5f, half = (max - min) * 0.5f;
  const btScalar reach = std::fabs(d.x()) * half.x() + std::fabs(d.y()) * half.y() + std::fabs(d.z()) * half.z();
  lo = std::min(lo, d.dot(centre) - reach);
  hi = std::max(hi, d.dot(centre) + reach);
}

}  // namespace

std::optional<std::pair<glm::vec3, glm::vec3>> PhysicsWorld::bodyBounds(BodyId body) const {
  const BodyRecord* record = impl_->body(body);
  if (record == nullptr || record->body->getBroadphaseHandle() == nullptr) return std::nullopt;
  const btBroadphaseProxy& proxy = *record->body->getBroadphaseHandle();
  return std::pair(toGlm(proxy.m_aabbMin), toGlm(proxy.m_aabbMax));
}

std::vector<BodyId> PhysicsWorld::bodiesInBox(glm::vec3 lo, glm::vec3 hi) const {
  struct Collect : btBroadphaseAabbCallback {
    const Impl* w = nullptr;
    std::vector<BodyId> found;
    bool process(const btBroadphaseProxy* proxy) override {
      const auto* object = static_cast<const btCollisionObject*>(proxy->m_clientObject);
      if (object != nullptr && object->getUserIndex2() == kKindBody)
        found.push_back(w->bodyIdAt(uint32_t(object->getUserIndex())));
      return true;
    }
  } collect;
  collect.w = impl_.get();
  if (!finite(lo) || !finite(hi)) return {};
  impl_->broadphase.aabbTest(toBt(lo), toBt(hi), collect);
  std::sort(collect.found.begin(), collect.found.end(),
            [](BodyId a, BodyId b) { return a.index < b.index; });
  return collect.found;
}

std::optional<glm::vec2> PhysicsWorld::extentAlong(BodyId body, glm::vec3 direction) const {
  const BodyRecord* record = impl_->body(body);
  if (record == nullptr || !finite(direction) || glm::dot(direction, direction) <= 0.0f) return std::nullopt;
  const btRigidBody& b = *record->body;
  const btTransform& t = b.getWorldTransform();
  // The interval in the body frame, shifted by the body's position along the direction.
  const btVector3 d = t.getBasis().transpose() * toBt(direction);
  btScalar lo = BT_LARGE_FLOAT, hi = -BT_LARGE_FLOAT;
  btTransform identity;
  identity.setIdentity();
  projectShape(*b.getCollisionShape(), identity, d, lo, hi);
  const btScalar at = toBt(direction).dot(t.getOrigin());
  return glm::vec2(lo + at, hi + at);
}

// ---- joints ----

Result<JointId> PhysicsWorld::createJoint(const JointDef& def) {
  using R = Result<JointId>;
  Impl& w = *impl_;
  BodyRecord* a = w.body(def.bodyA);
  BodyRecord* b = w.body(def.bodyB);
  if (a == nullptr || b == nullptr) {
    return R::failure(PhysicsStatus::StaleHandle, "createJoint: a body handle is null or destroyed");
  }
  if (def.bodyA == def.bodyB) {
    return R::failure(PhysicsStatus::InvalidArgument, "createJoint: bodyA and bodyB are the same body");
  }
  if (a->mass <= 0.0f && b->mass <= 0.0f) {
    return R::failure(PhysicsStatus::InvalidArgument,
                      "createJoint: at least one body must be dynamic (both are static or kinematic)");
  }
  const std::optional<glm::quat> rotationA = normalisedRotation(def.frameA.rotation);
  const std::optional<glm::quat> rotationB = normalisedRotation(def.frameB.rotation);
  if (!finite(def.frameA.position) || !finite(def.frameB.position) || !rotationA || !rotationB) {
    return R::failure(PhysicsStatus::InvalidArgument,
                      "createJoint: frame positions must be finite and rotations finite, non-zero "
                      "quaternions");
  }
  const float pi = 3.14159265f;
  auto inRange = [](float x, float lo, float hi) { return std::isfinite(x) && x >= lo && x <= hi; };
  const btTransform frameA = detail::toBt(def.frameA.position, *rotationA);
  const btTransform frameB = detail::toBt(def.frameB.position, *rotationB);
  std::unique_ptr<btTypedConstraint> constraint;
  if (def.type == JointType::ConeTwist) {
    if (!inRange(def.swingSpan1, 0.0f, pi) || !inRange(def.swingSpan2, 0.0f, pi) ||
        !inRange(def.twistSpan, 0.0f, pi)) {
      return R::failure(PhysicsStatus::InvalidArgument,
                        "createJoint: cone-twist spans must be finite and in [0, pi]");
    }
    auto cone = std::make_unique<btConeTwistConstraint>(*a->body, *b->body, frameA, frameB);
    cone->setLimit(def.swingSpan1, def.swingSpan2, def.twistSpan);
    constraint = std::move(cone);
  } else {
    if (!inRange(def.lowerLimit, -pi, pi) || !inRange(def.upperLimit, -pi, pi) ||
        def.lowerLimit > def.upperLimit) {
      return R::failure(PhysicsStatus::InvalidArgument,
                        "createJoint: hinge limits must be finite, in [-pi, pi], lower <= upper");
    }
    auto hinge = std::make_unique<btHingeConstraint>(*a->body, *b->body, frameA, frameB);
    // Bullet measures the hinge angle the other way round (left-handed about z): mirror the range.
    hinge->setLimit(-def.upperLimit, -def.lowerLimit);
    constraint = std::move(hinge);
  }
  // A joint needs both bodies simulated.
  if (a->frozen) w.thaw(*a);
  if (b->frozen) w.thaw(*b);
  btTypedConstraint* raw = constraint.get();
  // Chains of joints (a ragdoll) drift apart with the world's few iterations: joints get more.
  raw->setOverrideNumSolverIterations(kJointSolverIterations);
  JointRecord record;
  record.constraint = std::move(constraint);
  record.type = def.type;
  record.bodyA = def.bodyA;
  record.bodyB = def.bodyB;
  record.frameA = frameA;
  record.frameB = frameB;
  const auto key = w.joints.insert(std::move(record));
  w.world.addConstraint(raw, !def.collideConnected);
  if (a->mass > 0.0f) a->body->activate(true);
  if (b->mass > 0.0f) b->body->activate(true);
  return R::success(JointId{key.index, key.generation});
}

bool PhysicsWorld::destroyJoint(JointId joint) {
  if (impl_->joint(joint) == nullptr) return false;
  impl_->removeJoint(joint.index);
  return true;
}

bool PhysicsWorld::isValid(JointId joint) const { return impl_->joint(joint) != nullptr; }

uint32_t PhysicsWorld::jointCount() const { return impl_->joints.size(); }

uint32_t PhysicsWorld::triggerCount() const { return impl_->triggers.size(); }

std::optional<JointState> PhysicsWorld::jointState(JointId joint) const {
  const JointRecord* record = impl_->joint(joint);
  if (record == nullptr) return std::nullopt;
  const BodyRecord* a = impl_->body(record->bodyA);
  const BodyRecord* b = impl_->body(record->bodyB);
  if (a == nullptr || b == nullptr) return std::nullopt;
  const btTransform fa = a->body->getWorldTransform() * record->frameA;
  const btTransform fb = b->body->getWorldTransform() * record->frameB;
  JointState state;
  state.pivotA = toGlm(fa.getOrigin());
  state.pivotB = toGlm(fb.getOrigin());
  state.separation = glm::length(state.pivotA - state.pivotB);
  if (record->type == JointType::Hinge) {
    // Right-handed rotation of B's frame about the common z axis, seen from A's frame.
    const glm::quat relative = glm::inverse(toGlm(fa.getRotation())) * toGlm(fb.getRotation());
    glm::quat twist(relative.w, 0.0f, 0.0f, relative.z);
    const float length = glm::length(twist);
    if (length > 1e-6f) {
      twist /= length;
      if (twist.w < 0.0f) twist = -twist;
      state.hingeAngle = 2.0f * std::atan2(twist.z, twist.w);
    }
  } else {
    // Swing: the angle between the two twist (x) axes; twist: the rotation about B's x axis left
    // after removing the swing (swing-twist decomposition of the relative rotation).
    const glm::quat qa = toGlm(fa.getRotation());
    const glm::quat qb = toGlm(fb.getRotation());
    const glm::vec3 xa = qa * glm::vec3(1, 0, 0);
    const glm::vec3 xb = qb * glm::vec3(1, 0, 0);
    state.swingAngle = std::acos(std::clamp(glm::dot(xa, xb), -1.0f, 1.0f));
    const glm::quat relative = glm::inverse(qa) * qb;  // B's frame seen from A's frame
    glm::quat twist(relative.w, relative.x, 0.0f, 0.0f);
    const float length = glm::length(twist);
    if (length > 1e-6f) {
      twist /= length;
      if (twist.w < 0.0f) twist = -twist;
      state.twistAngle = 2.0f * std::atan2(twist.x, twist.w);
    }
  }
  return state;
}

// ---- triggers ----

Result<TriggerId> PhysicsWorld::createTrigger(const TriggerDef& def) {
  using R = Result<TriggerId>;
  Impl& w = *impl_;
  ShapeRecord* shape = w.liveShape(def.shape);
  if (shape == nullptr) {
    return R::failure(PhysicsStatus::StaleHandle,
                      "createTrigger: the shape handle is null or destroyed");
  }
  if (shape->built.type == ShapeType::ConcaveMesh || shape->built.type == ShapeType::StaticMesh) {
    return R::failure(PhysicsStatus::UnsupportedCombination,
                      "createTrigger: trigger shapes must be convex or compound, not meshes");
  }
  const std::optional<glm::quat> rotation = normalisedRotation(def.rotation);
  if (!finite(def.position) || !rotation) {
    return R::failure(PhysicsStatus::InvalidArgument,
                      "createTrigger: position must be finite and rotation a finite, non-zero "
                      "quaternion");
  }
  auto ghost = std::make_unique<btPairCachingGhostObject>();
  ghost->setCollisionShape(shape->built.shape.get());
  ghost->setWorldTransform(detail::toBt(def.position, *rotation));
  ghost->setCollisionFlags(ghost->getCollisionFlags() |
                           btCollisionObject::CF_NO_CONTACT_RESPONSE);
  // Triggers never sleep, so they also see sleeping bodies.
  ghost->setActivationState(DISABLE_DEACTIVATION);
  btPairCachingGhostObject* raw = ghost.get();
  TriggerRecord record;
  record.ghost = std::move(ghost);
  record.shapeIndex = def.shape.index;
  record.userData = def.userData;
  record.persistent = def.persistent;
  const auto key = w.triggers.insert(std::move(record));
  raw->setUserIndex(int(key.index));
  raw->setUserIndex2(kKindTrigger);
  int mask = btBroadphaseProxy::AllFilter & ~btBroadphaseProxy::SensorTrigger;
  if (!def.detectStatic) mask &= ~btBroadphaseProxy::StaticFilter;
  w.world.addCollisionObject(raw, btBroadphaseProxy::SensorTrigger, mask);
  ++shape->users;
  return R::success(TriggerId{key.index, key.generation});
}

bool PhysicsWorld::destroyTrigger(TriggerId trigger) {
  Impl& w = *impl_;
  TriggerRecord* record = w.trigger(trigger);
  if (record == nullptr) return false;
  if (!record->spent) w.world.removeCollisionObject(record->ghost.get());
  const uint32_t shapeIndex = record->shapeIndex;
  w.triggers.erase(trigger.index);
  w.releaseShapeUser(shapeIndex);
  w.forgetTouches([&](const auto& touch) { return touch.first == trigger; });
  return true;
}

bool PhysicsWorld::isValid(TriggerId trigger) const { return impl_->trigger(trigger) != nullptr; }

bool PhysicsWorld::setTriggerTransform(TriggerId trigger, const BodyTransform& transform) {
  TriggerRecord* record = impl_->trigger(trigger);
  const std::optional<glm::quat> rotation = normalisedRotation(transform.rotation);
  if (record == nullptr || !finite(transform.position) || !rotation) return false;
  record->ghost->setWorldTransform(detail::toBt(transform.position, *rotation));
  if (!record->spent) impl_->world.updateSingleAabb(record->ghost.get());
  return true;
}

std::optional<BodyTransform> PhysicsWorld::triggerTransform(TriggerId trigger) const {
  const TriggerRecord* record = impl_->trigger(trigger);
  if (record == nullptr) return std::nullopt;
  const btTransform& t = record->ghost->getWorldTransform();
  return BodyTransform{toGlm(t.getOrigin()), toGlm(t.getRotation())};
}

std::optional<uint64_t> PhysicsWorld::triggerUserData(TriggerId trigger) const {
  const TriggerRecord* record = impl_->trigger(trigger);
  if (record == nullptr) return std::nullopt;
  return record->userData;
}

bool PhysicsWorld::isTriggerSpent(TriggerId trigger) const {
  const TriggerRecord* record = impl_->trigger(trigger);
  return record != nullptr && record->spent;
}

// ---- events and queries ----

std::span<const TriggerEvent> PhysicsWorld::triggerEvents() const { return impl_->triggerEvents; }
std::span<const ContactEvent> PhysicsWorld::contactEvents() const { return impl_->contactEvents; }

std::optional<RayHit> PhysicsWorld::raycast(glm::vec3 from, glm::vec3 to) const {
  if (!finite(from) || !finite(to) || from == to) return std::nullopt;
  const btVector3 btFrom = toBt(from), btTo = toBt(to);
  btCollisionWorld::ClosestRayResultCallback callback(btFrom, btTo);
  callback.m_collisionFilterGroup = btBroadphaseProxy::DefaultFilter;
  callback.m_collisionFilterMask = btBroadphaseProxy::AllFilter & ~btBroadphaseProxy::SensorTrigger;
  impl_->world.rayTest(btFrom, btTo, callback);
  if (!callback.hasHit() || callback.m_collisionObject == nullptr ||
      callback.m_collisionObject->getUserIndex2() != kKindBody) {
    return std::nullopt;
  }
  RayHit hit;
  hit.body = impl_->bodyIdAt(uint32_t(callback.m_collisionObject->getUserIndex()));
  hit.point = toGlm(callback.m_hitPointWorld);
  hit.fraction = callback.m_closestHitFraction;
  glm::vec3 normal = toGlm(callback.m_hitNormalWorld);
  const float length = glm::length(normal);
  normal = length > 0.0f ? normal / length : -glm::normalize(to - from);
  if (glm::dot(normal, to - from) > 0.0f) normal = -normal;
  hit.normal = normal;
  return hit;
}

uint64_t PhysicsWorld::stateHash() const {
  uint64_t hash = 0xcbf29ce484222325ull;
  impl_->bodies.forEach([&](uint32_t index, uint32_t generation, const BodyRecord& r) {
    hashBytes(hash, &index, sizeof(index));
    hashBytes(hash, &generation, sizeof(generation));
    const btTransform& t = r.body->getWorldTransform();
    hashVector(hash, t.getOrigin());
    for (int row = 0; row < 3; ++row) hashVector(hash, t.getBasis()[row]);
    hashVector(hash, r.body->getLinearVelocity());
    hashVector(hash, r.body->getAngularVelocity());
  });
  return hash;
}

}  // namespace cleave::physics
