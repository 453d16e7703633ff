// SPDX-License-Identifier: MIT
// The plain data of one split as it goes through the three stages (docs/architecture.md):
//
//   prepare (main thread, Split phase)  reads the world into a SplitJob;
//   compute (any thread)                computeSplit(job) -> SplitOutcome, a PieceSpec per piece;
//   commit  (main thread, fixed tick)   creates shapes, bodies, joints, entities and GPU meshes.
//
// A job holds no pointer into the world: entities are ids, meshes, welds, collider parts and
// skeletons are shared immutable values (shared_ptr<const ...>) that the world may drop meanwhile
// without harm. A spec says everything commit needs without computing anything heavy: mesh, weld,
// mass, body frame, velocity, collider hulls ready for the physics bridge (body frame, shrunk by
// their margin), ragdoll bones and joints. Poses in a spec are those of the prepare tick; commit
// moves them rigidly with the parent if it moved in between (SplitSystem docs).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "cleave/components/split_budget.h"
#include "cleave/components/split_times.h"
#include "cleave/components/splitable.h"
#include "cleave/ecs/entity.h"
#include "cleave/geometry/collider_parts.h"
#include "cleave/geometry/mesh_splitter.h"
#include "cleave/physics/joint_def.h"
#include "cleave/render/packed_mesh.h"
#include "cleave/render/renderer.h"

namespace cleave::components {

struct SkinnedAsset;

// The body frame of a mesh of mass properties `props` (cut space = model x mesh space) and `mass`:
// origin at the centre of mass, axes along the principal axes of inertia, the principal moments
// (each floored at a small share of the largest, so that a sliver never gets zero inertia), and
// the mesh offset (mesh space -> body frame).
struct BodyFrame {
  glm::dvec3 position{0.0};
  glm::dquat rotation{1.0, 0.0, 0.0, 0.0};
  glm::dvec3 moments{0.0};     // principal inertia, kg m^2
  glm::dmat4 meshOffset{1.0};  // mesh space -> body frame
};
BodyFrame bodyFrameFor(const geometry::MassProperties& props, double mass, const glm::dmat4& model);

// The mesh's positions mapped by `m` (a body frame's mesh offset, or a model matrix), as floats.
std::vector<glm::vec3> transformedPoints(const geometry::MeshData& mesh, const glm::dmat4& m);

// PieceKind (splitable.h): what a piece becomes; each kind is a strategy of piece_kind.h.

// The parent's frame and motion at prepare (the body is authoritative when there is one).
struct ParentMotion {
  glm::dvec3 centre{0.0};                   // body origin (centre of mass), world
  glm::dquat rotation{1.0, 0.0, 0.0, 0.0};  // body rotation
  glm::dvec3 velocity{0.0};                 // m/s
  glm::dvec3 angularVelocity{0.0};          // rad/s
  double mass = 0.0;                        // kg (MassInfo when present)
};

// A part of a hierarchy target (a descendant with a mesh), as the job carries it.
struct HierarchyPartData {
  ecs::Entity entity;
  std::shared_ptr<const geometry::MeshData> mesh;
  glm::dmat4 toParent{1.0};  // the part's mesh space -> the target entity's space
  std::vector<render::Material> materials;
  std::string name;
  bool visible = true;
};

struct SplitJob {
  uint64_t sequence = 0;       // the request's arrival order (commits go in prepare order: the budget's)
  uint64_t preparedTick = 0;
  uint64_t commitTick = 0;     // preparedTick + commitDelayTicks, later for a long compute (split_budget.h)
  double estimatedWorkerMilliseconds = 0.0;  // the budget's estimate of the compute
  SplitRequest request;
  std::string targetName;      // its Name, if it had one
  // The mesh to cut (mesh space) and what is known of it. For a hierarchy, `mesh` is null and the
  // compute merges `hierarchyParts` (part 0 is the target's own mesh when it has one).
  std::shared_ptr<const geometry::MeshData> mesh;
  std::shared_ptr<const geometry::MeshWeld> weld;  // null: welded in compute (and returned)
  geometry::SharedColliderParts parts;              // null: decomposed in compute when needed
  std::vector<HierarchyPartData> hierarchyParts;
  glm::dmat4 model{1.0};       // mesh space -> cut space (world) at prepare
  // Skinned targets: cut in this pose (bind space -> mesh space per joint).
  std::shared_ptr<const SkinnedAsset> skin;
  std::vector<glm::mat4> jointMatrices;
  geometry::Plane plane;       // world
  geometry::SplitOptions options;
  Splitable settings;          // the target's Splitable (pieces get a copy)
  ParentMotion parent;
  uint32_t depth = 1;          // cuts deep the pieces will be
  // The piece budget's smallest body (piece_budget.h): smaller pieces are debris (or removed).
  double minBodyVolume = 0.0;      // m^3, beside Splitable::minPieceVolume
  double minBodyThickness = 0.0;   // m, smallest extent along the principal axes (rigid jobs)
  std::vector<render::Material> materials;  // piece materials, the cap material in place
  bool hasMaterialChoice = false;
  int materialChoice = 0;
  bool packForGpu = false;     // a renderer will draw the pieces: compute packs their vertex buffers

  bool hierarchy() const { return !hierarchyParts.empty(); }
  bool skinned() const { return skin != nullptr; }
};

// One collider hull ready for the physics bridge: body-frame vertices of the part shrunk by
// `margin` (physics::ShapeDef::preparedHull / ConvexPart::margin).
struct HullSpec {
  std::vector<glm::vec3> points;
  float margin = 0.f;
};

// A ragdoll as commit creates it: bones at their prepare-tick poses (world), joints with frames in
// the bodies' frames, and how skeleton joints ride on the bones.
struct RagdollBoneSpec {
  uint16_t joint = 0;
  glm::dvec3 centre{0.0};
  glm::dquat rotation{1.0, 0.0, 0.0, 0.0};
  float radius = 0.f, halfHeight = 0.f, mass = 0.f;
};
struct RagdollJointSpec {
  uint16_t parentBone = 0, childBone = 0, skeletonJoint = 0;
  physics::JointDef def;  // bodies filled at commit; frames and limits here
};
struct RagdollSpec {
  std::vector<RagdollBoneSpec> bones;
  std::vector<RagdollJointSpec> joints;
  size_t anchor = 0;
  std::vector<uint16_t> carrier;   // per skeleton joint
  std::vector<glm::mat4> carried;  // per skeleton joint, in its carrier's frame
  std::vector<glm::mat4> jointMatrices;  // the piece's joint matrices relative to the anchor frame
};

struct HierarchyChildSpec {
  size_t part = 0;  // index into SplitJob::hierarchyParts
  std::shared_ptr<const geometry::MeshData> mesh;
  std::shared_ptr<const render::PackedMesh> packed;  // when the job packs for the GPU
  const geometry::MeshData* packedFrom = nullptr;     // the mesh `packed` was made from
};

struct PieceSpec {
  PieceKind kind = PieceKind::Rigid;
  int side = 0;                  // +1 above the plane, -1 below
  uint32_t capLoops = 0;
  std::shared_ptr<const geometry::MeshData> mesh;  // drawn (bind space when the skin is kept)
  // `mesh` packed for upload (SplitJob::packForGpu). Commit uploads it only while `mesh` is still the
  // mesh it was made from (packedFrom): a handler that replaces the mesh gets its new mesh drawn.
  std::shared_ptr<const render::PackedMesh> packed;
  const geometry::MeshData* packedFrom = nullptr;
  std::shared_ptr<const geometry::MeshWeld> weld;  // null: unknown (welded anew if cut again)
  double volume = 0.0, mass = 0.0;
  bool closed = true;
  BodyFrame frame;               // world, at prepare
  glm::dvec3 offsetFromParent{0.0};  // frame.position - parent centre, world, at prepare
  glm::dvec3 impulse{0.0};           // added velocity, world, at prepare
  glm::dvec3 velocity{0.0};          // v + w x r + impulse, at prepare
  // Collider (Rigid, KeepAnimating, Baked): hulls, or a concave mesh (ConcaveMesh mode).
  std::vector<HullSpec> hulls;
  std::vector<glm::vec3> concavePositions;  // body frame
  std::vector<uint32_t> concaveIndices;
  double colliderVolume = 0.0;   // of the unshrunk parts (fit = colliderVolume / volume)
  geometry::SharedColliderParts parts;  // mesh space: what the piece's own cuts clip
  RagdollSpec ragdoll;
  std::vector<HierarchyChildSpec> children;
  std::string name;
};

struct SplitOutcome {
  geometry::SplitStatus status = geometry::SplitStatus::Ok;
  std::string message;
  std::vector<PieceSpec> pieces;
  uint32_t openChains = 0;  // section chains left open (geometry::SplitResult::openChains)
  // Skinned jobs, whose pieces share the parent's mass by their part of the volume: the closed posed
  // source's volume, integrated on its own before the cut (0 otherwise), and the pieces' volumes
  // summed, so that a check of the pieces does not hold by construction.
  double posedVolume = 0.0;
  double piecesVolume = 0.0;
  // Worked out for the source in compute, for the split system to keep (null: nothing new).
  std::shared_ptr<const geometry::MeshWeld> sourceWeld;
  geometry::SharedColliderParts sourceParts;
  ComputeTimes times;  // split_times.h
};

}  // namespace cleave::components
