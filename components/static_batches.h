// SPDX-License-Identifier: MIT
// StaticBatches: frozen pieces drawn as one mesh per region, so that the draw calls stop growing
// with every cut. A session of cutting leaves a thousand or more frozen pieces (piece_budget.h);
// each was one draw (one per material), and on a software rasterizer the draws, not the pixels,
// were most of a frame's time.
//
// The ground (x, z) is divided into square cells of `cellSize` metres. Once a cell holds at least
// `minPieces` frozen pieces and the set of them has not changed for `settleTicks` ticks, the
// pieces are merged into one GPU mesh in world space, one submesh per distinct material, and drawn
// with it instead of one by one. A batch is dissolved the frame any of its pieces thaws, fades, is
// cut, goes or changes mesh: its pieces are drawn one by one again until the cell settles anew.
// At most `buildsPerUpdate` cells are built in an update (lowest cell first).
//
// It is a drawing cache only: it reads the world and never changes it, so the simulation and its
// state hash are the same with it on or off. Pieces skinned, invisible, or whose first material
// casts no shadow or is a checker (the shadow pass reads a draw's first material) stay single.
//
// Memory: while a piece is drawn by a batch its own GPU mesh is evicted (Renderer::evictMesh: the
// handle stays, the vertex storage goes; on a software rasterizer that storage is process memory,
// and a session's thousand frozen pieces would otherwise be held twice). When the batch dissolves,
// each of its pieces still there gets its storage back, packed again from its MeshRenderer::source.
//
// Ownership: the batches' GPU meshes belong to this object; they are freed when a batch dissolves,
// by release(), by setRenderer() (on the old renderer) and by the destructor. The renderer must
// outlive the batches or be taken away with setRenderer(nullptr) first, and the world given to
// update() must outlive them (a Simulation's does).
#pragma once

#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "cleave/ecs/world.h"
#include "cleave/render/renderer.h"

namespace cleave::components {

struct StaticBatchSettings {
  bool enabled = true;
  float cellSize = 8.0f;         // m, square cells on the ground plane
  uint32_t minPieces = 8;        // fewer frozen pieces in a cell are drawn one by one
  uint32_t settleTicks = 30;     // the cell's frozen set unchanged this long before it is built
  uint32_t buildsPerUpdate = 1;
};

struct StaticBatchStats {
  uint32_t batches = 0;      // built now
  uint32_t pieces = 0;       // frozen pieces drawn through a batch now
  uint64_t builds = 0;       // over the run
  uint64_t dissolved = 0;    // batches dissolved over the run
  uint64_t restored = 0;     // pieces given their own mesh back when their batch dissolved, over the run
};

// What release() does with the batched pieces' own meshes: give them back (the pieces are drawn one
// by one from now on), or leave them evicted because the world is about to be cleared (its entities'
// meshes are destroyed with them, evicted or not).
enum class PieceMeshes { Restore, Drop };

class StaticBatches {
 public:
  StaticBatches() = default;
  ~StaticBatches();
  StaticBatches(const StaticBatches&) = delete;
  StaticBatches& operator=(const StaticBatches&) = delete;

  void setRenderer(render::Renderer* renderer);  // frees the batches held on the old one
  void setSettings(const StaticBatchSettings& settings);  // turning it off frees the batches
  const StaticBatchSettings& settings() const { return settings_; }
  const StaticBatchStats& stats() const { return stats_; }

  // Once a frame before drawing, at the game's `tick`: dissolves broken batches, builds settled
  // cells. It reads the world only (its views need it mutable).
  void update(ecs::World& world, uint64_t tick);
  // The piece is drawn by a batch (submitMeshes skips it).
  bool covers(ecs::Entity e) const { return e.index < coveredBy_.size() && coveredBy_[e.index] == e; }
  // Submits every built batch to the renderer (between its beginFrame and endFrame).
  void submit() const;
  // Frees every batch (batching turned off, a level unloading, a game releasing its world).
  void release(PieceMeshes pieces = PieceMeshes::Restore);

 private:
  using CellKey = std::pair<int32_t, int32_t>;
  struct Batch {
    std::vector<ecs::Entity> pieces;
    std::vector<render::MeshHandle> pieceMeshes;  // each piece's own mesh when it was merged
    render::MeshHandle gpu;
    std::vector<render::Material> materials;
    bool closed = true;  // every piece in it is closed: back faces culled
  };
  struct Cell {
    Batch batch;
    uint32_t waiting = 0;        // frozen pieces in the cell outside its batch, last frame
    uint64_t changedTick = 0;    // when `waiting` last changed
  };

  CellKey cellOf(const ecs::World& world, ecs::Entity e) const;
  void dissolveBroken(const ecs::World& world);
  void countWaiting(ecs::World& world);
  void buildSettled(ecs::World& world);
  void build(ecs::World& world, const CellKey& key, Cell& cell);
  void dissolve(Cell& cell, PieceMeshes pieces = PieceMeshes::Restore);
  void restorePieces(const Batch& batch, const std::vector<ecs::Entity>& except = {});

  render::Renderer* renderer_ = nullptr;
  ecs::World* world_ = nullptr;  // the world of the last update: its pieces' meshes are restored
  StaticBatchSettings settings_;
  StaticBatchStats stats_;
  std::map<CellKey, Cell> cells_;
  std::vector<ecs::Entity> coveredBy_;  // by entity index: the entity a batch draws there
  uint64_t tick_ = 0;
};

// A piece the batches may draw: frozen, visible, not skinned, first material casting a shadow.
bool batchable(const ecs::World& world, ecs::Entity e);

}  // namespace cleave::components
