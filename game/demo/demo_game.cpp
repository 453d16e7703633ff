// SPDX-License-Identifier: MIT
#include "game/demo/demo_game.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstdio>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "cleave/components/scene_components.h"
#include "cleave/components/scene_loader.h"
#include "cleave/components/split_log.h"
#include "cleave/components/splitable.h"
#include "cleave/components/splitable_object.h"
#include "cleave/assets/procedural_character.h"
#include "cleave/assets/procedural_textures.h"
#include "cleave/ecs/hierarchy.h"
#include "cleave/geometry/primitives.h"
#include "cleave/log/log.h"
#include "game/demo/spawn_spots.h"

namespace cleave::demo {

namespace {

constexpr float kMoveSpeed = 4.5f;         // m/s
constexpr float kLookSensitivity = 0.0035f;  // rad per pixel
constexpr float kPushImpulse = 6.f;        // N s per kg of the pushed body (a velocity change)
constexpr float kCutReach = 60.f;          // metres a drag cut reaches from the camera


// Object 6 walks a small circle: kWalkSeconds of walking, then kIdleSeconds standing, crossfading
// between the clips. Its body is kinematic and set on the circle every tick.
constexpr float kWalkRadius = 0.6f;        // metres
constexpr float kWalkAngularSpeed = 1.1f;  // rad/s: about 0.66 m/s along the circle
constexpr float kWalkSeconds = 6.f;
constexpr float kIdleSeconds = 2.f;
constexpr float kCrossfadeSeconds = 0.35f;

// The walking state of a generated character in the demo.
struct Walker {
  glm::vec3 centre{0.f};      // of the circle, on the floor
  float angle = 0.f;          // radians around the circle
  float seconds = 0.f;        // into the current walk/idle phase
  bool walking = true;
  glm::mat4 bodyFromRoot{1.f};  // the body frame relative to the character's feet frame
};

glm::mat4 walkerRoot(const Walker& w) {
  const glm::vec3 at = w.centre + kWalkRadius * glm::vec3(std::sin(w.angle), 0.f, std::cos(w.angle));
  // Facing the direction of travel: +z turned onto the circle's tangent.
  return glm::translate(glm::mat4(1.f), at) *
         glm::mat4_cast(glm::angleAxis(w.angle + glm::half_pi<float>(), glm::vec3(0, 1, 0)));
}

}  // namespace

DemoGame::DemoGame() = default;
DemoGame::~DemoGame() = default;

components::SplitWorld DemoGame::splitWorld() {
  return components::SplitWorld{app_->world(), *physics_, &app_->renderer()};
}

void DemoGame::createMaterials() {
  render::Renderer& r = app_->renderer();
  auto texture = [&](assets::TextureKind kind, int size, uint32_t seed) {
    const assets::Image img = assets::makeTexture(kind, size, seed);
    const render::TextureHandle h = r.createTexture(img.width, img.height, img.rgba).valueOr({});
    textures_.push_back(h);
    return h;
  };
  const render::TextureHandle wood = texture(assets::TextureKind::Wood, 256, 3);
  const render::TextureHandle marble = texture(assets::TextureKind::Marble, 256, 5);
  const render::TextureHandle melon = texture(assets::TextureKind::Melon, 256, 7);
  const render::TextureHandle metal = texture(assets::TextureKind::BrushedMetal, 256, 9);

  render::Material m;
  m.albedo = wood;
  m.specular = 0.15f;
  m.shininess = 24.f;
  looks_[0] = m;
  lookNames_[0] = "wood";
  m = {};
  m.albedo = metal;
  m.baseColor = glm::vec4(0.95f, 0.95f, 1.0f, 1.f);
  m.specular = 1.2f;
  m.shininess = 90.f;
  m.reflectivity = 0.55f;
  looks_[1] = m;
  lookNames_[1] = "metal";
  m = {};
  m.albedo = marble;
  m.specular = 0.6f;
  m.shininess = 60.f;
  m.reflectivity = 0.06f;
  looks_[2] = m;
  lookNames_[2] = "marble";
  m = {};
  m.albedo = melon;
  m.specular = 0.35f;
  m.shininess = 40.f;
  looks_[3] = m;
  lookNames_[3] = "melon";
  m = {};
  m.shading = render::Shading::DebugNormals;
  looks_[4] = m;
  lookNames_[4] = "debug normals";
  m = {};
  m.shading = render::Shading::CheckerCube;
  m.baseColor = glm::vec4(0.85f, 0.85f, 0.8f, 1.f);
  m.checkerColor = glm::vec4(0.1f, 0.25f, 0.55f, 1.f);
  m.checkerScale = 4.f;
  looks_[5] = m;
  lookNames_[5] = "checker by position";
  m = {};
  m.baseColor = glm::vec4(0.9f, 0.85f, 0.7f, 1.f);
  m.specular = 1.5f;
  m.shininess = 120.f;
  m.reflectivity = 0.9f;
  looks_[6] = m;
  lookNames_[6] = "environment";

  // Caps: the inside of each material. Wood shows its grain, the melon its red flesh (the atlas
  // rectangle of the cap UVs points into the flesh half of the texture).
  capLooks_ = looks_;
  capLooks_[0].baseColor = glm::vec4(1.1f, 1.05f, 0.95f, 1.f);
  capLooks_[1].reflectivity = 0.2f;
  capLooks_[1].baseColor = glm::vec4(0.8f, 0.8f, 0.85f, 1.f);
  createCharacterLooks();

  floorMaterial_.shading = render::Shading::Checker;
  floorMaterial_.baseColor = glm::vec4(0.62f, 0.62f, 0.6f, 1.f);
  floorMaterial_.checkerColor = glm::vec4(0.16f, 0.17f, 0.19f, 1.f);
  floorMaterial_.checkerScale = 1.f;
  floorMaterial_.specular = 0.1f;
}

// The generated character and its multi-part figure: its colours by material id, skin soft and
// slightly glossy, and the cut caps (material 1) red flesh.
void DemoGame::createCharacterLooks() {
  const assets::ProceduralCharacter made = assets::makeProceduralCharacter();
  auto asset = std::make_shared<components::SkinnedAsset>();
  asset->skeleton = made.skeleton;
  asset->clips = {made.idle, made.walk};
  characterAsset_ = asset;
  characterMesh_ = std::make_shared<geometry::MeshData>(made.mesh);
  figureMesh_ = std::make_shared<geometry::MeshData>(assets::makeCharacterParts(made));
  characterMaterials_.clear();
  for (size_t id = 0; id < made.materialColors.size(); ++id) {
    render::Material look;
    look.baseColor = made.materialColors[id];
    look.specular = id == 0 ? 0.35f : 0.12f;
    look.shininess = id == 0 ? 28.f : 12.f;
    characterMaterials_.push_back(look);
  }
  render::Material flesh;
  flesh.baseColor = glm::vec4(0.72f, 0.1f, 0.09f, 1.f);
  flesh.specular = 0.6f;
  flesh.shininess = 48.f;
  if (characterMaterials_.size() < 2) characterMaterials_.resize(2);
  characterMaterials_[1] = flesh;
}

components::ResourceCounts DemoGame::resources() const {
  return components::countResources(physics_, app_ ? &app_->renderer() : nullptr);
}

void DemoGame::releaseAll() {
  if (sim_) sim_->batches().release(components::PieceMeshes::Drop);  // the world is cleared next
  if (app_) app_->world().clear();
}

void DemoGame::createFloor() {
  ecs::World& world = app_->world();
  const ecs::Entity floor = world.create();
  world.add<ecs::Name>(floor, ecs::Name{"floor"});
  ecs::Transform t;
  t.position = glm::vec3(0.f, -0.5f, 0.f);
  world.add<ecs::Transform>(floor, t);
  world.add<ecs::WorldTransform>(floor, ecs::WorldTransform{ecs::localMatrix(t)});
  auto mesh = std::make_shared<geometry::MeshData>(geometry::primitives::box(glm::vec3(60.f, 0.5f, 60.f)));
  components::MeshRenderer mr;
  mr.source = mesh;
  mr.gpu = app_->renderer().uploadMesh(*mesh).valueOr({});
  mr.materials = {floorMaterial_};
  world.add<components::MeshRenderer>(floor, std::move(mr));
  auto shape = physics_->createShape(physics::ShapeDef::box(glm::vec3(60.f, 0.5f, 60.f)));
  physics::BodyDef def;
  def.shape = shape.value();
  def.position = t.position;
  def.userData = components::toUserData(floor);
  auto body = physics_->createBody(def);
  world.add<components::RigidBody>(floor, components::RigidBody{body.value(), shape.value()});
}

ecs::Entity DemoGame::spawn(ObjectKind kind, const glm::vec3& position, const glm::quat& rotation) {
  ecs::World& world = app_->world();
  // Every spawn of a kind shares the kind's mesh, made at its first spawn (as a game shares an
  // asset's): the split system then welds and decomposes it once for all of them.
  std::shared_ptr<const geometry::MeshData>& shared = kindMeshes_[size_t(kind)];
  const bool known = shared != nullptr;
  geometry::MeshData mesh;
  components::Splitable splitable;
  // Pieces move apart a little (m/s, each along the plane normal away from the cut), so a cut made
  // along the view direction still shows.
  splitable.splitImpulse = 0.6;
  int look = 0;
  std::string name;
  switch (kind) {
    case ObjectKind::WoodenCube:
      if (!known) mesh = geometry::primitives::box(glm::vec3(0.5f));
      splitable.convexHint = true;
      splitable.density = 600.0;
      look = 0;
      name = "wooden cube";
      break;
    case ObjectKind::MetalSphere:
      if (!known) mesh = geometry::primitives::uvSphere(0.5f, 32, 16);
      splitable.convexHint = true;
      splitable.density = 7800.0;
      look = 1;
      name = "metal sphere";
      break;
    case ObjectKind::MarbleCylinder:
      if (!known) mesh = geometry::primitives::cylinder(0.4f, 1.2f, 32);
      splitable.convexHint = true;
      splitable.density = 2700.0;
      splitable.splitImpulse = 1.5;
      look = 2;
      name = "marble cylinder";
      break;
    case ObjectKind::MelonEllipsoid:
      if (!known) mesh = geometry::primitives::ellipsoid(glm::vec3(0.45f, 0.35f, 0.35f), 32, 16);
      // The outside is rind: the texture's u in [0, 0.5) (procedural_textures.h); the ellipsoid's
      // u runs once around it in [0, 1], kept a texel short of the flesh at the seam.
      for (glm::vec2& uv : mesh.uv0) uv.x *= 0.49f;  // (nothing when the mesh is shared)
      splitable.convexHint = true;
      splitable.density = 950.0;
      splitable.capUvMode = geometry::CapUvMode::NormalizedBounds;
      splitable.capAtlasRect = glm::vec4(0.5f, 0.f, 0.5f, 1.f);  // the red flesh half of the texture
      look = 3;
      name = "melon";
      break;
    case ObjectKind::MultiPart:
      return spawnFigure(position, rotation);
    case ObjectKind::Skinned:
      return spawnCharacter(position, rotation);
    case ObjectKind::Torus:
      if (!known) mesh = geometry::primitives::torus(0.5f, 0.2f, 48, 24);
      splitable.density = 1200.0;
      look = 6;
      name = "torus";
      break;
    case ObjectKind::StoneBlock:
      if (!known) mesh = geometry::primitives::box(glm::vec3(0.4f, 0.3f, 0.3f));
      splitable.convexHint = true;
      splitable.density = 2400.0;
      look = 2;  // marble
      name = "stone block";
      break;
  }
  splitable.capMaterial = capLooks_[size_t(look)];
  splitable.capMaterialId = 1;

  components::SplitableObject object;
  object.name = name;
  object.transform.position = position;
  object.transform.rotation = rotation;
  if (!known) shared = std::make_shared<const geometry::MeshData>(std::move(mesh));
  object.mesh = shared;
  object.materials = {looks_[size_t(look)], capLooks_[size_t(look)]};
  object.splitable = splitable;
  components::SplitWorld sw = splitWorld();
  const ecs::Entity e = components::createSplitableObject(sw, std::move(object));
  world.add<components::MaterialChoice>(e, components::MaterialChoice{look});
  const base::Status made = components::makeDynamicBody(sw, e, splitable.density, splitable.collider, splits_);
  if (!made.ok())
    std::fprintf(stderr, "demo: %s has no body: %s\n", name.c_str(), made.message.c_str());
  return e;
}

namespace {

// Where a kind's centre rests above the floor (the line-up's heights) and the radius of its
// footprint, metres.
struct Footprint {
  float restHeight;
  float radius;
};

Footprint footprintOf(ObjectKind kind) {
  switch (kind) {
    case ObjectKind::WoodenCube: return {0.5f, 0.71f};
    case ObjectKind::MetalSphere: return {0.5f, 0.5f};
    case ObjectKind::MarbleCylinder: return {0.6f, 0.4f};
    case ObjectKind::MelonEllipsoid: return {0.35f, 0.45f};
    case ObjectKind::MultiPart: return {1.05f, 0.6f};
    case ObjectKind::Skinned: return {0.6f, 0.5f};
    case ObjectKind::Torus: return {0.2f, 0.7f};
    case ObjectKind::StoneBlock: return {0.3f, 0.5f};
  }
  return {0.5f, 0.7f};
}

// The footprint of a mesh in the world: the circle around its (x, z) bounds.
FloorCircle footprintOf(const geometry::MeshData& mesh, const glm::mat4& toWorld) {
  glm::vec2 lo(INFINITY), hi(-INFINITY);
  for (const glm::vec3& p : mesh.positions) {
    const glm::vec3 w(toWorld * glm::vec4(p, 1.f));
    lo = glm::min(lo, glm::vec2(w.x, w.z));
    hi = glm::max(hi, glm::vec2(w.x, w.z));
  }
  return {(lo + hi) * 0.5f, 0.5f * glm::length(hi - lo)};
}

}  // namespace

ecs::Entity DemoGame::spawnInFront(ObjectKind kind, const glm::vec3& forward) {
  ecs::World& world = app_->world();
  std::vector<FloorCircle> occupied;
  for (auto [e, mr, wt] : world.view<components::MeshRenderer, ecs::WorldTransform>()) {
    if (!mr.source || mr.source->positions.empty()) continue;
    const FloorCircle c = footprintOf(*mr.source, wt.matrix * mr.meshOffset);
    if (c.radius < 5.f) occupied.push_back(c);  // not the floor
  }
  for (auto [e, skin, wt] : world.view<components::SkinnedMesh, ecs::WorldTransform>())
    occupied.push_back({glm::vec2(wt.matrix[3].x, wt.matrix[3].z), 0.5f});
  const Footprint f = footprintOf(kind);
  const glm::vec2 spot = freeSpawnSpot(glm::vec2(cameraPosition_.x, cameraPosition_.z), glm::vec2(forward.x, forward.z),
                                       f.radius, occupied);
  // A hair above the floor, so it settles without a drop.
  const float lift = kind == ObjectKind::Skinned ? 0.f : 0.02f;
  return spawn(kind, glm::vec3(spot.x, f.restHeight + lift, spot.y), glm::quat(1.f, 0.f, 0.f, 0.f));
}

ecs::Entity DemoGame::spawnCharacter(const glm::vec3& position, const glm::quat& rotation) {
  ecs::World& world = app_->world();
  // The feet stand on the floor (y = 0) below `position`, facing along the circle.
  Walker walker;
  walker.centre = glm::vec3(position.x, 0.f, position.z) - kWalkRadius * glm::vec3(0.f, 0.f, 1.f);
  (void)rotation;
  const glm::mat4 root = walkerRoot(walker);
  components::SplitableObject object{"skinned character", {}, characterMesh_, characterMaterials_, {}};
  object.transform.position = glm::vec3(root[3]);
  object.transform.rotation = glm::quat_cast(glm::mat3(root));
  object.splitable.density = 1000.0;  // the body's mass; pieces share it by posed volume
  object.splitable.capMaterialId = 1;
  object.splitable.capMaterial = characterMaterials_[1];
  object.splitable.skinnedPieces = components::SkinnedPieceMode::Ragdoll;
  const components::Splitable splitable = object.splitable;
  components::SplitWorld sw = splitWorld();
  const ecs::Entity e = components::createSplitableObject(sw, std::move(object));
  world.add<components::SkinnedMesh>(e, components::makeSkinnedMesh(characterAsset_, "walk"));
  const base::Status made = components::makeSkinnedBody(sw, e, splitable.density, /*kinematic=*/true);
  if (!made.ok()) {
    std::fprintf(stderr, "demo: the character has no body: %s\n", made.message.c_str());
  } else {
    const auto& body = world.get<components::RigidBody>(e);
    const auto bt = physics_->bodyTransform(body.body);
    const glm::mat4 bodyWorld = glm::translate(glm::mat4(1.f), bt->position) * glm::mat4_cast(bt->rotation);
    walker.bodyFromRoot = glm::inverse(root) * bodyWorld;
  }
  world.add<Walker>(e, walker);
  return e;
}

ecs::Entity DemoGame::spawnFigure(const glm::vec3& position, const glm::quat& rotation) {
  ecs::World& world = app_->world();
  components::SplitableObject object{"figure", {}, figureMesh_, characterMaterials_, {}};
  object.transform.position = glm::vec3(position.x, 0.f, position.z);  // feet on the floor
  object.transform.rotation = rotation;
  object.splitable.density = 1000.0;
  object.splitable.capMaterialId = 1;
  object.splitable.capMaterial = capLooks_[5];
  object.splitable.skinnedPieces = components::SkinnedPieceMode::Bake;
  object.splitable.separateIslands = false;  // each side of a cut stays one figure piece
  const components::Splitable splitable = object.splitable;
  components::SplitWorld sw = splitWorld();
  const ecs::Entity e = components::createSplitableObject(sw, std::move(object));
  world.add<components::SkinnedMesh>(e, components::makeSkinnedMesh(characterAsset_, "idle"));
  world.add<components::MaterialChoice>(e, components::MaterialChoice{5});
  const base::Status made = components::makeSkinnedBody(sw, e, splitable.density, /*kinematic=*/true);
  if (!made.ok())
    std::fprintf(stderr, "demo: the figure has no body: %s\n", made.message.c_str());
  return e;
}

void DemoGame::walkCharacters(double dt) {
  ecs::World& world = app_->world();
  for (auto [e, walker, skin] : world.view<Walker, components::SkinnedMesh>()) {
    walker.seconds += float(dt);
    const float phase = walker.walking ? kWalkSeconds : kIdleSeconds;
    if (walker.seconds >= phase) {
      walker.seconds -= phase;
      walker.walking = !walker.walking;
      skin.animator.play(characterAsset_->clip(walker.walking ? "walk" : "idle"), kCrossfadeSeconds);
    }
    // Speed follows the clip blend, so the feet do not slide while the fade runs.
    const float weight = skin.animator.blendWeight();
    const float speed = walker.walking ? weight : 1.f - weight;
    walker.angle += kWalkAngularSpeed * speed * float(dt);
    if (const auto* rb = world.tryGet<components::RigidBody>(e)) {
      const glm::mat4 body = walkerRoot(walker) * walker.bodyFromRoot;
      physics_->setBodyTransform(rb->body, physics::BodyTransform{glm::vec3(body[3]), glm::quat_cast(glm::mat3(body))});
    }
  }
}

base::Status DemoGame::loadSceneFile(const std::string& path) {
  components::SceneContext context{app_->world(), *physics_, &app_->renderer(), splits_, {}};
  // Material names of the scene file map to the demo's looks; caps get the inside look.
  context.materials = [this](const std::string& name, bool cap) {
    if (name == "floor") return floorMaterial_;
    static const char* aliases[7][2] = {{"wood", "wooden"},  {"metal", "steel"},
                                        {"marble", "stone"}, {"melon", "watermelon"},
                                        {"normals", "debug"}, {"checker", "checker3d"},
                                        {"environment", "env"}};
    for (size_t k = 0; k < 7; ++k) {
      if (name == lookNames_[k] || name == aliases[k][0] || name == aliases[k][1])
        return cap ? capLooks_[k] : looks_[k];
    }
    render::Material plain;
    plain.baseColor = glm::vec4(0.75f, 0.72f, 0.68f, 1.f);
    plain.specular = 0.3f;
    return plain;
  };
  components::SceneLoadResult scene = components::loadScene(path, context);
  if (!scene.ok()) return scene;
  for (const components::SceneEntity& e : scene.entities) {
    for (size_t k = 0; k < 7; ++k) {
      if (e.material == lookNames_[k] && app_->world().alive(e.entity))
        app_->world().add<components::MaterialChoice>(e.entity, components::MaterialChoice{int(k)});
    }
  }
  sceneRunner_ = std::make_unique<components::SceneRunner>(scene.splitters);
  cameraPosition_ = scene.cameraPosition;
  const glm::vec3 look = scene.cameraTarget - scene.cameraPosition;
  if (glm::length(look) > 1e-4f) {
    const glm::vec3 d = glm::normalize(look);
    yaw_ = std::atan2(-d.x, -d.z);
    pitch_ = std::asin(std::clamp(d.y, -1.f, 1.f));
  }
  return {};
}

base::Status DemoGame::setup(app::App& app) {
  app_ = &app;
  components::SplitBudgetSettings budget;
  // Main-thread split work is kept under 4 ms a tick: the estimates are fitted to single cuts and
  // run 2-3x low in a burst (many uploads and bodies at once), so the budget is 1 ms of estimate.
  // 6 ms of compute is started per tick (a third of a frame on one worker). Charged by estimate, so
  // replays are the same on any machine and thread count.
  budget.millisecondsPerTick = 1.0;
  budget.workerMillisecondsPerTick = 6.0;
  budget.maxSplitsPerTick = 32;
  if (app.options().splitThreads >= 0) budget.threads = uint32_t(app.options().splitThreads);
  sim_ = std::make_unique<components::Simulation>(app.world(), budget, &app.renderer());
  physics_ = &sim_->physics();
  splits_ = &sim_->splits();
  if (const char* dir = std::getenv("CLEAVE_SPLIT_FAILURE_DIR"); dir && *dir)
    splits_->setFailureDumpDirectory(dir);
  createMaterials();
  if (!app.options().scenePath.empty()) {
    if (base::Status loaded = loadSceneFile(app.options().scenePath); !loaded.ok()) return loaded;
  } else {
    createFloor();
    // The thesis's line-up: one of each object, plus a second row to have something to push into.
    const glm::quat upright(1.f, 0.f, 0.f, 0.f);
    spawn(ObjectKind::WoodenCube, {-3.f, 0.5f, 0.f}, upright);
    spawn(ObjectKind::MetalSphere, {-1.5f, 0.5f, 0.f}, upright);
    spawn(ObjectKind::MarbleCylinder, {0.f, 0.6f, 0.f}, upright);
    spawn(ObjectKind::MelonEllipsoid, {1.5f, 0.35f, 0.f}, upright);
    spawn(ObjectKind::Torus, {3.f, 0.2f, 0.f}, upright);
    spawn(ObjectKind::MultiPart, {-1.f, 1.05f, -2.5f}, upright);
    spawn(ObjectKind::Skinned, {1.2f, 0.6f, -2.5f}, upright);
  }

  app.addSystem(app::Phase::Gameplay, "demo.gameplay", [this](app::TickContext& c) { gameplay(c); });
  components::SplittingHooks hooks;
  hooks.camera = [this] { return glm::dvec3(cameraPosition_); };
  hooks.committed = [this](app::TickContext& c, const std::vector<components::SplitEvent>& events) {
    splitLog_.record(c.tick, events);
    splitStats_.record(*splits_);
  };
  components::installSplitting(app, *sim_, std::move(hooks));
  app.addSystem(app::Phase::Render, "demo.render", [this](app::TickContext& c) { render(c); });
  app.setUi([this](app::TickContext& c) { drawInspector(c); });
  if (app.options().inspector) {
    if (const base::Status opened = inspector_.open(app); !opened.ok())
      log::warning("cleave-demo", "--inspector: %s", opened.message.c_str());
  }
  app.setStateDumpExtension([this](ecs::Entity e, nlohmann::json& out) { dumpExtension(e, out); });
  app.setFrameDumpExtension([this](nlohmann::json& line) {
    nlohmann::json splits;
    splitLog_.writeJson(splits);
    line["splits"] = std::move(splits);
    line["piece_budget"] = components::toJson(splits_->pieces().stats());
    line["looks_cycled"] = looksShown_;  // every look Q/E switched an object to, sorted
    line["notice"] = tick_ < noticeUntil_ ? notice_ : std::string();
    // The HUD's boxes and the extent of the text in each (x, y, w, h in pixels), with the frame size:
    // tests check that text fits its box and boxes fit the frame.
    nlohmann::json hud = nlohmann::json::array();
    for (const HudItem& item : hudLayout_) {
      hud.push_back({{"what", item.what},
                     {"box", {item.box.x, item.box.y, item.box.z, item.box.w}},
                     {"text", {item.content.x, item.content.y, item.content.z, item.content.w}}});
    }
    const glm::ivec2 frame = app_->platform().frameSize();
    line["hud"] = {{"frame", {frame.x, frame.y}}, {"items", std::move(hud)}};
    inspector_.writeJson(line["inspector"]);
    const auto& stats = splits_->budget().stats();
    line["budget"] = {{"deferred_total", splitStats_.deferredTotal},
                      {"max_queue", splitStats_.maxQueue},
                      {"max_split_ms", stats.maxSplitMilliseconds},
                      {"max_split_work_ms_in_a_tick", splitStats_.maxWorkMsInATick},
                      {"max_split_wait_ms_in_a_tick", splitStats_.maxWaitMsInATick},
                      {"queue", stats.queueLength}};
  });
  return {};
}

glm::vec3 DemoGame::rayDirection(glm::vec2 pixel, glm::ivec2 frame) const {
  const float aspect = float(frame.x) / float(frame.y);
  const float tanHalf = std::tan(1.0f * 0.5f);
  const float x = (2.f * pixel.x / float(frame.x) - 1.f) * tanHalf * aspect;
  const float y = (1.f - 2.f * pixel.y / float(frame.y)) * tanHalf;
  const glm::quat orientation = glm::angleAxis(yaw_, glm::vec3(0, 1, 0)) *
                                glm::angleAxis(pitch_, glm::vec3(1, 0, 0));
  return glm::normalize(orientation * glm::vec3(x, y, -1.f));
}

ecs::Entity DemoGame::entityUnderCrosshair(glm::vec3* hitPoint) {
  const glm::ivec2 frame = app_->platform().frameSize();
  return splitableAlong(rayDirection(glm::vec2(frame) * 0.5f, frame), hitPoint);
}

// The splitable the ray from the camera along `dir` hits first, if any.
ecs::Entity DemoGame::splitableAlong(const glm::vec3& dir, glm::vec3* hitPoint) const {
  const auto hit = physics_->raycast(cameraPosition_, cameraPosition_ + dir * 100.f);
  if (!hit) return {};
  const auto user = physics_->bodyUserData(hit->body);
  if (!user) return {};
  const ecs::Entity e = components::fromUserData(*user);
  if (!app_->world().alive(e) || !app_->world().has<components::Splitable>(e)) return {};
  if (hitPoint) *hitPoint = hit->point;
  return e;
}

namespace {

// The shortest rotation taking +Y to the unit vector `to`.
glm::quat rotationFromUp(const glm::vec3& to) {
  const glm::vec3 up(0.f, 1.f, 0.f);
  const float c = glm::dot(up, to);
  if (c < -0.99999f) return glm::angleAxis(glm::pi<float>(), glm::vec3(1.f, 0.f, 0.f));
  const glm::vec3 axis = glm::cross(up, to);
  const float s = std::sqrt((1.f + c) * 2.f);
  return glm::normalize(glm::quat(s * 0.5f, axis.x / s, axis.y / s, axis.z / s));
}

}  // namespace

void DemoGame::shatterUnderCrosshair(app::TickContext& c) {
  glm::vec3 point;
  if (!c.world.alive(entityUnderCrosshair(&point))) {
    notify("nothing to shatter under the crosshair");
    return;
  }
  components::Splitter hammer;
  hammer.kind = components::SplitterKind::Shatter;
  hammer.lifetime = components::SplitterLifetime::OneTick;
  hammer.playerCaused = true;
  hammer.halfExtents = glm::vec3(0.15f);
  hammer.shatter.cells = 16;
  hammer.shatter.seed = c.tick;
  hammer.shatter.impactRadius = 0.3;
  hammer.shatter.outwardImpulse = 2.0;
  components::SplitWorld sw = splitWorld();
  components::createSplitter(sw, "shatter", physics::ShapeDef::box(hammer.halfExtents), point,
                             glm::quat(1.f, 0.f, 0.f, 0.f), hammer);
}

void DemoGame::notify(const std::string& text) {
  notice_ = text;
  noticeUntil_ = tick_ + 90;  // a second and a half
}

// Rays through 48 points of the drawn line: does any of them hit a splitable? (The cut's trigger
// is the wedge between the line's end rays; an object thinner than the rays' spacing can slip
// between them here and still be cut: the message then errs on the side of silence.)
bool DemoGame::lineCrossesSplitable(glm::vec2 from, glm::vec2 to, glm::ivec2 frame) const {
  constexpr int kSamples = 48;
  for (int k = 0; k <= kSamples; ++k) {
    const glm::vec2 at = glm::mix(from, to, float(k) / kSamples);
    if (app_->world().alive(splitableAlong(rayDirection(at, frame)))) return true;
  }
  return false;
}

void DemoGame::dragCut(app::TickContext& c, glm::vec2 from, glm::vec2 to) {
  if (glm::length(to - from) < 4.f) return;
  if (!lineCrossesSplitable(from, to, c.frameSize)) notify("missed: the line crosses nothing to cut");
  const glm::vec3 a = rayDirection(from, c.frameSize);
  const glm::vec3 b = rayDirection(to, c.frameSize);
  glm::vec3 normal = glm::cross(a, b);
  if (glm::length(normal) < 1e-6f) return;
  normal = glm::normalize(normal);
  // A one-tick splitter whose trigger is the thin wedge between the two rays: only what lies under
  // the drawn line is cut.
  const float thickness = 0.01f;
  std::vector<glm::vec3> points;
  const glm::vec3 tips[3] = {cameraPosition_, cameraPosition_ + a * kCutReach,
                             cameraPosition_ + b * kCutReach};
  for (const glm::vec3& p : tips) {
    points.push_back(p + normal * thickness);
    points.push_back(p - normal * thickness);
  }
  const glm::vec3 centre = (tips[0] + tips[1] + tips[2]) / 3.f;
  // The splitter frame: origin on the plane, local +Y along the plane normal.
  const glm::quat rotation = rotationFromUp(normal);
  const glm::quat inverse = glm::inverse(rotation);
  for (glm::vec3& p : points) p = inverse * (p - centre);
  components::Splitter splitter;
  splitter.lifetime = components::SplitterLifetime::OneTick;
  splitter.playerCaused = true;
  components::SplitWorld sw = splitWorld();
  components::createSplitter(sw, "drag cut", physics::ShapeDef::convexHull(points), centre, rotation, splitter);
}

void DemoGame::gameplay(app::TickContext& c) {
  tick_ = c.tick;
  walkCharacters(c.dt);
  if (sceneRunner_) {
    components::SplitWorld sw = splitWorld();
    sceneRunner_->update(sw, c.tick, c.dt);
  }
  if (!updateModes(c)) return;
  const glm::vec3 forward = updateCamera(c);
  objectKeys(c, forward);
  dragToCut(c);
}

// Escape frees the mouse (the camera stops turning, the cursor shows), a left click takes it back
// and a second Escape quits (false: the game is quitting); F1 the inspector; holding Space split
// mode. The cursor shows in split mode, with the mouse freed, and while the inspector is open.
bool DemoGame::updateModes(app::TickContext& c) {
  const input::InputState& in = c.input;
  using input::Key;
  if (in.pressed(Key::Escape)) {
    if (mouseFree_) {
      c.app.requestQuit();
      return false;
    }
    mouseFree_ = true;
  } else if (mouseFree_ && !splitMode_ && !inspector_.isOpen() && in.pressed(input::MouseButton::Left)) {
    mouseFree_ = false;
  }
  if (in.pressed(Key::F1)) toggleInspector(c);
  const bool wantSplitMode = in.held(Key::Space);
  if (wantSplitMode != splitMode_) {
    splitMode_ = wantSplitMode;
    dragging_ = false;
  }
  const bool cursorFree = splitMode_ || mouseFree_ || inspector_.isOpen();
  if (cursorFree != cursorFree_) {
    cursorFree_ = cursorFree;
    c.platform.setCursorMode(cursorFree ? app::CursorMode::Normal : app::CursorMode::Captured);
  }
  return true;
}

// Mouse look (when the cursor is captured) and WASD, Shift+E up; returns the forward direction on
// the floor.
glm::vec3 DemoGame::updateCamera(app::TickContext& c) {
  const input::InputState& in = c.input;
  using input::Key;
  if (!cursorFree_) {
    yaw_ -= in.mouseDelta().x * kLookSensitivity;
    pitch_ = std::clamp(pitch_ - in.mouseDelta().y * kLookSensitivity, -1.5f, 1.5f);
  }
  const glm::quat yawOnly = glm::angleAxis(yaw_, glm::vec3(0, 1, 0));
  const glm::vec3 forward = yawOnly * glm::vec3(0, 0, -1);
  const glm::vec3 right = yawOnly * glm::vec3(1, 0, 0);
  glm::vec3 move(0.f);
  if (in.held(Key::W)) move += forward;
  if (in.held(Key::S)) move -= forward;
  if (in.held(Key::D)) move += right;
  if (in.held(Key::A)) move -= right;
  if (in.held(Key::E) && in.held(Key::LeftShift)) move.y += 1.f;
  if (glm::length(move) > 0.f) cameraPosition_ += glm::normalize(move) * kMoveSpeed * float(c.dt);
  cameraPosition_.y = std::max(cameraPosition_.y, 0.3f);
  return forward;
}

// H help, 1-8 spawn, Q/E the look of the object under the crosshair, F a shatter at it, the right
// button a push.
void DemoGame::objectKeys(app::TickContext& c, const glm::vec3& forward) {
  const input::InputState& in = c.input;
  using input::Key;
  if (in.pressed(Key::H)) showHelp_ = !showHelp_;
  const Key spawnKeys[8] = {Key::Num1, Key::Num2, Key::Num3, Key::Num4,
                            Key::Num5, Key::Num6, Key::Num7, Key::Num8};
  for (int k = 0; k < 8; ++k)
    if (in.pressed(spawnKeys[k])) spawnInFront(ObjectKind(k + 1), forward);
  if (in.pressed(Key::Q) || (in.pressed(Key::E) && !in.held(Key::LeftShift))) cycleLook(c, in.pressed(Key::Q) ? 6 : 1);
  // F throws a shatter at the object under the crosshair: a one-tick shatter splitter at the point
  // the crosshair hits, 16 cells gathered around it, the pieces flying off at 2 m/s.
  if (in.pressed(Key::F)) shatterUnderCrosshair(c);
  if (in.pressed(input::MouseButton::Right)) pushUnderCrosshair(c);
}

// The object under the crosshair takes the look `step` places on (of the seven), its cap with it.
void DemoGame::cycleLook(app::TickContext& c, int step) {
  const ecs::Entity target = entityUnderCrosshair();
  auto* choice = c.world.tryGet<components::MaterialChoice>(target);
  if (!choice) return;
  choice->index = (choice->index + step) % 7;
  looksShown_.insert(lookNames_[size_t(choice->index)]);
  if (auto* mr = c.world.tryGet<components::MeshRenderer>(target)) {
    mr->materials[0] = looks_[size_t(choice->index)];
    if (mr->materials.size() > 1) mr->materials[1] = capLooks_[size_t(choice->index)];
  }
  if (auto* sp = c.world.tryGet<components::Splitable>(target)) sp->capMaterial = capLooks_[size_t(choice->index)];
}

// The right button pushes the object under the crosshair where the crosshair hits it.
void DemoGame::pushUnderCrosshair(app::TickContext& c) {
  glm::vec3 point;
  const ecs::Entity target = entityUnderCrosshair(&point);
  auto* rb = c.world.tryGet<components::RigidBody>(target);
  if (!rb) {
    notify("nothing to push under the crosshair");
    return;
  }
  const float mass = physics_->bodyMass(rb->body).value_or(1.f);
  const glm::vec3 dir = rayDirection(glm::vec2(c.frameSize) * 0.5f, c.frameSize);
  physics_->activate(rb->body);
  physics_->applyImpulse(rb->body, dir * kPushImpulse * mass, point);
}

// In split mode, a drag with the left button cuts along the line drawn.
void DemoGame::dragToCut(app::TickContext& c) {
  if (!splitMode_) return;
  const input::InputState& in = c.input;
  if (in.pressed(input::MouseButton::Left)) {
    dragging_ = true;
    dragStart_ = dragEnd_ = in.mousePosition();
  }
  if (dragging_) dragEnd_ = in.mousePosition();
  if (dragging_ && in.released(input::MouseButton::Left)) {
    dragging_ = false;
    dragCut(c, dragStart_, dragEnd_);
  }
}

void DemoGame::render(app::TickContext& c) {
  render::Camera camera;
  camera.position = cameraPosition_;
  const glm::quat orientation = glm::angleAxis(yaw_, glm::vec3(0, 1, 0)) *
                                glm::angleAxis(pitch_, glm::vec3(1, 0, 0));
  camera.view = glm::lookAt(cameraPosition_, cameraPosition_ + orientation * glm::vec3(0, 0, -1),
                            glm::vec3(0, 1, 0));
  render::Lighting lighting;
  lighting.shadowCenter = cameraPosition_ + orientation * glm::vec3(0, 0, -6.f);
  lighting.shadowCenter.y = 0.f;
  lighting.shadowRadius = 12.f;
  c.renderer.beginFrame(c.frameSize.x, c.frameSize.y, camera, lighting);
  sim_->submitMeshes(c.tick);
  drawHud(c);
}

namespace {

// The HUD's size follows the frame: 2 at 1280 x 720 (its design size), from 1 to 3.
float hudScaleFor(glm::ivec2 frame) {
  return std::clamp(std::min(float(frame.x) / 640.f, float(frame.y) / 360.f), 1.f, 3.f);
}

// stb_easy_font glyphs are about 8 px high (descenders included) at scale 1.
constexpr float kGlyphHeight = 8.f;

}  // namespace

void DemoGame::hudBox(app::TickContext& c, const char* what, const glm::vec4& box, const glm::vec4& color) {
  c.renderer.submitOverlayRect(box, color);
  hudLayout_.push_back({what, box, glm::vec4(box.x, box.y, 0.f, 0.f)});
}

void DemoGame::hudText(app::TickContext& c, const std::string& text, glm::vec2 at, float scale, const glm::vec4& color) {
  c.renderer.submitText(text, at, scale, color);
  const glm::vec4 rect(at, render::Renderer::textWidth(text, scale), kGlyphHeight * scale);
  // Text drawn inside the last box grows that box's content; text on its own is a box of its own.
  if (!hudLayout_.empty() && hudLayout_.back().open) {
    glm::vec4& content = hudLayout_.back().content;
    if (content.z == 0.f && content.w == 0.f) {
      content = rect;
    } else {
      const glm::vec2 lo = glm::min(glm::vec2(content), glm::vec2(rect));
      const glm::vec2 hi = glm::max(glm::vec2(content) + glm::vec2(content.z, content.w),
                                    glm::vec2(rect) + glm::vec2(rect.z, rect.w));
      content = glm::vec4(lo, hi - lo);
    }
  } else {
    hudLayout_.push_back({"text", rect, rect, false});
  }
}

uint32_t DemoGame::countPieces() const {
  uint32_t pieces = 0;
  for (auto [e, origin] : app_->world().view<components::SplitOrigin>()) {
    (void)e;
    (void)origin;
    ++pieces;
  }
  return pieces;
}

void DemoGame::toggleInspector(app::TickContext& c) {
  const std::string why = inspector_.toggle(c.app);
  if (!why.empty()) notify(why);
}

void DemoGame::drawInspector(app::TickContext& c) {
  const inspector::InspectorFeed feed{c.world, *splits_, splitLog_, splitStats_.history, entityUnderCrosshair(),
                                      countPieces()};
  inspector_.draw(c, feed);
}

void DemoGame::drawStatsPanel(app::TickContext& c, float u) {
  const auto& stats = splits_->budget().stats();
  const uint32_t pieces = countPieces();
  char texts[4][256];
  const glm::vec4 white(1.f), dim(0.f, 0.f, 0.f, 0.45f);
  // Headless runs draw no frames to count: they show the tick rate (as fast as the ticks run).
  const bool headless = c.app.headless();
  std::snprintf(texts[0], sizeof(texts[0]), "%s %.0f   tick %.2f ms", headless ? "TPS" : "FPS",
                headless ? c.app.ticksPerSecond() : c.app.framesPerSecond(), c.app.lastTickMilliseconds());
  std::snprintf(texts[1], sizeof(texts[1]), "splits this tick %u   queue %u", splitStats_.splitsThisTick, stats.queueLength);
  // The main thread's own split work and what it waited for the workers (their time: the inspector).
  std::snprintf(texts[2], sizeof(texts[2]), "split ms %.2f  wait %.2f", splitStats_.times.work, splitStats_.times.wait);
  const components::PieceBudgetStats& kept = splits_->pieces().stats();
  std::snprintf(texts[3], sizeof(texts[3]), "pieces %u  awake %u  frozen %u   tick %llu", pieces, kept.awake,
                kept.frozen, static_cast<unsigned long long>(c.tick));
  // The panel fits its longest line: the counts as they are, the timings at their widest usual
  // figures (so that its size does not change with the wall clock).
  const float gw = 120.f * u, gh = 12.f * u;  // the split-time graph
  float panel = gw + 4.f * u;
  const char* widest[] = {texts[1], texts[3], "FPS 9999   tick 99.99 ms", "split ms 99.99  wait 99.99"};
  for (const char* text : widest) panel = std::max(panel, render::Renderer::textWidth(text, u));
  hudBox(c, "stats", glm::vec4(4.f * u, 4.f * u, panel + 8.f * u, 59.f * u), dim);
  for (int k = 0; k < 4; ++k) hudText(c, texts[k], {8.f * u, (7.f + 10.f * float(k)) * u}, u, white);
  // Graph: split ms per tick against the budget line.
  components::drawSplitGraph(c.renderer, splitStats_.history, splits_->budget().settings().millisecondsPerTick,
                             glm::vec4(8.f * u, 48.f * u, gw, gh));
  hudLayout_.back().open = false;
}

void DemoGame::drawHelp(app::TickContext& c, float u) {
  const char* help[] = {"WASD move, mouse look",     "hold Space: split mode, drag left button to cut",
                        "right button: push",        "1-8: spawn cube, sphere, cylinder, melon,",
                        "     figure, skinned, torus, stone block", "Q/E: cycle the material under the crosshair",
                        "F: shatter what is under the crosshair",
                        "Esc: free the mouse; Esc again: quit",
                        "F1: inspector (split settings, budget, log)", "H: this help"};
  float width = 0.f;
  for (const char* h : help) width = std::max(width, render::Renderer::textWidth(h, u));
  const float pad = 7.5f * u, line = 14.f * u;
  const glm::vec2 size(width + 2.f * pad, line * float(std::size(help)) + 2.f * pad - (line - kGlyphHeight * u));
  const glm::vec2 corner = glm::vec2(c.frameSize) * 0.5f - 0.5f * size;
  hudBox(c, "help", glm::vec4(corner, size), glm::vec4(0, 0, 0, 0.6f));
  float y = corner.y + pad;
  for (const char* h : help) {
    hudText(c, h, {corner.x + pad, y}, u, glm::vec4(1.f));
    y += line;
  }
  hudLayout_.back().open = false;
}

void DemoGame::drawHud(app::TickContext& c) {
  render::Renderer& r = c.renderer;
  hudLayout_.clear();
  const float u = hudScaleFor(c.frameSize);  // the text scale; 2 at 1280 x 720
  drawStatsPanel(c, u);
  // Crosshair, drag line, help.
  const glm::vec4 white(1.f);
  const glm::vec2 mid = glm::vec2(c.frameSize) * 0.5f;
  const float arm = 4.f * u;
  const glm::vec2 cross[4] = {mid - glm::vec2(arm, 0), mid + glm::vec2(arm, 0), mid - glm::vec2(0, arm),
                              mid + glm::vec2(0, arm)};
  if (!showHelp_) r.submitOverlayLines(cross, white);  // not over the help text
  if (dragging_) {
    const glm::vec2 drag[2] = {dragStart_, dragEnd_};
    r.submitOverlayLines(drag, glm::vec4(1.f, 0.9f, 0.2f, 1.f));
  }
  const glm::vec4 yellow(1, 0.9f, 0.2f, 1);
  auto centred = [&](const std::string& text, float y) {
    hudText(c, text, {mid.x - 0.5f * render::Renderer::textWidth(text, u), y}, u, yellow);
  };
  if (splitMode_) centred("SPLIT MODE: drag to cut", 70.f * u);
  if (mouseFree_) centred("MOUSE FREE: click to look around, Esc again to quit", 82.f * u);
  if (c.tick < noticeUntil_) centred(notice_, mid.y + 12.f * u);
  // A start-up hint for the first ten seconds.
  if (c.tick < 600 && !showHelp_) centred("H: help   Esc: free the mouse (twice: quit)", float(c.frameSize.y) - 17.f * u);
  if (showHelp_) drawHelp(c, u);
}

void DemoGame::dumpExtension(ecs::Entity e, nlohmann::json& out) {
  ecs::World& world = app_->world();
  if (const auto* mi = world.tryGet<components::MassInfo>(e)) {
    out["mass"] = mi->mass;
    out["volume"] = mi->volume;
  }
  if (const auto* rb = world.tryGet<components::RigidBody>(e)) {
    if (const auto state = physics_->bodyState(rb->body)) {
      out["center_of_mass"] = {state->transform.position.x, state->transform.position.y,
                               state->transform.position.z};
      out["linear_velocity"] = {state->linearVelocity.x, state->linearVelocity.y, state->linearVelocity.z};
      out["angular_velocity"] = {state->angularVelocity.x, state->angularVelocity.y,
                                 state->angularVelocity.z};
      out["awake"] = state->awake;
    }
  }
  if (const auto* origin = world.tryGet<components::SplitOrigin>(e)) out["split_from"] = origin->parentId;
  if (const auto* choice = world.tryGet<components::MaterialChoice>(e))
    out["look"] = lookNames_[size_t(choice->index) % lookNames_.size()];
  // The lowest point of a rigid mesh in the world, to check it against the floor (skinned meshes
  // are drawn posed, not as their bind-space vertices: left out).
  const auto* mr = world.tryGet<components::MeshRenderer>(e);
  const auto* t = world.tryGet<ecs::Transform>(e);
  if (mr && mr->source && mr->source->joints.empty() && t && ecs::parentOf(world, e) == ecs::kNullEntity) {
    const glm::mat4 toWorld = ecs::localMatrix(*t) * mr->meshOffset;
    float lowest = INFINITY;
    for (const glm::vec3& p : mr->source->positions) lowest = std::min(lowest, (toWorld * glm::vec4(p, 1.f)).y);
    out["lowest_y"] = lowest;
  }
}

}  // namespace cleave::demo
