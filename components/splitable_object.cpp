// SPDX-License-Identifier: MIT
#include "cleave/components/splitable_object.h"

namespace cleave::components {

ecs::Entity createSplitableObject(SplitWorld& w, SplitableObject object) {
  ecs::World& world = w.world;
  const ecs::Entity e = world.create();
  world.add<ecs::Name>(e, ecs::Name{std::move(object.name)});
  world.add<ecs::Transform>(e, object.transform);
  world.add<ecs::WorldTransform>(e, ecs::WorldTransform{ecs::localMatrix(object.transform)});
  MeshRenderer mr;
  mr.source = std::move(object.mesh);
  if (w.renderer && mr.source) mr.gpu = w.renderer->uploadMesh(*mr.source).valueOr({});
  mr.materials = std::move(object.materials);
  world.add<MeshRenderer>(e, std::move(mr));
  world.add<Splitable>(e, std::move(object.splitable));
  return e;
}

}  // namespace cleave::components
