// SPDX-License-Identifier: MIT
// Reading a scene file into its descriptors (scene_desc.h): every field checked for its type, range
// and the names it may take, the first error reported with its line and JSON pointer.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include <glm/gtc/matrix_transform.hpp>

#include "cleave/assets/mesh_io.h"
#include "cleave/components/scene_components.h"
#include "cleave/components/scene_desc.h"
#include "cleave/geometry/primitives.h"

namespace cleave::components::scene_json {

namespace {

bool readTransform(Reader& rd, const Node& parent, ecs::Transform& t, bool allowScale) {
  if (!parent.has("transform")) return true;
  const Node n = parent.child("transform");
  if (allowScale) {
    if (!rd.expectObject(n, {"position", "rotation", "scale"})) return false;
  } else if (!rd.expectObject(n, {"position", "rotation"})) {
    return false;
  }
  if (!rd.vec3(n, "position", t.position)) return false;
  if (n.has("rotation")) {
    const Node r = n.child("rotation");
    if (!rd.expectObject(r, {"quaternion", "euler_degrees"})) return false;
    if (r.has("quaternion") == r.has("euler_degrees"))
      return rd.fail(r, "give exactly one of 'quaternion' [w, x, y, z] or 'euler_degrees' [x, y, z]");
    if (r.has("quaternion")) {
      double q[4];
      if (!rd.vector(r.child("quaternion"), q, 4)) return false;
      const double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
      if (!(len > 1e-9)) return rd.fail(r.child("quaternion"), "the quaternion has zero length");
      t.rotation = glm::normalize(glm::quat(float(q[0]), float(q[1]), float(q[2]), float(q[3])));
    } else {
      double e[3];
      if (!rd.vector(r.child("euler_degrees"), e, 3)) return false;
      // Rotations about the world X, then Y, then Z axes.
      const glm::dquat qx = glm::angleAxis(glm::radians(e[0]), glm::dvec3(1, 0, 0));
      const glm::dquat qy = glm::angleAxis(glm::radians(e[1]), glm::dvec3(0, 1, 0));
      const glm::dquat qz = glm::angleAxis(glm::radians(e[2]), glm::dvec3(0, 0, 1));
      t.rotation = glm::quat(glm::normalize(qz * qy * qx));
    }
  }
  if (allowScale && n.has("scale")) {
    const Node s = n.child("scale");
    if (s->is_number()) {
      double v = 1.0;
      if (!rd.number(s, v)) return false;
      if (!(v > 0.0)) return rd.fail(s, "expected a scale > 0");
      t.scale = glm::vec3(float(v));
    } else if (!rd.vec3(n, "scale", t.scale, /*positive=*/true)) {
      return false;
    }
  }
  return true;
}

// ---------------------------------------------------------------------------------------------
// Mesh primitives: one table row per primitive names its fields (in the order they are read and
// checked), their defaults and limits, and the builder that makes the mesh of the values read.

struct PrimitiveField {
  enum Kind {
    Positive,
    Count,
    Extents
  };                          // a number > 0, a whole number in [min, max], 3 numbers > 0
  const char* key = nullptr;  // null ends a row's fields
  Kind kind = Positive;
  double value = 0.0;  // default of Positive and Count
  uint32_t minimum = 0, maximum = 0;
  glm::vec3 extents{0.f};  // default of Extents
};

constexpr size_t kMaxPrimitiveFields = 5;

// The values of a row's fields, by field slot (number[k] for Positive, count[k] for Count).
struct PrimitiveValues {
  double number[kMaxPrimitiveFields] = {};
  uint32_t count[kMaxPrimitiveFields] = {};
  glm::vec3 extents{0.f};
  float f(size_t k) const { return float(number[k]); }
};

struct PrimitiveRow {
  const char* name;
  PrimitiveField fields[kMaxPrimitiveFields];
  geometry::MeshData (*build)(const PrimitiveValues&);
  // A pair of fields where the first must be below the second (slots), or -1.
  int smaller = -1, larger = -1;
};

PrimitiveField positiveField(const char* key, double value) {
  return {key, PrimitiveField::Positive, value, 0, 0, {}};
}
PrimitiveField countField(const char* key, uint32_t value, uint32_t minimum, uint32_t maximum) {
  return {key, PrimitiveField::Count, double(value), minimum, maximum, {}};
}
PrimitiveField extentsField(const char* key, glm::vec3 value) {
  return {key, PrimitiveField::Extents, 0.0, 0, 0, value};
}

namespace P = geometry::primitives;
using V = PrimitiveValues;

const PrimitiveRow kPrimitives[] = {
    {"box",
     {extentsField("half_extents", glm::vec3(0.5f))},
     [](const V& v) { return P::box(v.extents); }},
    {"sphere",
     {positiveField("radius", 0.5), countField("segments", 32, 3, 1024),
      countField("rings", 16, 2, 1024)},
     [](const V& v) { return P::uvSphere(v.f(0), v.count[1], v.count[2]); }},
    {"ellipsoid",
     {extentsField("radii", glm::vec3(0.5f, 0.35f, 0.35f)), countField("segments", 32, 3, 1024),
      countField("rings", 16, 2, 1024)},
     [](const V& v) { return P::ellipsoid(v.extents, v.count[1], v.count[2]); }},
    {"cylinder",
     {positiveField("radius", 0.4), positiveField("height", 1.0),
      countField("segments", 32, 3, 1024)},
     [](const V& v) { return P::cylinder(v.f(0), v.f(1), v.count[2]); }},
    {"torus",
     {positiveField("major_radius", 0.5), positiveField("minor_radius", 0.2),
      countField("segments", 48, 3, 1024), countField("sides", 24, 3, 1024)},
     [](const V& v) { return P::torus(v.f(0), v.f(1), v.count[2], v.count[3]); },
     1,
     0},
    {"capsule",
     {positiveField("radius", 0.3), positiveField("height", 0.6),
      countField("segments", 24, 3, 1024), countField("rings", 12, 2, 1024)},
     [](const V& v) { return P::capsule(v.f(0), v.f(1), v.count[2], v.count[3]); }},
    {"comb",
     {countField("teeth", 2, 1, 256), positiveField("pitch", 0.2),
      positiveField("tooth_length", 0.6), positiveField("spine_height", 0.2),
      positiveField("depth", 0.3)},
     [](const V& v) { return P::combPrism(v.count[0], v.f(1), v.f(2), v.f(3), v.f(4)); }},
    {"star",
     {countField("points", 5, 3, 256), positiveField("outer_radius", 1.0),
      positiveField("inner_radius", 0.4), positiveField("height", 0.5)},
     [](const V& v) { return P::starPrism(v.count[0], v.f(1), v.f(2), v.f(3)); },
     2,
     1},
    {"tetrahedron",
     {positiveField("radius", 0.5)},
     [](const V& v) { return P::tetrahedron(v.f(0)); }},
    {"hollow_sphere",
     {positiveField("outer_radius", 0.5), positiveField("inner_radius", 0.4),
      countField("segments", 32, 3, 1024), countField("rings", 16, 2, 1024)},
     [](const V& v) { return P::hollowSphere(v.f(0), v.f(1), v.count[2], v.count[3]); },
     1,
     0},
};

// Reads one field into slot k (its default when absent).
bool readPrimitiveField(Reader& rd, const Node& n, const PrimitiveField& field, size_t k,
                        PrimitiveValues& v) {
  switch (field.kind) {
    case PrimitiveField::Positive:
      v.number[k] = field.value;
      return rd.number(n, field.key, v.number[k], true);
    case PrimitiveField::Count:
      v.count[k] = uint32_t(field.value);
      return rd.integer32(n, field.key, v.count[k], field.minimum, field.maximum);
    case PrimitiveField::Extents:
      v.extents = field.extents;
      return rd.vec3(n, field.key, v.extents, true);
  }
  return false;
}

// Reads the fields of `row` from n (defaults for those absent) and checks its limits.
bool readPrimitiveFields(Reader& rd, const Node& n, const PrimitiveRow& row, PrimitiveValues& v) {
  const char* allowed[kMaxPrimitiveFields + 1] = {"primitive"};
  size_t fieldCount = 0;
  while (fieldCount < kMaxPrimitiveFields && row.fields[fieldCount].key != nullptr) {
    allowed[fieldCount + 1] = row.fields[fieldCount].key;
    ++fieldCount;
  }
  if (!rd.expectObject(n, std::span<const char* const>(allowed, fieldCount + 1))) return false;
  for (size_t k = 0; k < fieldCount; ++k) {
    const PrimitiveField& field = row.fields[k];
    if (!readPrimitiveField(rd, n, field, k, v)) return false;
  }
  if (row.smaller >= 0 && !(v.number[row.smaller] < v.number[row.larger])) {
    const std::string smaller = row.fields[row.smaller].key, larger = row.fields[row.larger].key;
    return rd.fail(n.child(smaller), smaller + " must be below " + larger);
  }
  return true;
}

std::string primitiveNames() {
  std::string names;
  for (const PrimitiveRow& row : kPrimitives)
    names += (names.empty() ? "" : ", ") + std::string(row.name);
  return names;
}

bool readPrimitive(Reader& rd, const Node& n, EntityDesc& d) {
  std::string kind;
  if (!rd.string(n, "primitive", kind)) return false;
  for (const PrimitiveRow& row : kPrimitives) {
    if (kind != row.name) continue;
    PrimitiveValues values;
    if (!readPrimitiveFields(rd, n, row, values)) return false;
    d.mesh = row.build(values);
    if (kind == "box") {  // a static box gets a box collider
      d.isBox = true;
      d.boxHalfExtents = values.extents;
    }
    return true;
  }
  return rd.fail(n.child("primitive"),
                 "unknown primitive '" + kind + "' (expected one of: " + primitiveNames() + ")");
}

bool readMeshFile(Reader& rd, const Node& n, const std::string& baseDirectory, EntityDesc& d) {
  if (!rd.expectObject(n, {"file"})) return false;
  std::string file;
  if (!rd.string(n, "file", file)) return false;
  std::filesystem::path p(file);
  if (p.is_relative()) p = std::filesystem::path(baseDirectory) / p;
  assets::MeshReadResult r = assets::loadMesh(p.lexically_normal().string());
  if (!r.ok()) return rd.fail(n.child("file"), "cannot load the model: " + r.message);
  d.mesh = std::move(r.mesh);
  return true;
}

bool readMesh(Reader& rd, const Node& n, const std::string& baseDirectory, EntityDesc& d) {
  if (!n->is_object()) return rd.fail(n, std::string("expected an object, found ") + typeName(*n));
  if (n.has("primitive") == n.has("file"))
    return rd.fail(n, "give exactly one of 'primitive' (a name) or 'file' (a model path)");
  d.hasMesh = true;
  return n.has("file") ? readMeshFile(rd, n, baseDirectory, d) : readPrimitive(rd, n, d);
}

bool readSplitable(Reader& rd, const Node& n, EntityDesc& d) {
  if (n->is_boolean()) {
    d.splitable = n->get<bool>();
    return true;
  }
  if (!rd.expectObject(n, {"convex", "cap", "cap_material", "cap_material_id", "cap_uv", "cap_uv_per_metre",
                           "cap_atlas_rect", "cap_uv_per_border", "mass_mode", "density", "split_impulse",
                           "min_piece_volume", "small_pieces", "separate_islands", "max_depth", "handler",
                           "open_sections", "islands", "retirement"}))
    return false;
  d.splitable = true;
  Splitable& s = d.split;
  int uv = int(s.capUvMode == geometry::CapUvMode::NormalizedBounds);
  int massMode = int(s.massMode);
  int small = int(s.smallPieces);
  int open = int(s.openSections);
  int islands = int(s.islands);
  int retirement = int(s.retirement);
  d.splitDensityGiven = n.has("density");
  d.capMaterialIdGiven = n.has("cap_material_id");
  if (!rd.boolean(n, "convex", s.convexHint) || !rd.boolean(n, "cap", s.cap) ||
      !rd.string(n, "cap_material", d.capMaterial) ||
      !rd.integer32(n, "cap_material_id", s.capMaterialId, 0, 255) ||
      !rd.choice(n, "cap_uv", {"world_planar", "normalized_bounds"}, uv) ||
      !rd.number(n, "cap_uv_per_metre", s.capUvPerMetre, true) ||
      !rd.vec4(n, "cap_atlas_rect", s.capAtlasRect) || !rd.boolean(n, "cap_uv_per_border", s.capUvPerBorder) ||
      !rd.choice(n, "mass_mode", {"density", "keep_parent_mass"}, massMode) ||
      !rd.number(n, "density", s.density, true) || !rd.nonNegative(n, "split_impulse", s.splitImpulse) ||
      !rd.nonNegative(n, "min_piece_volume", s.minPieceVolume) ||
      !rd.choice(n, "small_pieces", {"remove", "debris"}, small) ||
      !rd.boolean(n, "separate_islands", s.separateIslands) ||
      !rd.integer32(n, "max_depth", s.maxDepth, 1, 64) || !rd.string(n, "handler", s.handler) ||
      !rd.choice(n, "open_sections", {"refuse", "cap_closed", "bridge"}, open) ||
      !rd.choice(n, "islands", {"touching", "connected"}, islands) ||
      !rd.choice(n, "retirement", {"default", "freeze", "fade", "remove"}, retirement))
    return false;
  s.retirement = PieceRetirement(retirement);
  s.openSections = geometry::OpenSectionMode(open);
  s.islands = geometry::IslandMode(islands);
  s.capUvMode = uv == 1 ? geometry::CapUvMode::NormalizedBounds : geometry::CapUvMode::WorldPlanar;
  s.massMode = MassMode(massMode);
  s.smallPieces = SmallPieceMode(small);
  return true;
}

bool readEntity(Reader& rd, const Node& n, const std::string& baseDirectory, bool insideBody, EntityDesc& d) {
  if (!rd.expectObject(n, {"name", "mesh", "material", "transform", "body", "splitable", "children"}))
    return false;
  d.path = n.path;
  if (!rd.string(n, "name", d.name) || !rd.string(n, "material", d.material)) return false;
  if (n.has("mesh") && !readMesh(rd, n.child("mesh"), baseDirectory, d)) return false;
  if (!readTransform(rd, n, d.transform, true)) return false;
  if (n.has("body")) {
    const Node b = n.child("body");
    if (insideBody)
      return rd.fail(b, "a child of an object with a body is part of that body and has no body of its own");
    if (!d.hasMesh) return rd.fail(b, "a body needs a 'mesh' on the same object");
    if (!rd.expectObject(b, {"type", "density", "mass", "linear_velocity", "angular_velocity", "collider"}))
      return false;
    int type = 1;
    int collider = 0;
    if (!rd.choice(b, "type", {"static", "dynamic"}, type)) return false;
    d.body = type == 1 ? BodyKind::Dynamic : BodyKind::Static;
    if (b.has("density") && b.has("mass")) return rd.fail(b.child("mass"), "give 'density' or 'mass', not both");
    if (!rd.number(b, "density", d.density, true)) return false;
    if (b.has("mass")) {
      double m = 0.0;
      if (!rd.number(b, "mass", m, true)) return false;
      d.mass = m;
    }
    if (!rd.vec3(b, "linear_velocity", d.linearVelocity) || !rd.vec3(b, "angular_velocity", d.angularVelocity) ||
        !rd.choice(b, "collider", {"auto", "convex_hull", "compound", "concave_mesh"}, collider))
      return false;
    d.collider = ColliderMode(collider);
    if (d.body == BodyKind::Static) {
      for (const char* key : {"mass", "linear_velocity", "angular_velocity"})
        if (b.has(key)) return rd.fail(b.child(key), std::string("a static body has no '") + key + "'");
    }
  }
  if (n.has("splitable")) {
    const Node s = n.child("splitable");
    if (d.body == BodyKind::None)
      return rd.fail(s, insideBody ? "a child of a body is split with its parent: put 'splitable' on the parent"
                                   : "a splitable object needs a 'body'");
    if (!s->is_boolean() && !s->is_object())
      return rd.fail(s, std::string("expected true, false or an object, found ") + typeName(*s));
    if (!readSplitable(rd, s, d)) return false;
  }
  if (n.has("children")) {
    const Node c = n.child("children");
    if (!c->is_array()) return rd.fail(c, std::string("expected an array, found ") + typeName(*c));
    for (size_t k = 0; k < c->size(); ++k) {
      EntityDesc child;
      if (!readEntity(rd, c.at(k), baseDirectory, insideBody || d.body != BodyKind::None, child)) return false;
      d.children.push_back(std::move(child));
    }
  }
  return true;
}

// "kind" and, for "shatter", its fields (geometry::fracture through a split job).
bool readShatter(Reader& rd, const Node& n, ScheduledSplitter& s) {
  int kind = 0;
  if (!rd.choice(n, "kind", {"plane", "shatter"}, kind)) return false;
  s.kind = kind == 1 ? SplitterKind::Shatter : SplitterKind::Plane;
  if (s.kind == SplitterKind::Plane) {
    for (const char* key : {"cells", "seed", "impact_point", "impact_radius", "outward_impulse"})
      if (n.has(key)) return rd.fail(n.child(key), std::string("only a shatter splitter has '") + key + "'");
    return true;
  }
  uint64_t cells = s.shatter.cells;
  glm::vec3 impact(0.f);
  if (!rd.integer(n, "cells", cells, 1, 256) || !rd.integer(n, "seed", s.shatter.seed) ||
      !rd.vec3(n, "impact_point", impact) || !rd.nonNegative(n, "impact_radius", s.shatter.impactRadius) ||
      !rd.nonNegative(n, "outward_impulse", s.shatter.outwardImpulse))
    return false;
  s.shatter.cells = uint32_t(cells);
  s.shatter.impactGiven = n.has("impact_point");
  s.shatter.impactPoint = glm::dvec3(impact);
  return true;
}

bool readSplitter(Reader& rd, const Node& n, ScheduledSplitter& s) {
  if (!rd.expectObject(n, {"name", "lifetime", "half_extents", "transform", "velocity", "fire_tick",
                           "start_tick", "end_tick", "player_caused", "kind", "cells", "seed", "impact_point",
                           "impact_radius", "outward_impulse"}))
    return false;
  if (!readShatter(rd, n, s)) return false;
  int lifetime = 1;
  if (!rd.string(n, "name", s.name) || !rd.choice(n, "lifetime", {"persistent", "one_tick"}, lifetime) ||
      !rd.vec3(n, "half_extents", s.halfExtents, true) || !rd.vec3(n, "velocity", s.velocity) ||
      !rd.boolean(n, "player_caused", s.playerCaused))
    return false;
  s.schedule = lifetime == 0 ? SplitterSchedule::Persistent : SplitterSchedule::OneTick;
  ecs::Transform t;
  if (!readTransform(rd, n, t, false)) return false;
  s.position = t.position;
  s.rotation = t.rotation;
  const uint64_t kMaxTick = uint64_t(1) << 40;
  if (s.schedule == SplitterSchedule::OneTick) {
    for (const char* key : {"start_tick", "end_tick"})
      if (n.has(key)) return rd.fail(n.child(key), std::string("a one-tick splitter has no '") + key + "' (use fire_tick)");
    if (!n.has("fire_tick")) return rd.fail(n, "a one-tick splitter needs 'fire_tick'");
    if (!rd.integer(n, "fire_tick", s.fireTick, 0, kMaxTick)) return false;
  } else {
    if (n.has("fire_tick")) return rd.fail(n.child("fire_tick"), "a persistent splitter has no 'fire_tick' (use start_tick)");
    if (!rd.integer(n, "start_tick", s.startTick, 0, kMaxTick)) return false;
    if (n.has("end_tick")) {
      uint64_t end = 0;
      if (!rd.integer(n, "end_tick", end, s.startTick + 1, kMaxTick)) return false;
      s.endTick = end;
    }
  }
  return true;
}

// The piece budget (piece_budget.h): limits, policy, fade time, hit speed, the smallest body.
bool readPieceBudget(Reader& rd, const Node& b, SceneDesc& scene) {
  if (!rd.expectObject(b, {"enabled", "max_live_pieces", "max_awake_pieces", "max_frozen_pieces", "max_debris",
                           "max_retirements_per_tick", "policy", "fade_seconds", "hit_speed", "restless_seconds",
                           "min_body_volume", "min_body_thickness"}))
    return false;
  scene.pieceBudgetGiven = true;
  PieceBudgetSettings& s = scene.pieceBudget;
  int policy = int(s.policy) - 1;
  double fade = s.fadeSeconds, hit = s.hitSpeed, restless = s.restlessSeconds;
  if (!rd.boolean(b, "enabled", s.enabled) || !rd.integer32(b, "max_live_pieces", s.maxLivePieces, 0) ||
      !rd.integer32(b, "max_awake_pieces", s.maxAwakePieces, 0) ||
      !rd.integer32(b, "max_frozen_pieces", s.maxFrozenPieces, 0) || !rd.integer32(b, "max_debris", s.maxDebris, 0) ||
      !rd.integer32(b, "max_retirements_per_tick", s.maxRetirementsPerTick, 1) ||
      !rd.choice(b, "policy", {"freeze", "fade", "remove"}, policy) || !rd.nonNegative(b, "fade_seconds", fade) ||
      !rd.nonNegative(b, "hit_speed", hit) || !rd.nonNegative(b, "restless_seconds", restless) ||
      !rd.nonNegative(b, "min_body_volume", s.minBodyVolume) ||
      !rd.nonNegative(b, "min_body_thickness", s.minBodyThickness))
    return false;
  s.policy = PieceRetirement(policy + 1);
  s.fadeSeconds = float(fade);
  s.hitSpeed = float(hit);
  s.restlessSeconds = float(restless);
  return true;
}

}  // namespace

bool readScene(Reader& rd, const json& root, const std::string& baseDirectory, SceneDesc& scene) {
  const Node n{&root, {}};
  if (!rd.expectObject(n, {"version", "description", "gravity", "floor", "budget", "piece_budget", "camera",
                           "ticks", "entities", "splitters"}))
    return false;
  if (n.has("version")) {
    uint64_t version = 1;
    if (!rd.integer(n, "version", version)) return false;
    if (version != 1) return rd.fail(n.child("version"), "this build reads scene format version 1");
  }
  std::string description;
  if (!rd.string(n, "description", description)) return false;
  if (!rd.vec3(n, "gravity", scene.gravity) || !rd.integer(n, "ticks", scene.ticks, 0, uint64_t(1) << 40))
    return false;
  if (n.has("floor")) {
    const Node f = n.child("floor");
    if (f->is_boolean()) {
      scene.floor.present = f->get<bool>();
    } else {
      if (!rd.expectObject(f, {"height", "half_extents", "material"})) return false;
      scene.floor.present = true;
      if (!rd.number(f, "height", scene.floor.height) ||
          !rd.vec3(f, "half_extents", scene.floor.halfExtents, true) ||
          !rd.string(f, "material", scene.floor.material))
        return false;
    }
  }
  if (n.has("budget")) {
    const Node b = n.child("budget");
    if (!rd.expectObject(b, {"milliseconds_per_tick", "max_splits_per_tick", "max_activations_per_tick",
                             "max_queue_length", "deterministic", "threads", "commit_delay_ticks",
                             "worker_milliseconds_per_tick", "estimated_main_ms",
                             "estimated_worker_ms_per_triangle"}))
      return false;
    scene.budgetGiven = true;
    SplitBudgetSettings& s = scene.budget;
    if (!rd.number(b, "milliseconds_per_tick", s.millisecondsPerTick, true) ||
        !rd.integer32(b, "max_splits_per_tick", s.maxSplitsPerTick, 1) ||
        !rd.integer32(b, "max_activations_per_tick", s.maxActivationsPerTick, 1) ||
        !rd.integer32(b, "max_queue_length", s.maxQueueLength, 1) ||
        !rd.boolean(b, "deterministic", s.deterministic) ||
        !rd.integer32(b, "threads", s.threads, 0) ||
        !rd.integer32(b, "commit_delay_ticks", s.commitDelayTicks, 0) ||
        !rd.nonNegative(b, "worker_milliseconds_per_tick", s.workerMillisecondsPerTick) ||
        !rd.nonNegative(b, "estimated_main_ms", s.estimatedMainMilliseconds) ||
        !rd.nonNegative(b, "estimated_worker_ms_per_triangle", s.estimatedWorkerMillisecondsPerTriangle))
      return false;
  }
  if (n.has("piece_budget") && !readPieceBudget(rd, n.child("piece_budget"), scene)) return false;
  if (n.has("camera")) {
    const Node c = n.child("camera");
    if (!rd.expectObject(c, {"position", "target"}) || !rd.vec3(c, "position", scene.cameraPosition) ||
        !rd.vec3(c, "target", scene.cameraTarget))
      return false;
  }
  if (n.has("entities")) {
    const Node e = n.child("entities");
    if (!e->is_array()) return rd.fail(e, std::string("expected an array, found ") + typeName(*e));
    for (size_t k = 0; k < e->size(); ++k) {
      EntityDesc d;
      if (!readEntity(rd, e.at(k), baseDirectory, false, d)) return false;
      scene.entities.push_back(std::move(d));
    }
  }
  if (n.has("splitters")) {
    const Node s = n.child("splitters");
    if (!s->is_array()) return rd.fail(s, std::string("expected an array, found ") + typeName(*s));
    for (size_t k = 0; k < s->size(); ++k) {
      ScheduledSplitter sp;
      if (!readSplitter(rd, s.at(k), sp)) return false;
      if (sp.name.empty()) sp.name = "splitter " + std::to_string(k);
      scene.splitters.push_back(std::move(sp));
    }
  }
  return true;
}

}  // namespace cleave::components::scene_json
