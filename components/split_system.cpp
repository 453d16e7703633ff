// SPDX-License-Identifier: MIT
#include "cleave/components/split_system.h"
#include "cleave/components/static_batches.h"
#include "cleave/components/split_clock.h"
#include "cleave/components/skinned.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <span>
#include <unordered_map>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "cleave/components/piece_kind.h"
#include "cleave/components/split_compute.h"
#include "cleave/components/split_hierarchy.h"
#include "cleave/components/split_log.h"
#include "cleave/components/split_budget.h"
#include "cleave/components/split_cost.h"
#include "cleave/ecs/command_buffer.h"
#include "cleave/ecs/hierarchy.h"
#include "cleave/geometry/mass_properties.h"
#include "cleave/log/log.h"

namespace cleave::components {

namespace {

// The frame and motion of an entity now: its body's when it has one, else its Transform's.
ParentMotion motionOf(SplitWorld& w, ecs::Entity e) {
  ParentMotion m;
  if (const auto* t = w.world.tryGet<ecs::Transform>(e)) {
    m.centre = glm::dvec3(t->position);
    m.rotation = glm::dquat(t->rotation);
  }
  if (const auto* rb = w.world.tryGet<RigidBody>(e); rb && w.physics.isValid(rb->body)) {
    if (const auto state = w.physics.bodyState(rb->body)) {
      m.centre = glm::dvec3(state->transform.position);
      m.rotation = glm::dquat(state->transform.rotation);
      m.velocity = glm::dvec3(state->linearVelocity);
      m.angularVelocity = glm::dvec3(state->angularVelocity);
      m.mass = state->mass;
    }
  }
  if (const auto* mi = w.world.tryGet<MassInfo>(e)) m.mass = mi->mass;
  return m;
}

// The rigid motion that takes the frame `then` to the frame `now` (identity, exactly, when equal).
glm::dmat4 motionBetween(const ParentMotion& then, const ParentMotion& now) {
  if (then.centre == now.centre && then.rotation == now.rotation) return glm::dmat4(1.0);
  const glm::dmat4 a = glm::translate(glm::dmat4(1.0), then.centre) * glm::mat4_cast(then.rotation);
  const glm::dmat4 b = glm::translate(glm::dmat4(1.0), now.centre) * glm::mat4_cast(now.rotation);
  return b * glm::inverse(a);
}

}  // namespace

struct SplitSystem::Scratch {
  // Structural changes of the current batch; made for the world of the first call.
  std::unique_ptr<ecs::CommandBuffer> commands;
  ecs::World* commandsWorld = nullptr;
  SplitComputeScratch inlineCompute;  // splitNow
};

SplitSystem::SplitSystem(SplitBudgetSettings budget)
    : budget_(budget), scratch_(std::make_unique<Scratch>()) {}
SplitSystem::~SplitSystem() {
  if (workers_) workers_->waitAll();
}

namespace {

ecs::CommandBuffer& commandsFor(std::unique_ptr<ecs::CommandBuffer>& buffer, ecs::World*& owner,
                                ecs::World& world) {
  if (!buffer || owner != &world) {
    buffer = std::make_unique<ecs::CommandBuffer>(world);
    owner = &world;
  }
  return *buffer;
}

}  // namespace

void SplitSystem::flush(SplitWorld& w) {
  if (scratch_->commands && scratch_->commandsWorld == &w.world) w.world.apply(*scratch_->commands);
}

void SplitSystem::registerHandler(const std::string& name, SplitHandler handler) {
  handlers_[name] = std::move(handler);
}

void SplitSystem::setTaskExecutor(SplitTaskExecutor executor) {
  executor_ = std::move(executor);
  if (workers_) workers_->setExecutor(executor_);
}

SplitWorkers& SplitSystem::workers() {
  const uint32_t threads = budget_.settings().threads;
  if (!workers_ || workers_->threads() != threads) {
    if (workers_) {
      workers_->waitAll();
      computedElsewhere_ += workers_->tasksRunElsewhere();
    }
    workers_ = std::make_unique<SplitWorkers>(threads);
    if (executor_) workers_->setExecutor(executor_);
  }
  return *workers_;
}

void SplitSystem::request(const SplitRequest& request) { budget_.enqueue(request); }

uint64_t SplitSystem::jobsComputedOffTheCallingThread() const {
  return computedElsewhere_ + (workers_ ? workers_->tasksRunElsewhere() : 0);
}

geometry::SharedColliderParts SplitSystem::colliderParts(const std::shared_ptr<const geometry::MeshData>& mesh,
                                                         ColliderMode mode) {
  if (!mesh) return nullptr;
  if (const MeshKnowledge::Entry* k = knowledge_.find(mesh); k && k->parts) return k->parts;
  const ColliderPlan plan = planCollider(*mesh, glm::dmat4(1.0), mode, false, nullptr, *scratch_->inlineCompute.concave);
  knowledge_.remember(mesh).parts = plan.parts;
  return plan.parts;
}

uint64_t toUserData(ecs::Entity e) { return (uint64_t(e.generation) << 32) | uint64_t(e.index); }

ecs::Entity fromUserData(uint64_t v) {
  ecs::Entity e;
  e.index = uint32_t(v & 0xffffffffu);
  e.generation = uint32_t(v >> 32);
  return e;
}

namespace {

// True when the plane through `origin` with unit `normal` passes through the body's collider.
bool planeCrossesBody(const physics::PhysicsWorld& physics, physics::BodyId body, const glm::dvec3& normal,
                      const glm::dvec3& origin) {
  const auto extent = physics.extentAlong(body, glm::vec3(normal));
  if (!extent) return false;
  const double d = glm::dot(normal, origin);
  return double(extent->x) < d && d < double(extent->y);
}

}  // namespace

void SplitSystem::gatherTriggerRequests(SplitWorld& w, uint64_t tick) {
  // (splitter index, object id) of every touch of a persistent splitter in the last step: an object
  // whose bodies (a ragdoll has several) no longer touch the blade has left it, and its next touch
  // is a new pass.
  std::vector<std::pair<uint32_t, uint64_t>> touching;
  // (splitter index, object id) asked for in this call: an object of several bodies (a ragdoll's
  // bones) touching a one-tick splitter is asked for once.
  std::vector<std::pair<uint32_t, uint64_t>> asked;
  for (const physics::TriggerEvent& ev : w.physics.triggerEvents()) {
    const auto splitterUser = w.physics.triggerUserData(ev.trigger);
    const auto bodyUser = w.physics.bodyUserData(ev.body);
    if (!splitterUser || !bodyUser) continue;
    const ecs::Entity splitterEntity = fromUserData(*splitterUser);
    const ecs::Entity target = fromUserData(*bodyUser);
    if (!w.world.alive(splitterEntity) || !w.world.alive(target)) continue;
    auto* splitter = w.world.tryGet<Splitter>(splitterEntity);
    if (!splitter) continue;
    const bool persistent = splitter->lifetime == SplitterLifetime::Persistent;
    // A touch that goes on matters to a persistent splitter whose plane did not cross the body yet.
    if (ev.kind == physics::TriggerEventKind::Stay && !persistent) continue;
    if (ev.kind == physics::TriggerEventKind::End) continue;  // passes end below
    if (persistent) touching.emplace_back(splitterEntity.index, *bodyUser);
    if (!w.world.has<Splitable>(target)) continue;
    // A persistent splitter cuts an object once per pass: the pieces of its own cut appear touching
    // it (their caps lie on its plane) and are not cut again.
    if (persistent &&
        std::find(splitter->passing.begin(), splitter->passing.end(), *bodyUser) != splitter->passing.end())
      continue;
    const auto* wt = w.world.tryGet<ecs::WorldTransform>(splitterEntity);
    if (!wt) continue;
    const glm::dmat4 m(wt->matrix);
    const glm::dvec3 origin(m[3]);
    const glm::dvec3 normal = glm::normalize(glm::transpose(glm::inverse(glm::dmat3(m))) * glm::dvec3(0, 1, 0));
    // The trigger box is thicker than the plane: a body that touches the box but lies wholly on one
    // side of the plane is not asked for (yet); a persistent blade asks once its plane crosses it.
    if (splitter->kind == SplitterKind::Plane && !planeCrossesBody(w.physics, ev.body, normal, origin)) continue;
    if (std::find(asked.begin(), asked.end(), std::pair(splitterEntity.index, *bodyUser)) != asked.end()) continue;
    asked.emplace_back(splitterEntity.index, *bodyUser);
    if (persistent) splitter->passing.push_back(*bodyUser);
    SplitRequest r;
    r.target = target;
    r.planeNormal = normal;
    r.planeOffset = glm::dot(normal, origin);
    r.splitter = splitterEntity;
    r.playerCaused = splitter->playerCaused;
    r.requestedTick = tick;
    if (splitter->kind == SplitterKind::Shatter) {
      r.shatter = true;
      r.shatterSpec = splitter->shatter;
      if (!r.shatterSpec.impactGiven) r.shatterSpec.impactPoint = origin;
    }
    budget_.enqueue(r);
    splitter->cuts++;
  }
  // One-tick splitters are gone after the step that reported their touches.
  ecs::CommandBuffer& commands = commandsFor(scratch_->commands, scratch_->commandsWorld, w.world);
  std::sort(touching.begin(), touching.end());
  for (auto [e, splitter] : w.world.view<Splitter>()) {
    std::erase_if(splitter.passing, [&](uint64_t id) {
      return !w.world.alive(fromUserData(id)) ||
             (splitter.lifetime == SplitterLifetime::Persistent &&
              !std::binary_search(touching.begin(), touching.end(), std::pair(e.index, id)));
    });
    if (splitter.lifetime == SplitterLifetime::OneTick && w.physics.isTriggerSpent(splitter.trigger)) {
      commands.destroy(e);
    }
  }
  flush(w);
}

void SplitSystem::settlePieces(SplitWorld& w, uint64_t tick, double dt) {
  pieces_.update(w, tick, camera_, float(dt));
}

void SplitSystem::activatePending(SplitWorld& w) {
  // Bodies woken here count against this tick's activations, so pieces created awake by this tick's
  // splits and the queued ones together stay within maxActivationsPerTick.
  for (physics::BodyId body : activations_.beginTick(budget_.settings().maxActivationsPerTick))
    w.physics.activate(body);
}

uint64_t SplitSystem::commitTickFor(uint64_t tick, double workerMilliseconds) const {
  uint64_t latest = 0;
  for (const Pending& p : pending_) latest = std::max(latest, p.job->commitTick);
  return components::commitTickFor(budget_.settings(), tick, workerMilliseconds, latest);
}

SplitCost SplitSystem::estimate(SplitWorld& w, const SplitRequest& r) const {
  const geometry::ColliderPartSet* parts = nullptr;
  if (const auto* cp = w.world.tryGet<ColliderParts>(r.target); cp && cp->parts) {
    parts = cp->parts.get();
  } else if (const auto* mr = w.world.tryGet<MeshRenderer>(r.target); mr && mr->source) {
    if (const MeshKnowledge::Entry* k = knowledge_.find(mr->source); k && k->parts) parts = k->parts.get();
  }
  SplitCostInputs in;
  in.parts = parts;
  if (const auto* mr = w.world.tryGet<MeshRenderer>(r.target); mr && mr->source)
    in.triangles = double(mr->source->indices.size() / 3);
  const auto* sp = w.world.tryGet<Splitable>(r.target);
  in.skinned = w.world.has<SkinnedMesh>(r.target);
  in.ragdoll = in.skinned && sp && sp->skinnedPieces == SkinnedPieceMode::Ragdoll;
  in.shatterCells = r.shatter ? std::max<uint32_t>(r.shatterSpec.cells, 1) : 0;
  return estimateSplitCost(budget_.settings(), in);
}

// The world as the budget sees it for one tick's prepare.
class SplitSystem::Host final : public SplitBudgetHost {
 public:
  Host(SplitSystem& system, SplitWorld& w, uint64_t tick) : system_(system), w_(w), tick_(tick) {}

  bool isAlive(ecs::Entity e) const override { return w_.world.alive(e) && w_.world.has<Splitable>(e); }
  glm::dvec3 positionOf(ecs::Entity e) const override {
    const auto* t = w_.world.tryGet<ecs::Transform>(e);
    return t ? glm::dvec3(t->position) : glm::dvec3(0.0);
  }
  bool isBusy(ecs::Entity e) const override {
    return std::any_of(system_.pending_.begin(), system_.pending_.end(),
                       [&](const Pending& p) { return p.job->request.target == e; });
  }
  SplitCost estimate(const SplitRequest& r) const override { return system_.estimate(w_, r); }
  bool execute(const SplitRequest& r) override { return system_.startSplit(w_, r, tick_); }
  double nowMilliseconds() const override { return components::nowMilliseconds(); }

 private:
  SplitSystem& system_;
  SplitWorld& w_;
  uint64_t tick_;
};

// Prepares one split and hands its compute to the workers; false (with its event) when prepare
// refused it.
bool SplitSystem::startSplit(SplitWorld& w, const SplitRequest& r, uint64_t tick) {
  const double prepareStart = nowMilliseconds();
  auto job = std::make_shared<SplitJob>();
  SplitEvent failed;
  if (!prepare(w, r, tick, *job, failed)) {
    failed.times.prepare = nowMilliseconds() - prepareStart;
    events_.push_back(std::move(failed));
    return false;
  }
  Pending p;
  p.weldKnown = job->weld != nullptr;
  p.partsKnown = job->parts != nullptr;
  p.job = job;
  p.prepareMilliseconds = nowMilliseconds() - prepareStart;  // without an inline compute
  p.task = workers().submit(std::move(job));
  pending_.push_back(std::move(p));
  return true;
}

void SplitSystem::prepareSplits(SplitWorld& w, uint64_t tick, const glm::dvec3& cameraPosition) {
  const double start = nowMilliseconds();
  events_.clear();
  camera_ = cameraPosition;
  activatePending(w);
  Host host(*this, w, tick);
  budget_.runTick(tick, cameraPosition, host);
  flush(w);
  if (tickOfMainMs_ != tick) tickMainMs_ = 0.0;
  tickOfMainMs_ = tick;
  tickMainMs_ += nowMilliseconds() - start;
}

void SplitSystem::commitSplits(SplitWorld& w, uint64_t tick) {
  const double start = nowMilliseconds();
  if (tickOfMainMs_ != tick) {
    events_.clear();
    tickMainMs_ = 0.0;
  }
  // Every job due, in the order they were prepared in (the budget's total order); the others wait.
  std::vector<Pending> later;
  for (Pending& p : pending_) {
    if (p.job->commitTick > tick) {
      later.push_back(std::move(p));
      continue;
    }
    events_.push_back(commit(w, p, tick));
    const geometry::SplitStatus status = events_.back().status;
    if (status != geometry::SplitStatus::Ok && status != geometry::SplitStatus::PlaneMissesMesh) budget_.recordFailure();
  }
  pending_ = std::move(later);
  // Structural changes after the iteration: pieces appear, originals go.
  flush(w);
  tickOfMainMs_ = tick;
  tickMainMs_ += nowMilliseconds() - start;

}

void SplitSystem::runSplits(SplitWorld& w, uint64_t tick, const glm::dvec3& cameraPosition) {
  prepareSplits(w, tick, cameraPosition);
  commitSplits(w, tick);
}

SplitEvent SplitSystem::splitNow(SplitWorld& w, ecs::Entity target, const SplitRequest& request,
                                 uint64_t tick) {
  for (Pending& p : pending_) events_.push_back(commit(w, p, tick));  // jobs in flight go first
  pending_.clear();
  flush(w);
  const double start = nowMilliseconds();
  auto job = std::make_shared<SplitJob>();
  SplitEvent ev;
  SplitRequest r = request;
  r.target = target;
  if (!prepare(w, r, tick, *job, ev)) {
    ev.times.prepare = nowMilliseconds() - start;
    return ev;
  }
  job->commitTick = tick;
  Pending p;
  p.weldKnown = job->weld != nullptr;
  p.partsKnown = job->parts != nullptr;
  p.job = job;
  p.prepareMilliseconds = nowMilliseconds() - start;
  SplitWorkers inline0(0);
  p.task = inline0.submit(std::move(job));
  ev = commit(w, p, tick);
  // The structural changes are main-thread work of this split too.
  const double flushStart = nowMilliseconds();
  flush(w);
  const double flushMs = nowMilliseconds() - flushStart;
  ev.times.commit += flushMs;
  return ev;
}

namespace {

// The split options of a target's Splitable.
geometry::SplitOptions optionsFor(const Splitable& sp, bool hierarchy) {  // caps: by provenance
  geometry::SplitOptions options;
  options.cap = sp.cap;
  options.capMaterialId = sp.capMaterialId;
  options.uvMode = sp.capUvMode;
  options.uvPerMetre = sp.capUvPerMetre;
  options.atlasRect = sp.capAtlasRect;
  options.uvPerBorder = sp.capUvPerBorder;
  // The parts of a hierarchy are usually disjoint meshes (a head above a body) that form one
  // object: each side stays one piece.
  options.separateIslands = sp.separateIslands && !hierarchy;
  options.openSections = sp.openSections;
  options.islands = sp.islands;
  return options;
}

}  // namespace

bool SplitSystem::prepare(SplitWorld& w, const SplitRequest& request, uint64_t tick, SplitJob& job, SplitEvent& ev) {
  const ecs::Entity target = request.target;
  ev.tick = ev.preparedTick = tick;
  ev.original = target;
  const auto* name = w.world.tryGet<ecs::Name>(target);
  if (name) ev.originalName = name->value;
  const auto* mr = w.world.tryGet<MeshRenderer>(target);
  const auto* sp = w.world.tryGet<Splitable>(target);
  const auto* t = w.world.tryGet<ecs::Transform>(target);
  const auto* skin = w.world.tryGet<SkinnedMesh>(target);
  const bool hierarchy = t && !skin && gatherParts(w.world, target, job.hierarchyParts);
  if ((!hierarchy && (!mr || !mr->source)) || !sp || !t) {
    ev.status = geometry::SplitStatus::InvalidInput;
    ev.message = "target has no mesh, Splitable or Transform";
    log::warning("cleave", "split of %s (entity %u) at tick %llu kept whole: %s",
                 ev.originalName.empty() ? "an object" : ev.originalName.c_str(), target.index,
                 static_cast<unsigned long long>(tick), ev.message.c_str());
    return false;
  }
  if (!hierarchy) job.hierarchyParts.clear();
  job.sequence = request.sequence;
  job.preparedTick = tick;
  job.estimatedWorkerMilliseconds = estimate(w, request).worker;
  job.commitTick = commitTickFor(tick, job.estimatedWorkerMilliseconds);
  job.request = request;
  job.targetName = name ? name->value : std::string();
  job.parent = motionOf(w, target);
  ev.parentMass = job.parent.mass;
  const glm::dmat4 entityToWorld = glm::translate(glm::dmat4(1.0), job.parent.centre) *
                                   glm::mat4_cast(job.parent.rotation) *
                                   glm::scale(glm::dmat4(1.0), glm::dvec3(t->scale));
  job.model = hierarchy ? entityToWorld : entityToWorld * glm::dmat4(mr->meshOffset);
  if (!hierarchy) {
    job.mesh = mr->source;
    if (const MeshKnowledge::Entry* k = knowledge_.find(mr->source)) {
      job.weld = k->weld;
      job.parts = k->parts;
    }
    if (const auto* cp = w.world.tryGet<ColliderParts>(target); cp && cp->parts) job.parts = cp->parts;
  }
  // A skinned target is cut in its current pose: the cut space is the skinned mesh in the world.
  if (skin && !skin->jointMatrices.empty() && !mr->source->joints.empty()) {
    job.skin = skin->asset;
    job.jointMatrices = skin->jointMatrices;
    job.parts = nullptr;  // bind-space parts do not follow the pose
  }
  job.packForGpu = w.renderer != nullptr;
  job.plane = geometry::Plane{request.planeNormal, request.planeOffset};
  job.options = optionsFor(*sp, hierarchy);
  job.settings = *sp;
  const auto* origin = w.world.tryGet<SplitOrigin>(target);
  job.depth = origin ? origin->generation + 1 : 1;
  job.minBodyVolume = pieces_.settings().minBodyVolume;
  job.minBodyThickness = pieces_.settings().minBodyThickness;
  job.materials = mr ? mr->materials : std::vector<render::Material>{};
  if (job.materials.size() <= sp->capMaterialId)
    job.materials.resize(sp->capMaterialId + 1, job.materials.empty() ? render::Material{} : job.materials.back());
  job.materials[sp->capMaterialId] = sp->capMaterial;
  if (const auto* choice = w.world.tryGet<MaterialChoice>(target)) {
    job.hasMaterialChoice = true;
    job.materialChoice = choice->index;
  }
  return true;
}

SplitEvent SplitSystem::commit(SplitWorld& w, Pending& pending, uint64_t tick) {
  const double start = nowMilliseconds();
  workers().wait(*pending.task);
  const double waited = nowMilliseconds() - start;
  const SplitJob& job = *pending.job;
  SplitOutcome& outcome = pending.task->outcome;
  SplitEvent ev;
  ev.tick = tick;
  ev.preparedTick = job.preparedTick;
  ev.original = job.request.target;
  ev.originalName = job.targetName;
  ev.parentMass = job.parent.mass;
  ev.weldKnown = pending.weldKnown;
  ev.partsKnown = pending.partsKnown;
  ev.times.prepare = pending.prepareMilliseconds;
  ev.times.wait = waited;
  ev.times.compute = outcome.times;
  ev.estimatedWorkerMilliseconds = job.estimatedWorkerMilliseconds;

  ev.openChains = outcome.openChains;
  ev.posedVolume = outcome.posedVolume;
  ev.piecesVolume = outcome.piecesVolume;
  // What compute worked out for the source is kept whatever happens next.
  if (job.mesh && (outcome.sourceWeld || outcome.sourceParts)) {
    MeshKnowledge::Entry& k = knowledge_.remember(job.mesh);
    if (outcome.sourceWeld) k.weld = outcome.sourceWeld;
    if (outcome.sourceParts) k.parts = outcome.sourceParts;
  }
  auto finish = [&](geometry::SplitStatus status, const std::string& message) {
    ev.status = status;
    ev.message = message;
    if (status != geometry::SplitStatus::Ok && status != geometry::SplitStatus::PlaneMissesMesh)
      log::warning("cleave", "split of %s (entity %u) at tick %llu kept whole: %s",
                   ev.originalName.empty() ? "an object" : ev.originalName.c_str(), ev.original.index,
                   static_cast<unsigned long long>(tick), message.c_str());
    ev.times.commit = nowMilliseconds() - start - waited;
    return ev;
  };
  if (outcome.status != geometry::SplitStatus::Ok) {
    if (outcome.status != geometry::SplitStatus::PlaneMissesMesh && !failureDumpDirectory_.empty() && job.mesh)
      writeFailureCase(failureDumpDirectory_, job.targetName, job.preparedTick, job.request.target, *job.mesh,
                       job.model, job.plane, geometry::toString(outcome.status), outcome.message);
    return finish(outcome.status, outcome.message);
  }
  const ecs::Entity target = job.request.target;
  if (!w.world.alive(target) || !w.world.has<Splitable>(target))
    return finish(geometry::SplitStatus::InvalidInput, "the target was gone before its pieces were committed");
  if (job.skinned() && !w.world.has<SkinnedMesh>(target))
    return finish(geometry::SplitStatus::InvalidInput, "the target lost its skin before its pieces were committed");
  if (!hierarchyUnchanged(w.world, job))
    return finish(geometry::SplitStatus::InvalidInput, "a part of the target changed before its pieces were committed");
  if (!job.settings.handler.empty()) {
    const auto it = handlers_.find(job.settings.handler);
    if (it == handlers_.end())
      return finish(geometry::SplitStatus::InvalidInput, "no split handler named '" + job.settings.handler + "'");
    if (it->second(job, outcome) == HandlerDecision::KeepOriginal)
      return finish(geometry::SplitStatus::Ok, "the custom handler kept the original");
    for (const PieceSpec& p : outcome.pieces)
      if (!p.mesh)
        return finish(geometry::SplitStatus::InvalidInput, "the custom handler gave a piece without a mesh");
    for (const PieceSpec& p : outcome.pieces)
      for (const HierarchyChildSpec& child : p.children)
        if (!child.mesh || child.part >= job.hierarchyParts.size())
          return finish(geometry::SplitStatus::InvalidInput, "the custom handler gave a child part without a mesh");
  }
  commitPieces(w, job, outcome, ev);
  return finish(geometry::SplitStatus::Ok, {});
}

namespace {

// The components every piece gets, then those of its kind.
void addPieceComponents(PieceCommit& c, const PieceSpec& spec, const PieceKindStrategy& kind, ecs::Entity e,
                        const ecs::Transform& transform, MeshRenderer renderer, const glm::dvec3& velocity) {
  c.commands.add<ecs::Transform>(e, transform);
  c.commands.add<ecs::WorldTransform>(e, ecs::WorldTransform{ecs::localMatrix(transform)});
  c.commands.add<ecs::Name>(e, ecs::Name{spec.name});
  c.commands.add<MeshRenderer>(e, std::move(renderer));
  MassInfo info;
  info.mass = spec.mass;
  info.volume = spec.volume;
  info.density = spec.volume > 0.0 ? spec.mass / spec.volume : 0.0;
  info.closed = spec.closed;
  c.commands.add<MassInfo>(e, info);
  SplitOrigin so;
  so.parent = c.job.request.target;
  so.parentId = toUserData(c.job.request.target);
  so.generation = c.job.depth;
  so.tick = c.ev.tick;
  so.retirement = c.job.settings.retirement;
  c.commands.add<SplitOrigin>(e, so);
  if (kind.hasBody()) c.commands.add<PieceMotion>(e, PieceMotion{});
  if (c.job.hasMaterialChoice) c.commands.add<MaterialChoice>(e, MaterialChoice{c.job.materialChoice});
  // A piece drawn with its skin (KeepAnimating, or debris a handler made of a ragdoll piece): the
  // copy of the animator keeps playing in the body's frame.
  if (!kind.skinnedByBones() && c.skin && !spec.mesh->joints.empty()) c.commands.add<SkinnedMesh>(e, *c.skin);
  kind.addComponents(c, spec, e, velocity);
}

}  // namespace

void SplitSystem::commitPiece(PieceCommit& c, PieceSpec& spec) {
  const ecs::Entity e = c.commands.create();
  const glm::dvec3 velocity = c.m.velocity(spec);
  ecs::Transform transform;
  transform.position = glm::vec3(c.m.position(spec.frame.position));
  transform.rotation = glm::quat(c.m.rotation(spec.frame.rotation));
  transform.scale = glm::vec3(1.f);
  MeshRenderer renderer;
  renderer.source = spec.mesh;
  renderer.materials = c.job.materials;
  renderer.meshOffset = glm::mat4(spec.frame.meshOffset);
  RigidBody rb;
  const double shapeStart = nowMilliseconds();
  // Its body (or bones); a piece nothing could hold falls as debris.
  if (!pieceKind(spec.kind).attach(c, spec, e, transform, renderer, rb, velocity)) spec.kind = PieceKind::Debris;
  const PieceKindStrategy& kind = pieceKind(spec.kind);
  c.ev.times.shapes += nowMilliseconds() - shapeStart;
  if (c.w.renderer) {
    const double uploadStart = nowMilliseconds();
    const bool packed = spec.packed && spec.packedFrom == spec.mesh.get();
    renderer.gpu = (packed ? c.w.renderer->uploadPacked(*spec.packed) : c.w.renderer->uploadMesh(*spec.mesh)).valueOr({});
    c.ev.times.uploads += nowMilliseconds() - uploadStart;
  }
  addPieceComponents(c, spec, kind, e, transform, std::move(renderer), velocity);
  if (kind.hasBody()) {
    c.commands.add<RigidBody>(e, rb);
    // The cells of a shattered posed skinned mesh are final: the pose may pass through itself at the
    // joints, and a cell cut from such a surface does not keep its mass exactly when cut again.
    const bool finalCell = c.job.skinned() && c.job.request.shatter;
    if (c.job.depth < c.job.settings.maxDepth && !finalCell) {
      c.commands.add<Splitable>(e, c.job.settings);
      if (spec.parts) c.commands.add<ColliderParts>(e, ColliderParts{spec.parts});
      if (spec.weld || spec.parts) {  // known when the piece is cut: no weld, no decomposition
        MeshKnowledge::Entry& k = knowledge_.remember(spec.mesh);
        k.weld = spec.weld;
        k.parts = spec.parts;
      }
    }
  }
  if (c.job.hierarchy()) addHierarchyChildren(c, spec, e, transform);
  c.ev.pieces.push_back(e);
  c.ev.capLoops.push_back(spec.capLoops);
  c.ev.kinds.push_back(spec.kind);
  c.ev.colliderFit.push_back(spec.volume > 0.0 && kind.hasBody() ? spec.colliderVolume / spec.volume : 0.0);
  c.ev.piecesMass += spec.mass;
}

void SplitSystem::commitPieces(SplitWorld& w, const SplitJob& job, SplitOutcome& outcome, SplitEvent& ev) {
  Scratch& s = *scratch_;
  const ecs::Entity target = job.request.target;
  PieceCommit c{w, job, commandsFor(s.commands, s.commandsWorld, w.world), ParentMoved{}, nullptr, ev, activations_,
                budget_.settings().maxActivationsPerTick};
  c.m.now = motionOf(w, target);
  c.m.motion = motionBetween(job.parent, c.m.now);
  c.m.moved = c.m.motion != glm::dmat4(1.0);
  c.m.turn = glm::dmat3(c.m.motion);
  if (job.skinned()) c.skin = w.world.tryGet<SkinnedMesh>(target);
  for (PieceSpec& spec : outcome.pieces) commitPiece(c, spec);
  // A persistent splitter does not cut the pieces of its own cut again during this pass.
  if (auto* blade = w.world.tryGet<Splitter>(job.request.splitter);
      blade && blade->lifetime == SplitterLifetime::Persistent) {
    std::erase(blade->passing, toUserData(target));
    for (ecs::Entity piece : ev.pieces) blade->passing.push_back(toUserData(piece));
  }
  // Frozen pieces that rested on the original thaw (piece_budget.h).
  if (const auto* rb = w.world.tryGet<RigidBody>(target)) pieces_.disturb(w.physics, rb->body);
  // The original goes (its subtree with it), and its hooks free what it held; the pieces carry
  // copies of its parts.
  if (job.hierarchy()) {
    c.commands.destroyRecursive(target);
  } else {
    c.commands.destroy(target);
  }
  totalPieces_ += ev.pieces.size();
}

}  // namespace cleave::components
