// SPDX-License-Identifier: MIT
#include "game/arena/arena_game.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "cleave/components/scene_components.h"
#include "cleave/components/skinned.h"
#include "cleave/components/splitable.h"
#include "cleave/components/splitable_object.h"
#include "cleave/ecs/hierarchy.h"
#include "cleave/log/log.h"
#include "cleave/geometry/primitives.h"
#include "game/arena/arena_layout.h"
#include "game/arena/arena_surroundings.h"

namespace cleave::arena {

namespace {

namespace prim = geometry::primitives;

constexpr float kDiscHeight = 1.0f;       // m above the floor: waist height of the gladiators
constexpr float kDiscRadius = 0.45f;      // m
constexpr float kDiscSpeed = 13.f;        // m/s outbound
constexpr float kDiscReturnSpeed = 15.f;  // m/s homing back
constexpr int kDiscBounces = 3;
constexpr float kDiscFlightSeconds = 2.6f;  // it turns back after this even without its bounces
constexpr int kSwordTicks = 10;
constexpr int kSpinTicks = 18;
constexpr float kSpinRadius = 2.7f;       // m
constexpr int kHammerTicks = 14;          // from raising the hammer to its landing
constexpr float kHammerReach = 1.7f;      // m from the player to where it lands
constexpr glm::vec3 kHammerHalfExtents(0.95f, 1.0f, 0.95f);  // what it shatters, from the floor up
constexpr uint64_t kPieceLifeTicks = 420;   // 7 s before a piece starts to shrink
constexpr uint64_t kPieceShrinkTicks = 45;
constexpr size_t kMaxPieces = 260;          // more than this: the oldest go early
constexpr int kHitFreezeTicks = 60;         // a frozen enemy whose split never comes walks on
constexpr double kCrumbVolume = 1.5e-3;     // m^3: pieces smaller than this are not cut again
constexpr double kLimbShare = 0.2;          // gladiator pieces under this share of its mass: no ragdoll


// The shortest rotation taking +Y to the unit vector `to`.
glm::quat rotationFromUp(const glm::vec3& to) {
  const glm::vec3 up(0.f, 1.f, 0.f);
  const float c = glm::dot(up, to);
  if (c < -0.99999f) return glm::angleAxis(kPi, glm::vec3(1.f, 0.f, 0.f));
  const glm::vec3 axis = glm::cross(up, to);
  const float s = std::sqrt((1.f + c) * 2.f);
  return glm::normalize(glm::quat(s * 0.5f, axis.x / s, axis.y / s, axis.z / s));
}

}  // namespace

uint8_t ArenaGame::weaponIndex(const std::string& splitterName) {
  for (size_t w = 1; w < kWeaponCount; ++w)
    if (splitterName == kWeaponSplitterNames[w]) return uint8_t(w);
  return 0;
}

const char* toString(MatchState state) {
  switch (state) {
    case MatchState::Menu: return "menu";
    case MatchState::Starting: return "starting";
    case MatchState::Intermission: return "intermission";
    case MatchState::Playing: return "playing";
    case MatchState::Defeated: return "defeated";
    case MatchState::Quitting: return "quitting";
  }
  return "?";
}

ArenaGame::ArenaGame() = default;
ArenaGame::~ArenaGame() = default;

components::SplitWorld ArenaGame::splitWorld() {
  return components::SplitWorld{app_->world(), *physics_, &app_->renderer()};
}

EnemyContext ArenaGame::enemyContext() {
  return EnemyContext{app_->world(), *physics_, &app_->renderer(), materials_};
}

float ArenaGame::nextRandom() {
  // xorshift64*: the same seed gives the same arena on every machine.
  rng_ ^= rng_ >> 12;
  rng_ ^= rng_ << 25;
  rng_ ^= rng_ >> 27;
  return float((rng_ * 2685821657736338717ull) >> 40) / float(1u << 24);
}

// ---------------------------------------------------------------------------------------------
// Building

ecs::Entity ArenaGame::addStatic(const std::string& name, geometry::MeshData mesh,
                                 std::vector<render::Material> materials, bool collide) {
  ecs::World& world = app_->world();
  const ecs::Entity e = world.create();
  world.add<ecs::Name>(e, ecs::Name{name});
  world.add<ecs::Transform>(e, ecs::Transform{});
  world.add<ecs::WorldTransform>(e, ecs::WorldTransform{});
  world.add<ArenaTag>(e, ArenaTag{ArenaTag::Level});
  auto source = std::make_shared<geometry::MeshData>(std::move(mesh));
  if (collide) {
    auto shape = physics_->createShape(physics::ShapeDef::convexHull(source->positions));
    if (shape.ok()) {
      physics::BodyDef def;
      def.shape = shape.value();
      def.userData = components::toUserData(e);
      auto body = physics_->createBody(def);
      staticShapes_.push_back(shape.value());
      if (body.ok()) staticBodies_.push_back(body.value());
    }
  }
  components::MeshRenderer mr;
  mr.source = source;
  mr.gpu = app_->renderer().uploadMesh(*source).valueOr({});
  mr.materials = std::move(materials);
  world.add<components::MeshRenderer>(e, std::move(mr));
  return e;
}

void ArenaGame::buildLevel() {
  buildFloorAndWall();
  buildGatesAndPillars();
  // Outside the wall: the stands with their crowd, and turf out to the fog, so that no view from
  // inside the arena shows the void.
  const StandsLayout stands;
  addStatic("stands", standsMesh(stands), {materials_.stands, materials_.stands, materials_.standsRiser}, false);
  addStatic("crowd", crowdMesh(stands, 31), materials_.crowd, false);
  addStatic("turf", groundRing(stands.innerRadius - 0.3f, 160.f, -0.03f, 0.15f), {materials_.turf}, false);
}

void ArenaGame::buildFloorAndWall() {
  // The sand-stone floor: a disc a little wider than the wall ring, flagstones mapped from above.
  geometry::MeshData floor = prim::cylinder(13.2f, 1.f, 96);
  prim::transform(floor, glm::translate(glm::mat4(1.f), glm::vec3(0.f, -0.5f, 0.f)));
  planarUv(floor, 0.4f);
  addStatic("floor", std::move(floor), {materials_.floor}, false);
  auto floorShape = physics_->createShape(physics::ShapeDef::box(glm::vec3(14.f, 0.5f, 14.f)));
  if (floorShape.ok()) {
    physics::BodyDef def;
    def.shape = floorShape.value();
    def.position = glm::vec3(0.f, -0.5f, 0.f);
    def.friction = 0.8f;
    auto body = physics_->createBody(def);
    staticShapes_.push_back(floorShape.value());
    if (body.ok()) staticBodies_.push_back(body.value());
  }

  // The wall: a ring of stone blocks with merlons on top, one collider per block, and four gates.
  constexpr int kBlocks = 32;
  const float blockRadius = kArenaRadius + 0.45f;
  const glm::vec3 blockHalf(1.27f, 1.4f, 0.45f);
  geometry::MeshData wall;
  bool first = true;
  auto shape = physics_->createShape(physics::ShapeDef::box(blockHalf));
  if (shape.ok()) staticShapes_.push_back(shape.value());
  for (int k = 0; k < kBlocks; ++k) {
    const float angle = 2.f * kPi * float(k) / float(kBlocks);
    const glm::vec2 at = compass(angle) * blockRadius;
    const glm::quat rot = glm::angleAxis(kPi - angle, glm::vec3(0, 1, 0));
    const glm::mat4 m = glm::translate(glm::mat4(1.f), glm::vec3(at.x, blockHalf.y, at.y)) * glm::mat4_cast(rot);
    geometry::MeshData block = prim::box(blockHalf);
    geometry::MeshData merlon = prim::box(glm::vec3(0.42f, 0.28f, 0.38f));
    prim::transform(merlon, glm::translate(glm::mat4(1.f), glm::vec3(0.f, blockHalf.y + 0.28f, 0.05f)));
    setMaterial(merlon, 1);
    block = prim::merge(block, merlon);
    prim::transform(block, m);
    wall = first ? std::move(block) : prim::merge(wall, block);
    first = false;
    if (shape.ok()) {
      physics::BodyDef def;
      def.shape = shape.value();
      def.position = glm::vec3(at.x, blockHalf.y, at.y);
      def.rotation = rot;
      auto body = physics_->createBody(def);
      if (body.ok()) staticBodies_.push_back(body.value());
    }
  }
  addStatic("wall", std::move(wall), {materials_.wall, materials_.wallTrim}, false);
}

void ArenaGame::buildGatesAndPillars() {
  geometry::MeshData gates;
  bool first = true;
  first = true;
  for (int g = 0; g < 4; ++g) {
    const float angle = float(g) * kPi * 0.5f;
    const glm::vec2 at = compass(angle) * (kArenaRadius - 0.04f);
    geometry::MeshData door = prim::box(glm::vec3(0.95f, 1.15f, 0.06f));
    geometry::MeshData lintel = prim::box(glm::vec3(1.2f, 0.16f, 0.1f));
    prim::transform(lintel, glm::translate(glm::mat4(1.f), glm::vec3(0.f, 1.3f, 0.f)));
    setMaterial(lintel, 1);
    door = prim::merge(door, lintel);
    prim::transform(door, glm::translate(glm::mat4(1.f), glm::vec3(at.x, 1.15f, at.y)) *
                              glm::mat4_cast(glm::angleAxis(kPi - angle, glm::vec3(0, 1, 0))));
    gates = first ? std::move(door) : prim::merge(gates, door);
    first = false;
  }
  addStatic("gates", std::move(gates), {materials_.gate, materials_.wallTrim}, false);

  // Four marble pillars on the diagonals (obstacles for the enemies, bumpers for the disc).
  for (int p = 0; p < 4; ++p) {
    const float angle = kPi * 0.25f + float(p) * kPi * 0.5f;
    const glm::vec2 at = compass(angle) * 7.2f;
    geometry::MeshData column = prim::cylinder(0.42f, 3.0f, 24);
    prim::transform(column, glm::translate(glm::mat4(1.f), glm::vec3(0.f, 1.8f, 0.f)));
    geometry::MeshData base = prim::box(glm::vec3(0.62f, 0.15f, 0.62f));
    prim::transform(base, glm::translate(glm::mat4(1.f), glm::vec3(0.f, 0.15f, 0.f)));
    geometry::MeshData capital = prim::box(glm::vec3(0.6f, 0.12f, 0.6f));
    prim::transform(capital, glm::translate(glm::mat4(1.f), glm::vec3(0.f, 3.42f, 0.f)));
    geometry::MeshData pillar = prim::merge(prim::merge(base, column), capital);
    prim::transform(pillar, glm::translate(glm::mat4(1.f), glm::vec3(at.x, 0.f, at.y)));
    addStatic("pillar", std::move(pillar), {materials_.pillar}, true);
    pillars_.push_back(Obstacle{at, 0.55f});
  }
}

ecs::Entity ArenaGame::spawnDynamic(const std::string& name, geometry::MeshData mesh,
                                    std::vector<render::Material> materials,
                                    const components::Splitable& splitable, glm::vec3 position,
                                    glm::quat rotation, ArenaTag::Kind kind) {
  ecs::World& world = app_->world();
  components::SplitableObject object;
  object.name = name;
  object.transform.position = position;
  object.transform.rotation = rotation;
  object.mesh = std::make_shared<geometry::MeshData>(std::move(mesh));
  object.materials = std::move(materials);
  object.splitable = splitable;
  components::SplitWorld sw = splitWorld();
  const ecs::Entity e = components::createSplitableObject(sw, std::move(object));
  world.add<ArenaTag>(e, ArenaTag{kind});
  const base::Status made = components::makeDynamicBody(sw, e, splitable.density, splitable.collider, splits_);
  if (!made.ok()) {
    std::fprintf(stderr, "arena: %s has no body: %s\n", name.c_str(), made.message.c_str());
    removeEntity(e);
    return {};
  }
  return e;
}

ecs::Entity ArenaGame::spawnProp(PropKind kind, glm::vec3 position, float yaw) {
  components::Splitable s;
  const glm::quat rot = glm::angleAxis(yaw, glm::vec3(0, 1, 0));
  if (kind == PropKind::Crate) {
    s.convexHint = true;
    s.density = 450.0;
    s.capMaterial = materials_.crateCap;
    s.splitImpulse = 0.5;
    return spawnDynamic("crate", prim::box(glm::vec3(0.55f)), {materials_.crate, materials_.crateCap}, s,
                        position + glm::vec3(0.f, 0.55f, 0.f), rot, ArenaTag::Prop);
  }
  s.density = 1700.0;
  s.capMaterial = materials_.urnCap;
  s.splitImpulse = 0.4;
  return spawnDynamic("urn", urnMesh(), {materials_.urn, materials_.urnCap}, s, position + glm::vec3(0.f, 0.002f, 0.f),
                      rot, ArenaTag::Prop);
}

void ArenaGame::spawnProps() {
  // Crates and urns around the sand, one crate on the north gate's path. Every match starts with
  // these, whole, where they stand here (resetToMenu).
  const struct {
    PropKind kind;
    glm::vec2 at;
    float yaw;
  } props[] = {
      {PropKind::Crate, {0.8f, -5.2f}, 0.3f},   {PropKind::Crate, {-7.6f, -3.6f}, 0.8f},
      {PropKind::Crate, {8.2f, 3.2f}, 0.1f},    {PropKind::Crate, {-3.2f, 8.4f}, 1.1f},
      {PropKind::Crate, {5.0f, -8.8f}, 0.5f},   {PropKind::Urn, {-1.4f, -7.6f}, 0.f},
      {PropKind::Urn, {6.4f, -5.2f}, 0.f},      {PropKind::Urn, {-8.6f, 2.2f}, 0.f},
      {PropKind::Urn, {2.8f, 8.2f}, 0.f},       {PropKind::Urn, {-5.2f, -8.6f}, 0.f},
  };
  for (const auto& p : props) spawnProp(p.kind, glm::vec3(p.at.x, 0.f, p.at.y), p.yaw);
}

void ArenaGame::spawnMenuCubes() {
  components::Splitable s;
  s.convexHint = true;
  s.density = 2500.0;
  s.capMaterial = materials_.metalCap;
  s.splitImpulse = 1.2;
  const glm::quat upright(1.f, 0.f, 0.f, 0.f);
  startCube_ = spawnDynamic("start cube", prim::box(glm::vec3(0.45f)), {materials_.startCube, materials_.metalCap},
                            s, {-1.1f, 0.451f, 2.0f}, upright, ArenaTag::MenuCube);
  quitCube_ = spawnDynamic("quit cube", prim::box(glm::vec3(0.45f)), {materials_.quitCube, materials_.metalCap}, s,
                           {1.1f, 0.451f, 2.0f}, upright, ArenaTag::MenuCube);
}

void ArenaGame::createPlayer() {
  characterMesh_ = app_->renderer().uploadMesh(character_.mesh).valueOr({});
  animator_ = anim::Animator(&character_.skeleton);
  animator_.play(&character_.idle);
  bladeMesh_ = app_->renderer().uploadMesh(prim::box(glm::vec3(0.03f, 0.012f, 0.5f))).valueOr({});
  discMesh_ = app_->renderer().uploadMesh(prim::torus(0.36f, 0.05f, 32, 8)).valueOr({});
  hammerMesh_ = app_->renderer().uploadMesh(prim::box(glm::vec3(0.32f, 0.2f, 0.2f))).valueOr({});

  ecs::World& world = app_->world();
  player_ = world.create();
  world.add<ecs::Name>(player_, ecs::Name{"player"});
  ecs::Transform t;
  t.position = glm::vec3(0.f, 0.87f, 0.f);
  world.add<ecs::Transform>(player_, t);
  world.add<ecs::WorldTransform>(player_, ecs::WorldTransform{ecs::localMatrix(t)});
  world.add<ArenaTag>(player_, ArenaTag{ArenaTag::Player});
  auto shape = physics_->createShape(physics::ShapeDef::capsule(0.3f, 0.55f));
  if (!shape.ok()) return;
  physics::BodyDef def;
  def.shape = shape.value();
  def.mass = 80.f;
  def.position = t.position;
  def.allowSleep = false;
  def.userData = components::toUserData(player_);
  auto body = physics_->createBody(def);
  if (body.ok()) {
    world.add<components::RigidBody>(player_, components::RigidBody{body.value(), shape.value()});
  } else {
    physics_->destroyShape(shape.value());
  }
}

base::Status ArenaGame::setup(app::App& app) {
  app_ = &app;
  health_ = tuning_.player.health;
  rng_ = app.options().seed * 0x9e3779b97f4a7c15ull + 0x632be59bd9b4e019ull;
  // The budget: 4 ms of main-thread split work a tick, charged by estimate so replays stay exact;
  // the heavy part of a split (the cut, the collider parts, the ragdoll fits) runs on workers.
  components::SplitBudgetSettings budget;
  budget.millisecondsPerTick = 4.0;
  budget.workerMillisecondsPerTick = 8.0;
  budget.maxSplitsPerTick = 8;
  budget.maxActivationsPerTick = 24;
  if (app.options().splitThreads >= 0) budget.threads = uint32_t(app.options().splitThreads);
  sim_ = std::make_unique<components::Simulation>(app.world(), budget, &app.renderer());
  physics_ = &sim_->physics();
  splits_ = &sim_->splits();
  // The piece budget: limbs and shards fade rather than freeze (the sand must stay readable, and the
  // arena's own lifetime below shrinks what stays); a bound on simulated and awake pieces keeps the
  // physics step inside the tick in the busiest waves.
  components::PieceBudgetSettings pieces;
  pieces.policy = components::PieceRetirement::Fade;
  pieces.maxLivePieces = 200;
  pieces.maxAwakePieces = 80;
  pieces.maxDebris = 64;
  splits_->pieces().setSettings(pieces);
  // Gladiators fall as ragdoll halves; what a blow only clips off (a hand, a head) flies away as
  // skinned debris instead of a ragdoll of its own.
  splits_->registerHandler("arena.gladiator", [](const components::SplitJob& job, components::SplitOutcome& out) {
    for (components::PieceSpec& piece : out.pieces)
      if (piece.kind == components::PieceKind::Ragdoll && piece.mass < kLimbShare * job.parent.mass)
        piece.kind = components::PieceKind::Debris;
    return components::HandlerDecision::Commit;
  });
  if (const char* dir = std::getenv("CLEAVE_SPLIT_FAILURE_DIR"); dir && *dir) splits_->setFailureDumpDirectory(dir);

  character_ = assets::makeProceduralCharacter();
  materials_ = createArenaMaterials(app.renderer(), character_.materialColors);
  enemyMeshes_ = makeEnemyMeshes(character_);
  buildLevel();
  createPlayer();
  spawnProps();
  spawnMenuCubes();
  ecs::updateWorldTransforms(app.world());

  app.addSystem(app::Phase::Gameplay, "arena.gameplay", [this](app::TickContext& c) { gameplay(c); });
  app.addSystem(app::Phase::Triggers, "arena.triggers", [this](app::TickContext& c) { triggers(c); });
  components::SplittingHooks hooks;
  hooks.camera = [this] { return glm::dvec3(cameraPosition_); };
  hooks.committed = [this](app::TickContext& c, const std::vector<components::SplitEvent>& events) {
    committed(c, events);
  };
  components::installSplitting(app, *sim_, std::move(hooks));
  app.addSystem(app::Phase::PhysicsSync, "arena.pieces", [this](app::TickContext& c) { physicsSync(c); });
  app.addSystem(app::Phase::Animation, "arena.animation", [this](app::TickContext& c) { animation(c); });
  app.addSystem(app::Phase::Render, "arena.render", [this](app::TickContext& c) { render(c); });
  app.setStateDumpExtension([this](ecs::Entity e, nlohmann::json& out) { dumpEntity(e, out); });
  app.setFrameDumpExtension([this](nlohmann::json& line) { dumpFrame(line); });
  app.setUi([this](app::TickContext& c) { drawInspector(c); });
  if (app.options().inspector) {
    if (const base::Status opened = inspector_.open(app); !opened.ok())
      log::warning("cleave-arena", "--inspector: %s", opened.message.c_str());
  }
  return {};
}

// ---------------------------------------------------------------------------------------------
// Camera and cursor

glm::vec2 ArenaGame::cursorInFrame(const input::InputState& in, glm::ivec2 frame) const {
  // Mouse coordinates are window pixels. A replay that declares its window size (a Resize event)
  // plays the same at any frame size; otherwise the window is the frame.
  const glm::ivec2 window = in.windowSize().x > 0 && in.windowSize().y > 0 ? in.windowSize() : frame;
  return in.mousePosition() * glm::vec2(frame) / glm::vec2(window);
}

glm::vec3 ArenaGame::rayDirection(glm::vec2 pixel, glm::ivec2 frame) const {
  const float aspect = float(frame.x) / float(std::max(frame.y, 1));
  const float tanHalf = std::tan(0.9f * 0.5f);
  const float x = (2.f * pixel.x / float(std::max(frame.x, 1)) - 1.f) * tanHalf * aspect;
  const float y = (1.f - 2.f * pixel.y / float(std::max(frame.y, 1))) * tanHalf;
  const glm::vec3 forward = glm::normalize(cameraTarget_ - cameraPosition_);
  const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
  const glm::vec3 up = glm::cross(right, forward);
  return glm::normalize(forward + right * x + up * y);
}

bool ArenaGame::cursorOnFloor(const input::InputState& in, glm::ivec2 frame, glm::vec3* point) const {
  const glm::vec3 dir = rayDirection(cursorInFrame(in, frame), frame);
  if (dir.y > -1e-3f) return false;
  const float t = -cameraPosition_.y / dir.y;
  *point = cameraPosition_ + dir * t;
  return true;
}

ecs::Entity ArenaGame::splitableUnderCursor(const input::InputState& in, glm::ivec2 frame) const {
  const glm::vec3 dir = rayDirection(cursorInFrame(in, frame), frame);
  const auto hit = physics_->raycast(cameraPosition_, cameraPosition_ + dir * 40.f);
  const auto user = hit ? physics_->bodyUserData(hit->body) : std::nullopt;
  if (!user) return {};
  const ecs::Entity e = components::fromUserData(*user);
  return app_->world().alive(e) && app_->world().has<components::Splitable>(e) ? e : ecs::Entity{};
}

void ArenaGame::toggleInspector(app::TickContext& c) {
  inspectorNotice_ = inspector_.toggle(c.app);
  if (!inspectorNotice_.empty()) inspectorNoticeUntil_ = c.tick + 120;
}

void ArenaGame::drawInspector(app::TickContext& c) {
  uint32_t pieces = 0;
  for (auto [e, origin] : c.world.view<components::SplitOrigin>()) {
    (void)e;
    (void)origin;
    ++pieces;
  }
  const inspector::InspectorFeed feed{c.world, *splits_, splitLog_, splitStats_.history,
                                      splitableUnderCursor(c.input, c.frameSize), pieces};
  inspector_.draw(c, feed);
}

void ArenaGame::updateCamera(float dt) {
  if (state_ == MatchState::Menu) {
    cameraBlend_ = 0.f;
  } else {
    cameraBlend_ = std::min(1.f, cameraBlend_ + dt / 1.3f);
  }
  const float b = cameraBlend_ * cameraBlend_ * (3.f - 2.f * cameraBlend_);
  const glm::vec3 player(playerPosition_.x, 0.f, playerPosition_.y);
  const glm::vec3 menuPosition(0.f, 1.75f, 6.6f), menuTarget(0.f, 0.85f, 1.5f);
  const glm::vec3 followPosition = player + glm::vec3(0.f, 14.f, 7.f);
  const glm::vec3 followTarget = player + glm::vec3(0.f, 0.f, -1.f);
  cameraPosition_ = glm::mix(menuPosition, followPosition, b);
  cameraTarget_ = glm::mix(menuTarget, followTarget, b);
}

// ---------------------------------------------------------------------------------------------
// Gameplay

ecs::Entity ArenaGame::makeSplitter(const std::string& name, const physics::ShapeDef& shapeDef, glm::vec3 position,
                                    glm::quat rotation, bool persistent) {
  components::Splitter splitter;
  splitter.lifetime = persistent ? components::SplitterLifetime::Persistent : components::SplitterLifetime::OneTick;
  splitter.playerCaused = true;
  components::SplitWorld sw = splitWorld();
  const ecs::Entity e = components::createSplitter(sw, name, shapeDef, position, rotation, splitter);
  if (app_->world().alive(e)) app_->world().add<ArenaTag>(e, ArenaTag{ArenaTag::Weapon});
  return e;
}

components::ResourceCounts ArenaGame::resources() const {
  return components::countResources(physics_, app_ ? &app_->renderer() : nullptr);
}

void ArenaGame::releaseAll() {
  if (!app_) return;
  if (sim_) sim_->batches().release(components::PieceMeshes::Drop);  // the world is cleared next
  app_->world().clear();
  for (physics::BodyId body : staticBodies_) physics_->destroyBody(body);
  for (physics::ShapeId shape : staticShapes_) physics_->destroyShape(shape);
  staticBodies_.clear();
  staticShapes_.clear();
  for (render::MeshHandle* mesh : {&characterMesh_, &bladeMesh_, &discMesh_, &hammerMesh_}) {
    app_->renderer().destroyMesh(*mesh);
    *mesh = {};
  }
}

void ArenaGame::removeEntity(ecs::Entity e) {
  ecs::World& world = app_->world();
  if (!world.alive(e)) return;
  world.destroy(e);  // its hooks free its body, bones, GPU mesh or trigger
  // A ragdoll piece goes with every bone body: count it, and any bone body still alive afterwards.
  if (auto it = ragdollBones_.find(e); it != ragdollBones_.end()) {
    ++ragdollPiecesRemoved_;
    for (physics::BodyId body : it->second)
      if (physics_->bodyState(body)) ++ragdollBodiesLeaked_;
    ragdollBones_.erase(it);
  }
}

void ArenaGame::updateMenu(app::TickContext& c) {
  if (!c.input.pressed(input::MouseButton::Left)) return;
  const glm::vec3 dir = rayDirection(cursorInFrame(c.input, c.frameSize), c.frameSize);
  const auto hit = physics_->raycast(cameraPosition_, cameraPosition_ + dir * 40.f);
  if (!hit) return;
  const auto user = physics_->bodyUserData(hit->body);
  if (!user) return;
  const ecs::Entity target = components::fromUserData(*user);
  if (!c.world.alive(target) || !c.world.has<components::Splitable>(target)) return;
  // A vertical plane along the click ray, leaning a little: the cube falls apart diagonally.
  glm::vec3 normal = glm::normalize(glm::cross(dir, glm::vec3(0, 1, 0)));
  normal = glm::normalize(glm::angleAxis(0.4f, dir) * normal);
  makeSplitter("menu cut", physics::ShapeDef::box(glm::vec3(0.9f, 0.01f, 0.9f)), hit->point, rotationFromUp(normal),
               false);
}

void ArenaGame::updatePlayer(app::TickContext& c) {
  const input::InputState& in = c.input;
  using input::Key;
  glm::vec2 move(0.f);
  if (in.held(Key::W)) move.y -= 1.f;
  if (in.held(Key::S)) move.y += 1.f;
  if (in.held(Key::A)) move.x -= 1.f;
  if (in.held(Key::D)) move.x += 1.f;
  const glm::vec2 before = playerPosition_;
  if (glm::length(move) > 0.f) playerPosition_ += glm::normalize(move) * tuning_.player.speed * float(c.dt);
  for (const Obstacle& o : pillars_) {
    const glm::vec2 d = playerPosition_ - o.centre;
    const float len = glm::length(d);
    if (len < o.radius + kPlayerRadius && len > 1e-5f) playerPosition_ = o.centre + d / len * (o.radius + kPlayerRadius);
  }
  const float r = glm::length(playerPosition_);
  if (r > kArenaRadius - kPlayerRadius - 0.1f) playerPosition_ *= (kArenaRadius - kPlayerRadius - 0.1f) / r;
  playerSpeed_ = glm::length(playerPosition_ - before) / float(c.dt);
  glm::vec3 aim;
  if (cursorOnFloor(in, c.frameSize, &aim)) {
    aimPoint_ = aim;
    const glm::vec2 d(aim.x - playerPosition_.x, aim.z - playerPosition_.y);
    if (glm::length(d) > 0.2f) playerYaw_ = std::atan2(d.x, d.y);
  }
}

void ArenaGame::throwDisc() {
  const glm::vec2 dir = forwardOf(playerYaw_);
  disc_ = Disc{};
  disc_.active = true;
  disc_.position = playerPosition_ + dir * 0.7f;
  disc_.direction = dir;
  disc_.splitter = makeSplitter("energy disc", physics::ShapeDef::box(glm::vec3(kDiscRadius, 0.03f, kDiscRadius)),
                                glm::vec3(disc_.position.x, kDiscHeight, disc_.position.y),
                                glm::quat(1.f, 0.f, 0.f, 0.f), true);
  ++match_.discThrows;
}

void ArenaGame::swingSword(bool spin) {
  const glm::vec2 f = forwardOf(playerYaw_);
  swing_ = Swing{};
  swing_.spin = spin;
  swing_.duration = swing_.ticksLeft = spin ? kSpinTicks : kSwordTicks;
  swing_.yaw = playerYaw_;
  if (spin) {
    swing_.tilt = 0.1f;
    std::vector<glm::vec3> points;
    for (int k = 0; k < 24; ++k) {
      const float a = 2.f * kPi * float(k) / 24.f;
      for (float h : {-0.02f, 0.02f}) points.push_back(glm::vec3(std::cos(a) * kSpinRadius, h, std::sin(a) * kSpinRadius));
    }
    const glm::quat rot = glm::angleAxis(playerYaw_, glm::vec3(0, 1, 0)) * glm::angleAxis(swing_.tilt, glm::vec3(0, 0, 1));
    makeSplitter("spin attack", physics::ShapeDef::convexHull(points),
                 glm::vec3(playerPosition_.x, 1.05f, playerPosition_.y), rot, false);
    ++match_.spinAttacks;
    return;
  }
  // Alternate the slash: down to the left, then down to the right.
  swing_.tilt = (match_.swordSwings % 2 == 0) ? 0.32f : -0.32f;
  const glm::quat rot = glm::angleAxis(playerYaw_, glm::vec3(0, 1, 0)) * glm::angleAxis(swing_.tilt, glm::vec3(0, 0, 1));
  const glm::vec3 centre = glm::vec3(playerPosition_.x, 1.1f, playerPosition_.y) + glm::vec3(f.x, 0.f, f.y) * 1.25f;
  makeSplitter("sword swing", physics::ShapeDef::box(glm::vec3(1.9f, 0.02f, 1.0f)), centre, rot, false);
  ++match_.swordSwings;
}

void ArenaGame::updateWeapons(app::TickContext& c) {
  const input::InputState& in = c.input;
  if (in.pressed(input::MouseButton::Left) && c.tick >= swordReadyTick_ && swing_.ticksLeft == 0) {
    swingSword(false);
    swordReadyTick_ = c.tick + ticksOf(tuning_.player.swordCooldownSeconds);
  }
  if (in.pressed(input::MouseButton::Right) && !disc_.active) throwDisc();
  if (in.pressed(input::Key::Space) && c.tick >= spinReadyTick_ && swing_.ticksLeft == 0) {
    swingSword(true);
    spinReadyTick_ = c.tick + ticksOf(tuning_.player.spinCooldownSeconds);
  }
  if (in.pressed(input::Key::E) && c.tick >= hammerReadyTick_ && hammer_.ticksLeft == 0 && swing_.ticksLeft == 0) {
    hammer_.ticksLeft = kHammerTicks;
    hammer_.yaw = playerYaw_;
    hammer_.at = playerPosition_ + forwardOf(playerYaw_) * kHammerReach;
    hammerReadyTick_ = c.tick + ticksOf(tuning_.player.hammerCooldownSeconds);
  }
}

// The hammer comes down; as it lands, a one-tick shatter splitter breaks what stands where it
// lands into cells thrown out from the point of impact (crates, urns and gladiators alike).
void ArenaGame::updateHammer(app::TickContext& c) {
  if (hammer_.ticksLeft == 0 || --hammer_.ticksLeft > 0) return;
  components::Splitter blow;
  blow.kind = components::SplitterKind::Shatter;
  blow.lifetime = components::SplitterLifetime::OneTick;
  blow.playerCaused = true;
  blow.halfExtents = kHammerHalfExtents;
  blow.shatter.cells = tuning_.player.hammerCells;
  blow.shatter.seed = c.tick;
  blow.shatter.impactPoint = glm::dvec3(hammer_.at.x, 0.3, hammer_.at.y);
  blow.shatter.impactGiven = true;
  blow.shatter.impactRadius = 0.6;
  blow.shatter.outwardImpulse = tuning_.player.hammerOutwardImpulse;
  components::SplitWorld sw = splitWorld();
  const ecs::Entity e = components::createSplitter(
      sw, kWeaponSplitterNames[4], physics::ShapeDef::box(kHammerHalfExtents),
      glm::vec3(hammer_.at.x, kHammerHalfExtents.y, hammer_.at.y), glm::angleAxis(hammer_.yaw, glm::vec3(0, 1, 0)), blow);
  if (c.world.alive(e)) c.world.add<ArenaTag>(e, ArenaTag{ArenaTag::Weapon});
  ++match_.hammerBlows;
}

void ArenaGame::updateDisc(app::TickContext& c) {
  if (!disc_.active) return;
  const float dt = float(c.dt);
  disc_.age += dt;
  disc_.spin += dt * 18.f;
  if (!disc_.returning) {
    disc_.position += disc_.direction * kDiscSpeed * dt;
    // Bounce off the wall ring and the pillars (reflection about the surface normal).
    const float r = glm::length(disc_.position);
    if (r > kArenaRadius - kDiscRadius) {
      const glm::vec2 n = disc_.position / r;
      disc_.position = n * (kArenaRadius - kDiscRadius);
      if (glm::dot(disc_.direction, n) > 0.f) disc_.direction = glm::reflect(disc_.direction, n);
      ++disc_.bounces;
    }
    for (const Obstacle& o : pillars_) {
      const glm::vec2 d = disc_.position - o.centre;
      const float len = glm::length(d);
      if (len < o.radius + kDiscRadius && len > 1e-5f) {
        const glm::vec2 n = d / len;
        disc_.position = o.centre + n * (o.radius + kDiscRadius);
        if (glm::dot(disc_.direction, n) < 0.f) disc_.direction = glm::reflect(disc_.direction, n);
        ++disc_.bounces;
      }
    }
    if (disc_.bounces >= kDiscBounces || disc_.age > kDiscFlightSeconds) disc_.returning = true;
  } else {
    const glm::vec2 d = playerPosition_ - disc_.position;
    const float len = glm::length(d);
    if (len < 0.8f) {
      removeEntity(disc_.splitter);
      disc_ = Disc{};
      return;
    }
    disc_.direction = d / len;
    disc_.position += disc_.direction * std::min(kDiscReturnSpeed * dt, len);
  }
  const glm::vec3 p(disc_.position.x, kDiscHeight, disc_.position.y);
  const glm::quat rot = glm::angleAxis(disc_.spin, glm::vec3(0, 1, 0));
  if (auto* t = c.world.tryGet<ecs::Transform>(disc_.splitter)) {
    t->position = p;
    t->rotation = rot;
    c.world.get<ecs::WorldTransform>(disc_.splitter).matrix = ecs::localMatrix(*t);
  }
  if (const auto* s = c.world.tryGet<components::Splitter>(disc_.splitter))
    physics_->setTriggerTransform(s->trigger, physics::BodyTransform{p, rot});
}

void ArenaGame::triggers(app::TickContext& c) {
  // Who did a blade touch in the last step? Those enemies stop in their tracks until their split
  // lands (it runs within the budget from the next tick, and the plane should still meet them).
  uint32_t hitsThisTick = 0;
  for (const physics::TriggerEvent& ev : physics_->triggerEvents()) {
    if (ev.kind != physics::TriggerEventKind::Begin) continue;
    const auto splitterUser = physics_->triggerUserData(ev.trigger);
    const auto bodyUser = physics_->bodyUserData(ev.body);
    if (!splitterUser || !bodyUser) continue;
    if (!c.world.has<components::Splitter>(components::fromUserData(*splitterUser))) continue;
    const ecs::Entity target = components::fromUserData(*bodyUser);
    const auto* splitterName = c.world.tryGet<ecs::Name>(components::fromUserData(*splitterUser));
    const uint8_t weapon = splitterName ? weaponIndex(splitterName->value) : 0;
    for (Enemy& e : enemies_) {
      if (e.entity == target && !e.hit) {
        freezeEnemy(e, float(kHitFreezeTicks) * float(c.dt));
        e.hitBy = weapon;
        e.walkPhase = float(c.tick) * 1e-9f;  // the freeze pose
        ++hitsThisTick;
      }
    }
  }
  match_.maxEnemiesHitInOneTick = std::max(match_.maxEnemiesHitInOneTick, hitsThisTick);
}

void ArenaGame::onSplit(const components::SplitEvent& ev, uint64_t tick) {
  splitLog_.record(tick, ev);
  const bool cut = ev.status == geometry::SplitStatus::Ok && !ev.pieces.empty();
  auto enemy = std::find_if(enemies_.begin(), enemies_.end(), [&](const Enemy& e) { return e.entity == ev.original; });
  if (!cut) {
    if (enemy != enemies_.end()) enemy->hit = false;  // the plane missed: it walks on
    return;
  }
  adoptPieces(ev, tick);
  if (enemy != enemies_.end()) {
    throwPiecesAway(*enemy, ev.pieces);
    const size_t kind = std::min(size_t(enemy->kind), kKindCount - 1);
    ++match_.killsByKind[kind][0];
    if (enemy->hitBy > 0 && enemy->hitBy < kWeaponCount) ++match_.killsByKind[kind][enemy->hitBy];
    enemies_.erase(enemy);
    ++match_.score;
    ++match_.enemiesKilled;
  }
  if (ev.originalName == "crate" || ev.originalName == "urn") ++match_.propsBroken;
  if (ev.original == startCube_ && state_ == MatchState::Menu) {
    state_ = MatchState::Starting;
    stateTick_ = tick;
    ++matchesStarted_;
  } else if (ev.original == quitCube_ && state_ == MatchState::Menu) {
    state_ = MatchState::Quitting;
    stateTick_ = tick;
  }
}

void ArenaGame::adoptPieces(const components::SplitEvent& ev, uint64_t tick) {
  ecs::World& world = app_->world();
  // A ragdoll piece cut again (by the disc on its way back, say) is gone with all its bone bodies.
  if (auto it = ragdollBones_.find(ev.original); it != ragdollBones_.end()) {
    ++ragdollPiecesCut_;
    for (physics::BodyId body : it->second)
      if (physics_->bodyState(body)) ++ragdollBodiesLeaked_;
    ragdollBones_.erase(it);
  }
  for (ecs::Entity piece : ev.pieces) {
    if (!world.alive(piece)) continue;
    if (const auto* ragdoll = world.tryGet<components::Ragdoll>(piece)) {
      auto& bones = ragdollBones_[piece];
      for (const components::RagdollBone& bone : ragdoll->bones) bones.push_back(bone.body);
      ++ragdollPiecesSpawned_;
    }
    world.add<ArenaTag>(piece, ArenaTag{ArenaTag::Piece});
    Fading f;
    f.bornTick = tick;
    if (const auto* mr = world.tryGet<components::MeshRenderer>(piece)) f.baseOffset = mr->meshOffset;
    world.add<Fading>(piece, f);
    // Crumbs stay whole: cutting them again adds work and nothing to see.
    if (const auto* mi = world.tryGet<components::MassInfo>(piece); mi && mi->volume < kCrumbVolume)
      world.remove<components::Splitable>(piece);
    ++piecesSpawned_;
  }
}

void ArenaGame::throwPiecesAway(const Enemy& enemy, const std::vector<ecs::Entity>& pieces) {
  // The blow throws the pieces away from the player, tumbling.
  ecs::World& world = app_->world();
  const glm::vec2 away = enemy.position - playerPosition_;
  const glm::vec2 dir = glm::length(away) > 1e-3f ? glm::normalize(away) : forwardOf(enemy.yaw + kPi);
  for (ecs::Entity piece : pieces) {
    const auto* rb = world.tryGet<components::RigidBody>(piece);
    const auto* mi = world.tryGet<components::MassInfo>(piece);
    const auto* t = world.tryGet<ecs::Transform>(piece);
    if (!rb || !mi || !t) continue;
    const float lift = t->position.y > 0.9f ? 1.2f : 0.3f;  // upper parts fly, legs buckle
    if (const auto* ragdoll = world.tryGet<components::Ragdoll>(piece)) {
      // A ragdoll half: every bone gets the same push (by its own mass), so the half is thrown
      // whole and its joints only carry the tumble.
      for (const components::RagdollBone& bone : ragdoll->bones) {
        const auto state = physics_->bodyState(bone.body);
        if (!state) continue;
        const glm::vec3 impulse = glm::vec3(dir.x * 1.6f, lift * 0.6f, dir.y * 1.6f) * bone.mass;
        physics_->applyImpulse(bone.body, impulse, state->transform.position + glm::vec3(0.f, 0.05f, 0.f));
      }
      continue;
    }
    const glm::vec3 impulse = glm::vec3(dir.x * 2.2f, lift, dir.y * 2.2f) * float(mi->mass);
    physics_->applyImpulse(rb->body, impulse, t->position + glm::vec3(0.f, 0.12f, 0.f));
  }
}

void ArenaGame::committed(app::TickContext& c, const std::vector<components::SplitEvent>& events) {
  const uint32_t killedBefore = match_.enemiesKilled;
  for (const components::SplitEvent& ev : events) onSplit(ev, c.tick);
  match_.maxKillsInOneTick = std::max(match_.maxKillsInOneTick, match_.enemiesKilled - killedBefore);
  splitStats_.record(*splits_);
}

void ArenaGame::updatePieces(uint64_t tick) {
  ecs::World& world = app_->world();
  struct Item {
    uint64_t born;
    ecs::Entity e;
  };
  std::vector<Item> items;
  for (auto [e, f] : world.view<Fading>()) items.push_back({f.bornTick, e});
  // Too many pieces: the oldest start to shrink now.
  if (items.size() > kMaxPieces) {
    std::sort(items.begin(), items.end(),
              [](const Item& a, const Item& b) { return a.born != b.born ? a.born < b.born : a.e < b.e; });
    for (size_t i = 0; i < items.size() - kMaxPieces; ++i) {
      auto& f = world.get<Fading>(items[i].e);
      if (tick >= kPieceLifeTicks) f.bornTick = std::min(f.bornTick, tick - kPieceLifeTicks);
    }
  }
  std::vector<ecs::Entity> doomed;
  for (auto [e, f, mr, t] : world.view<Fading, components::MeshRenderer, ecs::Transform>()) {
    const uint64_t age = tick - std::min(tick, f.bornTick);
    if (t.position.y < -1.f) {
      doomed.push_back(e);
      continue;
    }
    if (age < kPieceLifeTicks) continue;
    const float s = 1.f - float(age - kPieceLifeTicks) / float(kPieceShrinkTicks);
    if (s <= 0.02f) {
      doomed.push_back(e);
      continue;
    }
    mr.meshOffset = glm::scale(glm::mat4(1.f), glm::vec3(s)) * f.baseOffset;
  }
  // Render-only debris has no collider: it would sink through the floor, so it goes at the floor.
  for (auto [e, d, t] : world.view<components::Debris, ecs::Transform>()) {
    (void)d;
    if (t.position.y < -0.3f) doomed.push_back(e);
  }
  std::sort(doomed.begin(), doomed.end());
  doomed.erase(std::unique(doomed.begin(), doomed.end()), doomed.end());
  for (ecs::Entity e : doomed) {
    removeEntity(e);
    ++piecesRemoved_;
  }
}

void ArenaGame::physicsSync(app::TickContext& c) { updatePieces(c.tick); }

void ArenaGame::animation(app::TickContext& c) {
  // The skinned enemies played their clips in the split installer's Animation stage (their ragdoll
  // halves take their poses from their bones); here the player's own character.
  const bool walking = playerSpeed_ > 0.3f;
  const anim::AnimationClip* want = walking ? &character_.walk : &character_.idle;
  if (animator_.clip() != want) animator_.play(want, 0.25f);
  animator_.advance(float(c.dt) * (walking ? std::clamp(playerSpeed_ / 3.2f, 0.8f, 2.f) : 1.f));
  animator_.evaluate(pose_);
  anim::localToGlobal(character_.skeleton, pose_, jointGlobals_);
  anim::jointMatrices(character_.skeleton, jointGlobals_, jointMatrices_);
}

// ---------------------------------------------------------------------------------------------
// Drawing

void ArenaGame::drawWeapons(render::Renderer& r) {
  const glm::mat4 playerModel = glm::translate(glm::mat4(1.f), glm::vec3(playerPosition_.x, 0.f, playerPosition_.y)) *
                                glm::mat4_cast(glm::angleAxis(playerYaw_, glm::vec3(0, 1, 0)));
  const render::Material blade[] = {materials_.blade};
  if (swing_.ticksLeft > 0) {
    // The blade sweeps through the swing's plane; a fan of lines trails it.
    const float p = 1.f - float(swing_.ticksLeft) / float(swing_.duration);
    const glm::quat plane = glm::angleAxis(swing_.yaw, glm::vec3(0, 1, 0)) * glm::angleAxis(swing_.tilt, glm::vec3(0, 0, 1));
    const float from = swing_.spin ? -kPi : 1.7f, to = swing_.spin ? kPi : -1.7f;
    const float reach = swing_.spin ? kSpinRadius : 2.2f;
    const glm::vec3 pivot(playerPosition_.x, swing_.spin ? 1.05f : 1.1f, playerPosition_.y);
    auto along = [&](float a) { return plane * glm::vec3(std::sin(a), 0.f, std::cos(a)); };
    const float angle = glm::mix(from, to, p);
    const glm::vec3 d = along(angle);
    const glm::vec3 n = plane * glm::vec3(0, 1, 0);
    const glm::vec3 side = glm::cross(n, d);
    glm::mat4 model(1.f);
    model[0] = glm::vec4(side, 0.f);
    model[1] = glm::vec4(n, 0.f);
    model[2] = glm::vec4(d, 0.f);
    model[3] = glm::vec4(pivot + d * (reach * 0.5f + 0.2f), 1.f);
    model = model * glm::scale(glm::mat4(1.f), glm::vec3(1.f, 1.f, reach * 0.85f));
    r.submit(bladeMesh_, model, blade);
    std::vector<glm::vec3> arc;
    const int steps = 24;
    for (int k = 0; k < steps; ++k) {
      const float a0 = glm::mix(from, angle, float(k) / steps), a1 = glm::mix(from, angle, float(k + 1) / steps);
      for (float rad : {reach, reach * 0.75f, reach * 0.5f}) {
        arc.push_back(pivot + along(a0) * rad);
        arc.push_back(pivot + along(a1) * rad);
      }
    }
    r.submitLines(arc, glm::vec4(0.5f, 1.f, 1.f, 1.f));
  } else if (const int32_t hand = character_.skeleton.find("right_hand"); hand >= 0 && size_t(hand) < jointGlobals_.size()) {
    // At rest the energy blade hangs from the right hand, pointing forward and down.
    const glm::vec3 grip = glm::vec3(playerModel * jointGlobals_[size_t(hand)][3]);
    const glm::vec2 f = forwardOf(playerYaw_);
    const glm::vec3 d = glm::normalize(glm::vec3(f.x, -0.55f, f.y));
    const glm::vec3 side = glm::normalize(glm::cross(glm::vec3(0, 1, 0), d));
    const glm::vec3 n = glm::cross(d, side);
    glm::mat4 model(1.f);
    model[0] = glm::vec4(side, 0.f);
    model[1] = glm::vec4(n, 0.f);
    model[2] = glm::vec4(d, 0.f);
    model[3] = glm::vec4(grip + d * 0.5f, 1.f);
    r.submit(bladeMesh_, model, blade);
  }
  if (hammer_.ticksLeft > 0) {
    // Raised over the shoulder for the first third of the blow, then brought down where it lands.
    const float p = 1.f - float(hammer_.ticksLeft) / float(kHammerTicks);
    const float down = std::clamp((p - 0.35f) / 0.65f, 0.f, 1.f);
    const glm::vec3 shoulder(playerPosition_.x, 1.45f, playerPosition_.y);
    const glm::vec3 raised = shoulder + glm::vec3(0.f, 1.1f, 0.f) - glm::vec3(forwardOf(hammer_.yaw).x, 0.f, forwardOf(hammer_.yaw).y) * 0.3f;
    const glm::vec3 landed(hammer_.at.x, 0.22f, hammer_.at.y);
    const glm::vec3 head = p < 0.35f ? glm::mix(shoulder, raised, p / 0.35f) : glm::mix(raised, landed, down * down);
    const glm::mat4 model = glm::translate(glm::mat4(1.f), head) * glm::mat4_cast(glm::angleAxis(hammer_.yaw, glm::vec3(0, 1, 0)));
    const render::Material stone[] = {materials_.disc};
    r.submit(hammerMesh_, model, stone);
    r.submitLines(std::vector<glm::vec3>{shoulder, head}, glm::vec4(1.f, 0.8f, 0.4f, 1.f));
  }
  if (disc_.active) {
    const glm::mat4 model = glm::translate(glm::mat4(1.f), glm::vec3(disc_.position.x, kDiscHeight, disc_.position.y)) *
                            glm::mat4_cast(glm::angleAxis(disc_.spin, glm::vec3(0, 1, 0)));
    const render::Material disc[] = {materials_.disc};
    r.submit(discMesh_, model, disc);
    std::vector<glm::vec3> spokes;
    for (int k = 0; k < 3; ++k) {
      const float a = disc_.spin + float(k) * 2.f * kPi / 3.f;
      spokes.push_back(glm::vec3(disc_.position.x, kDiscHeight, disc_.position.y));
      spokes.push_back(glm::vec3(disc_.position.x + std::cos(a) * 0.36f, kDiscHeight,
                                 disc_.position.y + std::sin(a) * 0.36f));
    }
    r.submitLines(spokes, glm::vec4(0.8f, 1.f, 1.f, 1.f));
  }
}

void ArenaGame::render(app::TickContext& c) {
  render::Camera camera;
  camera.position = cameraPosition_;
  camera.view = glm::lookAt(cameraPosition_, cameraTarget_, glm::vec3(0, 1, 0));
  camera.verticalFovRadians = 0.9f;
  camera.farPlane = 200.f;
  render::Lighting lighting;
  // Late-afternoon sun: warm, low from the south-west, long shadows.
  lighting.sunDirection = glm::normalize(glm::vec3(0.55f, -0.62f, -0.56f));
  lighting.sunColor = glm::vec3(1.0f, 0.84f, 0.62f);
  lighting.sunIntensity = 1.8f;
  lighting.ambientColor = glm::vec3(0.30f, 0.27f, 0.30f);
  const glm::vec3 focus = state_ == MatchState::Menu ? glm::vec3(0.f, 0.f, 1.5f)
                                                     : glm::vec3(playerPosition_.x, 0.f, playerPosition_.y);
  lighting.shadowCenter = focus;
  lighting.shadowRadius = state_ == MatchState::Menu ? 9.f : 15.f;
  c.renderer.beginFrame(c.frameSize.x, c.frameSize.y, camera, lighting);
  sim_->submitMeshes(c.tick);
  const glm::mat4 playerModel = glm::translate(glm::mat4(1.f), glm::vec3(playerPosition_.x, 0.f, playerPosition_.y)) *
                                glm::mat4_cast(glm::angleAxis(playerYaw_, glm::vec3(0, 1, 0)));
  std::vector<render::Material> look = materials_.player;
  if (hurtFlash_ > 0.f)
    for (auto& m : look) m.baseColor = glm::mix(m.baseColor, glm::vec4(1.f, 0.15f, 0.1f, 1.f), hurtFlash_ * 1.5f);
  c.renderer.submitSkinned(characterMesh_, playerModel, jointMatrices_, look);
  drawWeapons(c.renderer);
  drawHud(c);
}

}  // namespace cleave::arena
