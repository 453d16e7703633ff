// SPDX-License-Identifier: MIT
// The compute stage of the split pipeline as plain data: jobs made by hand, computed without any
// world, physics or renderer; the same job gives the same bytes on every thread and through a
// host's task callback; pieces share the parent's mass and carry its velocity at their centre;
// carried parts clip into the pieces; ragdoll plans share the mass by influence.
#include "cleave/components/split_compute.h"

#include <gtest/gtest.h>

#include <cstring>
#include <deque>
#include <memory>
#include <thread>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "cleave/components/skinned.h"
#include "cleave/components/split_workers.h"
#include "cleave/assets/procedural_character.h"
#include "cleave/geometry/collider_parts.h"
#include "cleave/geometry/primitives.h"

namespace cleave::components {
namespace {

std::shared_ptr<SplitJob> jobFor(geometry::MeshData mesh, const glm::dvec3& normal, double offset) {
  auto job = std::make_shared<SplitJob>();
  job->mesh = std::make_shared<geometry::MeshData>(std::move(mesh));
  job->model = glm::translate(glm::dmat4(1.0), glm::dvec3(0.5, 1.0, -0.25));
  job->plane = geometry::Plane{normal, offset};
  job->settings.density = 800.0;
  job->settings.splitImpulse = 0.5;
  job->parent.centre = glm::dvec3(0.5, 1.0, -0.25);
  job->parent.velocity = glm::dvec3(1.0, 0.5, 0.0);
  job->parent.angularVelocity = glm::dvec3(0.0, 3.0, 1.0);
  job->parent.mass = 100.0;
  job->targetName = "thing";
  return job;
}

// The bytes of everything commit would use.
std::vector<uint8_t> bytesOf(const SplitOutcome& out) {
  std::vector<uint8_t> bytes;
  auto put = [&](const void* p, size_t n) {
    const auto* b = static_cast<const uint8_t*>(p);
    bytes.insert(bytes.end(), b, b + n);
  };
  put(&out.status, sizeof(out.status));
  for (const PieceSpec& p : out.pieces) {
    put(&p.kind, sizeof(p.kind));
    put(&p.mass, sizeof(p.mass));
    put(&p.frame, sizeof(p.frame));
    put(&p.velocity, sizeof(p.velocity));
    put(p.mesh->positions.data(), p.mesh->positions.size() * sizeof(glm::vec3));
    put(p.mesh->indices.data(), p.mesh->indices.size() * sizeof(uint32_t));
    for (const HullSpec& h : p.hulls) {
      put(h.points.data(), h.points.size() * sizeof(glm::vec3));
      put(&h.margin, sizeof(h.margin));
    }
    for (const RagdollBoneSpec& b : p.ragdoll.bones) put(&b, sizeof(b));
  }
  return bytes;
}

TEST(SplitCompute, BoxJobGivesPiecesWithExactMassMotionAndCarriedColliders) {
  auto job = jobFor(geometry::primitives::box(glm::vec3(0.5f, 0.25f, 0.25f)), glm::dvec3(1, 0, 0), 0.7);
  auto splitter = geometry::makeConcaveSplitter();
  job->parts = std::make_shared<const geometry::ColliderPartSet>(geometry::decomposeConvex(*job->mesh, *splitter));
  SplitComputeScratch scratch;
  SplitOutcome out;
  computeSplit(*job, scratch, out);
  ASSERT_EQ(out.status, geometry::SplitStatus::Ok) << out.message;
  ASSERT_EQ(out.pieces.size(), 2u);
  double mass = 0.0;
  for (const PieceSpec& p : out.pieces) {
    EXPECT_EQ(p.kind, PieceKind::Rigid);
    mass += p.mass;
    EXPECT_NEAR(p.mass, 800.0 * p.volume, 1e-9);
    // The parent's velocity at the piece's centre, plus the impulse along the normal, away from the cut.
    const glm::dvec3 r = p.frame.position - job->parent.centre;
    const glm::dvec3 expected = job->parent.velocity + glm::cross(job->parent.angularVelocity, r) +
                                glm::dvec3(0.5 * p.side, 0.0, 0.0);
    EXPECT_NEAR(glm::length(p.velocity - expected), 0.0, 1e-12);
    // One carried part, clipped exactly: the collider fits the piece.
    ASSERT_EQ(p.hulls.size(), 1u);
    ASSERT_TRUE(p.parts);
    EXPECT_EQ(p.parts->size(), 1u);
    EXPECT_NEAR(p.colliderVolume / p.volume, 1.0, 1e-9);
    EXPECT_GT(p.hulls[0].margin, 0.f);
    EXPECT_TRUE(p.weld);  // cut again without welding
  }
  EXPECT_NEAR(mass, 800.0 * 0.25, 1e-9);
  EXPECT_FALSE(out.sourceWeld == nullptr);  // the job had no weld: compute hands one back
  EXPECT_EQ(out.sourceParts, nullptr);     // the parts were known
}

TEST(SplitCompute, MissingPartsAreDecomposedOnceAndHandedBack) {
  auto job = jobFor(geometry::primitives::torus(0.5f, 0.15f, 32, 16), glm::dvec3(0, 0, 1), -0.2);
  SplitComputeScratch scratch;
  SplitOutcome out;
  computeSplit(*job, scratch, out);
  ASSERT_EQ(out.status, geometry::SplitStatus::Ok) << out.message;
  ASSERT_TRUE(out.sourceParts);
  EXPECT_GT(out.sourceParts->size(), 4u);
  for (const PieceSpec& p : out.pieces) {
    EXPECT_GT(p.hulls.size(), 1u);
    EXPECT_LT(p.colliderVolume / p.volume, 1.5);
    EXPECT_GT(p.colliderVolume / p.volume, 0.8);
  }
}

TEST(SplitCompute, FailedJobHasAReasonAndNoPiece) {
  geometry::MeshData bad = geometry::primitives::box(glm::vec3(0.5f));
  bad.positions[3].x = std::numeric_limits<float>::quiet_NaN();
  auto job = jobFor(std::move(bad), glm::dvec3(0, 1, 0), 1.0);
  SplitComputeScratch scratch;
  SplitOutcome out;
  computeSplit(*job, scratch, out);
  EXPECT_EQ(out.status, geometry::SplitStatus::InvalidInput);
  EXPECT_FALSE(out.message.empty());
  EXPECT_TRUE(out.pieces.empty());
  auto miss = jobFor(geometry::primitives::box(glm::vec3(0.5f)), glm::dvec3(0, 1, 0), 5.0);
  computeSplit(*miss, scratch, out);
  EXPECT_EQ(out.status, geometry::SplitStatus::PlaneMissesMesh);
}

TEST(SplitCompute, RagdollJobSharesTheParentMassOverItsBones) {
  const assets::ProceduralCharacter character = assets::makeProceduralCharacter();
  auto asset = std::make_shared<SkinnedAsset>();
  asset->skeleton = character.skeleton;
  asset->clips = {character.idle, character.walk};
  SkinnedMesh skin = makeSkinnedMesh(asset, "walk", 0.3f);
  auto job = jobFor(character.mesh, glm::dvec3(0.1, 1, 0.05), 1.9);
  job->skin = asset;
  job->jointMatrices = skin.jointMatrices;
  job->settings.skinnedPieces = SkinnedPieceMode::Ragdoll;
  SplitComputeScratch scratch;
  SplitOutcome out;
  computeSplit(*job, scratch, out);
  ASSERT_EQ(out.status, geometry::SplitStatus::Ok) << out.message;
  double total = 0.0;
  size_t ragdolls = 0;
  for (const PieceSpec& p : out.pieces) {
    total += p.mass;
    if (p.kind != PieceKind::Ragdoll) continue;
    ++ragdolls;
    double bones = 0.0;
    for (const RagdollBoneSpec& b : p.ragdoll.bones) bones += b.mass;
    EXPECT_NEAR(bones, p.mass, 1e-3 * p.mass);
    EXPECT_EQ(p.ragdoll.carrier.size(), character.skeleton.size());
    EXPECT_EQ(p.ragdoll.jointMatrices.size(), skin.jointMatrices.size());
    EXPECT_EQ(p.ragdoll.joints.size() + 1, p.ragdoll.bones.size());  // one tree of bones
  }
  EXPECT_GE(ragdolls, 1u);
  EXPECT_NEAR(total, 100.0, 1e-9);  // skinned pieces share the parent's mass
}

std::vector<std::shared_ptr<const SplitJob>> someJobs() {
  std::vector<std::shared_ptr<const SplitJob>> jobs;
  for (int k = 0; k < 12; ++k) {
    const double t = 0.1 * k;
    geometry::MeshData mesh = k % 3 == 0   ? geometry::primitives::torus(0.5f, 0.15f, 32, 16)
                              : k % 3 == 1 ? geometry::primitives::uvSphere(0.5f, 24, 12)
                                           : geometry::primitives::box(glm::vec3(0.4f, 0.3f, 0.2f));
    jobs.push_back(jobFor(std::move(mesh), glm::normalize(glm::dvec3(std::sin(t), 1.0, std::cos(3 * t))), 1.0 + 0.02 * k));
  }
  return jobs;
}

TEST(SplitWorkers, OutcomesAreTheSameBytesOnZeroOneAndThreeThreads) {
  const auto jobs = someJobs();
  std::vector<std::vector<uint8_t>> reference;
  for (uint32_t threads : {0u, 1u, 3u}) {
    SplitWorkers workers(threads);
    std::vector<std::shared_ptr<SplitWorkers::Task>> tasks;
    for (const auto& job : jobs) tasks.push_back(workers.submit(job));
    for (size_t i = 0; i < tasks.size(); ++i) {
      workers.wait(*tasks[i]);
      ASSERT_EQ(tasks[i]->outcome.status, geometry::SplitStatus::Ok) << tasks[i]->outcome.message;
      const std::vector<uint8_t> bytes = bytesOf(tasks[i]->outcome);
      if (threads == 0) {
        reference.push_back(bytes);
      } else {
        EXPECT_EQ(bytes, reference[i]) << "job " << i << " on " << threads << " threads";
      }
    }
  }
}

TEST(SplitWorkers, HostExecutorRunsEveryTaskOnceAndWaitingRunsOnesNotStarted) {
  const auto jobs = someJobs();
  // A host that only runs tasks when asked to: waiting must take over the ones it has not run.
  std::deque<std::function<void()>> hostQueue;
  size_t given = 0;
  SplitWorkers workers(0);
  workers.setExecutor([&](std::function<void()> task) {
    ++given;
    hostQueue.push_back(std::move(task));
  });
  std::vector<std::shared_ptr<SplitWorkers::Task>> tasks;
  for (const auto& job : jobs) tasks.push_back(workers.submit(job));
  EXPECT_EQ(given, jobs.size());
  // The host runs the first half on a thread of its own; the rest it never gets to before the wait.
  std::thread host([&] {
    for (size_t i = 0; i < jobs.size() / 2; ++i) hostQueue[i]();
  });
  host.join();
  size_t byCaller = 0;
  for (auto& task : tasks) {
    workers.wait(*task);
    byCaller += task->computedByCaller;
    EXPECT_EQ(task->outcome.status, geometry::SplitStatus::Ok);
  }
  EXPECT_EQ(byCaller, jobs.size() - jobs.size() / 2);
  for (size_t i = jobs.size() / 2; i < hostQueue.size(); ++i) hostQueue[i]();  // late: they do nothing
  SplitComputeScratch scratch;
  SplitOutcome inline0;
  computeSplit(*jobs[0], scratch, inline0);
  EXPECT_EQ(bytesOf(tasks[0]->outcome), bytesOf(inline0));
}

}  // namespace
}  // namespace cleave::components
