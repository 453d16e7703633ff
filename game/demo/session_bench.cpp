// SPDX-License-Identifier: MIT
// The session benchmark (cleave-demo --bench-session MINUTES): what a long session of cutting does
// to the tick. A field of 225 demo objects; a persistent blade sweeps across it every 12 seconds
// (vertical and tilted planes, turning by a fixed step), three objects are shattered every 30
// seconds, 25 fresh objects drop onto the field every minute; then 30 seconds of nothing. Every
// minute it prints the pieces (live, awake, frozen, debris), the tick's p50 / p99 / max with the
// split stages and the physics step apart, a frame of the field every 5 s (time, draw calls,
// triangles), resident memory and GPU meshes. It measures, it does not
// test; the same run is deterministic (a seeded generator, the budgets' own deterministic rules).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "cleave/components/scene_components.h"
#include "cleave/components/skinned.h"
#include "cleave/components/split_clock.h"
#include "game/demo/demo_game.h"

namespace cleave::demo {
namespace {

constexpr int kTicksPerMinute = 3600;
constexpr int kSide = 15;            // objects per row of the field
constexpr float kSpacing = 2.0f;     // metres between objects
const glm::vec3 kField(0.f, 0.f, -34.f);  // centre of the field, away from the demo's own objects

struct Minute {
  int minute = 0;
  uint32_t live = 0, awake = 0, frozen = 0, debris = 0, bodies = 0, maxLive = 0, maxAwake = 0;
  std::vector<double> tick, split, physics, frame;
  uint32_t drawCalls = 0, triangles = 0;  // of the minute's last frame
  double residentMb = 0.0;
  uint32_t gpuMeshes = 0;
  uint64_t splits = 0, pieces = 0;
};

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, size_t(p * double(v.size())))];
}

double residentMegabytes() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return double(resident) * 4096.0 / (1024.0 * 1024.0);
}

// A blade: a persistent splitter moving across the field in a straight line.
struct Blade {
  ecs::Entity entity;
  glm::vec3 start{0.f}, velocity{0.f};
  glm::quat rotation{1.f, 0.f, 0.f, 0.f};
  uint64_t startTick = 0, endTick = 0;
};

// A new blade for sweep `sweep`: crossing the field in 11 s, turned 0.7 rad further each sweep;
// every third plane leans (cuts pieces flat).
Blade startBlade(components::SplitWorld& sw, int sweep, uint64_t tick) {
  const float angle = 0.7f * float(sweep);
  const glm::vec3 across(std::cos(angle), 0.f, std::sin(angle));
  const float tilt = (sweep % 3 == 2) ? 1.1f : 0.f;
  const glm::vec3 normal = glm::normalize(across + glm::vec3(0.f, tilt, 0.f));
  Blade b;
  b.start = kField - across * 18.f + glm::vec3(0.f, 0.4f, 0.f);
  b.velocity = across * 3.2f;
  b.startTick = tick;
  b.endTick = tick + 660;
  // The blade's frame: local +Y the plane normal, local X along the field, local Z as near up as the
  // plane allows. 44 m long and 3.2 m tall, its lower edge at the floor.
  const glm::vec3 along = glm::normalize(glm::cross(normal, glm::vec3(0.f, 1.f, 0.f)));
  b.rotation = glm::quat_cast(glm::mat3(along, normal, glm::cross(along, normal)));
  b.start.y = 1.6f;
  components::Splitter splitter;
  splitter.lifetime = components::SplitterLifetime::Persistent;
  splitter.halfExtents = glm::vec3(22.f, 0.02f, 1.6f);
  b.entity = components::createSplitter(sw, "blade " + std::to_string(sweep), physics::ShapeDef::box(splitter.halfExtents),
                                        b.start, b.rotation, splitter);
  return b;
}

// Moves every blade to its place at `tick`; a blade past its end goes.
void moveBlades(components::SplitWorld& sw, std::vector<Blade>& blades, uint64_t tick) {
  for (Blade& b : blades) {
    if (!sw.world.alive(b.entity)) continue;
    if (tick >= b.endTick) {
      sw.world.destroy(b.entity);
      continue;
    }
    const glm::vec3 at = b.start + b.velocity * (float(tick - b.startTick) / 60.f);
    auto& t = sw.world.get<ecs::Transform>(b.entity);
    t.position = at;
    sw.world.get<ecs::WorldTransform>(b.entity).matrix = ecs::localMatrix(t);
    sw.physics.setTriggerTransform(sw.world.get<components::Splitter>(b.entity).trigger, physics::BodyTransform{at, b.rotation});
  }
  std::erase_if(blades, [&](const Blade& b) { return !sw.world.alive(b.entity); });
}

// Three shatters of 12 cells, on splitable objects of the field picked by the generator.
void requestShatters(ecs::World& world, components::SplitSystem& splits, std::mt19937& rng, uint64_t tick) {
  std::vector<ecs::Entity> targets;
  for (auto [e, sp, t] : world.view<components::Splitable, ecs::Transform>())
    if (t.position.y > -1.f && std::abs(t.position.z - kField.z) < 20.f) targets.push_back(e);
  std::sort(targets.begin(), targets.end(), [](ecs::Entity a, ecs::Entity b) { return a.index < b.index; });
  for (int k = 0; k < 3 && !targets.empty(); ++k) {
    const ecs::Entity e = targets[rng() % targets.size()];
    components::SplitRequest r;
    r.target = e;
    r.shatter = true;
    r.shatterSpec.cells = 12;
    r.shatterSpec.impactPoint = glm::dvec3(world.get<ecs::Transform>(e).position);
    r.requestedTick = tick;
    splits.request(r);
  }
}

// CLEAVE_SESSION_TRACE: every awake piece with its speeds, size, height, contacts and age.
void traceAwakePieces(components::SplitWorld& sw, uint64_t n, uint64_t tick) {
  std::map<uint32_t, int> contacts;
  for (const physics::ContactEvent& ev : sw.physics.contactEvents()) contacts[ev.bodyA.index]++, contacts[ev.bodyB.index]++;
  for (auto [e, origin, rb, info] : sw.world.view<components::SplitOrigin, components::RigidBody, components::MassInfo>()) {
    if (!sw.physics.isAwake(rb.body)) continue;
    const auto st = sw.physics.bodyState(rb.body);
    std::fprintf(stderr, "tick %llu awake %u: v %.3f w %.3f vol %.2e y %.3f contacts %d age %llu ragdoll %d\n",
                 (unsigned long long)n, e.index, glm::length(st->linearVelocity), glm::length(st->angularVelocity),
                 info.volume, st->transform.position.y, contacts[rb.body.index], (unsigned long long)(tick - origin.tick),
                 int(sw.world.has<components::Ragdoll>(e)));
  }
}

// CLEAVE_SESSION_TRACE on a slow tick: the awake pieces by motion (at rest, creeping, moving) and
// how many are younger than two seconds.
std::string awakeByMotion(components::SplitWorld& sw, uint64_t tick) {
  int rest = 0, creep = 0, moving = 0, young = 0;
  for (auto [e, origin, rb] : sw.world.view<components::SplitOrigin, components::RigidBody>()) {
    if (!sw.physics.isAwake(rb.body) || sw.physics.isFrozen(rb.body)) continue;
    const auto st = sw.physics.bodyState(rb.body);
    const float v = glm::length(st->linearVelocity), w = glm::length(st->angularVelocity);
    (v < 0.05f && w < 0.5f ? rest : v < 0.25f ? creep : moving)++;
    if (tick - origin.tick < 120) young++;
  }
  char text[96];
  std::snprintf(text, sizeof text, "rest %d creep %d moving %d young %d", rest, creep, moving, young);
  return text;
}

void printHeader() {
  std::printf("| minute | live (max) | awake | frozen | debris | tick p50 | p99 | max | split p99 | physics p50 | "
              "physics p99 | frame ms | draws | triangles | RSS MB | GPU meshes | splits |\n"
              "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
}

void printRow(const Minute& m, int minutes) {
  std::printf("| %d%s | %u (%u) | %u | %u | %u | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.1f | %u | %u | %.0f | %u | %llu |\n",
              m.minute, m.minute > minutes ? " (quiet)" : "", m.live, m.maxLive, m.awake, m.frozen, m.debris,
              percentile(m.tick, 0.5), percentile(m.tick, 0.99), percentile(m.tick, 1.0), percentile(m.split, 0.99),
              percentile(m.physics, 0.5), percentile(m.physics, 0.99), percentile(m.frame, 0.5), m.drawCalls, m.triangles,
              m.residentMb, m.gpuMeshes, (unsigned long long)m.splits);
  std::fflush(stdout);
}

void printJson(const std::vector<Minute>& report, const components::SplitSystem& splits) {
  nlohmann::json out;
  out["budget"] = splits.pieces().settings().enabled;
  out["threads"] = splits.budget().settings().threads;
  for (const Minute& m : report)
    out["minutes"].push_back({{"minute", m.minute}, {"live", m.live}, {"awake", m.awake}, {"frozen", m.frozen},
                              {"debris", m.debris}, {"bodies", m.bodies}, {"max_live", m.maxLive}, {"max_awake", m.maxAwake},
                              {"tick_p50_ms", percentile(m.tick, 0.5)}, {"tick_p99_ms", percentile(m.tick, 0.99)},
                              {"tick_max_ms", percentile(m.tick, 1.0)}, {"split_p99_ms", percentile(m.split, 0.99)},
                              {"physics_p50_ms", percentile(m.physics, 0.5)}, {"physics_p99_ms", percentile(m.physics, 0.99)},
                              {"frame_p50_ms", percentile(m.frame, 0.5)}, {"draw_calls", m.drawCalls}, {"triangles", m.triangles},
                              {"resident_mb", m.residentMb}, {"gpu_meshes", m.gpuMeshes}, {"splits", m.splits},
                              {"pieces", m.pieces}});
  out["retired"] = components::toJson(splits.pieces().stats());
  std::printf("%s\n", out.dump().c_str());
}

void printRetired(const components::SplitSystem& splits) {
  const components::PieceBudgetStats& s = splits.pieces().stats();
  std::printf("retired: %llu freezes (%.1f kg frozen at the end), %llu faded (%.1f kg), %llu removed (%.1f kg), "
              "%llu thawed, %llu debris removed; piece budget %s\n",
              (unsigned long long)s.frozenTotal, s.frozenMass, (unsigned long long)s.fadedTotal, s.fadedMass,
              (unsigned long long)s.removedTotal, s.removedMass, (unsigned long long)s.thawedTotal,
              (unsigned long long)s.debrisRemovedTotal, splits.pieces().settings().enabled ? "on" : "off");
}

// One tick of the session in the simulation's phase order, timed by stage into the minute's figures.
void timedTick(components::Simulation& sim, uint64_t tick, const glm::dvec3& camera, bool trace, Minute& m) {
  // t1: the splits done (after Commit); t2: the physics step done; t3: the tick done.
  const double t0 = components::nowMilliseconds();
  double t1 = t0, t2 = t0;
  for (const components::TickStageInfo& s : components::kTickOrder) {
    sim.run(s.stage, tick, app::kTickSeconds, camera);
    if (s.stage == components::TickStage::Commit) t1 = components::nowMilliseconds();
    if (s.stage == components::TickStage::PhysicsStep) t2 = components::nowMilliseconds();
  }
  const double t3 = components::nowMilliseconds();
  const components::PieceBudgetStats& s = sim.splits().pieces().stats();
  components::SplitWorld sw = sim.splitWorld();
  if (trace && t2 - t1 > 6.0)
    std::fprintf(stderr, "slow tick %llu: physics %.2f split %.2f live %u awake %u frozen %u contacts %zu triggers %zu %s\n",
                 (unsigned long long)tick, t2 - t1, t1 - t0, s.live, s.awake, s.frozen, sim.physics().contactEvents().size(),
                 sim.physics().triggerEvents().size(), awakeByMotion(sw, tick).c_str());
  m.tick.push_back(t3 - t0);
  m.split.push_back(t1 - t0);
  m.physics.push_back(t2 - t1);
  for (const components::SplitEvent& ev : sim.splits().lastEvents()) {
    m.splits++;
    m.pieces += ev.pieces.size();
  }
  m.maxLive = std::max(m.maxLive, s.live);
  m.maxAwake = std::max(m.maxAwake, s.awake);
}

// One frame of the field at 1280 x 720 as the player's camera would see it, timed up to its pixels
// being read back (so the GPU's work is in it; on a software rasterizer that is the processor's).
void timedFrame(components::Simulation& sim, uint64_t tick, const glm::vec3& eye, const glm::vec3& target, Minute& m) {
  components::SplitWorld sw = sim.splitWorld();
  if (!sw.renderer) return;
  render::Camera camera;
  camera.position = eye;
  camera.view = glm::lookAt(eye, target, glm::vec3(0.f, 1.f, 0.f));
  render::Lighting lighting;
  lighting.shadowCenter = glm::vec3(target.x, 0.f, target.z);
  lighting.shadowRadius = 24.f;
  const double t0 = components::nowMilliseconds();
  sw.renderer->beginFrame(1280, 720, camera, lighting);
  sim.submitMeshes(tick);
  const render::FrameStats stats = sw.renderer->endFrame();
  std::vector<uint8_t> rgba;
  int width = 0, height = 0;
  sw.renderer->readPixels(rgba, width, height);
  m.frame.push_back(components::nowMilliseconds() - t0);
  m.drawCalls = stats.drawCalls;
  m.triangles = stats.triangles;
}

}  // namespace

void DemoGame::benchmarkSession(int minutes, bool json) {
  ecs::World& world = app_->world();
  components::SplitWorld sw = splitWorld();
  std::mt19937 rng(12345);
  const ObjectKind kinds[] = {ObjectKind::WoodenCube,     ObjectKind::MetalSphere, ObjectKind::MarbleCylinder,
                              ObjectKind::MelonEllipsoid, ObjectKind::MultiPart,   ObjectKind::Torus,
                              ObjectKind::StoneBlock,     ObjectKind::Skinned};
  auto spot = [&](int i, float height) {
    const float half = 0.5f * kSpacing * float(kSide - 1);
    return kField + glm::vec3(kSpacing * float(i % kSide) - half, height, kSpacing * float(i / kSide) - half);
  };
  for (int i = 0; i < kSide * kSide; ++i) spawn(kinds[i % 8], spot(i, 0.7f), glm::quat(1.f, 0.f, 0.f, 0.f));
  const glm::dvec3 camera(kField + glm::vec3(0.f, 9.f, 24.f));
  const uint64_t first = 2000000;  // ticks of its own, after anything the demo did
  const uint64_t sessionTicks = uint64_t(minutes) * kTicksPerMinute;
  const uint64_t allTicks = sessionTicks + 30 * 60;  // then 30 s of quiet
  const bool trace = std::getenv("CLEAVE_SESSION_TRACE") != nullptr;
  std::vector<Blade> blades;
  std::vector<Minute> report(size_t(minutes) + 1);
  for (size_t m = 0; m < report.size(); ++m) report[m].minute = int(m) + 1;
  int sweep = 0;
  if (!json) printHeader();
  for (uint64_t n = 0; n < allTicks; ++n) {
    const uint64_t tick = first + n;
    const bool cutting = n < sessionTicks;
    if (cutting && n % 720 == 0) blades.push_back(startBlade(sw, sweep++, tick));  // a blade every 12 s
    moveBlades(sw, blades, tick);
    if (cutting && n % 1800 == 900) requestShatters(world, *splits_, rng, tick);  // every 30 s
    if (cutting && n % kTicksPerMinute == 1800) {  // fresh objects drop in
      for (int k = 0; k < 25; ++k)
        spawn(kinds[rng() % 8], spot(int(rng() % (kSide * kSide)), 2.5f + float(k % 5)), glm::quat(1.f, 0.f, 0.f, 0.f));
    }
    Minute& m = report[std::min<size_t>(n / kTicksPerMinute, report.size() - 1)];
    timedTick(*sim_, tick, camera, trace, m);
    const components::PieceBudgetStats& s = splits_->pieces().stats();
    if ((n + 1) % kTicksPerMinute == 0 || n + 1 == allTicks) {
      m.live = s.live, m.awake = s.awake, m.frozen = s.frozen, m.debris = s.debris;
      m.bodies = physics_->bodyCount();
      m.residentMb = residentMegabytes();
      m.gpuMeshes = resources().gpuMeshes;
      if (!json) printRow(m, minutes);  // as the minute ends: a long run shows its figures as it goes
    }
    sim_->batches().update(world, tick);  // as a game does each frame (it draws one every 5 s here)
    if ((n + 1) % 300 == 0) timedFrame(*sim_, tick, glm::vec3(camera), kField, m);  // every 5 s
    if (trace && (n + 1) % 600 == 0) traceAwakePieces(sw, n, tick);
    if (n + 1 == sessionTicks + 5 * 60) std::fprintf(stderr, "5 s after the last blade: %u awake of %u live\n", s.awake, s.live);
  }
  if (json) {
    printJson(report, *splits_);
  } else {
    printRetired(*splits_);
  }
  std::fflush(stdout);
}

}  // namespace cleave::demo
