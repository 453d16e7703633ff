// SPDX-License-Identifier: MIT
// CommandBuffer: structural changes recorded during iteration, carried out by World::apply().
//
//   CommandBuffer commands(world);
//   for (auto [e, health] : world.view<Health>())
//     if (health.value <= 0) commands.destroy(e);
//   Entity piece = commands.create();          // a real id, usable in later commands at once
//   commands.add(piece, Transform{});
//   world.apply(commands);                     // after the loop
//
// create() reserves the id immediately (safe during iteration: it touches no component pool), so
// the id can be stored inside other components (e.g. Parent{piece}) before the buffer is applied.
// A reserved id is not alive() until apply(). Commands run in recording order; a command whose
// entity is not alive when it runs (destroyed twice, stale, destroyed by an earlier command) is
// skipped and counted in ApplyResult::skipped, never an error.
//
// Ownership: the buffer refers to its World, which must outlive it. Destroying or clear()ing a
// buffer that was not applied returns its reserved ids to the World (they become stale).
// Not thread-safe.
#pragma once

#include <cstddef>
#include <functional>
#include <utility>
#include <vector>

#include "cleave/ecs/entity.h"
#include "cleave/ecs/world.h"

namespace cleave::ecs {

class CommandBuffer {
 public:
  explicit CommandBuffer(World& world) : world_(&world) {}
  ~CommandBuffer() { clear(); }
  CommandBuffer(const CommandBuffer&) = delete;
  CommandBuffer& operator=(const CommandBuffer&) = delete;

  // Reserves a new entity; it becomes alive when the buffer is applied.
  Entity create();

  // Destroys the entity (and its components) at apply time.
  void destroy(Entity entity) { commands_.push_back({Kind::Destroy, entity, {}}); }

  // Destroys the entity and its Children subtree at apply time (hierarchy.h destroyRecursive).
  void destroyRecursive(Entity entity) {
    commands_.push_back({Kind::DestroyRecursive, entity, {}});
  }

  // Adds (or overwrites) a component at apply time.
  template <class T>
  void add(Entity entity, T value) {
    // Each command runs once, so the stored value can be moved into the World.
    commands_.push_back({Kind::Edit, entity,
                         [value = std::move(value)](World& world, Entity e) mutable {
                           world.add<T>(e, std::move(value));
                         }});
  }

  // Removes a component at apply time (no effect if the entity has none).
  template <class T>
  void remove(Entity entity) {
    commands_.push_back(
        {Kind::Edit, entity, [](World& world, Entity e) { world.remove<T>(e); }});
  }

  size_t size() const { return commands_.size(); }
  bool empty() const { return commands_.empty(); }

  // Drops all commands; reserved ids go back to the World.
  void clear();

 private:
  friend class World;
  enum class Kind { Create, Destroy, DestroyRecursive, Edit };
  struct Command {
    Kind kind;
    Entity entity;
    std::function<void(World&, Entity)> edit;  // only for Kind::Edit
  };

  World* world_;
  std::vector<Command> commands_;
};

}  // namespace cleave::ecs
