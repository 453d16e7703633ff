// SPDX-License-Identifier: MIT
#include "cleave/components/skinned.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "cleave/components/scene_components.h"
#include "cleave/ecs/hierarchy.h"
#include "cleave/ecs/world.h"
#include "cleave/geometry/mass_properties.h"

namespace cleave::components {

namespace {

// Bones need this many dominated vertices for a capsule; others ride on a neighbour's body.
constexpr size_t kMinBoneVertices = 24;
constexpr float kMinBoneRadius = 0.015f;  // metres

glm::dmat4 blendFor(const geometry::MeshData& mesh, size_t i, std::span<const glm::mat4> joints) {
  glm::dmat4 blend(0.0);
  double total = 0.0;
  for (int k = 0; k < 4; ++k) {
    const double w = mesh.weights[i][k];
    if (w == 0.0) continue;
    blend += w * glm::dmat4(joints[mesh.joints[i][k]]);
    total += w;
  }
  return total > 0.0 ? blend / total : glm::dmat4(1.0);
}

// The rotation taking +Y (a capsule's axis) to the unit vector `to`.
glm::dquat rotationFromUp(const glm::dvec3& to) {
  const glm::dvec3 up(0.0, 1.0, 0.0);
  const double c = glm::dot(up, to);
  if (c < -0.999999) return glm::angleAxis(3.14159265358979323846, glm::dvec3(1.0, 0.0, 0.0));
  const glm::dvec3 axis = glm::cross(up, to);
  const double s = std::sqrt((1.0 + c) * 2.0);
  return glm::normalize(glm::dquat(s * 0.5, axis.x / s, axis.y / s, axis.z / s));
}

// Any unit vector perpendicular to the unit vector `a`, chosen deterministically.
glm::dvec3 perpendicular(const glm::dvec3& a) {
  const glm::dvec3 helper = std::abs(a.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  return glm::normalize(glm::cross(a, helper));
}

glm::dmat4 rigid(const physics::BodyTransform& t) {
  return glm::translate(glm::dmat4(1.0), glm::dvec3(t.position)) * glm::mat4_cast(glm::dquat(t.rotation));
}

bool hasName(const anim::Skeleton& skeleton, int32_t joint, const char* part) {
  return joint >= 0 && skeleton.joints[size_t(joint)].name.find(part) != std::string::npos;
}

}  // namespace

const anim::AnimationClip* SkinnedAsset::clip(const std::string& name) const {
  for (const anim::AnimationClip& c : clips)
    if (c.name == name) return &c;
  return nullptr;
}

SkinnedMesh makeSkinnedMesh(std::shared_ptr<const SkinnedAsset> asset, const std::string& clip,
                            float startTime) {
  SkinnedMesh s;
  s.asset = std::move(asset);
  s.animator = anim::Animator(&s.asset->skeleton);
  s.animator.play(s.asset->clip(clip), 0.f, true, startTime);
  s.animator.evaluateJointMatrices(s.jointMatrices);
  return s;
}

void bakeSkin(const geometry::MeshData& mesh, std::span<const glm::mat4> jointMatrices,
              geometry::MeshData& out) {
  out = mesh;
  if (mesh.joints.empty() || mesh.weights.size() != mesh.joints.size()) return;
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::dmat4 m = blendFor(mesh, i, jointMatrices);
    out.positions[i] = glm::vec3(m * glm::dvec4(glm::dvec3(mesh.positions[i]), 1.0));
    const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(m)));
    if (i < mesh.normals.size()) {
      const glm::dvec3 n = normalMatrix * glm::dvec3(mesh.normals[i]);
      const double length = glm::length(n);
      if (length > 0.0) out.normals[i] = glm::vec3(n / length);
    }
    if (i < mesh.tangents.size()) {
      const glm::dvec3 t = glm::dmat3(m) * glm::dvec3(glm::vec3(mesh.tangents[i]));
      const double length = glm::length(t);
      if (length > 0.0) out.tangents[i] = glm::vec4(glm::vec3(t / length), mesh.tangents[i].w);
    }
  }
  out.joints.clear();
  out.weights.clear();
}

void posedJointGlobals(const anim::Skeleton& skeleton, std::span<const glm::mat4> jointMatrices,
                       const glm::dmat4& model, std::vector<glm::dmat4>& out) {
  out.resize(skeleton.size());
  for (size_t j = 0; j < skeleton.size(); ++j) {
    const glm::dmat4 joint = j < jointMatrices.size() ? glm::dmat4(jointMatrices[j]) : glm::dmat4(1.0);
    out[j] = model * joint * glm::inverse(glm::dmat4(skeleton.joints[j].inverseBind));
  }
}

base::Status makeSkinnedBody(SplitWorld& w, ecs::Entity e, double density, bool kinematic) {
  auto refuse = [](std::string reason) {
    return base::Status::failure(base::StatusCode::InvalidArgument, std::move(reason));
  };
  auto* mr = w.world.tryGet<MeshRenderer>(e);
  auto* skin = w.world.tryGet<SkinnedMesh>(e);
  auto* t = w.world.tryGet<ecs::Transform>(e);
  if (!mr || !mr->source || !skin || !t) {
    return refuse("entity has no skinned mesh or transform");
  }
  geometry::MeshData posed;
  bakeSkin(*mr->source, skin->jointMatrices, posed);
  const glm::dmat4 model = glm::dmat4(ecs::localMatrix(*t)) * glm::dmat4(mr->meshOffset);
  const geometry::MassProperties props = geometry::computeMassProperties(posed, model);
  if (!(props.volume > 0.0)) {
    return refuse("posed mesh encloses no volume");
  }
  const double mass = density * props.volume;
  BodyFrame frame = bodyFrameFor(props, mass, model);
  if (kinematic) {  // the entity's own rotation, and no inertia: the game moves the body
    frame.rotation = glm::dquat(t->rotation);
    frame.moments = glm::dvec3(0.0);
    const glm::dmat4 bodyToWorld =
        glm::translate(glm::dmat4(1.0), frame.position) * glm::mat4_cast(frame.rotation);
    frame.meshOffset = glm::inverse(bodyToWorld) * model;
  }
  physics::ShapeDef hull = physics::ShapeDef::convexHull(transformedPoints(posed, frame.meshOffset));
  hull.maxHullVertices = 48;
  const auto shape = w.physics.createShape(hull);
  if (!shape.ok()) {
    return refuse("no collider: " + shape.message());
  }
  physics::BodyDef def;
  def.shape = shape.value();
  def.kinematic = kinematic;
  def.mass = kinematic ? 0.f : float(mass);
  if (!kinematic) def.localInertia = glm::vec3(frame.moments);
  def.position = glm::vec3(frame.position);
  def.rotation = glm::quat(frame.rotation);
  def.userData = toUserData(e);
  const auto body = w.physics.createBody(def);
  if (!body.ok()) {
    w.physics.destroyShape(shape.value());
    return refuse(body.message());
  }
  mr->meshOffset = glm::mat4(frame.meshOffset);
  placeOnBody(w, e, def, body.value(), shape.value(), mass, props, density);
  return {};
}

namespace {

struct BoneFit {
  uint16_t joint;
  glm::dvec3 centre;
  glm::dquat rotation;
  double radius, halfHeight, influence;
};

// Capsules for the kept joints that dominate enough vertices, each along its bone. `influence`
// gets the sum of weights per joint.
std::vector<BoneFit> fitBones(const geometry::MeshData& bindPiece, std::span<const glm::vec3> posed,
                              std::span<const uint16_t> keptJoints, const anim::Skeleton& skeleton,
                              std::span<const glm::dmat4> globals) {
  const size_t jointCount = skeleton.size();
  std::vector<double> influence(jointCount, 0.0);
  std::vector<std::vector<uint32_t>> dominated(jointCount);
  for (size_t i = 0; i < bindPiece.positions.size(); ++i) {
    int best = -1;
    float bestWeight = 0.f;
    for (int k = 0; k < 4; ++k) {
      const uint16_t j = bindPiece.joints[i][k];
      const float wgt = bindPiece.weights[i][k];
      if (wgt <= 0.f || j >= jointCount) continue;
      influence[j] += wgt;
      if (wgt > bestWeight) {
        bestWeight = wgt;
        best = j;
      }
    }
    if (best >= 0) dominated[size_t(best)].push_back(uint32_t(i));
  }
  auto origin = [&](size_t j) { return glm::dvec3(globals[j][3]); };
  std::vector<BoneFit> fits;
  for (uint16_t j : keptJoints) {
    if (j >= jointCount || dominated[j].size() < kMinBoneVertices) continue;
    const std::vector<uint32_t>& verts = dominated[j];
    glm::dvec3 centroid(0.0);
    for (uint32_t i : verts) centroid += glm::dvec3(posed[i]);
    centroid /= double(verts.size());
    // Axis: towards the joint's children (the bone), else along the parent bone, else +Y.
    glm::dvec3 childMean(0.0);
    int children = 0;
    for (size_t c = 0; c < jointCount; ++c) {
      if (skeleton.joints[c].parent == int32_t(j)) {
        childMean += origin(c);
        ++children;
      }
    }
    glm::dvec3 axis(0.0);
    if (children > 0) axis = childMean / double(children) - origin(j);
    if (glm::length(axis) < 1e-4 && skeleton.joints[j].parent >= 0)
      axis = origin(j) - origin(size_t(skeleton.joints[j].parent));
    if (glm::length(axis) < 1e-4) axis = glm::dvec3(globals[j] * glm::dvec4(0, 1, 0, 0));
    if (glm::length(axis) < 1e-9) axis = glm::dvec3(0, 1, 0);
    axis = glm::normalize(axis);
    double tMin = std::numeric_limits<double>::infinity(), tMax = -tMin, radial = 0.0;
    for (uint32_t i : verts) {
      const glm::dvec3 d = glm::dvec3(posed[i]) - centroid;
      const double t = glm::dot(d, axis);
      tMin = std::min(tMin, t);
      tMax = std::max(tMax, t);
      radial += glm::length(d - axis * t);
    }
    radial /= double(verts.size());
    BoneFit fit;
    fit.joint = j;
    // Radius a little inside the mean surface distance, so capsules stay inside the flesh.
    fit.radius = std::max(double(kMinBoneRadius), 0.85 * radial);
    fit.radius = std::min(fit.radius, std::max(double(kMinBoneRadius), 0.5 * (tMax - tMin)));
    fit.halfHeight = std::max(0.0, 0.5 * (tMax - tMin) - fit.radius);
    fit.centre = centroid + axis * (0.5 * (tMin + tMax));
    fit.rotation = rotationFromUp(axis);
    fit.influence = influence[j];
    fits.push_back(fit);
  }
  return fits;
}

// The nearest ancestor joint of `j` that has a bone, or -1.
int32_t boneAncestor(const anim::Skeleton& skeleton, const std::vector<int32_t>& boneOfJoint, size_t j) {
  int32_t p = skeleton.joints[j].parent;
  for (size_t guard = 0; p >= 0 && guard < skeleton.size(); ++guard) {
    if (boneOfJoint[size_t(p)] >= 0) return boneOfJoint[size_t(p)];
    p = skeleton.joints[size_t(p)].parent;
  }
  return -1;
}

// The joint of bone `b` to its parent bone: pivot at the bone's joint origin; hinges at elbows and
// knees, cone-twist elsewhere. Frames are in the two bodies' frames at their spec poses.
RagdollJointSpec jointFor(const RagdollSpec& spec, size_t b, size_t parentBone, const anim::Skeleton& skeleton,
                          std::span<const glm::dmat4> globals) {
  const uint16_t j = spec.bones[b].joint;
  const glm::dvec3 pivot(globals[j][3]);
  const RagdollBoneSpec& child = spec.bones[b];
  glm::dvec3 along = child.centre - pivot;
  along = glm::length(along) > 1e-6 ? glm::normalize(along) : glm::dvec3(child.rotation * glm::dvec3(0, 1, 0));
  RagdollJointSpec out;
  out.parentBone = uint16_t(parentBone);
  out.childBone = uint16_t(b);
  out.skeletonJoint = j;
  physics::JointDef& def = out.def;
  glm::dmat3 frame;
  if (hasName(skeleton, j, "forearm") || hasName(skeleton, j, "shin")) {
    // Elbows and knees turn about the joint's own x axis (the character's left-right axis).
    glm::dvec3 z = glm::dvec3(globals[j] * glm::dvec4(1, 0, 0, 0));
    z = z - along * glm::dot(z, along);
    z = glm::length(z) > 1e-6 ? glm::normalize(z) : perpendicular(along);
    const glm::dvec3 x = glm::normalize(glm::cross(glm::cross(z, along), z));
    frame = glm::dmat3(x, glm::cross(z, x), z);
    def.type = physics::JointType::Hinge;
    def.lowerLimit = -1.3f;
    def.upperLimit = 1.3f;
  } else {
    const glm::dvec3 y = perpendicular(along);
    frame = glm::dmat3(along, y, glm::cross(along, y));
    def.type = physics::JointType::ConeTwist;
    const bool spine = hasName(skeleton, j, "spine") || hasName(skeleton, j, "chest") ||
                       hasName(skeleton, j, "neck") || hasName(skeleton, j, "head");
    def.swingSpan1 = def.swingSpan2 = spine ? 0.45f : 0.8f;
    def.twistSpan = spine ? 0.3f : 0.5f;
  }
  const glm::dquat frameRotation = glm::normalize(glm::quat_cast(frame));
  auto local = [&](const RagdollBoneSpec& bone) {
    const glm::dquat inv = glm::inverse(bone.rotation);
    return physics::BodyTransform{glm::vec3(inv * (pivot - bone.centre)), glm::quat(inv * frameRotation)};
  };
  def.frameA = local(spec.bones[parentBone]);
  def.frameB = local(child);
  return out;
}

glm::dmat4 boneMatrix(const RagdollBoneSpec& bone) {
  return glm::translate(glm::dmat4(1.0), bone.centre) * glm::mat4_cast(bone.rotation);
}

}  // namespace

base::Status planRagdoll(const geometry::MeshData& bindPiece, std::span<const glm::vec3> posed,
                         std::span<const uint16_t> keptJoints, const anim::Skeleton& skeleton,
                         std::span<const glm::dmat4> globals, double mass, RagdollSpec& out) {
  out = RagdollSpec{};
  const size_t jointCount = skeleton.size();
  if (bindPiece.joints.empty() || posed.size() != bindPiece.positions.size() || globals.size() != jointCount) {
    return base::Status::failure(base::StatusCode::InvalidArgument,
                                 "ragdoll: the piece has no skin or the pose does not match it");
  }
  const std::vector<BoneFit> fits = fitBones(bindPiece, posed, keptJoints, skeleton, globals);
  double totalInfluence = 0.0;
  for (const BoneFit& f : fits) totalInfluence += f.influence;
  std::vector<int32_t> boneOfJoint(jointCount, -1);
  for (const BoneFit& f : fits) {
    if (!(f.radius > 0.0) || !std::isfinite(f.halfHeight) || !std::isfinite(f.centre.x)) continue;
    RagdollBoneSpec bone;
    bone.joint = f.joint;
    // The pose the body will have (the bridge stores floats): joint frames and carried transforms
    // are worked out against it.
    bone.centre = glm::dvec3(glm::vec3(f.centre));
    bone.rotation = glm::dquat(glm::normalize(glm::quat(f.rotation)));
    bone.radius = float(f.radius);
    bone.halfHeight = float(f.halfHeight);
    bone.mass = float(std::max(mass * f.influence / totalInfluence, 1e-6));
    boneOfJoint[f.joint] = int32_t(out.bones.size());
    out.bones.push_back(bone);
  }
  if (out.bones.empty()) {
    return base::Status::failure(base::StatusCode::InvalidArgument,
                                 "ragdoll: no bone of the piece has enough vertices for a capsule");
  }
  out.anchor = 0;
  for (size_t b = 1; b < out.bones.size(); ++b)
    if (out.bones[b].mass > out.bones[out.anchor].mass) out.anchor = b;
  for (size_t b = 0; b < out.bones.size(); ++b) {
    const int32_t parentBone = boneAncestor(skeleton, boneOfJoint, out.bones[b].joint);
    if (parentBone >= 0) out.joints.push_back(jointFor(out, b, size_t(parentBone), skeleton, globals));
  }
  // Every skeleton joint rides on a body: its own bone, the nearest ancestor's, else the anchor.
  out.carrier.assign(jointCount, uint16_t(out.anchor));
  out.carried.assign(jointCount, glm::mat4(1.f));
  for (size_t j = 0; j < jointCount; ++j) {
    int32_t bone = boneOfJoint[j];
    if (bone < 0) bone = boneAncestor(skeleton, boneOfJoint, j);
    if (bone < 0) bone = int32_t(out.anchor);
    out.carrier[j] = uint16_t(bone);
    out.carried[j] = glm::mat4(glm::inverse(boneMatrix(out.bones[size_t(bone)])) * globals[j]);
  }
  return {};
}

bool createRagdoll(physics::PhysicsWorld& physics, const RagdollSpec& spec, const RagdollDef& def, Ragdoll& out) {
  out = Ragdoll{};
  const glm::dmat4& motion = def.motion;
  const glm::dquat turn = glm::normalize(glm::quat_cast(glm::dmat3(motion)));
  std::vector<int32_t> created(spec.bones.size(), -1);
  for (size_t b = 0; b < spec.bones.size(); ++b) {
    const RagdollBoneSpec& s = spec.bones[b];
    const auto shape = physics.createShape(physics::ShapeDef::capsule(s.radius, s.halfHeight));
    if (!shape.ok()) continue;
    const glm::dvec3 centre(motion * glm::dvec4(s.centre, 1.0));
    physics::BodyDef bone;
    bone.shape = shape.value();
    bone.mass = s.mass;
    bone.position = glm::vec3(centre);
    bone.rotation = glm::quat(glm::normalize(turn * s.rotation));
    bone.linearVelocity = glm::vec3(def.velocity + glm::cross(def.angularVelocity, centre - def.parentCentre));
    bone.angularVelocity = glm::vec3(def.angularVelocity);
    bone.userData = def.userData;
    bone.collisionGroup = def.collisionGroup;
    bone.linearDamping = def.linearDamping;
    bone.angularDamping = def.angularDamping;
    bone.sleepLinearSpeed = def.sleepLinearSpeed;
    bone.sleepAngularSpeed = def.sleepAngularSpeed;
    bone.friction = def.friction;
    const auto body = physics.createBody(bone);
    if (!body.ok()) {
      physics.destroyShape(shape.value());
      continue;
    }
    created[b] = int32_t(out.bones.size());
    out.bones.push_back(RagdollBone{s.joint, body.value(), shape.value(), s.radius, s.halfHeight, s.mass});
  }
  if (out.bones.empty() || created[spec.anchor] < 0) {
    releaseRagdoll(physics, out);
    out = Ragdoll{};
    return false;
  }
  out.anchor = size_t(created[spec.anchor]);
  for (const RagdollJointSpec& j : spec.joints) {
    if (created[j.parentBone] < 0 || created[j.childBone] < 0) continue;
    physics::JointDef jointDef = j.def;
    jointDef.bodyA = out.bones[size_t(created[j.parentBone])].body;
    jointDef.bodyB = out.bones[size_t(created[j.childBone])].body;
    const auto joint = physics.createJoint(jointDef);
    if (!joint.ok()) continue;
    out.joints.push_back(RagdollJoint{joint.value(), uint16_t(created[j.parentBone]),
                                      uint16_t(created[j.childBone]), j.skeletonJoint, jointDef.type});
  }
  out.carrier.resize(spec.carrier.size());
  out.carried = spec.carried;
  for (size_t k = 0; k < spec.carrier.size(); ++k) {
    const int32_t bone = created[spec.carrier[k]];
    if (bone >= 0) {
      out.carrier[k] = uint16_t(bone);
    } else {  // its bone could not be made: ride on the anchor where the anchor is now
      out.carrier[k] = uint16_t(out.anchor);
      out.carried[k] = glm::mat4(glm::inverse(boneMatrix(spec.bones[spec.anchor])) *
                                 boneMatrix(spec.bones[spec.carrier[k]]) * glm::dmat4(spec.carried[k]));
    }
  }
  return true;
}

void ragdollJointMatrices(const physics::PhysicsWorld& physics, const Ragdoll& ragdoll,
                          const anim::Skeleton& skeleton, std::vector<glm::mat4>& out) {
  out.resize(skeleton.size());
  if (ragdoll.bones.empty()) return;
  std::vector<glm::dmat4> bodies(ragdoll.bones.size(), glm::dmat4(1.0));
  for (size_t b = 0; b < ragdoll.bones.size(); ++b)
    if (const auto t = physics.bodyTransform(ragdoll.bones[b].body)) bodies[b] = rigid(*t);
  const glm::dmat4 toEntity = glm::inverse(bodies[ragdoll.anchor]);
  for (size_t j = 0; j < skeleton.size() && j < ragdoll.carrier.size(); ++j) {
    out[j] = glm::mat4(toEntity * bodies[ragdoll.carrier[j]] * glm::dmat4(ragdoll.carried[j]) *
                       glm::dmat4(skeleton.joints[j].inverseBind));
  }
}

void updateAnimations(SplitWorld& w, float dt) {
  for (auto [e, skin] : w.world.view<SkinnedMesh>()) {
    if (const auto* ragdoll = w.world.tryGet<Ragdoll>(e)) {
      ragdollJointMatrices(w.physics, *ragdoll, skin.asset->skeleton, skin.jointMatrices);
      continue;
    }
    skin.animator.advance(dt * skin.speed);
    skin.animator.evaluateJointMatrices(skin.jointMatrices);
  }
}

void releaseRagdoll(physics::PhysicsWorld& physics, Ragdoll& ragdoll) {
  for (RagdollBone& bone : ragdoll.bones) {
    physics.destroyBody(bone.body);
    physics.destroyShape(bone.shape);
    bone.body = {};
    bone.shape = {};
  }
  ragdoll.joints.clear();
}

}  // namespace cleave::components
