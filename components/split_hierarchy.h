// SPDX-License-Identifier: MIT
// Hierarchy jobs: one Splitable on a parent cuts the meshes of its whole subtree together (its
// descendants without a body of their own) and copies the hierarchy to each side. What a hierarchy
// adds to each stage, in the order of the stages:
//   prepare  gatherParts: the parts and their placement into the job;
//   compute  mergeHierarchyParts: one mesh to cut, in the parent entity's space, part after part
//            (part 0 is the parent's own mesh when it has one), material ids kept; after the cut,
//            each piece's provenance (SplitPiece::sourceTriangles) gives each part its triangles
//            back (extractPart, planHierarchyChildren), the caps going to the parent; no limit on
//            the number of parts or materials;
//   commit   hierarchyUnchanged: refuse if a part changed meanwhile; addHierarchyChildren.
// Internal to the components library.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "cleave/components/split_job.h"
#include "cleave/ecs/hierarchy.h"
#include "cleave/ecs/world.h"

namespace cleave::components {

struct PieceCommit;  // piece_kind.h

// Collects the entity's own mesh (if any) and the meshes of its descendants without a body of their
// own, each with its transform to the entity. False when no descendant has a mesh (the plain
// single-mesh path applies).
bool gatherParts(const ecs::World& world, ecs::Entity root, std::vector<HierarchyPartData>& parts);

// The parts merged into one mesh in the parent entity's space.
struct MergedParts {
  geometry::MeshData mesh;
  std::vector<uint32_t> firstTriangle;  // per part, its first triangle in `mesh`; then the total
  // The part a triangle of `mesh` comes from.
  uint32_t partOf(uint32_t triangle) const;
};
MergedParts mergeHierarchyParts(const std::vector<HierarchyPartData>& parts);

inline constexpr uint32_t kNoPart = ~0u;  // extractPart: no part's triangles, the caps only

// The triangles of the merged `piece` that come from part `part` (and the caps of this cut, for
// `withCaps`), by the piece's provenance.
geometry::MeshData extractPart(const geometry::MeshData& piece, std::span<const uint32_t> sourceTriangles,
                               const MergedParts& merged, uint32_t part, bool withCaps);

// The piece's children: each part but the parent's own, taken out of the cut `whole` (packed for
// the GPU when the job packs).
void planHierarchyChildren(const SplitJob& job, const MergedParts& merged, const geometry::MeshData& whole,
                           std::span<const uint32_t> sourceTriangles, PieceSpec& spec);

// Every part the job carries is still there, with the mesh it had and without a body of its own.
bool hierarchyUnchanged(const ecs::World& world, const SplitJob& job);

// The piece's child entities, one per child spec, parented to it and drawn in its frame.
void addHierarchyChildren(PieceCommit& c, const PieceSpec& spec, ecs::Entity e, const ecs::Transform& transform);

}  // namespace cleave::components
