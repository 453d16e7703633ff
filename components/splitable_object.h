// SPDX-License-Identifier: MIT
// A drawn, splitable object as the games and the examples make one: its name, transform, mesh and
// materials, and its Splitable, before it gets the body that suits it.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "cleave/components/scene_components.h"
#include "cleave/components/split_system.h"
#include "cleave/components/splitable.h"
#include "cleave/ecs/hierarchy.h"
#include "cleave/geometry/mesh_data.h"
#include "cleave/render/renderer.h"

namespace cleave::components {

struct SplitableObject {
  std::string name;
  ecs::Transform transform;  // its place (the entity's Transform; its WorldTransform is made from it)
  std::shared_ptr<const geometry::MeshData> mesh;  // shared: the split system keeps its weld
  std::vector<render::Material> materials;         // by submesh material id (the cap's included)
  Splitable splitable;
};

// Creates the entity with Name, Transform, WorldTransform, a MeshRenderer (the mesh uploaded when
// `w` has a renderer) and the Splitable. The body is the caller's, made next: makeDynamicBody for a
// prop, makeSkinnedBody for a character, none for something only drawn until it is cut.
ecs::Entity createSplitableObject(SplitWorld& w, SplitableObject object);

}  // namespace cleave::components
