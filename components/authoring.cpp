// SPDX-License-Identifier: MIT
// Authoring helpers (authoring.h): splitter entities, and bodies made for authored objects from
// their meshes' exact mass properties.
#include "cleave/components/authoring.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "cleave/components/split_compute.h"
#include "cleave/components/split_hierarchy.h"
#include "cleave/components/split_system.h"
#include "cleave/ecs/hierarchy.h"
#include "cleave/geometry/mass_properties.h"

namespace cleave::components {

namespace {

// Rigid part of an affine matrix as a Transform (scale from the column lengths; shear is dropped).
ecs::Transform toTransform(const glm::dmat4& m) {
  ecs::Transform t;
  t.position = glm::vec3(m[3]);
  glm::dvec3 scale(glm::length(glm::dvec3(m[0])), glm::length(glm::dvec3(m[1])), glm::length(glm::dvec3(m[2])));
  glm::dmat3 r(glm::dvec3(m[0]) / scale.x, glm::dvec3(m[1]) / scale.y, glm::dvec3(m[2]) / scale.z);
  if (glm::determinant(r) < 0.0) {
    scale.x = -scale.x;
    r[0] = -r[0];
  }
  t.rotation = glm::normalize(glm::quat(glm::quat_cast(r)));
  t.scale = glm::vec3(scale);
  return t;
}

}  // namespace

void placeOnBody(SplitWorld& w, ecs::Entity e, const physics::BodyDef& def, physics::BodyId body,
                 physics::ShapeId shape, double mass, const geometry::MassProperties& props, double density) {
  if (auto* t = w.world.tryGet<ecs::Transform>(e)) {
    t->position = def.position;
    t->rotation = def.rotation;
    t->scale = glm::vec3(1.f);
  }
  w.world.add<RigidBody>(e, RigidBody{body, shape});
  MassInfo info;
  info.mass = mass;
  info.volume = props.volume;
  info.density = density;
  info.closed = props.closed;
  w.world.add<MassInfo>(e, info);
}

ecs::Entity createSplitter(SplitWorld& w, const std::string& name, const physics::ShapeDef& shape,
                           const glm::vec3& position, const glm::quat& rotation, Splitter splitter) {
  auto built = w.physics.createShape(shape);
  if (!built.ok()) return ecs::kNullEntity;
  const ecs::Entity e = w.world.create();
  ecs::Transform t;
  t.position = position;
  t.rotation = rotation;
  w.world.add<ecs::Name>(e, ecs::Name{name});
  w.world.add<ecs::Transform>(e, t);
  w.world.add<ecs::WorldTransform>(e, ecs::WorldTransform{ecs::localMatrix(t)});
  physics::TriggerDef def;
  def.shape = built.value();
  def.position = position;
  def.rotation = rotation;
  def.persistent = splitter.lifetime == SplitterLifetime::Persistent;
  def.userData = toUserData(e);
  auto trigger = w.physics.createTrigger(def);
  w.physics.destroyShape(built.value());  // the trigger keeps its own reference
  splitter.trigger = trigger.ok() ? trigger.value() : physics::TriggerId{};
  w.world.add<Splitter>(e, splitter);
  return e;
}

physics::Result<physics::ShapeId> createPlannedShape(physics::PhysicsWorld& physics,
                                                     const std::vector<HullSpec>& hulls,
                                                     const std::vector<glm::vec3>& concavePositions,
                                                     const std::vector<uint32_t>& concaveIndices) {
  if (!concavePositions.empty()) {
    auto r = physics.createShape(physics::ShapeDef::concaveMesh(concavePositions, concaveIndices));
    if (r.ok()) return r;
  }
  if (hulls.empty()) {
    return physics::Result<physics::ShapeId>::failure(physics::PhysicsStatus::DegenerateShape,
                                                      "no collider part holds any volume");
  }
  physics::ShapeDef def;
  if (hulls.size() == 1) {
    def = physics::ShapeDef::preparedHull(hulls[0].points, hulls[0].margin);
  } else {
    std::vector<physics::ConvexPart> parts(hulls.size());
    for (size_t i = 0; i < hulls.size(); ++i) {
      parts[i].points = hulls[i].points;
      parts[i].margin = hulls[i].margin;
    }
    def = physics::ShapeDef::compound(std::move(parts));
  }
  def.maxHullVertices = 48;  // parts are small: a coarse hull each keeps contacts cheap
  return physics.createShape(def);
}

base::Status makeDynamicBody(SplitWorld& w, ecs::Entity e, double density, ColliderMode collider,
                             SplitSystem* splits) {
  auto refuse = [](std::string reason) {
    return base::Status::failure(base::StatusCode::InvalidArgument, std::move(reason));
  };
  auto* t = w.world.tryGet<ecs::Transform>(e);
  std::vector<HierarchyPartData> parts;
  const bool hierarchy = t && gatherParts(w.world, e, parts);
  auto* mr = w.world.tryGet<MeshRenderer>(e);
  if ((!hierarchy && (!mr || !mr->source)) || !t) return refuse("entity has no mesh or transform");
  // A parent with meshes below it: one body for the whole subtree, from the merged meshes.
  MergedParts merged;
  if (hierarchy) merged = mergeHierarchyParts(parts);
  const geometry::MeshData& source = hierarchy ? merged.mesh : *mr->source;
  const glm::dmat4 oldLocal(ecs::localMatrix(*t));
  const glm::dmat4 model = hierarchy ? oldLocal : oldLocal * glm::dmat4(mr->meshOffset);
  const geometry::MassProperties props = geometry::computeMassProperties(source, model);
  if (!(props.volume > 0.0)) return refuse("mesh encloses no volume");
  const double mass = density * props.volume;
  const BodyFrame frame = bodyFrameFor(props, mass, model);
  // The collider parts (mesh space): the cache's for a shared authored mesh, else planned here.
  geometry::SharedColliderParts carried;
  if (splits && !hierarchy && (collider == ColliderMode::Auto || collider == ColliderMode::Compound)) carried = splits->colliderParts(mr->source, collider);
  auto splitter = geometry::makeConcaveSplitter();
  const ColliderPlan plan = planCollider(source, frame.meshOffset, collider, false, carried, *splitter);
  const auto planned = createPlannedShape(w.physics, plan.hulls, plan.concavePositions, plan.concaveIndices);
  if (!planned.ok()) return refuse("no collider: " + planned.message());
  const physics::ShapeId shape = planned.value();
  physics::BodyDef def;
  def.shape = shape;
  def.mass = float(mass);
  def.position = glm::vec3(frame.position);
  def.rotation = glm::quat(frame.rotation);
  def.localInertia = glm::vec3(frame.moments);
  def.userData = toUserData(e);
  auto body = w.physics.createBody(def);
  if (!body.ok()) {
    w.physics.destroyShape(shape);
    return refuse(body.message());
  }
  if (hierarchy) {
    // The entity moves to the body frame; its own mesh and its children keep their world placement.
    if (mr) mr->meshOffset = glm::mat4(frame.meshOffset * glm::dmat4(mr->meshOffset));
    if (const auto* children = w.world.tryGet<ecs::Children>(e)) {
      for (ecs::Entity child : children->entities) {
        auto* ct = w.world.tryGet<ecs::Transform>(child);
        if (ct && ecs::parentOf(w.world, child) == e)
          *ct = toTransform(frame.meshOffset * glm::dmat4(ecs::localMatrix(*ct)));
      }
    }
  } else {
    mr->meshOffset = glm::mat4(frame.meshOffset);
    if (collider == ColliderMode::Auto || collider == ColliderMode::Compound)
      w.world.add<ColliderParts>(e, ColliderParts{plan.parts});
  }
  placeOnBody(w, e, def, body.value(), shape, mass, props, density);
  return {};
}

}  // namespace cleave::components
