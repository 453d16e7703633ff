// SPDX-License-Identifier: MIT
// View: iteration over the entities that have all of a set of component types.
//
//   for (auto [entity, position, velocity] : world.view<Position, Velocity>()) { ... }
//   world.view<Position, Velocity>().each([](Entity e, Position& p, Velocity& v) { ... });
//
// Order (deterministic): the view walks the dense array of the smallest of its pools (the first of
// the template arguments on a tie) and skips entities missing one of the other components. The
// dense order is the order in which the components were added, except that removing a component
// moves the pool's last element into the hole. Sort the result yourself if you need another order
// (World::entities() is ascending by index).
//
// While a View object exists, the World is locked against structural changes (create, destroy, add,
// remove, apply): they are precondition violations (asserted in debug builds). Systems record such
// changes in a CommandBuffer and apply it after the loop. Reading and writing component values
// (get, tryGet, has, assignments through the references) is allowed. Keep views as temporaries of
// the loop; do not store them.
#pragma once

#include <cstddef>
#include <tuple>
#include <utility>

#include "cleave/ecs/component_pool.h"
#include "cleave/ecs/entity.h"

namespace cleave::ecs {

template <class... Ts>
class View {
  static_assert(sizeof...(Ts) >= 1, "a view needs at least one component type");

 public:
  // What the iterator yields: the entity and references to its components.
  using Item = std::tuple<Entity, Ts&...>;

  class Iterator {
   public:
    Iterator(const View* view, size_t position) : view_(view), position_(position) { skip(); }
    Item operator*() const { return view_->itemAt(position_); }
    Iterator& operator++() {
      ++position_;
      skip();
      return *this;
    }
    bool operator==(const Iterator& other) const { return position_ == other.position_; }

   private:
    void skip() {
      while (position_ < view_->lead_->size() && !view_->containsAll(view_->leadEntity(position_)))
        ++position_;
    }
    const View* view_;
    size_t position_;
  };

  // Made by World::view(); `lock` is the World's structural-change lock counter.
  View(int* lock, detail::ComponentPool<Ts>*... pools) : lock_(lock), pools_(pools...) {
    ++*lock_;
    lead_ = std::get<0>(pools_);
    ((pools->size() < lead_->size() ? (void)(lead_ = pools) : (void)0), ...);
  }
  ~View() {
    if (lock_ != nullptr) --*lock_;
  }
  View(const View&) = delete;
  View& operator=(const View&) = delete;
  View(View&& other) noexcept : lock_(other.lock_), pools_(other.pools_), lead_(other.lead_) {
    other.lock_ = nullptr;
  }
  View& operator=(View&&) = delete;

  Iterator begin() const { return Iterator(this, 0); }
  Iterator end() const { return Iterator(this, lead_->size()); }

  // Calls fn(Entity, Ts&...) for every matching entity, in the order documented above.
  template <class Fn>
  void each(Fn&& fn) const {
    for (size_t i = 0; i < lead_->size(); ++i) {
      const Entity entity = leadEntity(i);
      if (containsAll(entity))
        fn(entity, *std::get<detail::ComponentPool<Ts>*>(pools_)->tryGet(entity)...);
    }
  }

  // Upper bound of the number of matching entities (the size of the smallest pool).
  size_t sizeHint() const { return lead_->size(); }

 private:
  Entity leadEntity(size_t position) const { return lead_->entities()[position]; }
  bool containsAll(Entity entity) const {
    return (std::get<detail::ComponentPool<Ts>*>(pools_)->contains(entity) && ...);
  }
  Item itemAt(size_t position) const {
    const Entity entity = leadEntity(position);
    return Item(entity, *std::get<detail::ComponentPool<Ts>*>(pools_)->tryGet(entity)...);
  }

  int* lock_;
  std::tuple<detail::ComponentPool<Ts>*...> pools_;
  const detail::PoolBase* lead_ = nullptr;
};

}  // namespace cleave::ecs
