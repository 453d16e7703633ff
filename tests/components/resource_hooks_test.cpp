// SPDX-License-Identifier: MIT
// ResourceHooks: removing a component or destroying its entity frees what it holds in the physics
// world (bodies with their joints, shapes, triggers); without the hooks nothing is freed.
#include "cleave/components/resource_hooks.h"

#include <gtest/gtest.h>

#include "cleave/components/scene_components.h"
#include "cleave/components/split_system.h"
#include "cleave/components/splitable.h"

namespace cleave::components {
namespace {

RigidBody addBox(ecs::World& world, physics::PhysicsWorld& physics, ecs::Entity e, glm::vec3 at) {
  const physics::ShapeId shape = physics.createShape(physics::ShapeDef::box(glm::vec3(0.5f))).value();
  physics::BodyDef def;
  def.shape = shape;
  def.mass = 1.0f;
  def.position = at;
  const RigidBody rb{physics.createBody(def).value(), shape};
  world.add<RigidBody>(e, rb);
  return rb;
}

TEST(ResourceHooks, RemovingARigidBodyFreesItsBodyShapeAndJoints) {
  ecs::World world;
  physics::PhysicsWorld physics;
  ResourceHooks hooks(world, physics, nullptr);
  const ecs::Entity a = world.create();
  const ecs::Entity b = world.create();
  const RigidBody ra = addBox(world, physics, a, glm::vec3(0.f));
  addBox(world, physics, b, glm::vec3(1.f, 0.f, 0.f));
  physics::JointDef joint;
  joint.bodyA = ra.body;
  joint.bodyB = world.get<RigidBody>(b).body;
  ASSERT_TRUE(physics.createJoint(joint).ok());
  ASSERT_EQ(countResources(&physics, nullptr), (ResourceCounts{2, 2, 1, 0, 0}));
  EXPECT_TRUE(world.remove<RigidBody>(a));
  EXPECT_TRUE(world.alive(a));
  EXPECT_FALSE(physics.isValid(ra.body));
  EXPECT_EQ(countResources(&physics, nullptr), (ResourceCounts{1, 1, 0, 0, 0}));
  world.destroy(b);
  EXPECT_EQ(countResources(&physics, nullptr), ResourceCounts{});
}

TEST(ResourceHooks, DestroyingASplitterFreesItsTrigger) {
  ecs::World world;
  physics::PhysicsWorld physics;
  ResourceHooks hooks(world, physics, nullptr);
  SplitWorld w{world, physics, nullptr};
  const ecs::Entity blade =
      createSplitter(w, "blade", physics::ShapeDef::box(glm::vec3(1.f, 0.01f, 1.f)), glm::vec3(0.f), glm::quat(1, 0, 0, 0), {});
  ASSERT_TRUE(world.alive(blade));
  EXPECT_EQ(countResources(&physics, nullptr), (ResourceCounts{0, 1, 0, 1, 0}));
  world.destroy(blade);
  EXPECT_EQ(countResources(&physics, nullptr), ResourceCounts{});
}

TEST(ResourceHooks, WithoutTheHooksNothingIsFreed) {
  ecs::World world;
  physics::PhysicsWorld physics;
  const ecs::Entity e = world.create();
  {
    ResourceHooks hooks(world, physics, nullptr);
    addBox(world, physics, e, glm::vec3(0.f));
  }  // hooks removed
  world.destroy(e);
  EXPECT_EQ(countResources(&physics, nullptr), (ResourceCounts{1, 1, 0, 0, 0}));
  EXPECT_EQ(toString(countResources(&physics, nullptr)), "bodies=1 shapes=1 joints=0 triggers=0 gpu_meshes=0");
}

}  // namespace
}  // namespace cleave::components
