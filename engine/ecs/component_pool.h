// SPDX-License-Identifier: MIT
// Sparse-set storage of one component type (internal to the World; use World's member functions).
//
// Layout: `dense_` holds the entities that have the component and `components_` their values at the
// same positions (both contiguous, iterated by views); `sparse_` maps an entity index to its dense
// position. Removal moves the last element into the hole ("swap and pop"), so the dense order is
// insertion order except where a removal moved the last element forward. Components are stored by
// value and must be movable; pointers and references to them are invalidated by any add or remove
// of the same type.
#pragma once

#include <atomic>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

#include "cleave/ecs/entity.h"

namespace cleave::ecs {
class World;
// Names a destroy hook (World::onDestroy) so that it can be removed; 0 is never handed out.
using HookId = uint32_t;
}  // namespace cleave::ecs

namespace cleave::ecs::detail {

// Component type ids index the World's pool table. They are handed out in order of first use in the
// process and are never written to any output, so their values do not affect determinism.
using ComponentTypeId = uint32_t;

inline ComponentTypeId nextComponentTypeId() {
  static std::atomic<ComponentTypeId> counter{0};
  return counter.fetch_add(1, std::memory_order_relaxed);
}

template <class T>
ComponentTypeId componentTypeId() {
  static const ComponentTypeId id = nextComponentTypeId();
  return id;
}

class PoolBase {
 public:
  virtual ~PoolBase() = default;
  virtual bool contains(Entity entity) const = 0;
  // Removes the entity's component; false when it had none.
  virtual bool erase(Entity entity) = 0;
  // Removes the entity's component and then runs the type's destroy hooks on its last value (taken
  // out of the pool first, so a hook never sees it stored and cannot free it twice); false when
  // the entity had none.
  virtual bool release(World& world, Entity entity) = 0;
  virtual bool removeHook(HookId id) = 0;
  // Entities holding the component, in dense order.
  const std::vector<Entity>& entities() const { return dense_; }
  size_t size() const { return dense_.size(); }

 protected:
  static constexpr uint32_t kAbsent = std::numeric_limits<uint32_t>::max();

  // Dense position of the entity, or kAbsent (also for a stale id of a reused index).
  uint32_t find(Entity entity) const {
    if (entity.index >= sparse_.size()) return kAbsent;
    const uint32_t slot = sparse_[entity.index];
    if (slot == kAbsent || dense_[slot] != entity) return kAbsent;
    return slot;
  }

  std::vector<uint32_t> sparse_;  // entity index -> dense position or kAbsent
  std::vector<Entity> dense_;
};

template <class T>
class ComponentPool final : public PoolBase {
 public:
  bool contains(Entity entity) const override { return find(entity) != kAbsent; }

  T* tryGet(Entity entity) {
    const uint32_t slot = find(entity);
    return slot == kAbsent ? nullptr : &components_[slot];
  }
  const T* tryGet(Entity entity) const {
    const uint32_t slot = find(entity);
    return slot == kAbsent ? nullptr : &components_[slot];
  }

  // Inserts or overwrites the entity's component.
  T& insert(Entity entity, T value) {
    if (const uint32_t slot = find(entity); slot != kAbsent) {
      components_[slot] = std::move(value);
      return components_[slot];
    }
    if (entity.index >= sparse_.size()) sparse_.resize(size_t{entity.index} + 1, kAbsent);
    sparse_[entity.index] = static_cast<uint32_t>(dense_.size());
    dense_.push_back(entity);
    components_.push_back(std::move(value));
    return components_.back();
  }

  using Hook = std::function<void(World&, Entity, T&)>;

  void addHook(HookId id, Hook hook) { hooks_.emplace_back(id, std::move(hook)); }
  bool removeHook(HookId id) override {
    return std::erase_if(hooks_, [id](const auto& h) { return h.first == id; }) > 0;
  }

  bool release(World& world, Entity entity) override {
    T* component = tryGet(entity);
    if (component == nullptr) return false;
    if (hooks_.empty()) return erase(entity);
    T last = std::move(*component);
    erase(entity);
    for (auto& [id, hook] : hooks_) hook(world, entity, last);
    return true;
  }

  bool erase(Entity entity) override {
    const uint32_t slot = find(entity);
    if (slot == kAbsent) return false;
    const uint32_t last = static_cast<uint32_t>(dense_.size() - 1);
    if (slot != last) {
      dense_[slot] = dense_[last];
      components_[slot] = std::move(components_[last]);
      sparse_[dense_[slot].index] = slot;
    }
    dense_.pop_back();
    components_.pop_back();
    sparse_[entity.index] = kAbsent;
    return true;
  }

  // A value that absorbs writes made in violation of a precondition in release builds (add to a
  // dead entity, get of a missing component), so such a bug cannot corrupt the storage.
  T& scratch() {
    scratch_ = T{};
    return scratch_;
  }

 private:
  std::vector<T> components_;
  std::vector<std::pair<HookId, Hook>> hooks_;  // in registration order
  T scratch_{};
};

}  // namespace cleave::ecs::detail
