// SPDX-License-Identifier: MIT
// World: the entity registry and the component storage of one simulation.
//
// Entities are generational ids (entity.h). Components are plain structs stored by value in one
// sparse set per type (component_pool.h); a component type must be default-constructible and
// movable. An entity has at most one component of each type.
//
// Failure model: stale or null entities are never an error for queries (alive, has, tryGet return
// false / nullptr; destroy and remove return false). Calls with a precondition (add to a dead
// entity, get of a missing component, structural changes while a View exists, a CommandBuffer of
// another World) assert in debug builds; in release builds they leave the World unchanged (add and
// get then return a scratch value that is not stored).
//
// Determinism: ids are reused from a FIFO free list, so the same sequence of calls gives the same
// ids; entities() is ascending by index; views follow the documented dense order. Not thread-safe.
//
// Destroy hooks (onDestroy): a callback registered for a component type runs whenever a component
// of that type goes away with remove<T>, destroy, clear, or a CommandBuffer's destroy or remove at
// apply time; this is how an entity owns what its components hold (a physics body, a GPU mesh):
// nobody has to remember to free it. Overwriting a component with add<T> is not a removal and runs
// no hook (the caller replaces the value and owns what the old one held). Dropping the World runs
// no hook either: what the components refer to may be gone by then (call clear() first to free it).
#pragma once

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "cleave/ecs/component_pool.h"
#include "cleave/ecs/entity.h"
#include "cleave/ecs/view.h"

namespace cleave::ecs {

class CommandBuffer;

// What World::apply did: commands carried out, and commands skipped because their entity was not
// alive any more (e.g. destroyed twice, or by an earlier command of the same buffer).
struct ApplyResult {
  size_t applied = 0;
  size_t skipped = 0;
};

class World {
 public:
  World() = default;
  ~World();
  // A World is referred to by views and command buffers; it does not move.
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  // New entity without components. Reuses the oldest freed slot (FIFO) with its generation bumped.
  // Precondition: no View exists.
  Entity create();

  // Removes the entity and all its components; false (and no change) if it is not alive or is
  // being destroyed already (a hook destroying its own entity). The destroy hooks run first, type
  // by type in the order the types got their first hook; while they run the entity is still alive
  // and keeps the components whose hooks have not run yet (components a hook adds to it are
  // dropped with it). Does not touch other entities (see hierarchy.h destroyRecursive for subtrees)
  // unless a hook does. Precondition: no View exists.
  bool destroy(Entity entity);

  // Destroys every live entity, ascending by index, with their hooks; entities a hook creates
  // meanwhile are destroyed too (up to 64 passes). Ids stay stale as after destroy. Returns the
  // number destroyed. Precondition: no View exists.
  size_t clear();

  // Registers `hook`, run with the component's last value (no longer stored: has<T> is false) each
  // time a T leaves an entity (see the header comment). Hooks of one type run in registration
  // order. Returns an id for removeHook; 0 (nothing registered) for an empty function or when
  // called from inside a hook. A hook may destroy or change other entities and remove other
  // components of its own entity; it must not register or remove hooks.
  template <class T>
  HookId onDestroy(std::function<void(World&, Entity, T&)> hook) {
    assert(hookDepth_ == 0 && "destroy hooks are registered outside hooks");
    if (hookDepth_ != 0 || !hook) return 0;
    const HookId id = ++lastHookId_;
    const detail::ComponentTypeId type = detail::componentTypeId<T>();
    poolFor<T>().addHook(id, std::move(hook));
    if (std::find(hookOrder_.begin(), hookOrder_.end(), type) == hookOrder_.end()) hookOrder_.push_back(type);
    hookTypes_.emplace_back(id, type);
    return id;
  }

  // Removes a hook; false for an id that is not registered (or when called from inside a hook).
  bool removeHook(HookId id);

  // True for an entity created by this World and not destroyed since. False for kNullEntity, stale
  // ids, and ids reserved by a CommandBuffer that has not been applied yet.
  bool alive(Entity entity) const;

  size_t size() const { return aliveCount_; }  // number of live entities

  // Number of slots ever used; every entity index is below it (for per-index scratch arrays).
  uint32_t slotCount() const { return static_cast<uint32_t>(slots_.size()); }

  // All live entities, ascending by index (the order for state dumps and stable processing).
  std::vector<Entity> entities() const;

  // Adds the component, or overwrites the one the entity already has; returns the stored value
  // (valid until the next add/remove of the same type). Precondition: alive(entity), no View.
  template <class T>
  T& add(Entity entity, T value) {
    assert(structuralChangesAllowed() && "structural change during iteration; use a CommandBuffer");
    assert(alive(entity) && "add to a dead entity");
    detail::ComponentPool<T>& pool = poolFor<T>();
    if (!alive(entity) || lock_ != 0) return pool.scratch();
    return pool.insert(entity, std::move(value));
  }

  // The entity's component. Precondition: has<T>(entity).
  template <class T>
  T& get(Entity entity) {
    T* component = tryGet<T>(entity);
    assert(component != nullptr && "get of a missing component");
    return component != nullptr ? *component : poolFor<T>().scratch();
  }
  template <class T>
  const T& get(Entity entity) const {
    const T* component = tryGet<T>(entity);
    assert(component != nullptr && "get of a missing component");
    static const T kEmpty{};
    return component != nullptr ? *component : kEmpty;
  }

  // The entity's component, or nullptr if it has none (or is not alive).
  template <class T>
  T* tryGet(Entity entity) {
    detail::ComponentPool<T>* pool = findPool<T>();
    return pool != nullptr ? pool->tryGet(entity) : nullptr;
  }
  template <class T>
  const T* tryGet(Entity entity) const {
    const detail::ComponentPool<T>* pool = findPool<T>();
    return pool != nullptr ? pool->tryGet(entity) : nullptr;
  }

  template <class T>
  bool has(Entity entity) const {
    return tryGet<T>(entity) != nullptr;
  }

  // Removes the component, then runs its type's destroy hooks on it; false if the entity had none.
  // Precondition: no View exists.
  template <class T>
  bool remove(Entity entity) {
    assert(structuralChangesAllowed() && "structural change during iteration; use a CommandBuffer");
    detail::ComponentPool<T>* pool = findPool<T>();
    if (pool == nullptr || lock_ != 0) return false;
    ++hookDepth_;
    const bool removed = pool->release(*this, entity);
    --hookDepth_;
    return removed;
  }

  // Number of entities that have a T.
  template <class T>
  size_t count() const {
    const detail::ComponentPool<T>* pool = findPool<T>();
    return pool != nullptr ? pool->size() : 0;
  }

  // Entities having all of Ts (see view.h for the iteration order and the structural lock).
  template <class... Ts>
  View<Ts...> view() {
    return View<Ts...>(&lock_, &poolFor<Ts>()...);
  }

  // Carries out the buffer's commands in recording order and empties the buffer.
  // Precondition: the buffer was made for this World; no View exists.
  ApplyResult apply(CommandBuffer& buffer);

  // False while a View exists.
  bool structuralChangesAllowed() const { return lock_ == 0; }

 private:
  friend class CommandBuffer;

  // Dying: alive while its destroy hooks run.
  enum class SlotState : uint8_t { Free, Reserved, Alive, Dying };
  struct Slot {
    uint32_t generation = 1;
    SlotState state = SlotState::Free;
  };

  // Reservations: an id taken now (allowed during iteration: no pool changes) that becomes alive
  // when the buffer is applied, or goes back to the free list when the buffer drops it.
  Entity reserve();
  bool commitReservation(Entity entity);
  void releaseReservation(Entity entity);
  Entity takeSlot(SlotState state);
  void freeSlot(uint32_t index);

  template <class T>
  detail::ComponentPool<T>* findPool() const {
    const detail::ComponentTypeId id = detail::componentTypeId<T>();
    if (id >= pools_.size() || !pools_[id]) return nullptr;
    return static_cast<detail::ComponentPool<T>*>(pools_[id].get());
  }
  template <class T>
  detail::ComponentPool<T>& poolFor() {
    const detail::ComponentTypeId id = detail::componentTypeId<T>();
    if (id >= pools_.size()) pools_.resize(size_t{id} + 1);
    if (!pools_[id]) pools_[id] = std::make_unique<detail::ComponentPool<T>>();
    return static_cast<detail::ComponentPool<T>&>(*pools_[id]);
  }

  std::vector<Slot> slots_;
  std::deque<uint32_t> freeSlots_;  // FIFO: the oldest freed slot is reused first
  std::vector<std::unique_ptr<detail::PoolBase>> pools_;  // by component type id
  size_t aliveCount_ = 0;
  int lock_ = 0;  // number of live views
  std::vector<detail::ComponentTypeId> hookOrder_;  // types with hooks, by their first hook
  std::vector<std::pair<HookId, detail::ComponentTypeId>> hookTypes_;  // every hook's type
  HookId lastHookId_ = 0;
  int hookDepth_ = 0;  // > 0 while hooks run (nested when a hook removes or destroys)
};

}  // namespace cleave::ecs
