#include "components/split_system.h"
#include "components/skinned.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <span>
#include <unordered_map>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/ecs/command_buffer.h"
#include "engine/ecs/hierarchy.h"
#include "engine/geometry/convex_hull.h"
#include "engine/geometry/mass_properties.h"
#include "engine/geometry/primitives.h"

namespace cleave::components {

namespace {

double nowMs() {
  using namespace std::chrono;
  return duration<double, std::milli>(steady_clock::now().time_since_epoch()).count();
}

}  // namespace

BodyFrame bodyFrameFor(const geometry::MassProperties& props, double mass, const glm::dmat4& model) {
  BodyFrame f;
  f.position = props.centerOfMass;
  const double scale = props.volume > 0.0 ? mass / props.volume : 0.0;
  const geometry::PrincipalInertia principal = geometry::principalInertia(props.inertia * scale);
  f.rotation = glm::normalize(glm::quat_cast(principal.axes));
  // A piece must never get zero inertia (a sliver): floor each moment at a small share of the largest.
  const double largest = std::max({principal.moments.x, principal.moments.y, principal.moments.z, 1e-12});
  f.moments = glm::max(principal.moments, glm::dvec3(largest * 1e-3));
  const glm::dmat4 bodyToWorld = glm::translate(glm::dmat4(1.0), f.position) * glm::mat4_cast(f.rotation);
  f.meshOffset = glm::inverse(bodyToWorld) * model;
  return f;
}

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

std::vector<glm::vec3> transformedPoints(const geometry::MeshData& mesh, const glm::dmat4& m) {
  std::vector<glm::vec3> points;
  points.reserve(mesh.positions.size());
  for (const glm::vec3& p : mesh.positions) points.push_back(glm::vec3(m * glm::dvec4(p, 1.0)));
  return points;
}

namespace {

// Collider choice: is the closed mesh convex enough that its convex hull is a faithful collider?
// The hull of the points extreme along 64 spread directions lies inside the true hull; when even
// that inscribed hull exceeds the mesh volume by more than `slack`, the mesh has a real concavity.
// A concavity smaller than the slack is filled by the hull collider, by design. Cheap: 64 passes
// over the points and a hull of at most 64 points.
bool nearlyConvex(const geometry::MeshData& mesh, double slack = 0.03) {
  const size_t n = mesh.positions.size();
  if (n < 4 || mesh.indices.size() < 12) return false;
  const geometry::MassProperties props = geometry::computeMassProperties(mesh, glm::dmat4(1.0));
  if (!props.closed || !(props.volume > 0.0)) return false;
  constexpr int kDirections = 64;
  std::vector<uint32_t> extreme;
  extreme.reserve(kDirections);
  const double golden = 3.14159265358979323846 * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < kDirections; ++i) {
    const double z = 1.0 - 2.0 * (double(i) + 0.5) / double(kDirections);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const glm::dvec3 dir(r * std::cos(golden * i), r * std::sin(golden * i), z);
    uint32_t best = 0;
    double bestDot = -std::numeric_limits<double>::infinity();
    for (uint32_t v = 0; v < n; ++v) {
      const double d = glm::dot(dir, glm::dvec3(mesh.positions[v]));
      if (d > bestDot) {
        bestDot = d;
        best = v;
      }
    }
    extreme.push_back(best);
  }
  std::sort(extreme.begin(), extreme.end());
  extreme.erase(std::unique(extreme.begin(), extreme.end()), extreme.end());
  std::vector<glm::dvec3> points;
  points.reserve(extreme.size());
  for (uint32_t v : extreme) points.push_back(glm::dvec3(mesh.positions[v]));
  const geometry::ConvexHull hull = geometry::computeConvexHull(std::span<const glm::dvec3>(points));
  if (hull.status != geometry::HullStatus::Ok) return false;
  const geometry::MassProperties hullProps =
      geometry::computeMassProperties(std::span<const glm::dvec3>(hull.positions), hull.indices);
  return hullProps.volume <= props.volume * (1.0 + slack);
}

// Our own convex decomposition for colliders: cut the piece through its centre along the longest
// extent of its bounds, recursively, until every part is convex or the depth runs out.
void decompose(geometry::IMeshSplitter& splitter, const geometry::MeshData& mesh, int depth,
               std::vector<physics::ConvexPart>& parts) {
  if (mesh.positions.size() < 4) return;
  if (depth <= 0 || nearlyConvex(mesh)) {
    physics::ConvexPart part;
    part.points = mesh.positions;
    parts.push_back(std::move(part));
    return;
  }
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const auto& p : mesh.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const glm::vec3 extent = hi - lo;
  int axis = 0;
  if (extent.y > extent[axis]) axis = 1;
  if (extent.z > extent[axis]) axis = 2;
  geometry::Plane plane;
  plane.normal = glm::dvec3(0.0);
  plane.normal[axis] = 1.0;
  plane.offset = 0.5 * (double(lo[axis]) + double(hi[axis]));
  geometry::MeshContainer container;
  if (container.setMesh(mesh) != geometry::SplitStatus::Ok) return;
  geometry::SplitOptions options;
  options.computeMass = false;
  options.separateIslands = true;
  geometry::SplitResult result;
  if (splitter.split(container, plane, options, result) != geometry::SplitStatus::Ok) {
    physics::ConvexPart part;
    part.points = mesh.positions;
    parts.push_back(std::move(part));
    return;
  }
  for (const auto& piece : result.pieces) decompose(splitter, piece.mesh, depth - 1, parts);
}

// Writes the mesh of a failed split in cut space (an OBJ with the plane in its header) so the case
// can be reproduced with cleave-split or a unit test.
void writeFailureCase(const std::string& directory, const std::string& name, uint64_t tick,
                      ecs::Entity target, const geometry::MeshData& mesh, const glm::dmat4& model,
                      const geometry::Plane& plane, const char* status, const std::string& message) {
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  const std::string path = (std::filesystem::path(directory) /
                            ("split_failure_tick" + std::to_string(tick) + "_e" +
                             std::to_string(target.index) + ".obj")).string();
  std::ofstream out(path);
  if (!out) return;
  out.precision(17);
  out << "# split failure: " << (name.empty() ? "unnamed" : name) << ", tick " << tick << ", " << status
      << ": " << message << "\n";
  out << "# plane (cut space = world, after the model matrix): normal " << plane.normal.x << " " << plane.normal.y << " "
      << plane.normal.z << " offset " << plane.offset << "\n";
  // Vertices in mesh space exactly as stored (floats print exactly with 9 digits), and the model
  // matrix (column-major) that takes them to cut space, so the failing case replays bit for bit.
  out << "# model";
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) out << " " << float(model[c][r]);
  out << "\n";
  out.precision(9);
  for (const glm::vec3& p : mesh.positions) out << "v " << p.x << " " << p.y << " " << p.z << "\n";
  for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
    out << "f " << mesh.indices[i] + 1 << " " << mesh.indices[i + 1] + 1 << " " << mesh.indices[i + 2] + 1 << "\n";
  std::fprintf(stderr, "cleave: failed split written to %s\n", path.c_str());
}

}  // namespace

struct SplitSystem::Scratch {
  geometry::MeshContainer container;
  std::unique_ptr<geometry::IMeshSplitter> concave = geometry::makeConcaveSplitter();
  std::unique_ptr<geometry::IMeshSplitter> convex = geometry::makeConvexSplitter();
  geometry::SplitResult result;
  // Structural changes of the current batch; made for the world of the first call.
  std::unique_ptr<ecs::CommandBuffer> commands;
  ecs::World* commandsWorld = nullptr;
  std::vector<ecs::Entity> doomed;  // entities the batch destroys: their resources go first
  std::vector<SplitRequest> pending;
  uint32_t activationsThisTick = 0;
  // Welds of the meshes the system has cut or made, by mesh: a mesh cut again (every piece, and an
  // authored mesh that many objects share) is not welded again. An entry is valid while its mesh
  // lives (the weak pointer still points at it); dead entries are dropped when the table grows.
  struct KnownWeld {
    std::weak_ptr<const geometry::MeshData> mesh;
    geometry::MeshWeld weld;
  };
  std::unordered_map<const geometry::MeshData*, KnownWeld> welds;
  size_t weldsPruneAt = 64;

  const geometry::MeshWeld* knownWeld(const std::shared_ptr<const geometry::MeshData>& mesh) const {
    const auto it = welds.find(mesh.get());
    if (it == welds.end() || it->second.mesh.lock() != mesh) return nullptr;
    return &it->second.weld;
  }
  void keepWeld(const std::shared_ptr<const geometry::MeshData>& mesh, geometry::MeshWeld weld) {
    if (welds.size() >= weldsPruneAt) {
      std::erase_if(welds, [](const auto& entry) { return entry.second.mesh.expired(); });
      weldsPruneAt = std::max<size_t>(64, 2 * welds.size());
    }
    KnownWeld& entry = welds[mesh.get()];
    entry.mesh = mesh;
    entry.weld = std::move(weld);
  }
};

SplitSystem::SplitSystem(SplitBudgetSettings budget)
    : budget_(budget), scratch_(std::make_unique<Scratch>()) {}
SplitSystem::~SplitSystem() = default;

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
  for (ecs::Entity e : scratch_->doomed) releaseEntityResources(w, e);
  scratch_->doomed.clear();
  if (scratch_->commands && scratch_->commandsWorld == &w.world) w.world.apply(*scratch_->commands);
}

void SplitSystem::registerHandler(const std::string& name, SplitHandler handler) {
  handlers_[name] = std::move(handler);
}

void SplitSystem::request(const SplitRequest& request) { budget_.enqueue(request); }

uint64_t toUserData(ecs::Entity e) { return (uint64_t(e.generation) << 32) | uint64_t(e.index); }

ecs::Entity fromUserData(uint64_t v) {
  ecs::Entity e;
  e.index = uint32_t(v & 0xffffffffu);
  e.generation = uint32_t(v >> 32);
  return e;
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

void releaseEntityResources(SplitWorld& w, ecs::Entity e) {
  if (auto* ragdoll = w.world.tryGet<Ragdoll>(e)) releaseRagdoll(w.physics, *ragdoll);
  if (auto* rb = w.world.tryGet<RigidBody>(e)) {
    w.physics.destroyBody(rb->body);
    w.physics.destroyShape(rb->shape);
    rb->body = {};
    rb->shape = {};
  }
  if (auto* mr = w.world.tryGet<MeshRenderer>(e)) {
    if (w.renderer) w.renderer->destroyMesh(mr->gpu);
    mr->gpu = {};
  }
  if (auto* sp = w.world.tryGet<Splitter>(e)) {
    w.physics.destroyTrigger(sp->trigger);
    sp->trigger = {};
  }
}

namespace {

// Creates a collider for a mesh given in mesh space with the body frame's offset.
physics::ShapeId makeCollider(SplitWorld& w, geometry::IMeshSplitter& splitter,
                              const geometry::MeshData& mesh, const glm::dmat4& meshOffset,
                              ColliderMode mode, bool knownConvex, std::string* reason) {
  ColliderMode chosen = mode;
  // A piece of a convex mesh is convex (the intersection of two convex sets): no check needed.
  if (chosen == ColliderMode::Auto)
    chosen = knownConvex || nearlyConvex(mesh) ? ColliderMode::ConvexHull : ColliderMode::Compound;
  std::vector<glm::vec3> points = transformedPoints(mesh, meshOffset);
  if (chosen == ColliderMode::ConcaveMesh) {
    auto r = w.physics.createShape(physics::ShapeDef::concaveMesh(points, mesh.indices));
    if (r.ok()) return r.value();
    chosen = ColliderMode::ConvexHull;
  }
  if (chosen == ColliderMode::Compound) {
    geometry::MeshData bodySpace;
    bodySpace.positions = points;
    bodySpace.indices = mesh.indices;
    std::vector<physics::ConvexPart> parts;
    decompose(splitter, bodySpace, 3, parts);
    if (parts.size() > 1) {
      physics::ShapeDef def = physics::ShapeDef::compound(std::move(parts));
      def.maxHullVertices = 24;  // parts are small: a coarse hull each keeps building and contacts cheap
      auto r = w.physics.createShape(def);
      if (r.ok()) return r.value();
    }
  }
  physics::ShapeDef hullDef = physics::ShapeDef::convexHull(points);
  hullDef.maxHullVertices = 48;
  auto r = w.physics.createShape(hullDef);
  if (r.ok()) return r.value();
  if (reason) *reason = r.reason();
  return {};
}

}  // namespace

namespace {

// One Splitable on a parent cuts the meshes of its whole subtree together. The meshes are merged
// into the parent entity's space with their submesh material ids tagged by part:
// id = part * kPartStride + original id (part 0 is the parent's own mesh), and the caps get
// kMergedCapId. After the cut, the tags tell which triangles go back to which part.
constexpr uint32_t kPartStride = 64;
constexpr uint32_t kMergedCapId = kPartStride - 1;

struct HierarchyPart {
  ecs::Entity entity;
  const MeshRenderer* renderer = nullptr;
  glm::dmat4 toParent{1.0};  // the part's mesh space -> the parent entity's space
};

// Collects the parent's own mesh (if any) and the meshes of its descendants. Returns false when the
// subtree has no descendant with a mesh (the plain single-mesh path applies).
bool gatherParts(const ecs::World& world, ecs::Entity root, std::vector<HierarchyPart>& parts) {
  parts.clear();
  if (const auto* mr = world.tryGet<MeshRenderer>(root); mr && mr->source)
    parts.push_back({root, mr, glm::dmat4(mr->meshOffset)});
  size_t own = parts.size();
  struct Item {
    ecs::Entity entity;
    glm::dmat4 toParent;
    int depth;
  };
  std::vector<Item> stack;
  if (const auto* children = world.tryGet<ecs::Children>(root))
    for (auto it = children->entities.rbegin(); it != children->entities.rend(); ++it)
      stack.push_back({*it, glm::dmat4(1.0), 1});
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    if (!world.alive(item.entity) || item.depth > 64) continue;
    if (ecs::parentOf(world, item.entity) == ecs::kNullEntity) continue;
    if (world.has<RigidBody>(item.entity)) continue;  // a body of its own: an object of its own
    const auto* t = world.tryGet<ecs::Transform>(item.entity);
    const glm::dmat4 toParent = item.toParent * (t ? glm::dmat4(ecs::localMatrix(*t)) : glm::dmat4(1.0));
    if (const auto* mr = world.tryGet<MeshRenderer>(item.entity); mr && mr->source)
      parts.push_back({item.entity, mr, toParent * glm::dmat4(mr->meshOffset)});
    if (const auto* children = world.tryGet<ecs::Children>(item.entity))
      for (auto it = children->entities.rbegin(); it != children->entities.rend(); ++it)
        stack.push_back({*it, toParent, item.depth + 1});
  }
  return parts.size() > own && parts.size() < kPartStride;
}

// The merged mesh of the parts in the parent entity's space, material ids tagged by part.
geometry::MeshData mergeParts(const std::vector<HierarchyPart>& parts) {
  geometry::MeshData merged;
  for (size_t k = 0; k < parts.size(); ++k) {
    geometry::MeshData part = *parts[k].renderer->source;
    geometry::primitives::transform(part, glm::mat4(parts[k].toParent));
    if (part.submeshes.empty()) part.submeshes.push_back({0, uint32_t(part.indices.size()), 0});
    for (geometry::SubMesh& sub : part.submeshes)
      sub.materialId = uint32_t(k) * kPartStride + std::min(sub.materialId, kMergedCapId - 1);
    merged = merged.positions.empty() ? std::move(part) : geometry::primitives::merge(merged, part);
  }
  return merged;
}

// The triangles of `piece` whose tag says they belong to part `part` (and the caps, for `withCaps`),
// with the tags turned back into the part's own material ids (caps: capMaterialId).
geometry::MeshData extractPart(const geometry::MeshData& piece, uint32_t part, bool withCaps,
                               uint32_t capMaterialId) {
  std::vector<uint32_t> triangles;
  for (const geometry::SubMesh& sub : piece.submeshes) {
    const bool cap = sub.materialId == kMergedCapId;
    if (!(cap ? withCaps : sub.materialId / kPartStride == part)) continue;
    for (uint32_t i = 0; i < sub.indexCount / 3; ++i) triangles.push_back(sub.firstIndex / 3 + i);
  }
  geometry::MeshData out;
  if (triangles.empty()) return out;
  geometry::MeshContainer container;
  if (container.setMesh(piece) != geometry::SplitStatus::Ok) return out;
  container.extractTriangles(triangles, out);
  for (geometry::SubMesh& sub : out.submeshes)
    sub.materialId = sub.materialId == kMergedCapId ? capMaterialId : sub.materialId % kPartStride;
  return out;
}

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

bool makeDynamicBody(SplitWorld& w, ecs::Entity e, double density, ColliderMode collider,
                     std::string* error) {
  auto* t = w.world.tryGet<ecs::Transform>(e);
  std::vector<HierarchyPart> parts;
  const bool hierarchy = t && gatherParts(w.world, e, parts);
  auto* mr = w.world.tryGet<MeshRenderer>(e);
  if ((!hierarchy && (!mr || !mr->source)) || !t) {
    if (error) *error = "entity has no mesh or transform";
    return false;
  }
  // A parent with meshes below it: one body for the whole subtree, from the merged meshes.
  geometry::MeshData merged;
  if (hierarchy) merged = mergeParts(parts);
  const geometry::MeshData& source = hierarchy ? merged : *mr->source;
  const glm::dmat4 oldLocal(ecs::localMatrix(*t));
  const glm::dmat4 model = hierarchy ? oldLocal : oldLocal * glm::dmat4(mr->meshOffset);
  const geometry::MassProperties props = geometry::computeMassProperties(source, model);
  if (!(props.volume > 0.0)) {
    if (error) *error = "mesh encloses no volume";
    return false;
  }
  const double mass = density * props.volume;
  const BodyFrame frame = bodyFrameFor(props, mass, model);
  auto splitter = geometry::makeConcaveSplitter();
  std::string reason;
  const physics::ShapeId shape = makeCollider(w, *splitter, source, frame.meshOffset, collider,
                                               /*knownConvex=*/false, &reason);
  if (shape.isNull()) {
    if (error) *error = "no collider: " + reason;
    return false;
  }
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
    if (error) *error = body.reason();
    return false;
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
  }
  placeOnBody(w, e, def, body.value(), shape, mass, props, density);
  return true;
}

void SplitSystem::gatherTriggerRequests(SplitWorld& w, uint64_t tick) {
  for (const physics::TriggerEvent& ev : w.physics.triggerEvents()) {
    if (ev.kind == physics::TriggerEventKind::Stay) continue;
    const auto splitterUser = w.physics.triggerUserData(ev.trigger);
    const auto bodyUser = w.physics.bodyUserData(ev.body);
    if (!splitterUser || !bodyUser) continue;
    const ecs::Entity splitterEntity = fromUserData(*splitterUser);
    const ecs::Entity target = fromUserData(*bodyUser);
    if (!w.world.alive(splitterEntity) || !w.world.alive(target)) continue;
    auto* splitter = w.world.tryGet<Splitter>(splitterEntity);
    if (!splitter) continue;
    const bool persistent = splitter->lifetime == SplitterLifetime::Persistent;
    if (ev.kind == physics::TriggerEventKind::End) {
      // It left the blade: the next touch is a new pass.
      if (persistent) std::erase(splitter->passing, *bodyUser);
      continue;
    }
    if (!w.world.has<Splitable>(target)) continue;
    // A persistent splitter cuts an object once per pass: the pieces of its own cut appear touching
    // it (their caps lie on its plane) and are not cut again.
    if (persistent) {
      if (std::find(splitter->passing.begin(), splitter->passing.end(), *bodyUser) != splitter->passing.end())
        continue;
      splitter->passing.push_back(*bodyUser);
    }
    const auto* wt = w.world.tryGet<ecs::WorldTransform>(splitterEntity);
    if (!wt) continue;
    const glm::dmat4 m(wt->matrix);
    const glm::dvec3 origin(m[3]);
    const glm::dvec3 normal = glm::normalize(glm::transpose(glm::inverse(glm::dmat3(m))) * glm::dvec3(0, 1, 0));
    SplitRequest r;
    r.target = target;
    r.planeNormal = normal;
    r.planeOffset = glm::dot(normal, origin);
    r.splitter = splitterEntity;
    r.playerCaused = splitter->playerCaused;
    r.requestedTick = tick;
    budget_.enqueue(r);
    splitter->cuts++;
  }
  // One-tick splitters are gone after the step that reported their touches.
  ecs::CommandBuffer& commands = commandsFor(scratch_->commands, scratch_->commandsWorld, w.world);
  for (auto [e, splitter] : w.world.view<Splitter>()) {
    std::erase_if(splitter.passing, [&](uint64_t id) { return !w.world.alive(fromUserData(id)); });
    if (splitter.lifetime == SplitterLifetime::OneTick && w.physics.isTriggerSpent(splitter.trigger)) {
      commands.destroy(e);
      scratch_->doomed.push_back(e);
    }
  }
  flush(w);
}

void SplitSystem::activatePending(SplitWorld& w) {
  // Bodies woken here count against this tick's activations, so pieces created awake by this tick's
  // splits and the queued ones together stay within maxActivationsPerTick.
  const std::vector<uint64_t> keys = budget_.takeActivations();
  scratch_->activationsThisTick = uint32_t(keys.size());
  for (uint64_t key : keys) {
    physics::BodyId body;
    body.index = uint32_t(key & 0xffffffffu);
    body.generation = uint32_t(key >> 32);
    w.physics.activate(body);
  }
}

void SplitSystem::runSplits(SplitWorld& w, uint64_t tick, const glm::dvec3& cameraPosition) {
  events_.clear();
  budget_.setCostEstimator([&w, this](const SplitRequest& r) {
    const SplitBudgetSettings& settings = budget_.settings();
    double triangles = 0.0;
    if (const auto* mr = w.world.tryGet<MeshRenderer>(r.target); mr && mr->source)
      triangles = double(mr->source->indices.size() / 3);
    return settings.estimatedMillisecondsPerSplit + settings.estimatedMillisecondsPerTriangle * triangles;
  });
  budget_.runTick(
      tick, cameraPosition,
      [&](ecs::Entity e) { return w.world.alive(e) && w.world.has<Splitable>(e); },
      [&](ecs::Entity e) {
        const auto* t = w.world.tryGet<ecs::Transform>(e);
        return t ? glm::dvec3(t->position) : glm::dvec3(0.0);
      },
      [&](const SplitRequest& r) {
        SplitEvent ev = splitOne(w, r.target, r, tick);
        scratch_->container.release();  // do not keep the (doomed) target's mesh alive
        const bool ok = ev.status == geometry::SplitStatus::Ok ||
                        ev.status == geometry::SplitStatus::PlaneMissesMesh;
        events_.push_back(std::move(ev));
        return ok;
      },
      nowMs);
  budget_.setCostEstimator({});  // it refers to `w`, which only lives for this call
  // Structural changes after the iteration: pieces appear, originals go.
  flush(w);
}

SplitEvent SplitSystem::splitNow(SplitWorld& w, ecs::Entity target, const SplitRequest& request,
                                 uint64_t tick) {
  SplitEvent ev = splitOne(w, target, request, tick);
  scratch_->container.release();
  flush(w);
  return ev;
}

SplitEvent SplitSystem::splitOne(SplitWorld& w, ecs::Entity target, const SplitRequest& request,
                                 uint64_t tick) {
  const double start = nowMs();
  SplitEvent ev;
  ev.tick = tick;
  ev.original = target;
  if (const auto* n = w.world.tryGet<ecs::Name>(target)) ev.originalName = n->value;
  auto fail = [&](geometry::SplitStatus status, const std::string& message) {
    ev.status = status;
    ev.message = message;
    ev.milliseconds = nowMs() - start;
    if (status != geometry::SplitStatus::PlaneMissesMesh)
      std::fprintf(stderr, "cleave: split of %s (entity %u) at tick %llu kept whole: %s\n",
                   ev.originalName.empty() ? "an object" : ev.originalName.c_str(), target.index,
                   static_cast<unsigned long long>(tick), message.c_str());
    return ev;
  };
  const auto* mr = w.world.tryGet<MeshRenderer>(target);
  const auto* sp = w.world.tryGet<Splitable>(target);
  const auto* rb = w.world.tryGet<RigidBody>(target);
  const auto* t = w.world.tryGet<ecs::Transform>(target);
  std::vector<HierarchyPart> parts;
  const bool hierarchy = t && !w.world.has<SkinnedMesh>(target) && gatherParts(w.world, target, parts);
  if ((!hierarchy && (!mr || !mr->source)) || !sp || !t)
    return fail(geometry::SplitStatus::InvalidInput, "target has no mesh, Splitable or Transform");
  // A parent with meshes below it is cut as one merged mesh in its own space (see gatherParts).
  geometry::MeshData merged;
  if (hierarchy) merged = mergeParts(parts);
  const geometry::MeshData& source = hierarchy ? merged : *mr->source;
  const glm::mat4 sourceOffset = hierarchy ? glm::mat4(1.f) : mr->meshOffset;

  // The parent's motion and frame (the body is authoritative when there is one).
  glm::dvec3 parentCom(t->position);
  glm::dquat parentRot(t->rotation);
  glm::dvec3 v(0.0), omega(0.0);
  double parentMass = 0.0;
  if (rb && w.physics.isValid(rb->body)) {
    const auto state = w.physics.bodyState(rb->body);
    if (state) {
      parentCom = glm::dvec3(state->transform.position);
      parentRot = glm::dquat(state->transform.rotation);
      v = glm::dvec3(state->linearVelocity);
      omega = glm::dvec3(state->angularVelocity);
      parentMass = state->mass;
    }
  }
  if (const auto* mi = w.world.tryGet<MassInfo>(target)) parentMass = mi->mass;
  ev.parentMass = parentMass;
  const glm::dmat4 entityToWorld = glm::translate(glm::dmat4(1.0), parentCom) * glm::mat4_cast(parentRot) *
                                   glm::scale(glm::dmat4(1.0), glm::dvec3(t->scale));
  const glm::dmat4 model = entityToWorld * glm::dmat4(sourceOffset);

  Scratch& s = *scratch_;
  std::string message;
  const double setupStart = nowMs();
  const geometry::MeshWeld* known = hierarchy ? nullptr : s.knownWeld(mr->source);  // reset below if stale
  ev.weldKnown = known != nullptr;
  // The container shares the renderer's mesh (no copy); a merged hierarchy mesh is copied. A kept
  // weld that no longer fits the mesh (its arrays were changed in place, which meshes must not be)
  // is dropped and the mesh welded anew.
  geometry::SplitStatus set = hierarchy ? s.container.setMesh(source, &message)
                                        : s.container.setMesh(mr->source, known, &message);
  if (set != geometry::SplitStatus::Ok && known) {
    s.welds.erase(mr->source.get());
    known = nullptr;
    ev.weldKnown = false;
    set = s.container.setMesh(mr->source, nullptr, &message);
  }
  if (set != geometry::SplitStatus::Ok) return fail(geometry::SplitStatus::InvalidInput, message);
  if (!known && !hierarchy) {
    geometry::MeshWeld weld;
    s.container.copyWeld(weld);
    s.keepWeld(mr->source, std::move(weld));
  }
  // A skinned target is cut in its current pose: the cut space is the skinned mesh in the world.
  const auto* skin = w.world.tryGet<SkinnedMesh>(target);
  if (skin && (hierarchy || skin->jointMatrices.empty() || source.joints.empty())) skin = nullptr;
  if (skin) {
    if (s.container.setSkinningPose(skin->jointMatrices, glm::mat4(model), &message) != geometry::SplitStatus::Ok)
      return fail(geometry::SplitStatus::InvalidInput, message);
  } else {
    s.container.setTransform(glm::mat4(model));
  }
  ev.setupMilliseconds = nowMs() - setupStart;
  geometry::SplitOptions options;
  options.cap = sp->cap;
  options.capMaterialId = hierarchy ? kMergedCapId : sp->capMaterialId;
  options.uvMode = sp->capUvMode;
  options.uvPerMetre = sp->capUvPerMetre;
  options.atlasRect = sp->capAtlasRect;
  options.uvPerBorder = sp->capUvPerBorder;
  // The parts of a hierarchy are usually disjoint meshes (a head above a body) that form one
  // object: each side stays one piece.
  options.separateIslands = sp->separateIslands && !hierarchy;
  const geometry::Plane plane{request.planeNormal, request.planeOffset};
  geometry::IMeshSplitter& splitter = sp->convexHint ? *s.convex : *s.concave;
  const double geometryStart = nowMs();
  const geometry::SplitStatus status = splitter.split(s.container, plane, options, s.result);
  ev.geometryMilliseconds = nowMs() - geometryStart;
  if (status != geometry::SplitStatus::Ok) {
    if (status != geometry::SplitStatus::PlaneMissesMesh && !failureDumpDirectory_.empty())
      writeFailureCase(failureDumpDirectory_, ev.originalName, tick, target, source, model, plane,
                       geometry::toString(status), s.result.message);
    return fail(status, s.result.message);
  }

  if (!sp->handler.empty()) {
    auto it = handlers_.find(sp->handler);
    if (it == handlers_.end())
      return fail(geometry::SplitStatus::InvalidInput, "no split handler named '" + sp->handler + "'");
    if (!it->second(w, target, request, s.result))
      return fail(geometry::SplitStatus::Ok, "the custom handler kept the original");
    ev.milliseconds = nowMs() - start;
    return ev;
  }

  double totalVolume = 0.0;
  for (const auto& piece : s.result.pieces) totalVolume += std::max(piece.mass.volume, 0.0);
  if (!(totalVolume > 0.0)) return fail(geometry::SplitStatus::InvalidInput, "pieces enclose no volume");
  const glm::dvec3 n = glm::normalize(request.planeNormal);

  const Splitable pieceSplitable = *sp;
  const auto* origin = w.world.tryGet<SplitOrigin>(target);
  const uint32_t depth = origin ? origin->generation + 1 : 1;
  const auto* name = w.world.tryGet<ecs::Name>(target);
  const auto* choice = w.world.tryGet<MaterialChoice>(target);

  std::vector<render::Material> materials = mr ? mr->materials : std::vector<render::Material>{};
  if (materials.size() <= sp->capMaterialId) {
    materials.resize(sp->capMaterialId + 1, materials.empty() ? render::Material{} : materials.back());
  }
  materials[sp->capMaterialId] = sp->capMaterial;

  ecs::CommandBuffer& commands = commandsFor(s.commands, s.commandsWorld, w.world);
  // Skinned targets share the parent's mass by posed volume whatever the mass mode: skinning does not
  // keep volume exactly, so density x posed volume would make the mass drift with the pose.
  const bool shareParentMass = sp->massMode == MassMode::KeepParentMass || (skin && parentMass > 0.0);
  std::vector<glm::dmat4> globals;  // ragdolls: world transforms of the joints in the cut pose
  if (skin && sp->skinnedPieces == SkinnedPieceMode::Ragdoll)
    posedJointGlobals(skin->asset->skeleton, skin->jointMatrices, model, globals);
  uint32_t k = 0;
  for (auto& piece : s.result.pieces) {
    const double volume = std::max(piece.mass.volume, 0.0);
    const double mass = shareParentMass ? parentMass * volume / totalVolume : sp->density * volume;
    const bool small = volume < sp->minPieceVolume;
    if (small && sp->smallPieces == SmallPieceMode::Remove) continue;
    const BodyFrame frame = bodyFrameFor(piece.mass, std::max(mass, 1e-9), model);
    const glm::dvec3 velocity = v + glm::cross(omega, frame.position - parentCom) +
                                n * (double(piece.side) * sp->splitImpulse);

    const ecs::Entity e = commands.create();
    // Skinned pieces: the posed mesh (mesh space) gives the collider; Bake pieces and small ones are
    // drawn from it too, the others keep their skin and a copy of the animator.
    SkinnedPieceMode skinMode = sp->skinnedPieces;
    geometry::MeshData posed;
    if (skin) {
      bakeSkin(piece.mesh, skin->jointMatrices, posed);
      if (small) skinMode = SkinnedPieceMode::Bake;
    }
    const bool keepSkin = skin && skinMode != SkinnedPieceMode::Bake;
    Ragdoll ragdoll;
    bool isRagdoll = false;
    if (keepSkin && skinMode == SkinnedPieceMode::Ragdoll) {
      std::vector<glm::vec3> worldPositions;
      worldPositions.reserve(posed.positions.size());
      for (const glm::vec3& p : posed.positions)
        worldPositions.push_back(glm::vec3(model * glm::dvec4(glm::dvec3(p), 1.0)));
      std::string reason;
      const double colliderStart = nowMs();
      isRagdoll = buildRagdoll(w, piece.mesh, worldPositions, piece.joints, skin->asset->skeleton, globals,
                               std::max(mass, 1e-6), v, omega, parentCom, toUserData(e), toUserData(e) | (1ull << 63),
                               ragdoll, &reason);
      ev.colliderMilliseconds += nowMs() - colliderStart;
      if (!isRagdoll) skinMode = SkinnedPieceMode::KeepAnimating;  // too few vertices for any bone
    }
    // Hierarchy: the piece entity draws the parent's part and the caps; each child part with
    // triangles on this side becomes a child entity (below). The collider covers them all.
    geometry::MeshData wholePiece;
    if (hierarchy) {
      wholePiece = std::move(piece.mesh);
      piece.mesh = extractPart(wholePiece, 0, true, sp->capMaterialId);
    }
    auto mesh = std::make_shared<geometry::MeshData>(keepSkin ? std::move(piece.mesh)
                                                              : skin ? std::move(posed) : std::move(piece.mesh));
    const geometry::MeshData& colliderMesh = hierarchy ? wholePiece : keepSkin ? posed : *mesh;
    // The piece's weld comes with it (kept below if the piece can be cut again), unless its vertices
    // changed: hierarchy parts are extracted again, and a baked skin may pose two vertices of one
    // bind position apart; or the split left it unknown.
    const bool weldKnown = !hierarchy && (keepSkin || !skin) && !piece.weld.positionIds.empty();
    MeshRenderer renderer;
    renderer.source = mesh;
    renderer.materials = materials;
    renderer.meshOffset = glm::mat4(frame.meshOffset);
    if (w.renderer) {
      const double uploadStart = nowMs();
      renderer.gpu = w.renderer->uploadMesh(*mesh);
      ev.uploadMilliseconds += nowMs() - uploadStart;
    }
    ecs::Transform transform;
    transform.position = glm::vec3(frame.position);
    transform.rotation = glm::quat(frame.rotation);
    transform.scale = glm::vec3(1.f);

    bool debris = small;
    physics::ShapeId shape;
    physics::BodyId body;
    if (isRagdoll) {
      // The entity frame is the anchor bone's body frame; joint matrices are relative to it.
      const RagdollBone& anchor = ragdoll.bones[ragdoll.anchor];
      const physics::BodyTransform at = *w.physics.bodyTransform(anchor.body);
      transform.position = at.position;
      transform.rotation = at.rotation;
      renderer.meshOffset = glm::mat4(1.f);
      shape = anchor.shape;
      body = anchor.body;
      const glm::dmat4 toAnchor =
          glm::inverse(glm::translate(glm::dmat4(1.0), glm::dvec3(at.position)) * glm::mat4_cast(glm::dquat(at.rotation))) *
          model;
      SkinnedMesh pieceSkin = *skin;
      for (glm::mat4& m : pieceSkin.jointMatrices) m = glm::mat4(toAnchor * glm::dmat4(m));
      commands.add<SkinnedMesh>(e, std::move(pieceSkin));
      commands.add<Ragdoll>(e, std::move(ragdoll));
    }
    if (!debris && !isRagdoll) {
      std::string reason;
      const double colliderStart = nowMs();
      shape = makeCollider(w, *s.concave, colliderMesh, frame.meshOffset, sp->collider,
                           sp->convexHint, &reason);
      ev.colliderMilliseconds += nowMs() - colliderStart;
      if (shape.isNull()) debris = true;  // a flat sliver: no hull can hold it
    }
    if (!debris && !isRagdoll) {
      physics::BodyDef def;
      def.shape = shape;
      def.mass = float(std::max(mass, 1e-6));
      def.position = transform.position;
      def.rotation = transform.rotation;
      def.linearVelocity = glm::vec3(velocity);
      def.angularVelocity = glm::vec3(omega);
      def.localInertia = glm::vec3(frame.moments);
      def.userData = toUserData(e);
      const bool awakeNow = s.activationsThisTick < budget_.settings().maxActivationsPerTick;
      def.startAwake = awakeNow;
      auto created = w.physics.createBody(def);
      if (created.ok()) {
        body = created.value();
        if (awakeNow) {
          s.activationsThisTick++;
        } else {
          budget_.queueActivation((uint64_t(body.generation) << 32) | body.index);
        }
      } else {
        w.physics.destroyShape(shape);
        shape = {};
        debris = true;
      }
    }
    commands.add<ecs::Transform>(e, transform);
    commands.add<ecs::WorldTransform>(e, ecs::WorldTransform{ecs::localMatrix(transform)});
    commands.add<ecs::Name>(e, ecs::Name{(name ? name->value : std::string("piece")) + "/" +
                                         (piece.side > 0 ? "a" : "b") + std::to_string(k)});
    commands.add<MeshRenderer>(e, std::move(renderer));
    MassInfo info;
    info.mass = mass;
    info.volume = volume;
    info.density = volume > 0.0 ? mass / volume : 0.0;
    info.closed = piece.mass.closed;
    commands.add<MassInfo>(e, info);
    SplitOrigin so;
    so.parent = target;
    so.parentId = toUserData(target);
    so.generation = depth;
    commands.add<SplitOrigin>(e, so);
    if (choice) commands.add<MaterialChoice>(e, *choice);
    // KeepAnimating: the copy of the animator keeps playing in the body's frame.
    if (keepSkin && !isRagdoll) commands.add<SkinnedMesh>(e, *skin);
    if (debris) {
      Debris d;
      d.velocity = glm::vec3(velocity);
      d.angularVelocity = glm::vec3(omega);
      commands.add<Debris>(e, d);
    } else {
      commands.add<RigidBody>(e, RigidBody{body, shape});
      if (depth < sp->maxDepth) {
        commands.add<Splitable>(e, pieceSplitable);
        if (weldKnown) s.keepWeld(mesh, std::move(piece.weld));
      }
    }
    if (hierarchy) {
      std::vector<ecs::Entity> children;
      for (size_t part = 0; part < parts.size(); ++part) {
        if (parts[part].entity == target) continue;
        geometry::MeshData childMesh = extractPart(wholePiece, uint32_t(part), false, sp->capMaterialId);
        if (childMesh.indices.empty()) continue;
        const ecs::Entity child = commands.create();
        auto childSource = std::make_shared<geometry::MeshData>(std::move(childMesh));
        MeshRenderer childRenderer;
        childRenderer.source = childSource;
        childRenderer.materials = parts[part].renderer->materials;
        childRenderer.meshOffset = glm::mat4(frame.meshOffset);  // merged space -> the piece's frame
        childRenderer.visible = parts[part].renderer->visible;
        if (w.renderer) {
          const double uploadStart = nowMs();
          childRenderer.gpu = w.renderer->uploadMesh(*childSource);
          ev.uploadMilliseconds += nowMs() - uploadStart;
        }
        const auto* childName = w.world.tryGet<ecs::Name>(parts[part].entity);
        commands.add<ecs::Transform>(child, ecs::Transform{});
        commands.add<ecs::WorldTransform>(child, ecs::WorldTransform{ecs::localMatrix(transform)});
        commands.add<ecs::Name>(child, ecs::Name{(childName ? childName->value : std::string("part")) + "/" +
                                                 (piece.side > 0 ? "a" : "b") + std::to_string(k)});
        commands.add<ecs::Parent>(child, ecs::Parent{e});
        commands.add<MeshRenderer>(child, std::move(childRenderer));
        children.push_back(child);
      }
      commands.add<ecs::Children>(e, ecs::Children{std::move(children)});
    }
    ev.pieces.push_back(e);
    ev.capLoops.push_back(piece.capLoops);
    ev.piecesMass += mass;
    ++k;
  }
  // A persistent splitter does not cut the pieces of its own cut again during this pass.
  if (auto* blade = w.world.tryGet<Splitter>(request.splitter);
      blade && blade->lifetime == SplitterLifetime::Persistent) {
    std::erase(blade->passing, toUserData(target));
    for (ecs::Entity piece : ev.pieces) blade->passing.push_back(toUserData(piece));
  }
  if (hierarchy) {
    // The original subtree goes with its GPU meshes; the pieces carry copies of its parts.
    for (const HierarchyPart& part : parts)
      if (part.entity != target) s.doomed.push_back(part.entity);
    commands.destroyRecursive(target);
  } else {
    commands.destroy(target);
  }
  s.doomed.push_back(target);
  totalPieces_ += ev.pieces.size();
  ev.milliseconds = nowMs() - start;
  return ev;
}

void syncTransformsFromBodies(SplitWorld& w) {
  for (auto [e, rb, t] : w.world.view<RigidBody, ecs::Transform>()) {
    const auto bt = w.physics.bodyTransform(rb.body);
    if (!bt) continue;
    t.position = bt->position;
    t.rotation = bt->rotation;
  }
  ecs::updateWorldTransforms(w.world);
}

void submitMeshes(SplitWorld& w) {
  if (!w.renderer) return;
  for (auto [e, mr, wt] : w.world.view<MeshRenderer, ecs::WorldTransform>()) {
    if (!mr.visible || !mr.gpu.valid() || mr.materials.empty()) continue;
    // Skinned meshes draw in their current pose (GPU skinning).
    if (const auto* skin = w.world.tryGet<SkinnedMesh>(e); skin && !skin->jointMatrices.empty()) {
      w.renderer->submitSkinned(mr.gpu, wt.matrix * mr.meshOffset, skin->jointMatrices, mr.materials);
      continue;
    }
    w.renderer->submit(mr.gpu, wt.matrix * mr.meshOffset, mr.materials);
  }
}

void updateDebris(SplitWorld& w, float dt) {
  ecs::CommandBuffer commands(w.world);
  std::vector<ecs::Entity> doomed;
  const glm::vec3 gravity = w.physics.gravity();
  for (auto [e, d, t] : w.world.view<Debris, ecs::Transform>()) {
    d.velocity += gravity * dt;
    t.position += d.velocity * dt;
    const float angle = glm::length(d.angularVelocity) * dt;
    if (angle > 0.f) t.rotation = glm::normalize(glm::angleAxis(angle, glm::normalize(d.angularVelocity)) * t.rotation);
    d.secondsLeft -= dt;
    if (d.secondsLeft <= 0.f || t.position.y < -50.f) {
      commands.destroy(e);
      doomed.push_back(e);
    }
  }
  for (ecs::Entity e : doomed) releaseEntityResources(w, e);
  w.world.apply(commands);
}

}  // namespace cleave::components
