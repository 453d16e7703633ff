// SPDX-License-Identifier: MIT
// What is known of meshes by the split system (mesh_knowledge.h).
#include "cleave/components/mesh_knowledge.h"

#include <algorithm>

namespace cleave::components {

const MeshKnowledge::Entry* MeshKnowledge::find(const std::shared_ptr<const geometry::MeshData>& mesh) const {
  const auto it = entries_.find(mesh.get());
  if (it == entries_.end() || it->second.mesh.lock() != mesh) return nullptr;
  return &it->second;
}

MeshKnowledge::Entry& MeshKnowledge::remember(const std::shared_ptr<const geometry::MeshData>& mesh) {
  if (entries_.size() >= prunedAt_) {
    std::erase_if(entries_, [](const auto& e) { return e.second.mesh.expired(); });
    prunedAt_ = std::max<size_t>(64, 2 * entries_.size());
  }
  Entry& e = entries_[mesh.get()];
  if (e.mesh.lock() != mesh) e = Entry{mesh, nullptr, nullptr};
  return e;
}

}  // namespace cleave::components
