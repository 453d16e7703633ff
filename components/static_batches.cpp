// SPDX-License-Identifier: MIT
// Static batches of frozen pieces (static_batches.h): dissolve what broke, count what waits, build
// what settled.
#include "cleave/components/static_batches.h"

#include <algorithm>
#include <cmath>

#include "cleave/components/piece_budget.h"
#include "cleave/components/scene_components.h"
#include "cleave/components/skinned.h"
#include "cleave/render/packed_mesh.h"

namespace cleave::components {

bool batchable(const ecs::World& world, ecs::Entity e) {
  if (!world.has<Frozen>(e) || world.has<SkinnedMesh>(e) || !world.has<ecs::WorldTransform>(e)) return false;
  const auto* mr = world.tryGet<MeshRenderer>(e);
  if (!mr || !mr->visible || !mr->gpu.valid() || !mr->source || mr->materials.empty()) return false;
  const render::Material& first = mr->materials.front();
  return first.castsShadow && first.shading != render::Shading::Checker;
}

namespace {

// One piece's packed mesh appended to the batch in world space: positions by `model`, normals by
// its inverse transpose, tangents by its rotation part (handedness kept); its triangles go to the
// index list of each submesh's material in the batch.
void appendPiece(const render::PackedMesh& piece, const glm::mat4& model, const std::vector<uint32_t>& materialOf,
                 render::PackedMesh& batch, std::vector<std::vector<uint32_t>>& indicesByMaterial) {
  const glm::mat3 linear(model);
  const glm::mat3 normalMatrix = glm::transpose(glm::inverse(linear));
  const uint32_t base = uint32_t(batch.vertexCount());
  const bool mirrored = glm::determinant(linear) < 0.f;
  for (size_t v = 0; v < piece.vertexCount(); ++v) {
    const float* in = &piece.vertices[v * 12];
    const glm::vec3 p = glm::vec3(model * glm::vec4(in[0], in[1], in[2], 1.f));
    const glm::vec3 n = glm::normalize(normalMatrix * glm::vec3(in[3], in[4], in[5]));
    const glm::vec3 t = linear * glm::vec3(in[8], in[9], in[10]);
    const float tl = glm::length(t);
    const glm::vec3 tn = tl > 0.f ? t / tl : glm::vec3(1.f, 0.f, 0.f);
    batch.vertices.insert(batch.vertices.end(), {p.x, p.y, p.z, n.x, n.y, n.z, in[6], in[7], tn.x, tn.y, tn.z, in[11]});
  }
  for (const geometry::SubMesh& s : piece.submeshes) {
    const uint32_t material = materialOf[std::min<size_t>(s.materialId, materialOf.size() - 1)];
    std::vector<uint32_t>& out = indicesByMaterial[material];
    for (uint32_t i = 0; i < s.indexCount; i += 3) {
      const uint32_t* tri = &piece.indices[s.firstIndex + i];
      // A mirroring model turns the winding inside out: put it back, so culling keeps the outside.
      if (mirrored) {
        out.insert(out.end(), {base + tri[0], base + tri[2], base + tri[1]});
      } else {
        out.insert(out.end(), {base + tri[0], base + tri[1], base + tri[2]});
      }
    }
  }
}

// The batch's material list grows by the piece's materials not in it yet; returns, per material of
// the piece, its index in the batch's list.
std::vector<uint32_t> mergeMaterials(const std::vector<render::Material>& own, std::vector<render::Material>& batch) {
  std::vector<uint32_t> index(own.size());
  for (size_t m = 0; m < own.size(); ++m) {
    auto found = std::find(batch.begin(), batch.end(), own[m]);
    if (found == batch.end()) found = batch.insert(batch.end(), own[m]);
    index[m] = uint32_t(found - batch.begin());
  }
  return index;
}

}  // namespace

StaticBatches::~StaticBatches() { release(); }

void StaticBatches::setRenderer(render::Renderer* renderer) {
  release();
  renderer_ = renderer;
}

void StaticBatches::setSettings(const StaticBatchSettings& settings) {
  const bool rebuild = !settings.enabled || settings.cellSize != settings_.cellSize;
  settings_ = settings;
  if (rebuild) release();
}

void StaticBatches::release(PieceMeshes pieces) {
  for (auto& [key, cell] : cells_) dissolve(cell, pieces);
  cells_.clear();
  coveredBy_.clear();
  stats_.batches = stats_.pieces = 0;
}

StaticBatches::CellKey StaticBatches::cellOf(const ecs::World& world, ecs::Entity e) const {
  const glm::vec4 at = world.get<ecs::WorldTransform>(e).matrix[3];
  return {int32_t(std::floor(at.x / settings_.cellSize)), int32_t(std::floor(at.z / settings_.cellSize))};
}

void StaticBatches::update(ecs::World& world, uint64_t tick) {
  if (!renderer_ || !settings_.enabled) return;
  world_ = &world;
  tick_ = tick;
  dissolveBroken(world);
  countWaiting(world);
  buildSettled(world);
}

// The batch's pieces still there, with the mesh they had when merged, get their storage back
// (but those in `except`, merged again at once).
void StaticBatches::restorePieces(const Batch& b, const std::vector<ecs::Entity>& except) {
  if (!renderer_ || !world_) return;
  for (size_t i = 0; i < b.pieces.size(); ++i) {
    const ecs::Entity e = b.pieces[i];
    if (std::find(except.begin(), except.end(), e) != except.end()) continue;
    const auto* mr = world_->alive(e) ? world_->tryGet<MeshRenderer>(e) : nullptr;
    if (!mr || !mr->source || mr->gpu != b.pieceMeshes[i] || renderer_->isResident(mr->gpu)) continue;
    if (renderer_->restoreMesh(mr->gpu, render::packMesh(*mr->source)).ok()) stats_.restored++;
  }
}

void StaticBatches::dissolve(Cell& cell, PieceMeshes pieces) {
  Batch& b = cell.batch;
  if (!b.gpu.valid()) return;
  if (pieces == PieceMeshes::Restore) restorePieces(b);
  if (renderer_) renderer_->destroyMesh(b.gpu);
  for (ecs::Entity e : b.pieces)
    if (covers(e)) coveredBy_[e.index] = ecs::kNullEntity;
  stats_.batches--;
  stats_.pieces -= uint32_t(b.pieces.size());
  b = Batch{};
  cell.changedTick = tick_;
}

// A batch whose piece thawed, faded, went or changed mesh no longer draws what is there.
void StaticBatches::dissolveBroken(const ecs::World& world) {
  for (auto& [key, cell] : cells_) {
    const Batch& b = cell.batch;
    if (!b.gpu.valid()) continue;
    for (size_t i = 0; i < b.pieces.size(); ++i) {
      const ecs::Entity e = b.pieces[i];
      const auto* mr = world.alive(e) ? world.tryGet<MeshRenderer>(e) : nullptr;
      if (!mr || !batchable(world, e) || mr->gpu != b.pieceMeshes[i]) {
        dissolve(cell);
        stats_.dissolved++;
        break;
      }
    }
  }
}

// Frozen pieces outside any batch, by cell; a cell whose count changed starts settling again.
void StaticBatches::countWaiting(ecs::World& world) {
  std::map<CellKey, uint32_t> waiting;
  for (auto [e, frozen] : world.view<Frozen>())
    if (!covers(e) && batchable(world, e)) waiting[cellOf(world, e)]++;
  for (auto it = cells_.begin(); it != cells_.end();) {
    const auto found = waiting.find(it->first);
    const uint32_t now = found == waiting.end() ? 0 : found->second;
    if (now != it->second.waiting) it->second.changedTick = tick_;
    it->second.waiting = now;
    it = now == 0 && !it->second.batch.gpu.valid() ? cells_.erase(it) : std::next(it);
  }
  for (const auto& [key, count] : waiting) {
    if (cells_.count(key)) continue;
    cells_[key] = Cell{Batch{}, count, tick_};
  }
}

void StaticBatches::buildSettled(ecs::World& world) {
  uint32_t built = 0;
  for (auto& [key, cell] : cells_) {
    if (built >= settings_.buildsPerUpdate) break;
    if (cell.waiting == 0 || tick_ - cell.changedTick < settings_.settleTicks) continue;
    if (cell.waiting + cell.batch.pieces.size() < settings_.minPieces) continue;
    build(world, key, cell);
    ++built;
  }
}

// Every batchable piece of the cell (those of its old batch too), in entity order, merged.
void StaticBatches::build(ecs::World& world, const CellKey& key, Cell& cell) {
  std::vector<ecs::Entity> pieces;
  for (auto [e, frozen] : world.view<Frozen>())
    if (batchable(world, e) && cellOf(world, e) == key) pieces.push_back(e);
  std::sort(pieces.begin(), pieces.end(), [](ecs::Entity a, ecs::Entity b) { return a.index < b.index; });
  Batch b;
  render::PackedMesh merged;
  std::vector<std::vector<uint32_t>> indicesByMaterial;
  for (ecs::Entity e : pieces) {
    const MeshRenderer& mr = world.get<MeshRenderer>(e);
    const render::PackedMesh packed = render::packMesh(*mr.source);
    if (!packed.ok()) continue;  // drawn one by one, as it was
    const std::vector<uint32_t> materialOf = mergeMaterials(mr.materials, b.materials);
    indicesByMaterial.resize(b.materials.size());
    appendPiece(packed, world.get<ecs::WorldTransform>(e).matrix * mr.meshOffset, materialOf, merged, indicesByMaterial);
    b.pieces.push_back(e);
    b.pieceMeshes.push_back(mr.gpu);
    const auto* info = world.tryGet<MassInfo>(e);
    b.closed = b.closed && info && info->closed;
  }
  for (uint32_t m = 0; m < indicesByMaterial.size(); ++m) {
    if (indicesByMaterial[m].empty()) continue;
    merged.submeshes.push_back({uint32_t(merged.indices.size()), uint32_t(indicesByMaterial[m].size()), m});
    merged.indices.insert(merged.indices.end(), indicesByMaterial[m].begin(), indicesByMaterial[m].end());
  }
  // The old batch's pieces merged again keep their storage evicted; any other gets it back.
  auto gpu = b.pieces.empty() ? base::Expected<render::MeshHandle>::failure(base::StatusCode::InvalidArgument, "")
                              : renderer_->uploadPacked(merged);
  restorePieces(cell.batch, gpu.ok() ? b.pieces : std::vector<ecs::Entity>{});
  dissolve(cell, PieceMeshes::Drop);
  cell.waiting = 0;
  if (!gpu.ok()) return;
  b.gpu = gpu.value();
  for (size_t i = 0; i < b.pieces.size(); ++i) {
    const ecs::Entity e = b.pieces[i];
    if (coveredBy_.size() <= e.index) coveredBy_.resize(e.index + 1, ecs::kNullEntity);
    coveredBy_[e.index] = e;
    renderer_->evictMesh(b.pieceMeshes[i]);
  }
  stats_.batches++;
  stats_.pieces += uint32_t(b.pieces.size());
  stats_.builds++;
  cell.batch = std::move(b);
  cell.changedTick = tick_;
}

void StaticBatches::submit() const {
  if (!renderer_) return;
  for (const auto& [key, cell] : cells_)
    if (cell.batch.gpu.valid()) renderer_->submit(cell.batch.gpu, glm::mat4(1.f), cell.batch.materials, cell.batch.closed);
}

}  // namespace cleave::components
