// SPDX-License-Identifier: MIT
// Private (not installed): a slot table with generations, behind the public handles of physics
// (bodies, shapes, triggers, joints) and of the renderer (meshes, textures).
//
// Freed slots are reused last-in first-out, so the handle sequence depends only on the sequence of
// create/destroy calls (deterministic). Iteration is in index order.
#pragma once

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

namespace cleave::base::detail {

template <class T>
class SlotPool {
 public:
  struct Key {
    uint32_t index = 0;
    uint32_t generation = 0;
  };

  Key insert(T item) {
    uint32_t index;
    if (!free_.empty()) {
      index = free_.back();
      free_.pop_back();
    } else {
      index = static_cast<uint32_t>(slots_.size());
      slots_.emplace_back();
    }
    Slot& slot = slots_[index];
    slot.item.emplace(std::move(item));
    ++live_;
    return Key{index, slot.generation};
  }

  T* get(uint32_t index, uint32_t generation) {
    if (generation == 0 || index >= slots_.size()) return nullptr;
    Slot& slot = slots_[index];
    if (slot.generation != generation || !slot.item) return nullptr;
    return &*slot.item;
  }
  const T* get(uint32_t index, uint32_t generation) const {
    return const_cast<SlotPool*>(this)->get(index, generation);
  }
  // The live item at an index whatever its generation (for Bullet back-references).
  T* atIndex(uint32_t index) {
    if (index >= slots_.size() || !slots_[index].item) return nullptr;
    return &*slots_[index].item;
  }
  const T* atIndex(uint32_t index) const { return const_cast<SlotPool*>(this)->atIndex(index); }
  uint32_t generationAt(uint32_t index) const {
    return index < slots_.size() ? slots_[index].generation : 0;
  }

  // Destroys the item and bumps the generation so old keys become stale. Precondition: live.
  void erase(uint32_t index) {
    Slot& slot = slots_[index];
    slot.item.reset();
    ++slot.generation;
    if (slot.generation == 0) slot.generation = 1;  // 0 is the null handle
    free_.push_back(index);
    --live_;
  }

  uint32_t size() const { return live_; }
  uint32_t capacity() const { return static_cast<uint32_t>(slots_.size()); }

  template <class F>
  void forEach(F&& f) {
    for (uint32_t i = 0; i < slots_.size(); ++i) {
      if (slots_[i].item) f(i, slots_[i].generation, *slots_[i].item);
    }
  }
  template <class F>
  void forEach(F&& f) const {
    for (uint32_t i = 0; i < slots_.size(); ++i) {
      if (slots_[i].item) f(i, slots_[i].generation, *slots_[i].item);
    }
  }

 private:
  struct Slot {
    std::optional<T> item;
    uint32_t generation = 1;
  };
  std::vector<Slot> slots_;
  std::vector<uint32_t> free_;
  uint32_t live_ = 0;
};

}  // namespace cleave::base::detail
