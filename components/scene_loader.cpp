// SPDX-License-Identifier: MIT
// Loading a scene (scene_loader.h): the file read into descriptors (scene_read.cpp), then the
// world built from them: entities, bodies, GPU meshes, splitters; nothing is left behind on error.
#include "cleave/components/scene_loader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "cleave/components/scene_components.h"
#include "cleave/components/scene_desc.h"
#include "cleave/ecs/hierarchy.h"
#include "cleave/geometry/mass_properties.h"
#include "cleave/geometry/primitives.h"

namespace cleave::components {

using nlohmann::json;
using namespace scene_json;

namespace {

struct Builder {
  SceneContext& ctx;
  SceneLoadResult& result;
  std::vector<ecs::Entity> created;
  std::string error;
  std::vector<std::string> errorPath;

  SplitWorld splitWorld() { return SplitWorld{ctx.world, ctx.physics, ctx.renderer}; }

  render::Material material(const std::string& name, bool cap) const {
    return ctx.materials ? ctx.materials(name, cap) : render::Material{};
  }

  // The object's mesh with its children merged in (each child's transform relative to it), every
  // part on its own material slot; `names` gets the material name of each slot.
  static void gather(const EntityDesc& d, const glm::mat4& toRoot, geometry::MeshData& out,
                     std::vector<std::string>& names) {
    if (d.hasMesh && !d.mesh.indices.empty()) {
      geometry::MeshData part = d.mesh;
      const uint32_t slot = uint32_t(names.size());
      names.push_back(d.material);
      if (part.submeshes.empty()) {
        part.submeshes.push_back(geometry::SubMesh{0, uint32_t(part.indices.size()), slot});
      } else {
        for (auto& sm : part.submeshes) sm.materialId = slot;
      }
      if (toRoot != glm::mat4(1.f)) geometry::primitives::transform(part, toRoot);
      out = out.indices.empty() ? std::move(part) : geometry::primitives::merge(out, part);
    }
    for (const EntityDesc& c : d.children) gather(c, toRoot * ecs::localMatrix(c.transform), out, names);
  }

  ecs::Entity newEntity(const std::string& name, const ecs::Transform& t) {
    const ecs::Entity e = ctx.world.create();
    created.push_back(e);
    ctx.world.add<ecs::Name>(e, ecs::Name{name});
    ctx.world.add<ecs::Transform>(e, t);
    ctx.world.add<ecs::WorldTransform>(e, ecs::WorldTransform{ecs::localMatrix(t)});
    return e;
  }

  void addRenderer(ecs::Entity e, geometry::MeshData mesh, const std::vector<std::string>& names) {
    auto source = std::make_shared<geometry::MeshData>(std::move(mesh));
    MeshRenderer mr;
    mr.source = source;
    if (ctx.renderer) mr.gpu = ctx.renderer->uploadMesh(*source).valueOr({});
    for (const std::string& n : names) mr.materials.push_back(material(n, false));
    if (mr.materials.empty()) mr.materials.push_back(material("", false));
    ctx.world.add<MeshRenderer>(e, std::move(mr));
  }

  bool createFloor(const FloorDesc& f) {
    ecs::Transform t;
    t.position = glm::vec3(0.f, f.height - f.halfExtents.y, 0.f);
    const ecs::Entity e = newEntity("floor", t);
    addRenderer(e, geometry::primitives::box(f.halfExtents), {f.material});
    auto shape = ctx.physics.createShape(physics::ShapeDef::box(f.halfExtents));
    if (!shape.ok()) return failWith("floor: " + shape.message(), {"floor"});
    physics::BodyDef def;
    def.shape = shape.value();
    def.position = t.position;
    def.userData = toUserData(e);
    auto body = ctx.physics.createBody(def);
    if (!body.ok()) {
      ctx.physics.destroyShape(shape.value());
      return failWith("floor: " + body.message(), {"floor"});
    }
    ctx.world.add<RigidBody>(e, RigidBody{body.value(), shape.value()});
    result.floor = e;
    return true;
  }

  bool failWith(const std::string& message, const std::vector<std::string>& path = {}) {
    error = message;
    errorPath = path;
    return false;
  }

  // `group` is the entity of the enclosing object without a body (null at the root) and
  // `groupWorld` its world transform.
  bool create(const EntityDesc& d, ecs::Entity group, const ecs::Transform& groupWorld) {
    const std::string name = d.name.empty() ? "object" : d.name;
    if (d.body == BodyKind::None) {
      const ecs::Entity e = newEntity(name, d.transform);
      if (d.hasMesh) addRenderer(e, d.mesh, {d.material});
      if (!group.isNull()) ecs::setParent(ctx.world, e, group);
      result.entities.push_back(SceneEntity{e, d.name, d.material, false, false, group});
      ecs::Transform world;
      world.position = groupWorld.position + groupWorld.rotation * (groupWorld.scale * d.transform.position);
      world.rotation = groupWorld.rotation * d.transform.rotation;
      world.scale = groupWorld.scale * d.transform.scale;
      for (const EntityDesc& c : d.children)
        if (!create(c, e, world)) return false;
      return true;
    }

    // A body is a root: its pose is the world pose (composed through enclosing groups).
    ecs::Transform t;
    t.position = groupWorld.position + groupWorld.rotation * (groupWorld.scale * d.transform.position);
    t.rotation = groupWorld.rotation * d.transform.rotation;
    t.scale = groupWorld.scale * d.transform.scale;
    geometry::MeshData mesh;
    std::vector<std::string> names;
    gather(d, glm::mat4(1.f), mesh, names);
    if (mesh.indices.empty()) return failWith(name + ": the mesh has no triangles", d.path);
    const bool plainBox = d.isBox && d.children.empty();
    const ecs::Entity e = newEntity(name, t);
    geometry::MeshData keep = mesh;
    addRenderer(e, std::move(mesh), names);

    double density = d.density;
    if (d.splitable) {
      Splitable s = d.split;
      if (!d.capMaterialIdGiven) s.capMaterialId = uint32_t(names.size());
      s.capMaterial = material(d.capMaterial.empty() ? d.material : d.capMaterial, true);
      auto& mr = ctx.world.get<MeshRenderer>(e);
      if (mr.materials.size() <= s.capMaterialId) mr.materials.resize(s.capMaterialId + 1, mr.materials.back());
      mr.materials[s.capMaterialId] = s.capMaterial;
      s.collider = d.collider;
      ctx.world.add<Splitable>(e, s);
    }

    SplitWorld sw = splitWorld();
    if (d.body == BodyKind::Dynamic) {
      if (d.mass) {
        const auto props = geometry::computeMassProperties(keep, glm::dmat4(ecs::localMatrix(t)));
        if (!(props.volume > 0.0)) return failWith(name + ": the mesh encloses no volume", d.path);
        density = *d.mass / props.volume;
      }
      if (auto* s = ctx.world.tryGet<Splitable>(e); s && !d.splitDensityGiven) s->density = density;
      if (const base::Status made = makeDynamicBody(sw, e, density, d.collider, ctx.splits); !made.ok())
        return failWith(name + ": " + made.message, d.path);
      const auto& rb = ctx.world.get<RigidBody>(e);
      if (d.linearVelocity != glm::vec3(0.f) || d.angularVelocity != glm::vec3(0.f))
        ctx.physics.setVelocity(rb.body, d.linearVelocity, d.angularVelocity);
    } else {
      physics::Result<physics::ShapeId> shape =
          plainBox ? ctx.physics.createShape(physics::ShapeDef::box(d.boxHalfExtents * t.scale)) : [&] {
            std::vector<glm::vec3> points;
            points.reserve(keep.positions.size());
            for (const glm::vec3& p : keep.positions) points.push_back(p * t.scale);
            return ctx.physics.createShape(physics::ShapeDef::staticMesh(points, keep.indices));
          }();
      if (!shape.ok()) return failWith(name + ": no collider: " + shape.message(), d.path);
      physics::BodyDef def;
      def.shape = shape.value();
      def.position = t.position;
      def.rotation = t.rotation;
      def.userData = toUserData(e);
      auto body = ctx.physics.createBody(def);
      if (!body.ok()) {
        ctx.physics.destroyShape(shape.value());
        return failWith(name + ": " + body.message(), d.path);
      }
      ctx.world.add<RigidBody>(e, RigidBody{body.value(), shape.value()});
      if (d.splitable && !d.splitDensityGiven) ctx.world.get<Splitable>(e).density = density;
    }
    result.entities.push_back(SceneEntity{e, d.name, d.material, d.body == BodyKind::Dynamic, d.splitable, {}});
    return true;
  }

  void rollback() {
    for (ecs::Entity e : created) ctx.world.destroy(e);  // its hooks free what it holds
    created.clear();
  }
};

SceneLoadResult syntaxError(const std::string& file, const std::string& text, const json::parse_error& e) {
  SceneLoadResult r;
  const size_t byte = e.byte > 0 ? size_t(e.byte - 1) : 0;
  const size_t end = std::min(byte, text.size());
  int line = 1;
  size_t lineStart = 0;
  for (size_t k = 0; k < end; ++k) {
    if (text[k] == '\n') {
      ++line;
      lineStart = k + 1;
    }
  }
  const size_t column = end - lineStart + 1;
  std::string detail = e.what();
  // "[json.exception.parse_error.101] parse error at line 3, column 5: syntax error ..." -> the part
  // after the position.
  if (const size_t p = detail.find("syntax error"); p != std::string::npos) detail = detail.substr(p);
  const std::string key = lastKeyBefore(text, end);
  r.errorFile = file;
  r.errorLine = line;
  r.errorField = key.empty() ? "" : key;
  r.setFailure(base::StatusCode::ParseError, file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " +
            (key.empty() ? std::string("at the start") : "after field '" + key + "'") + ": " + detail);
  return r;
}

}  // namespace

ecs::Entity SceneLoadResult::find(const std::string& name) const {
  for (const SceneEntity& e : entities)
    if (e.name == name) return e.entity;
  return {};
}

ecs::Entity createSplitterEntity(SplitWorld& w, const ScheduledSplitter& s) {
  Splitter splitter;
  splitter.lifetime =
      s.schedule == SplitterSchedule::Persistent ? SplitterLifetime::Persistent : SplitterLifetime::OneTick;
  splitter.playerCaused = s.playerCaused;
  splitter.halfExtents = s.halfExtents;
  splitter.kind = s.kind;
  splitter.shatter = s.shatter;
  return createSplitter(w, s.name, physics::ShapeDef::box(s.halfExtents), s.position, s.rotation, splitter);
}

SceneLoadResult loadSceneFromString(const std::string& text, const std::string& name,
                                    const std::string& baseDirectory, SceneContext& ctx) {
  json root;
  try {
    root = json::parse(text, nullptr, /*allow_exceptions=*/true, /*ignore_comments=*/true);
  } catch (const json::parse_error& e) {
    return syntaxError(name, text, e);
  } catch (const std::exception& e) {
    SceneLoadResult r;
    r.errorFile = name;
    r.setFailure(base::StatusCode::ParseError, name + ": " + e.what());
    return r;
  }

  SceneDesc scene;
  Reader rd(name, text);
  SceneLoadResult result;
  bool read = false;
  try {
    read = readScene(rd, root, baseDirectory, scene);
  } catch (const std::exception& e) {  // defensive: the reader checks types before every access
    result.errorFile = name;
    result.setFailure(base::StatusCode::ParseError, name + ": " + e.what());
    return result;
  }
  if (!read || rd.failed()) {
    rd.fillError(result);
    return result;
  }

  result.gravity = scene.gravity;
  result.budget = ctx.splits ? ctx.splits->budget().settings() : SplitBudgetSettings{};
  if (scene.budgetGiven) result.budget = scene.budget;
  result.pieceBudget = ctx.splits ? ctx.splits->pieces().settings() : PieceBudgetSettings{};
  if (scene.pieceBudgetGiven) result.pieceBudget = scene.pieceBudget;
  result.cameraPosition = scene.cameraPosition;
  result.cameraTarget = scene.cameraTarget;
  result.ticks = scene.ticks;

  // Gravity first: bodies take the world's gravity when they are created.
  const glm::vec3 previousGravity = ctx.physics.gravity();
  ctx.physics.setGravity(scene.gravity);
  Builder b{ctx, result, {}, {}, {}};
  bool ok = !scene.floor.present || b.createFloor(scene.floor);
  for (size_t k = 0; ok && k < scene.entities.size(); ++k) ok = b.create(scene.entities[k], {}, ecs::Transform{});
  SplitWorld sw{ctx.world, ctx.physics, ctx.renderer};
  for (ScheduledSplitter& s : scene.splitters) {
    if (!ok) break;
    if (s.schedule == SplitterSchedule::Persistent && s.startTick == 0) {
      s.entity = createSplitterEntity(sw, s);
      s.created = true;
      b.created.push_back(s.entity);
    }
  }
  if (!ok) {
    b.rollback();
    ctx.physics.setGravity(previousGravity);
    result = SceneLoadResult();
    rd.fail(Node{&root, b.errorPath}, b.error);
    rd.fillError(result);
    return result;
  }
  if (ctx.splits && scene.budgetGiven) ctx.splits->budget().setSettings(scene.budget);
  if (ctx.splits && scene.pieceBudgetGiven) ctx.splits->pieces().setSettings(scene.pieceBudget);
  ecs::updateWorldTransforms(ctx.world);
  result.splitters = std::move(scene.splitters);
  result.code = base::StatusCode::Ok;
  return result;
}

SceneLoadResult loadScene(const std::string& path, SceneContext& ctx) {
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  if (!in || std::filesystem::is_directory(path, ec)) {
    SceneLoadResult r;
    r.errorFile = path;
    r.setFailure(base::StatusCode::IoError, path + ": cannot open the scene file (missing or unreadable)");
    return r;
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const std::string base = std::filesystem::path(path).parent_path().string();
  return loadSceneFromString(buffer.str(), path, base.empty() ? "." : base, ctx);
}

}  // namespace cleave::components
