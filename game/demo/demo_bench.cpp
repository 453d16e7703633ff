// SPDX-License-Identifier: MIT
// The demo's split benchmarks (cleave-demo --bench-splits N, --bench-burst; docs/performance.md).
// They measure, they do not test: medians of wall times on this machine, printed as a table or JSON.
#include <algorithm>
#include <cstdlib>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cleave/ecs/hierarchy.h"
#include "cleave/components/split_clock.h"
#include "game/demo/demo_game.h"

namespace cleave::demo {
namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

struct ObjectRun {
  std::string name;
  size_t triangles = 0, pieces = 0;
  double partsWork = 0.0;
  size_t parts = 0;
  std::vector<double> mainMs, workerMs, colliderMs, fit;
};

// A burst: every target requested in one tick, then the stages stepped until all are committed.
struct BurstRun {
  uint64_t ticksToCommit = 0;
  double maxMainMs = 0.0;   // main-thread split work in one tick (prepare + commit, waits excluded)
  double maxWaitMs = 0.0;   // waiting for late jobs in one tick
  std::vector<double> mainMsPerTick;  // ticks that committed something
  size_t splits = 0, pieces = 0;
};

}  // namespace

void DemoGame::benchmarkSplits(int repeats, bool json) {
  ecs::World& world = app_->world();
  components::SplitWorld sw = splitWorld();
  const char* names[] = {"", "wooden cube", "metal sphere", "marble cylinder", "melon",
                         "multi-part figure", "skinned character", "torus", "stone block"};
  // Every object cut once by a plane, then three shattered into 16 cells (F in the demo).
  struct Case {
    int kind;
    uint32_t cells;  // 0: a plane cut
  };
  const Case cases[] = {{1, 0}, {2, 0}, {3, 0}, {4, 0}, {5, 0}, {6, 0}, {7, 0}, {8, 0}, {2, 16}, {7, 16}, {8, 16}};
  std::vector<ObjectRun> runs;
  for (const auto [kind, cells] : cases) {
    ObjectRun run;
    run.name = std::string(names[kind]) + (cells ? ", shatter " + std::to_string(cells) : "");
    for (int i = 0; i < repeats; ++i) {
      const glm::vec3 at(100.f + 5.f * float(kind), 2.f, 100.f);
      const ecs::Entity e = spawn(ObjectKind(kind), at, glm::quat(1.f, 0.f, 0.f, 0.f));
      if (const auto* mr = world.tryGet<components::MeshRenderer>(e)) run.triangles = mr->source->indices.size() / 3;
      if (const auto* cp = world.tryGet<components::ColliderParts>(e); cp && cp->parts) {
        run.parts = cp->parts->size();
        run.partsWork = geometry::partsWork(*cp->parts);
      }
      const auto* t = world.tryGet<ecs::Transform>(e);
      const glm::dvec3 centre = t ? glm::dvec3(t->position) : glm::dvec3(at);
      components::SplitRequest request;
      request.target = e;
      request.planeNormal = glm::normalize(glm::dvec3(0.3, 1.0, 0.2));
      request.planeOffset = glm::dot(request.planeNormal, centre);
      request.shatter = cells > 0;
      request.shatterSpec.cells = cells;
      request.shatterSpec.impactPoint = centre;
      const components::SplitEvent ev = splits_->splitNow(sw, e, request, 0);
      run.mainMs.push_back(ev.times.main());
      run.workerMs.push_back(ev.times.compute.total);
      run.colliderMs.push_back(ev.times.compute.collider + ev.times.shapes);
      run.fit.push_back(ev.colliderFit.empty() ? 0.0 : *std::max_element(ev.colliderFit.begin(), ev.colliderFit.end()));
      run.pieces = ev.pieces.size();
      for (ecs::Entity piece : ev.pieces) world.destroy(piece);
      world.destroy(e);
    }
    runs.push_back(std::move(run));
  }
  if (json) {
    nlohmann::json out;
    out["repeats"] = repeats;
    out["threads"] = splits_->budget().settings().threads;
    for (const ObjectRun& r : runs)
      out["objects"].push_back({{"name", r.name}, {"triangles", r.triangles}, {"pieces", r.pieces},
                                {"collider_parts", r.parts}, {"parts_work", r.partsWork}, {"main_ms", median(r.mainMs)}, {"worker_ms", median(r.workerMs)},
                                {"collider_ms", median(r.colliderMs)}, {"collider_volume_ratio", median(r.fit)}});
    std::printf("%s\n", out.dump().c_str());
  } else {
    std::printf("| object | triangles | pieces | main ms | worker ms | collider ms | collider fit |\n");
    std::printf("|---|---:|---:|---:|---:|---:|---:|\n");
    for (const ObjectRun& r : runs)
      std::printf("| %s | %zu | %zu | %.3f | %.3f | %.3f | %.2f |\n", r.name.c_str(), r.triangles, r.pieces,
                  median(r.mainMs), median(r.workerMs), median(r.colliderMs), median(r.fit));
  }
  std::fflush(stdout);
}

void DemoGame::benchmarkBurst(bool json) {
  ecs::World& world = app_->world();
  auto burst = [&](ObjectKind kind, int count, float spacing) {
    std::vector<ecs::Entity> targets;
    const int side = int(std::ceil(std::sqrt(double(count))));
    for (int i = 0; i < count; ++i) {
      const glm::vec3 at(200.f + spacing * float(i % side), 0.6f, 200.f + spacing * float(i / side));
      targets.push_back(spawn(kind, at, glm::quat(1.f, 0.f, 0.f, 0.f)));
    }
    const uint64_t start = 1000000 + uint64_t(kind) * 10000;  // ticks of their own
    for (ecs::Entity e : targets) {
      const glm::dvec3 centre(world.get<ecs::Transform>(e).position);
      components::SplitRequest r;
      r.target = e;
      r.planeNormal = glm::normalize(glm::dvec3(0.2, 1.0, 0.1));
      r.planeOffset = glm::dot(r.planeNormal, centre + glm::dvec3(0.0, 0.05, 0.0));
      r.requestedTick = start;
      splits_->request(r);
    }
    BurstRun run;
    uint64_t tick = start + 1;
    for (; tick < start + 2000 && run.splits < targets.size(); ++tick) {
      const double t0 = components::nowMilliseconds();
      sim_->prepare(tick, glm::dvec3(200.0, 2.0, 190.0));
      const double t1 = components::nowMilliseconds();
      sim_->commit(tick);
      const double t2 = components::nowMilliseconds();
      if (std::getenv("CLEAVE_BENCH_TRACE")) {
        double shapes = 0.0, uploads = 0.0, commits = 0.0, waits = 0.0;
        for (const components::SplitEvent& ev : splits_->lastEvents()) {
          shapes += ev.times.shapes;
          uploads += ev.times.uploads;
          commits += ev.times.commit;
          waits += ev.times.wait;
        }
        std::fprintf(stderr, "tick %llu prepare %.3f commit %.3f (events %zu: commit %.3f shapes %.3f uploads %.3f waits %.3f)\n",
                     (unsigned long long)tick, t1 - t0, t2 - t1, splits_->lastEvents().size(), commits, shapes, uploads, waits);
      }
      double waited = 0.0;
      for (const components::SplitEvent& ev : splits_->lastEvents()) {
        waited += ev.times.wait;
        ++run.splits;
        run.pieces += ev.pieces.size();
      }
      run.maxMainMs = std::max(run.maxMainMs, splits_->lastTickMainMilliseconds() - waited);
      if (!splits_->lastEvents().empty()) run.mainMsPerTick.push_back(splits_->lastTickMainMilliseconds() - waited);
      run.maxWaitMs = std::max(run.maxWaitMs, waited);
      sim_->stepPhysics(app::kTickSeconds);
      sim_->sync(app::kTickSeconds);
      sim_->animate(app::kTickSeconds);
    }
    run.ticksToCommit = tick - 1 - start;
    return run;
  };
  const BurstRun cubes = burst(ObjectKind::WoodenCube, 50, 1.5f);
  const BurstRun characters = burst(ObjectKind::Skinned, 100, 1.5f);
  const uint32_t threads = splits_->budget().settings().threads;
  if (json) {
    auto entry = [&](const BurstRun& r) {
      return nlohmann::json{{"ticks_to_commit", r.ticksToCommit}, {"max_main_ms_per_tick", r.maxMainMs},
                            {"median_main_ms_per_tick", median(r.mainMsPerTick)},
                            {"max_wait_ms_per_tick", r.maxWaitMs}, {"splits", r.splits}, {"pieces", r.pieces},
                            {"threads", threads}};
    };
    std::printf("%s\n", nlohmann::json{{"cubes_50", entry(cubes)}, {"skinned_100", entry(characters)}}.dump().c_str());
  } else {
    std::printf("| burst (%u threads) | splits | pieces | ticks to commit | max main ms/tick | median main ms/tick | "
                "max wait ms/tick |\n", threads);
    std::printf("|---|---:|---:|---:|---:|---:|---:|\n");
    for (const auto& [name, r] : {std::pair{"50 cubes", cubes}, std::pair{"100 characters", characters}})
      std::printf("| %s | %zu | %zu | %llu | %.3f | %.3f | %.3f |\n", name, r.splits, r.pieces,
                  (unsigned long long)r.ticksToCommit, r.maxMainMs, median(r.mainMsPerTick), r.maxWaitMs);
  }
  std::fflush(stdout);
}

}  // namespace cleave::demo
