// SPDX-License-Identifier: MIT
// Hierarchy jobs (split_hierarchy.h): gathering a subtree's meshes, merging them for the cut, taking
// the pieces apart into parts again, and the pieces' child entities.
#include "cleave/components/split_hierarchy.h"

#include <algorithm>

#include "cleave/components/piece_kind.h"
#include "cleave/components/split_clock.h"
#include "cleave/components/split_system.h"
#include "cleave/geometry/mesh_container.h"
#include "cleave/geometry/primitives.h"

namespace cleave::components {

// Collects the target's own mesh (if any) and the meshes of its descendants (those without a body
// of their own). Returns false when the subtree has no descendant with a mesh (the plain
// single-mesh path applies).
bool gatherParts(const ecs::World& world, ecs::Entity root, std::vector<HierarchyPartData>& parts) {
  parts.clear();
  auto add = [&](ecs::Entity e, const MeshRenderer& mr, const glm::dmat4& toParent) {
    HierarchyPartData part;
    part.entity = e;
    part.mesh = mr.source;
    part.toParent = toParent * glm::dmat4(mr.meshOffset);
    part.materials = mr.materials;
    part.visible = mr.visible;
    if (const auto* n = world.tryGet<ecs::Name>(e)) part.name = n->value;
    parts.push_back(std::move(part));
  };
  if (const auto* mr = world.tryGet<MeshRenderer>(root); mr && mr->source) add(root, *mr, glm::dmat4(1.0));
  const size_t own = parts.size();
  struct Item {
    ecs::Entity entity;
    glm::dmat4 toParent;
    int depth;
  };
  std::vector<Item> stack;
  if (const auto* children = world.tryGet<ecs::Children>(root))
    for (auto it = children->entities.rbegin(); it != children->entities.rend(); ++it)
      stack.push_back({*it, glm::dmat4(1.0), 1});
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    if (!world.alive(item.entity) || item.depth > 64) continue;
    if (ecs::parentOf(world, item.entity) == ecs::kNullEntity) continue;
    if (world.has<RigidBody>(item.entity)) continue;  // a body of its own: an object of its own
    const auto* t = world.tryGet<ecs::Transform>(item.entity);
    const glm::dmat4 toParent = item.toParent * (t ? glm::dmat4(ecs::localMatrix(*t)) : glm::dmat4(1.0));
    if (const auto* mr = world.tryGet<MeshRenderer>(item.entity); mr && mr->source) add(item.entity, *mr, toParent);
    if (const auto* children = world.tryGet<ecs::Children>(item.entity))
      for (auto it = children->entities.rbegin(); it != children->entities.rend(); ++it)
        stack.push_back({*it, toParent, item.depth + 1});
  }
  return parts.size() > own;
}

uint32_t MergedParts::partOf(uint32_t triangle) const {
  const auto it = std::upper_bound(firstTriangle.begin(), firstTriangle.end(), triangle);
  return static_cast<uint32_t>(it - firstTriangle.begin()) - 1;
}

MergedParts mergeHierarchyParts(const std::vector<HierarchyPartData>& parts) {
  MergedParts merged;
  for (size_t k = 0; k < parts.size(); ++k) {
    geometry::MeshData part = *parts[k].mesh;
    geometry::primitives::transform(part, glm::mat4(parts[k].toParent));
    if (part.submeshes.empty()) part.submeshes.push_back({0, uint32_t(part.indices.size()), 0});
    merged.firstTriangle.push_back(static_cast<uint32_t>(merged.mesh.triangleCount()));
    merged.mesh = merged.mesh.positions.empty() ? std::move(part) : geometry::primitives::merge(merged.mesh, part);
  }
  merged.firstTriangle.push_back(static_cast<uint32_t>(merged.mesh.triangleCount()));
  return merged;
}

geometry::MeshData extractPart(const geometry::MeshData& piece, std::span<const uint32_t> sourceTriangles,
                               const MergedParts& merged, uint32_t part, bool withCaps) {
  std::vector<uint32_t> triangles;
  for (uint32_t t = 0; t < sourceTriangles.size(); ++t) {
    const uint32_t source = sourceTriangles[t];
    const bool cap = (source & geometry::kFromCap) != 0;
    if (cap ? withCaps : merged.partOf(source) == part) triangles.push_back(t);
  }
  geometry::MeshData out;
  if (triangles.empty()) return out;
  geometry::MeshContainer container;
  if (!container.setMesh(piece).ok()) return out;
  container.extractTriangles(triangles, out);
  return out;
}

void planHierarchyChildren(const SplitJob& job, const MergedParts& merged, const geometry::MeshData& whole,
                           std::span<const uint32_t> sourceTriangles, PieceSpec& spec) {
  for (size_t part = 0; part < job.hierarchyParts.size(); ++part) {
    if (job.hierarchyParts[part].entity == job.request.target) continue;
    geometry::MeshData child = extractPart(whole, sourceTriangles, merged, uint32_t(part), false);
    if (child.indices.empty()) continue;
    auto mesh = std::make_shared<geometry::MeshData>(std::move(child));
    std::shared_ptr<const render::PackedMesh> packed;
    if (job.packForGpu) packed = std::make_shared<render::PackedMesh>(render::packMesh(*mesh));
    const geometry::MeshData* from = packed ? mesh.get() : nullptr;
    spec.children.push_back({part, std::move(mesh), std::move(packed), from});
  }
}

bool hierarchyUnchanged(const ecs::World& world, const SplitJob& job) {
  for (const HierarchyPartData& part : job.hierarchyParts) {
    const auto* mr = world.tryGet<MeshRenderer>(part.entity);
    const bool same = world.alive(part.entity) && mr && mr->source == part.mesh &&
                      (part.entity == job.request.target || !world.has<RigidBody>(part.entity));
    if (!same) return false;
  }
  return true;
}

void addHierarchyChildren(PieceCommit& c, const PieceSpec& spec, ecs::Entity e, const ecs::Transform& transform) {
  std::vector<ecs::Entity> children;
  const size_t slash = spec.name.rfind('/');
  const std::string suffix = slash == std::string::npos ? std::string() : spec.name.substr(slash);
  for (const HierarchyChildSpec& childSpec : spec.children) {
    const HierarchyPartData& part = c.job.hierarchyParts[childSpec.part];
    const ecs::Entity child = c.commands.create();
    MeshRenderer renderer;
    renderer.source = childSpec.mesh;
    renderer.materials = part.materials;
    renderer.meshOffset = glm::mat4(spec.frame.meshOffset);  // merged space -> the piece's frame
    renderer.visible = part.visible;
    if (c.w.renderer) {
      const double uploadStart = nowMilliseconds();
      renderer.gpu = childSpec.packed && childSpec.packedFrom == childSpec.mesh.get()
                         ? c.w.renderer->uploadPacked(*childSpec.packed).valueOr({})
                         : c.w.renderer->uploadMesh(*childSpec.mesh).valueOr({});
      c.ev.times.uploads += nowMilliseconds() - uploadStart;
    }
    c.commands.add<ecs::Transform>(child, ecs::Transform{});
    c.commands.add<ecs::WorldTransform>(child, ecs::WorldTransform{ecs::localMatrix(transform)});
    c.commands.add<ecs::Name>(child, ecs::Name{(part.name.empty() ? std::string("part") : part.name) + suffix});
    c.commands.add<ecs::Parent>(child, ecs::Parent{e});
    c.commands.add<MeshRenderer>(child, std::move(renderer));
    children.push_back(child);
  }
  c.commands.add<ecs::Children>(e, ecs::Children{std::move(children)});
}

}  // namespace cleave::components
