// SPDX-License-Identifier: MIT
// Split + cap cost against triangle count. Each case builds its mesh and container once, warms a
// reused splitter and SplitResult up (so steady-state runs allocate nothing), then times split()
// alone. Counters: triangles of the input, pieces and cap triangles of the last run.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

#include "cleave/components/simulation.h"
#include "cleave/components/skinned.h"
#include "cleave/components/split_system.h"
#include "cleave/anim/animation_clip.h"
#include "cleave/ecs/hierarchy.h"
#include "cleave/assets/model.h"
#include "cleave/assets/procedural_character.h"
#include "cleave/geometry/fracture.h"
#include "cleave/geometry/mesh_splitter.h"
#include "cleave/geometry/primitives.h"

namespace cleave::geometry {
namespace {

namespace prim = primitives;

enum class Kind { Concave, Convex };

// The container set up with `mesh` (the cut space its source space) and a splitter warmed up by one
// split with each of `options` (threads started, scratch grown), as every split benchmark begins.
// False, with the benchmark skipped and told why, when the mesh or a split fails.
bool warmedUp(benchmark::State& state, const MeshData& mesh, const Plane& plane, Kind kind,
              std::initializer_list<const SplitOptions*> options, MeshContainer& container,
              std::unique_ptr<IMeshSplitter>& splitter, SplitResult& result) {
  if (const MeshStatus set = container.setMesh(mesh); !set.ok()) {
    state.SkipWithError(("setMesh failed: " + set.message).c_str());
    return false;
  }
  container.setTransform(glm::mat4(1.f));
  splitter = kind == Kind::Concave ? makeConcaveSplitter() : makeConvexSplitter();
  for (const SplitOptions* o : options) {
    if (splitter->split(container, plane, *o, result) != SplitStatus::Ok) {
      state.SkipWithError(("split failed: " + result.message).c_str());
      return false;
    }
  }
  return true;
}

void runSplit(benchmark::State& state, const MeshData& mesh, const Plane& plane, Kind kind) {
  MeshContainer container;
  std::unique_ptr<IMeshSplitter> splitter;
  SplitOptions options;
  SplitResult result;
  if (!warmedUp(state, mesh, plane, kind, {&options}, container, splitter, result)) return;
  for (auto _ : state) {
    splitter->split(container, plane, options, result);
    benchmark::DoNotOptimize(result.pieces.data());
    benchmark::ClobberMemory();
  }
  uint32_t capTriangles = 0;
  for (const SplitPiece& piece : result.pieces) capTriangles += piece.capTriangles;
  state.counters["triangles"] = double(mesh.triangleCount());
  state.counters["pieces"] = double(result.pieces.size());
  state.counters["capTriangles"] = double(capTriangles);
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(mesh.triangleCount()));
}

Plane tilted(double offset) {
  Plane p;
  p.normal = glm::normalize(glm::dvec3(0.3, 1.0, 0.2));
  p.offset = offset;
  return p;
}

// UV spheres of about 1k, 10k, 100k and 1M triangles: segments x rings chosen so that
// 2 * segments * (rings - 1) is close to the target.
MeshData sphereOf(int64_t target) {
  switch (target) {
    case 1000: return prim::uvSphere(1.f, 32, 17);      // 1024
    case 10000: return prim::uvSphere(1.f, 100, 51);    // 10000
    case 100000: return prim::uvSphere(1.f, 316, 159);  // 99856
    default: return prim::uvSphere(1.f, 1000, 501);     // 1000000
  }
}

void BM_ConcaveSplitSphere(benchmark::State& state) {
  runSplit(state, sphereOf(state.range(0)), tilted(0.1), Kind::Concave);
}
BENCHMARK(BM_ConcaveSplitSphere)->Arg(1000)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMicrosecond);

// SplitOptions::threads against one thread on the 1M sphere (the bar: range(0) = 2 threads
// at least 1.7 times as fast). One and range(0) threads alternate split by split, so that both see
// the same load of a noisy machine; the counters give each one's median and their ratio (what is
// timed is the pair). Run pinned to as many CPUs as threads:
//   taskset -c 0,1 build/bin/cleave-bench --benchmark_filter=ConcaveSplitSphereThreads
void BM_ConcaveSplitSphereThreads(benchmark::State& state) {
  MeshContainer container;
  std::unique_ptr<IMeshSplitter> splitter;
  SplitOptions one, many;
  many.threads = static_cast<uint32_t>(state.range(0));
  const Plane plane = tilted(0.1);
  SplitResult result;
  if (!warmedUp(state, sphereOf(1000000), plane, Kind::Concave, {&one, &many}, container, splitter, result)) return;
  using Clock = std::chrono::steady_clock;
  std::vector<double> oneMs, manyMs;
  for (auto _ : state) {
    const Clock::time_point a = Clock::now();
    splitter->split(container, plane, one, result);
    const Clock::time_point b = Clock::now();
    splitter->split(container, plane, many, result);
    const Clock::time_point c = Clock::now();
    benchmark::DoNotOptimize(result.pieces.data());
    oneMs.push_back(std::chrono::duration<double, std::milli>(b - a).count());
    manyMs.push_back(std::chrono::duration<double, std::milli>(c - b).count());
    state.SetIterationTime(std::chrono::duration<double>(c - a).count());
  }
  auto median = [](std::vector<double>& v) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  const double oneMedian = median(oneMs), manyMedian = median(manyMs);
  state.counters["oneThreadMs"] = oneMedian;
  state.counters["threadsMs"] = manyMedian;
  state.counters["ratio"] = oneMedian / manyMedian;
}
BENCHMARK(BM_ConcaveSplitSphereThreads)->Arg(2)->Iterations(60)->UseManualTime()->Unit(benchmark::kMillisecond);

// Container set-up from nothing (copy, weld by position, closedness, cut-space positions) of a
// sphere with positions only, as read from a PLY or STL file: the cost of a first cut of a mesh the
// engine has not seen. A piece made by a split does not pay it (it carries its weld).
void BM_ContainerSetMeshSphere(benchmark::State& state) {
  MeshData mesh = sphereOf(state.range(0));
  MeshData positionsOnly;
  positionsOnly.positions = mesh.positions;
  positionsOnly.indices = mesh.indices;
  for (auto _ : state) {
    MeshContainer container;
    container.setMesh(positionsOnly);
    container.setTransform(glm::mat4(1.f));
    benchmark::DoNotOptimize(container.positionIds().data());
  }
  state.counters["triangles"] = double(mesh.triangleCount());
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(mesh.triangleCount()));
}
BENCHMARK(BM_ContainerSetMeshSphere)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMicrosecond);

void BM_ConvexSplitSphere(benchmark::State& state) {
  runSplit(state, sphereOf(state.range(0)), tilted(0.1), Kind::Convex);
}
BENCHMARK(BM_ConvexSplitSphere)->Arg(1000)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMicrosecond);

void BM_ConcaveSplitTorusHorizontal100k(benchmark::State& state) {
  Plane plane;
  plane.normal = {0.0, 1.0, 0.0};
  plane.offset = 0.05;
  runSplit(state, prim::torus(1.f, 0.3f, 500, 100), plane, Kind::Concave);  // 100000 triangles
}
BENCHMARK(BM_ConcaveSplitTorusHorizontal100k)->Unit(benchmark::kMicrosecond);

void BM_ConcaveSplitComb32Teeth(benchmark::State& state) {
  Plane plane;
  plane.normal = {0.0, 1.0, 0.05};
  plane.offset = 0.5;  // across all 32 teeth: 33 pieces
  runSplit(state, prim::combPrism(32), plane, Kind::Concave);
}
BENCHMARK(BM_ConcaveSplitComb32Teeth)->Unit(benchmark::kMicrosecond);

// Fracture into Voronoi cells: a 1k-triangle sphere (uvSphere 32 x 16: 960 triangles) and the demo's
// torus (2,304 triangles) into range(0) cells; cells and seeds made once, outside the loop. range(1):
// 0 the cell clipper (as the engine fractures), 1 one split per cell plane (FractureMethod::Splits).
void runFracture(benchmark::State& state, const MeshData& mesh) {
  MeshContainer container;
  if (container.setMesh(mesh).code != SplitStatus::Ok) {
    state.SkipWithError("setMesh failed");
    return;
  }
  const glm::dvec3 lo = container.boundsMin(), hi = container.boundsMax();
  const std::vector<ConvexCell> cells =
      voronoiCells(fractureSeeds(uint32_t(state.range(0)), 1, lo, hi), lo - 0.01 * (hi - lo), hi + 0.01 * (hi - lo));
  const FractureMethod method = state.range(1) == 0 ? FractureMethod::Clipper : FractureMethod::Splits;
  size_t pieces = 0, bySplits = 0;
  for (auto _ : state) {
    FractureResult r = fracture(container, cells, SplitOptions{}, method);
    pieces = r.pieces.size();
    bySplits = r.carvedBySplits;
    benchmark::DoNotOptimize(r);
  }
  state.counters["pieces"] = double(pieces);
  state.counters["by_splits"] = double(bySplits);
}

void BM_FractureSphere1k(benchmark::State& state) { runFracture(state, primitives::uvSphere(0.5f, 32, 16)); }
BENCHMARK(BM_FractureSphere1k)->ArgsProduct({{16, 32}, {0, 1}})->Unit(benchmark::kMicrosecond);

void BM_FractureDemoTorus(benchmark::State& state) { runFracture(state, primitives::torus(0.5f, 0.2f, 48, 24)); }
BENCHMARK(BM_FractureDemoTorus)->ArgsProduct({{16, 32}, {0, 1}})->Unit(benchmark::kMicrosecond);

void BM_ConcaveSplitComb32TeethAlongExtrusion(benchmark::State& state) {
  Plane plane;
  plane.normal = {0.0, 0.0, 1.0};
  plane.offset = 0.01;  // one comb-shaped cap with 132 outline vertices
  runSplit(state, prim::combPrism(32), plane, Kind::Concave);
}
BENCHMARK(BM_ConcaveSplitComb32TeethAlongExtrusion)->Unit(benchmark::kMicrosecond);

// The generated 4k-triangle skinned character: each iteration poses it (walk clip sampled at an
// advancing time, joint matrices, MeshContainer::setSkinningPose) and cuts it across the waist
// with caps, the path from a split request to the pieces of a skinned mesh. "poseOnly" times the
// posing alone so the cut's share can be read off.
void runSkinnedCharacter(benchmark::State& state, bool split) {
  const assets::ProceduralCharacter character = assets::makeProceduralCharacter();
  MeshContainer container;
  if (const MeshStatus set = container.setMesh(character.mesh); !set.ok()) {
    state.SkipWithError(("setMesh failed: " + set.message).c_str());
    return;
  }
  std::unique_ptr<IMeshSplitter> splitter = makeConcaveSplitter();
  SplitOptions options;
  SplitResult result;
  anim::Pose pose;
  std::vector<glm::mat4> joints;
  Plane plane;
  plane.normal = glm::normalize(glm::dvec3(0.2, 1.0, 0.1));
  plane.offset = 1.05;
  float time = 0.f;
  auto poseAndCut = [&]() {
    anim::sampleClip(character.skeleton, character.walk, time, true, pose);
    anim::poseToJointMatrices(character.skeleton, pose, joints);
    time += 1.f / 60.f;
    container.setSkinningPose(joints, glm::mat4(1.f));
    return split ? splitter->split(container, plane, options, result) : SplitStatus::Ok;
  };
  if (poseAndCut() != SplitStatus::Ok) {  // warm-up
    state.SkipWithError(("split failed: " + result.message).c_str());
    return;
  }
  for (auto _ : state) {
    benchmark::DoNotOptimize(poseAndCut());
    benchmark::ClobberMemory();
  }
  state.counters["triangles"] = double(character.mesh.triangleCount());
  state.counters["pieces"] = double(result.pieces.size());
}

void BM_SkinnedCharacterPoseAndSplit(benchmark::State& state) { runSkinnedCharacter(state, true); }
BENCHMARK(BM_SkinnedCharacterPoseAndSplit)->Unit(benchmark::kMicrosecond);

void BM_SkinnedCharacterPoseOnly(benchmark::State& state) { runSkinnedCharacter(state, false); }
BENCHMARK(BM_SkinnedCharacterPoseOnly)->Unit(benchmark::kMicrosecond);

// MeshContainer::setSkinningPose alone on the generated character (one fixed walk pose): the
// per-vertex blend of joint matrices into cut-space positions.
void BM_SkinnedCharacterSetSkinningPose(benchmark::State& state) {
  const assets::ProceduralCharacter character = assets::makeProceduralCharacter();
  MeshContainer container;
  if (const MeshStatus set = container.setMesh(character.mesh); !set.ok()) {
    state.SkipWithError(("setMesh failed: " + set.message).c_str());
    return;
  }
  anim::Pose pose;
  std::vector<glm::mat4> joints;
  anim::sampleClip(character.skeleton, character.walk, 0.3f, true, pose);
  anim::poseToJointMatrices(character.skeleton, pose, joints);
  for (auto _ : state) {
    benchmark::DoNotOptimize(container.setSkinningPose(joints, glm::mat4(1.f)).code);
    benchmark::ClobberMemory();
  }
  state.counters["vertices"] = double(character.mesh.positions.size());
}
BENCHMARK(BM_SkinnedCharacterSetSkinningPose)->Unit(benchmark::kMicrosecond);

// Time from split request to pieces created for the generated character through the split system
// (renderer null): the walking character on a kinematic body is cut across the chest with
// SplitSystem::splitNow, which cuts in the pose, builds the pieces of the chosen mode (keep
// animating: skinned piece + collider; ragdoll: capsules and joints; bake: CPU skinning + collider),
// creates their bodies and applies the entity changes. Spawning and freeing are not timed.
// Arg: 0 KeepAnimating, 1 Ragdoll, 2 Bake.
void BM_SkinnedCharacterSplitSystem(benchmark::State& state) {
  using namespace cleave::components;
  const assets::ProceduralCharacter character = assets::makeProceduralCharacter();
  auto asset = std::make_shared<SkinnedAsset>();
  asset->skeleton = character.skeleton;
  asset->clips = {character.idle, character.walk};
  auto mesh = std::make_shared<const MeshData>(character.mesh);
  const auto mode = SkinnedPieceMode(state.range(0));
  ecs::World world;
  Simulation sim(world);
  SplitSystem& splits = sim.splits();
  SplitWorld w = sim.splitWorld();
  size_t pieces = 0;
  float time = 0.f;
  for (auto _ : state) {
    state.PauseTiming();
    const ecs::Entity e = world.create();
    world.add<ecs::Transform>(e, ecs::Transform{});
    world.add<ecs::WorldTransform>(e, ecs::WorldTransform{});
    MeshRenderer mr;
    mr.source = mesh;
    mr.materials.resize(5);
    world.add<MeshRenderer>(e, std::move(mr));
    world.add<SkinnedMesh>(e, makeSkinnedMesh(asset, "walk", time));
    time += 1.f / 60.f;
    Splitable sp;
    sp.skinnedPieces = mode;
    world.add<Splitable>(e, sp);
    if (const base::Status made = makeSkinnedBody(w, e, 1000.0, true); !made.ok()) {
      state.SkipWithError(made.message.c_str());
      return;
    }
    SplitRequest request;
    request.target = e;
    request.planeNormal = glm::normalize(glm::dvec3(0.2, 1.0, 0.1));
    request.planeOffset = 1.05;
    state.ResumeTiming();
    const SplitEvent ev = splits.splitNow(w, e, request, 0);
    state.PauseTiming();
    if (ev.status != SplitStatus::Ok) {
      state.SkipWithError(("split failed: " + ev.message).c_str());
      return;
    }
    pieces = ev.pieces.size();
    for (ecs::Entity piece : ev.pieces) world.destroy(piece);
    state.ResumeTiming();
  }
  state.counters["triangles"] = double(character.mesh.triangleCount());
  state.counters["pieces"] = double(pieces);
}
BENCHMARK(BM_SkinnedCharacterSplitSystem)
    ->ArgName("mode")  // 0 keep animating, 1 ragdoll, 2 bake
    ->Arg(0)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond);

// robot.glb from the models folder (CLEAVE_MODELS_DIR, else ../shared/models beside the sources;
// skipped when absent): its skinned meshes merged into one, posed at 0.5 s of its first clip and cut
// hollow (the parts are open and intersect) through the middle of the pose.
void BM_SkinnedRobotPoseAndSplit(benchmark::State& state) {
  const char* env = std::getenv("CLEAVE_MODELS_DIR");
  const std::string folder = env ? env : std::string(CLEAVE_SOURCE_DIR) + "/../shared/models";
  const assets::ModelLoadResult loaded = assets::loadModel(folder + "/robot.glb");
  if (!loaded.ok() || loaded.model.skins.empty()) {
    state.SkipWithError(("robot.glb not available: " + loaded.message).c_str());
    return;
  }
  const assets::ModelSkin& skin = loaded.model.skins[0];
  MeshData mesh;
  for (const assets::ModelMesh& part : loaded.model.meshes) {
    if (part.skin == 0) mesh = mesh.positions.empty() ? part.mesh : primitives::merge(mesh, part.mesh);
  }
  MeshContainer container;
  if (const MeshStatus set = container.setMesh(mesh); !set.ok()) {
    state.SkipWithError(("setMesh failed: " + set.message).c_str());
    return;
  }
  anim::Pose pose;
  std::vector<glm::mat4> joints;
  if (skin.clips.empty()) anim::restPose(skin.skeleton, pose);
  else anim::sampleClip(skin.skeleton, skin.clips[0], 0.5f, true, pose);
  anim::poseToJointMatrices(skin.skeleton, pose, joints);
  container.setSkinningPose(joints, glm::mat4(1.f));
  glm::dvec3 lo(1e30), hi(-1e30);
  for (const glm::dvec3& p : container.cutPositions()) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  Plane plane;
  plane.normal = glm::normalize(glm::dvec3(0.2, 1.0, 0.1));
  plane.offset = glm::dot(plane.normal, 0.5 * (lo + hi));
  std::unique_ptr<IMeshSplitter> splitter = makeConcaveSplitter();
  SplitOptions options;
  options.cap = false;
  SplitResult result;
  for (auto _ : state) {
    container.setSkinningPose(joints, glm::mat4(1.f));
    benchmark::DoNotOptimize(splitter->split(container, plane, options, result));
    benchmark::ClobberMemory();
  }
  state.counters["triangles"] = double(mesh.triangleCount());
  state.counters["pieces"] = double(result.pieces.size());
}
BENCHMARK(BM_SkinnedRobotPoseAndSplit)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace cleave::geometry
