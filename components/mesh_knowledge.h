// SPDX-License-Identifier: MIT
// MeshKnowledge: what the split system knows of the meshes it has cut or made, by mesh: its weld
// (position ids, closedness) and its collider parts. A mesh cut again (every piece, and an authored
// mesh that many objects share) is neither welded nor decomposed again.
//
// Who writes: prepare reads an entry into the job; commit writes what the compute worked out for the
// source (SplitOutcome::sourceWeld, sourceParts) and what each piece carries (PieceSpec::weld,
// parts); colliderParts() fills it for an authored mesh when its body is made; the cost model reads
// the parts. Threads: the main thread only (jobs carry shared, immutable copies to the workers).
// Lifetime: an entry is valid while its mesh lives (a weak pointer to it); entries of meshes that
// are gone are dropped when the table grows.
#pragma once

#include <cstddef>
#include <memory>
#include <unordered_map>

#include "cleave/geometry/collider_parts.h"
#include "cleave/geometry/mesh_data.h"
#include "cleave/geometry/split_types.h"

namespace cleave::components {

class MeshKnowledge {
 public:
  struct Entry {
    std::weak_ptr<const geometry::MeshData> mesh;
    std::shared_ptr<const geometry::MeshWeld> weld;  // null: not known
    geometry::SharedColliderParts parts;              // null: not known
  };

  // What is known of `mesh`, or null (nothing known, or its entry was for an earlier mesh at the
  // same address).
  const Entry* find(const std::shared_ptr<const geometry::MeshData>& mesh) const;
  // The entry of `mesh` to fill, made empty when new.
  Entry& remember(const std::shared_ptr<const geometry::MeshData>& mesh);
  size_t size() const { return entries_.size(); }

 private:
  std::unordered_map<const geometry::MeshData*, Entry> entries_;
  size_t prunedAt_ = 64;
};

}  // namespace cleave::components
