// The split systems: turn splitter touches into split requests (Triggers phase), execute requests
// gathered in earlier ticks within the SplitBudget (Split phase), and create the pieces.
//
// Piece creation (the thesis's CreateNewObjects): each piece gets its own entity with a render mesh
// (the parent's materials plus the cap material), a rigid body whose origin is the piece's centre of
// mass and whose axes are its principal axes of inertia, the exact mass and principal inertia, the
// velocity the parent had at that point (v + w x (c_piece - c_parent), w kept), an optional split
// impulse, and a collider chosen by the Splitable. The original entity is destroyed after the
// iteration. If a split fails the original stays whole and the reason is logged.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "components/scene_components.h"
#include "components/split_budget.h"
#include "components/splitable.h"
#include "engine/ecs/world.h"
#include "engine/geometry/mesh_splitter.h"
#include "engine/physics/physics_world.h"
#include "engine/render/renderer.h"

namespace cleave::components {

// Everything the split systems touch. The renderer may be null (pure simulation).
struct SplitWorld {
  ecs::World& world;
  physics::PhysicsWorld& physics;
  render::Renderer* renderer = nullptr;
};

// A custom handler (the thesis's ISplitable): called instead of the default piece creation with
// the request and the split result; returns false to keep the original.
using SplitHandler = std::function<bool(SplitWorld&, ecs::Entity target, const SplitRequest&,
                                        geometry::SplitResult&)>;

struct SplitEvent {
  uint64_t tick = 0;
  ecs::Entity original;
  std::string originalName;     // its Name at the time of the split, if it had one
  std::vector<ecs::Entity> pieces;
  std::vector<uint32_t> capLoops;  // per piece: boundary loops capped on it (2 for an annulus)
  geometry::SplitStatus status = geometry::SplitStatus::Ok;
  std::string message;
  double parentMass = 0.0;
  double piecesMass = 0.0;      // sum over pieces kept with colliders and debris
  double milliseconds = 0.0;          // the whole split, pieces created
  double setupMilliseconds = 0.0;     // of which: container set-up (copy, weld unless known, cut space)
  bool weldKnown = false;             // the mesh's weld was known (a piece, or a mesh cut before)
  double geometryMilliseconds = 0.0;  // of which: cut, caps, islands, mass properties
  double colliderMilliseconds = 0.0;  // of which: collider shapes
  double uploadMilliseconds = 0.0;    // of which: GPU mesh upload
};

class SplitSystem {
 public:
  explicit SplitSystem(SplitBudgetSettings budget = {});
  ~SplitSystem();

  SplitBudget& budget() { return budget_; }
  void registerHandler(const std::string& name, SplitHandler handler);
  // When set, a split that fails (other than a plane missing the mesh) writes the mesh in cut space
  // with the plane to an OBJ file in this directory, for a reproducible bug report.
  void setFailureDumpDirectory(std::string directory) { failureDumpDirectory_ = std::move(directory); }

  // Queues a request from gameplay (e.g. the drag cut). Executed from the next tick on.
  void request(const SplitRequest& request);

  // Triggers phase: reads the physics world's trigger events of the last step and queues a request
  // for every Splitable body a Splitter touched; one-tick splitters are destroyed afterwards.
  void gatherTriggerRequests(SplitWorld& w, uint64_t tick);

  // Split phase: executes queued requests within the budget and applies the structural changes.
  void runSplits(SplitWorld& w, uint64_t tick, const glm::dvec3& cameraPosition);

  // Activates bodies created by earlier splits, a few per tick (part of the Split phase).
  void activatePending(SplitWorld& w);

  // Splits `target` by the world plane now (no budget, no deferral): used by tests and tools.
  SplitEvent splitNow(SplitWorld& w, ecs::Entity target, const SplitRequest& request, uint64_t tick);

  // Events of the splits done in the last runSplits call.
  const std::vector<SplitEvent>& lastEvents() const { return events_; }
  uint64_t totalPiecesCreated() const { return totalPieces_; }

 private:
  struct Scratch;
  // One split; its structural changes wait in the batch until flush().
  SplitEvent splitOne(SplitWorld& w, ecs::Entity target, const SplitRequest& request, uint64_t tick);
  // Frees the resources of the entities the batch destroys, then applies the batch.
  void flush(SplitWorld& w);
  SplitBudget budget_;
  std::map<std::string, SplitHandler> handlers_;
  std::vector<SplitEvent> events_;
  std::unique_ptr<Scratch> scratch_;
  uint64_t totalPieces_ = 0;
  std::string failureDumpDirectory_;
};

// The id an entity goes by in physics user data and in state dumps: generation << 32 | index.
uint64_t toUserData(ecs::Entity e);
ecs::Entity fromUserData(uint64_t v);

// Creates a splitter entity (Name, Transform, WorldTransform and `splitter`, whose lifetime and
// player flag are kept) with a trigger of `shape` at `position`/`rotation`: persistent for a
// persistent splitter, one-shot otherwise. Its plane is the local +Y axis through `position`.
// Returns kNullEntity, creating nothing, when the shape cannot be built.
ecs::Entity createSplitter(SplitWorld& w, const std::string& name, const physics::ShapeDef& shape,
                           const glm::vec3& position, const glm::quat& rotation, Splitter splitter);

// Frees the GPU mesh and the physics body of an entity (to be followed by destroying the entity).
void releaseEntityResources(SplitWorld& w, ecs::Entity e);

// Creates the rigid body and collider for an authored object with a MeshRenderer, from its mesh's
// exact mass properties (density from its Splitable, or `density`). Sets RigidBody, MassInfo and the
// mesh offset so the body origin is the centre of mass. Returns false with a reason on failure.
bool makeDynamicBody(SplitWorld& w, ecs::Entity e, double density, ColliderMode collider,
                     std::string* error);

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

// The mesh's positions mapped by `m` (for example a body frame's mesh offset), as collider points.
std::vector<glm::vec3> transformedPoints(const geometry::MeshData& mesh, const glm::dmat4& m);

// Puts an authored entity on the body just made for it: its Transform moves to the body's pose
// (unit scale) and it gets RigidBody and MassInfo (mass, volume, density, closed from `props`).
// The mesh offset is the caller's.
void placeOnBody(SplitWorld& w, ecs::Entity e, const physics::BodyDef& def, physics::BodyId body,
                 physics::ShapeId shape, double mass, const geometry::MassProperties& props, double density);

// Physics sync (PhysicsSync phase): entity transforms follow their bodies.
void syncTransformsFromBodies(SplitWorld& w);

// Render phase: submits every visible MeshRenderer at WorldTransform x meshOffset.
void submitMeshes(SplitWorld& w);

// Debris: pieces without collider fall under gravity and vanish after a while.
struct Debris {
  glm::vec3 velocity{0.f};
  glm::vec3 angularVelocity{0.f};
  float secondsLeft = 3.f;
};
void updateDebris(SplitWorld& w, float dt);

}  // namespace cleave::components
