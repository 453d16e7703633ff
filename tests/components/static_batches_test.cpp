// SPDX-License-Identifier: MIT
// Static batches (static_batches.h) on a headless GL context: frozen pieces in a settled cell are
// drawn by one batch and look the same as drawn one by one; a cell still changing, or with too
// few pieces, is not built; a batch dissolves the update its piece thaws or goes; release() and
// the destructor free the batch meshes.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "cleave/components/piece_budget.h"
#include "cleave/components/scene_components.h"
#include "cleave/components/split_system.h"
#include "cleave/components/static_batches.h"
#include "cleave/geometry/primitives.h"
#include "tests/render/headless_gl.h"
#include "tests/render/image_compare.h"

namespace cleave::components {
namespace {

constexpr int kWidth = 320;
constexpr int kHeight = 180;

class BatchScene : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string why;
    if (!testing::startHeadless(context_, renderer_, why)) GTEST_SKIP() << "no headless GL: " << why;
    batches_.setRenderer(&renderer_);
  }

  // A frozen piece: a box, or (mirrored) a sphere scaled by -1 along x, with a lit material and a
  // cap material, at `at` turned about y by `yaw`.
  ecs::Entity addFrozen(glm::vec3 at, float yaw, glm::vec4 color, bool sphere = false) {
    auto mesh = std::make_shared<geometry::MeshData>(sphere ? geometry::primitives::uvSphere(0.3f, 16, 8)
                                                            : geometry::primitives::box(glm::vec3(0.2f, 0.3f, 0.25f)));
    const ecs::Entity e = world_.create();
    ecs::Transform t;
    t.position = at;
    t.rotation = glm::angleAxis(yaw, glm::vec3(0, 1, 0));
    world_.add<ecs::Transform>(e, t);
    world_.add<ecs::WorldTransform>(e, ecs::WorldTransform{ecs::localMatrix(t)});
    MeshRenderer mr;
    mr.source = mesh;
    mr.gpu = renderer_.uploadMesh(*mesh).valueOr({});
    render::Material look;
    look.baseColor = color;
    render::Material cap;
    cap.baseColor = glm::vec4(0.9f, 0.8f, 0.6f, 1.f);
    mr.materials = {look, cap};
    if (sphere) mr.meshOffset = glm::scale(glm::mat4(1.f), glm::vec3(-1.f, 1.f, 1.f));
    world_.add<MeshRenderer>(e, std::move(mr));
    world_.add<MassInfo>(e, MassInfo{1.0, 0.001, 1000.0, true});
    world_.add<Frozen>(e, Frozen{0});
    return e;
  }

  // Twelve pieces on a 4 x 3 grid in one 8 m cell, two of them mirrored spheres.
  std::vector<ecs::Entity> addHeap() {
    std::vector<ecs::Entity> out;
    for (int i = 0; i < 12; ++i) {
      const glm::vec3 at(0.7f * float(i % 4) + 0.5f, 0.3f + 0.1f * float(i % 3), 0.7f * float(i / 4) + 0.5f);
      const glm::vec4 color = i % 2 ? glm::vec4(0.7f, 0.3f, 0.2f, 1.f) : glm::vec4(0.3f, 0.5f, 0.7f, 1.f);
      out.push_back(addFrozen(at, 0.4f * float(i), color, i == 5 || i == 10));
    }
    return out;
  }

  void update(uint64_t tick) { batches_.update(world_, tick); }

  // One frame of the heap; the draw calls it took.
  std::vector<uint8_t> draw(uint32_t& drawCalls) {
    render::Camera camera;
    camera.position = glm::vec3(1.5f, 2.5f, 5.f);
    camera.view = glm::lookAt(camera.position, glm::vec3(1.5f, 0.3f, 1.2f), glm::vec3(0, 1, 0));
    render::Lighting lighting;
    lighting.shadowCenter = glm::vec3(1.5f, 0.f, 1.2f);
    lighting.shadowRadius = 4.f;
    renderer_.beginFrame(kWidth, kHeight, camera, lighting);
    SplitWorld w{world_, physics_, &renderer_};
    submitMeshes(w, &batches_);
    drawCalls = renderer_.endFrame().drawCalls;
    return testing::readFrame(renderer_, kWidth, kHeight);
  }

  std::unique_ptr<render::HeadlessGlContext> context_;
  render::Renderer renderer_;
  physics::PhysicsWorld physics_;
  ecs::World world_;
  StaticBatches batches_;
};

TEST_F(BatchScene, TwelveFrozenPiecesInASettledCellAreOneBatchAndLookTheSame) {
  addHeap();
  uint32_t single = 0, batched = 0;
  const std::vector<uint8_t> before = draw(single);
  EXPECT_EQ(single, 12u);  // twelve pieces of one submesh each
  for (uint64_t tick = 0; tick <= 30; ++tick) update(tick);
  EXPECT_EQ(batches_.stats().batches, 1u);
  EXPECT_EQ(batches_.stats().pieces, 12u);
  const std::vector<uint8_t> after = draw(batched);
  EXPECT_EQ(batched, 2u);  // one draw per material in use: blue and red (no piece shows its cap)
  const testing::ImageComparison same = testing::compareImages(before, after, kWidth, kHeight, {2, 0.002});
  EXPECT_TRUE(same.ok) << same.differingShare << " of the pixels differ, by up to " << same.largestDifference;
}

TEST_F(BatchScene, ACellIsBuiltOnlyWhenItHasSettledWithEnoughPieces) {
  std::vector<ecs::Entity> heap = addHeap();
  StaticBatchSettings s;
  s.minPieces = 13;
  batches_.setSettings(s);
  for (uint64_t tick = 0; tick <= 40; ++tick) update(tick);
  EXPECT_EQ(batches_.stats().batches, 0u) << "twelve pieces, thirteen needed";
  addFrozen(glm::vec3(2.f, 0.3f, 2.5f), 0.f, glm::vec4(1.f));  // the thirteenth, at tick 41
  for (uint64_t tick = 41; tick < 71; ++tick) update(tick);
  EXPECT_EQ(batches_.stats().batches, 0u) << "the cell changed at tick 41: it settles at 71";
  update(71);
  EXPECT_EQ(batches_.stats().batches, 1u);
  EXPECT_EQ(batches_.stats().pieces, 13u);
  for (ecs::Entity e : heap) EXPECT_TRUE(batches_.covers(e));
}

TEST_F(BatchScene, APieceThatThawsOrGoesDissolvesItsBatchInThatUpdate) {
  std::vector<ecs::Entity> heap = addHeap();
  for (uint64_t tick = 0; tick <= 30; ++tick) update(tick);
  ASSERT_EQ(batches_.stats().batches, 1u);
  world_.remove<Frozen>(heap[3]);  // thawed: it moves on its own from now on
  update(31);
  EXPECT_EQ(batches_.stats().batches, 0u);
  EXPECT_EQ(batches_.stats().dissolved, 1u);
  for (ecs::Entity e : heap) EXPECT_FALSE(batches_.covers(e));
  uint32_t draws = 0;
  draw(draws);
  EXPECT_EQ(draws, 12u);  // each piece on its own again
  for (uint64_t tick = 32; tick <= 61; ++tick) update(tick);
  EXPECT_EQ(batches_.stats().pieces, 11u) << "settled again without the thawed piece";
  world_.destroy(heap[7]);
  update(62);
  EXPECT_EQ(batches_.stats().batches, 0u);
  EXPECT_EQ(batches_.stats().dissolved, 2u);
}

// While batched, a piece's own GPU mesh holds no storage (the batch draws it); when the batch
// dissolves, every piece still there draws from its own mesh again, and the frame is the one drawn
// before any batch. release() gives the storage back too; release(Drop) leaves it to the world.
TEST_F(BatchScene, BatchedPiecesLendTheirMeshStorageAndGetItBackWhenTheBatchDissolves) {
  std::vector<ecs::Entity> heap = addHeap();
  auto resident = [&] {
    size_t n = 0;
    for (ecs::Entity e : heap)
      if (world_.alive(e)) n += renderer_.isResident(world_.get<MeshRenderer>(e).gpu);
    return n;
  };
  uint32_t draws = 0;
  const std::vector<uint8_t> single = draw(draws);
  for (uint64_t tick = 0; tick <= 30; ++tick) update(tick);
  ASSERT_EQ(batches_.stats().pieces, 12u);
  EXPECT_EQ(resident(), 0u);
  for (ecs::Entity e : heap) EXPECT_TRUE(renderer_.isValid(world_.get<MeshRenderer>(e).gpu)) << "the handle stays";
  world_.remove<Frozen>(heap[3]);
  update(31);
  EXPECT_EQ(resident(), 12u);
  EXPECT_EQ(batches_.stats().restored, 12u);
  const std::vector<uint8_t> again = draw(draws);
  EXPECT_EQ(draws, 12u);
  const testing::ImageComparison same = testing::compareImages(single, again, kWidth, kHeight, {0, 0.0});
  EXPECT_TRUE(same.ok) << same.differingShare << " of the pixels differ, by up to " << same.largestDifference;
  // Settled again without the thawed piece: eleven lend their storage; release() gives it back.
  for (uint64_t tick = 32; tick <= 61; ++tick) update(tick);
  ASSERT_EQ(batches_.stats().pieces, 11u);
  EXPECT_EQ(resident(), 1u);
  batches_.release();
  EXPECT_EQ(resident(), 12u);
  for (uint64_t tick = 62; tick <= 92; ++tick) update(tick);
  ASSERT_EQ(batches_.stats().pieces, 11u);
  batches_.release(PieceMeshes::Drop);  // the world is cleared next
  EXPECT_EQ(resident(), 1u);
}

TEST_F(BatchScene, ReleaseAndTheDestructorFreeTheBatchMeshes) {
  addHeap();
  const uint32_t pieces = renderer_.liveMeshCount();
  for (uint64_t tick = 0; tick <= 30; ++tick) update(tick);
  EXPECT_EQ(renderer_.liveMeshCount(), pieces + 1);
  batches_.release();
  EXPECT_EQ(renderer_.liveMeshCount(), pieces);
  {
    StaticBatches own;
    own.setRenderer(&renderer_);
    for (uint64_t tick = 0; tick <= 30; ++tick) own.update(world_, tick);
    EXPECT_EQ(renderer_.liveMeshCount(), pieces + 1);
  }
  EXPECT_EQ(renderer_.liveMeshCount(), pieces);
}

}  // namespace
}  // namespace cleave::components
