// SPDX-License-Identifier: MIT
// A growable list of trivially copyable items whose first item may lie past the start of its
// storage. Internal to the geometry library.
//
// The splitter's side lists are filled by several threads at once and must come out as one list
// in source order. Laid end to end after the threads are done, they cost a copy of half the
// triangles; instead, one thread fills its range backwards, ending where the next thread's range
// begins forwards, so that the two meet with nothing to move (Splitter::cutWholeAndCollect).
// place() gives the storage for that; adopt() then makes the written range the list. Otherwise it
// behaves as a vector of items that are only read after they are written: resize() leaves new
// items unwritten, and indices count from the first item.
//
// place() alone is also the splitter's grow-only scratch: storage written in full before it is
// read, kept from one split to the next, so a warmed-up split allocates nothing.
//
// Ownership: the list owns its storage. Growing moves the items to new storage, first item at its
// start: pointers into the list and into place()'s storage are then invalid (as for std::vector).
#pragma once

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <memory>
#include <type_traits>

namespace cleave::geometry::detail {

template <typename T>
class OffsetList {
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_default_constructible_v<T>);

 public:
  // Storage for at least `capacity` items, contents unspecified, the list emptied; returns its
  // start. Keeps the storage it has when that is big enough.
  T* place(size_t capacity) {
    first_ = size_ = 0;
    if (capacity > capacity_) {
      storage_ = std::make_unique_for_overwrite<T[]>(capacity);
      capacity_ = capacity;
    }
    return storage_.get();
  }
  // The storage's items [first, first + count), written through place()'s pointer, become the list.
  void adopt(size_t first, size_t count) {
    assert(first + count <= capacity_);
    first_ = first;
    size_ = count;
  }

  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  T* data() { return storage_.get() + first_; }
  const T* data() const { return storage_.get() + first_; }
  T* begin() { return data(); }
  T* end() { return data() + size_; }
  const T* begin() const { return data(); }
  const T* end() const { return data() + size_; }
  T& operator[](size_t i) { return data()[i]; }
  const T& operator[](size_t i) const { return data()[i]; }

  void clear() { first_ = size_ = 0; }
  void push_back(const T& item) {
    if (first_ + size_ == capacity_) grow(size_ + 1);
    storage_[first_ + size_++] = item;
  }
  // New items are left unwritten: fill them before they are read.
  void resize(size_t count) {
    if (first_ + count > capacity_) grow(count);
    size_ = count;
  }
  // Drops the items from `from` (a pointer into the list) to the end: the erase of remove_if.
  void truncate(const T* from) {
    assert(from >= begin() && from <= end());
    size_ = static_cast<size_t>(from - begin());
  }

 private:
  void grow(size_t needed) {
    const size_t capacity = std::max(needed, 2 * capacity_);
    std::unique_ptr<T[]> fresh = std::make_unique_for_overwrite<T[]>(capacity);
    std::copy_n(data(), size_, fresh.get());
    storage_ = std::move(fresh);
    capacity_ = capacity;
    first_ = 0;
  }

  std::unique_ptr<T[]> storage_;
  size_t capacity_ = 0;
  size_t first_ = 0;  // where the list starts in the storage
  size_t size_ = 0;
};

}  // namespace cleave::geometry::detail
