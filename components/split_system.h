// SPDX-License-Identifier: MIT
// The split systems: turn splitter touches into split requests (Triggers phase), prepare the
// requests gathered in earlier ticks within the SplitBudget (Split phase), compute them on worker
// threads, and commit their pieces at a fixed tick (Commit phase). The three stages and their plain
// data are in split_job.h; the compute stage in split_compute.h.
//
// Piece creation (the thesis's CreateNewObjects, the commit stage): each piece gets its own entity
// with a render mesh (the parent's materials plus the cap material), a rigid body whose origin is
// the piece's centre of mass and whose axes are its principal axes of inertia, the exact mass and
// principal inertia, the velocity the parent had at that point (v + w x (c_piece - c_parent), w
// kept), an optional split impulse, and the collider its spec carries: the parent's convex collider
// parts clipped by the plane (ColliderParts), so no cut decomposes or hulls anything on the main
// thread. The original entity is destroyed. If a split fails the original stays whole and the
// reason is logged.
//
// Timing: a request gathered in tick N is prepared from tick N+1 (budget permitting) and commits
// commitDelayTicks later, in request order, on any number of threads. If the parent moved between
// prepare and commit (one physics step), its pieces move rigidly with it and take its velocity at
// commit, so mass and momentum are those of the parent at commit. A target destroyed meanwhile
// commits nothing.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "cleave/components/activation_throttle.h"
#include "cleave/components/mesh_knowledge.h"
#include "cleave/components/piece_budget.h"
#include "cleave/components/scene_components.h"
#include "cleave/components/split_budget.h"
#include "cleave/components/split_job.h"
#include "cleave/components/split_times.h"
#include "cleave/components/split_workers.h"
#include "cleave/components/splitable.h"
#include "cleave/ecs/hierarchy.h"
#include "cleave/ecs/world.h"
#include "cleave/geometry/mesh_splitter.h"
#include "cleave/physics/physics_world.h"
#include "cleave/render/renderer.h"

namespace cleave::components {

// Everything the split systems touch. The renderer may be null (pure simulation).
struct SplitWorld {
  ecs::World& world;
  physics::PhysicsWorld& physics;
  render::Renderer* renderer = nullptr;
};

// A custom handler (the thesis's ISplitable), named by Splitable::handler: called on the main thread
// at commit with the job and its computed pieces, before anything is created. It may edit the
// specs (kinds, masses, velocities, meshes), drop or add pieces, or keep the original whole.
enum class HandlerDecision : uint8_t { Commit, KeepOriginal };
using SplitHandler = std::function<HandlerDecision(const SplitJob& job, SplitOutcome& outcome)>;

struct SplitEvent {
  uint64_t tick = 0;            // the commit tick (the tick the event is reported in)
  uint64_t preparedTick = 0;
  ecs::Entity original;
  std::string originalName;     // its Name at the time of the split, if it had one
  std::vector<ecs::Entity> pieces;
  std::vector<uint32_t> capLoops;  // per piece: boundary loops capped on it (2 for an annulus)
  std::vector<PieceKind> kinds;    // per piece
  std::vector<double> colliderFit; // per piece: collider volume / piece volume (0 without collider)
  uint32_t openChains = 0;         // section chains left open (art not watertight where cut)
  geometry::SplitStatus status = geometry::SplitStatus::Ok;
  std::string message;
  double parentMass = 0.0;
  double piecesMass = 0.0;      // sum over pieces kept with colliders and debris
  double posedVolume = 0.0;     // skinned: see SplitOutcome::posedVolume (0: not known)
  double piecesVolume = 0.0;    // the pieces' volumes as the split found them
  SplitTimes times;                   // by stage (split_times.h)
  double estimatedWorkerMilliseconds = 0.0;  // what the budget expected of the compute
  bool weldKnown = false;             // the mesh's weld was known (a piece, or a mesh cut before)
  bool partsKnown = false;            // the mesh's collider parts were known (carried or cached)
};

struct PieceCommit;  // piece_kind.h

class SplitSystem {
 public:
  explicit SplitSystem(SplitBudgetSettings budget = {});
  ~SplitSystem();
  SplitSystem(const SplitSystem&) = delete;
  SplitSystem& operator=(const SplitSystem&) = delete;

  // The budget and its settings (threads and commitDelayTicks among them; a change of threads takes
  // effect at the next prepare, after the jobs in flight are done).
  SplitBudget& budget() { return budget_; }
  const SplitBudget& budget() const { return budget_; }
  // The piece budget: what the splits leave behind (piece_budget.h). Its minimum body size applies
  // to the pieces of every split prepared from then on; settlePieces runs its tick.
  PieceBudget& pieces() { return pieces_; }
  const PieceBudget& pieces() const { return pieces_; }
  void registerHandler(const std::string& name, SplitHandler handler);
  // Runs compute tasks on the host's task system instead of our threads (empty: our own).
  void setTaskExecutor(SplitTaskExecutor executor);
  // When set, a split that fails (other than a plane missing the mesh) writes the mesh in cut space
  // with the plane to an OBJ file in this directory, for a reproducible bug report.
  void setFailureDumpDirectory(std::string directory) { failureDumpDirectory_ = std::move(directory); }

  // Queues a request from gameplay (e.g. the drag cut). Prepared from the next tick on.
  void request(const SplitRequest& request);

  // Triggers phase: reads the physics world's trigger events of the last step and queues a request
  // for every Splitable body a Splitter touched; one-tick splitters are destroyed afterwards.
  void gatherTriggerRequests(SplitWorld& w, uint64_t tick);

  // Split phase: activates bodies of earlier splits (a few per tick), then prepares queued requests
  // within the budget and starts their compute stage.
  void prepareSplits(SplitWorld& w, uint64_t tick, const glm::dvec3& cameraPosition);
  // Commit phase: commits, in request order, every job due by `tick` (waiting for late ones).
  void commitSplits(SplitWorld& w, uint64_t tick);
  // Both, as one phase (tests and tools that step the stages together).
  void runSplits(SplitWorld& w, uint64_t tick, const glm::dvec3& cameraPosition);

  // Activates bodies created by earlier splits, a few per tick (called by prepareSplits).
  void activatePending(SplitWorld& w);

  // PhysicsSync phase, after the transforms follow the bodies: the piece budget's tick (thaws hit
  // pieces, retires what is over its limits, fades), with the camera of the last prepare.
  void settlePieces(SplitWorld& w, uint64_t tick, double dt);

  // Splits `target` by the world plane now (no budget, no deferral, compute inline): used by tests
  // and tools. Jobs in flight are committed first.
  SplitEvent splitNow(SplitWorld& w, ecs::Entity target, const SplitRequest& request, uint64_t tick);

  // The convex collider parts of an authored mesh (mesh space), decomposed on first use and kept
  // for every instance and cut of it.
  geometry::SharedColliderParts colliderParts(const std::shared_ptr<const geometry::MeshData>& mesh,
                                              ColliderMode mode = ColliderMode::Auto);

  // Events of the splits committed (or failed at prepare) in the last prepare and commit calls.
  const std::vector<SplitEvent>& lastEvents() const { return events_; }
  uint64_t totalPiecesCreated() const { return totalPieces_; }
  size_t jobsInFlight() const { return pending_.size(); }
  // Bodies of pieces made asleep and waiting to be woken (activation_throttle.h).
  size_t activationsQueued() const { return activations_.queued(); }
  // Split jobs computed on another thread than the one that prepared them, over the system's life:
  // a test of "the same on N threads" checks it is above 0, so the threads really ran.
  uint64_t jobsComputedOffTheCallingThread() const;
  // Main-thread milliseconds spent in the split stages in the last tick (prepare + commit).
  double lastTickMainMilliseconds() const { return tickMainMs_; }

 private:
  struct Scratch;
  class Host;  // the world as the budget sees it, for one tick's prepare
  struct Pending {
    std::shared_ptr<SplitWorkers::Task> task;
    std::shared_ptr<const SplitJob> job;
    double prepareMilliseconds = 0.0;
    bool weldKnown = false;
    bool partsKnown = false;
  };
  // The tick a job prepared in `tick` commits in (SplitBudgetSettings::commitDelayTicks and after).
  uint64_t commitTickFor(uint64_t tick, double workerMilliseconds) const;
  // The budget's cost estimate of a request (main thread and worker milliseconds).
  SplitCost estimate(SplitWorld& w, const SplitRequest& r) const;
  // Prepares a split and submits its compute (the budget's execute); false when prepare refused it.
  bool startSplit(SplitWorld& w, const SplitRequest& request, uint64_t tick);
  // Prepare: reads the world into a job; false with the event filled when the target cannot be split.
  bool prepare(SplitWorld& w, const SplitRequest& request, uint64_t tick, SplitJob& job, SplitEvent& ev);
  // Commit: creates the pieces of a computed job (their structural changes wait in the batch).
  SplitEvent commit(SplitWorld& w, Pending& pending, uint64_t tick);
  void commitPieces(SplitWorld& w, const SplitJob& job, SplitOutcome& outcome, SplitEvent& ev);
  void commitPiece(PieceCommit& c, PieceSpec& spec);
  SplitWorkers& workers();
  // Applies the batch (the destroyed entities' hooks free what they held, resource_hooks.h).
  void flush(SplitWorld& w);
  SplitBudget budget_;
  ActivationThrottle activations_;
  MeshKnowledge knowledge_;
  PieceBudget pieces_;
  glm::dvec3 camera_{0.0};  // of the last prepare
  std::map<std::string, SplitHandler> handlers_;
  std::vector<SplitEvent> events_;
  std::unique_ptr<Scratch> scratch_;
  std::unique_ptr<SplitWorkers> workers_;
  uint64_t computedElsewhere_ = 0;  // by pools replaced since (a change of thread count)
  SplitTaskExecutor executor_;
  std::vector<Pending> pending_;  // prepared, in request order
  uint64_t totalPieces_ = 0;
  double tickMainMs_ = 0.0;
  uint64_t tickOfMainMs_ = ~0ull;
  std::string failureDumpDirectory_;
};

// The id an entity goes by in physics user data and in state dumps: generation << 32 | index.
uint64_t toUserData(ecs::Entity e);
ecs::Entity fromUserData(uint64_t v);

}  // namespace cleave::components

// The helpers that build what splits work on, and the systems that run beside them.
#include "cleave/components/authoring.h"
#include "cleave/components/world_systems.h"
