// SPDX-License-Identifier: MIT
// CutPositions: the cut-space positions of a MeshContainer's vertices, read as doubles (metres, the
// space the plane is given in). While the cut space is the source space (setMesh, or setTransform
// with the identity) they are the source's float positions themselves, widened on read: no copy is
// made, and a double holds every float exactly, so the values are the same as a copy's. After any
// other transform or a skinning pose they are the container's own array of doubles.
// Ownership: a view into the container and its mesh; valid until the container's next setMesh,
// setTransform, setSkinningPose or release. Nothing here fails or allocates but doubles().
#pragma once

#include <cstddef>
#include <iterator>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace cleave::geometry {

class CutPositions {
 public:
  CutPositions() = default;
  // The source's floats (the cut space is the source space).
  explicit CutPositions(std::span<const glm::vec3> source) : source_(source.data()), size_(source.size()) {}
  // Positions moved into cut space.
  explicit CutPositions(std::span<const glm::dvec3> moved) : moved_(moved.data()), size_(moved.size()) {}

  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  // True while the positions are the source's floats (no array of doubles is held).
  bool isSource() const { return source_ != nullptr; }
  // Vertex i (i < size()).
  glm::dvec3 operator[](size_t i) const { return source_ ? glm::dvec3(source_[i]) : moved_[i]; }
  // Asks the memory for vertex i (i < size()) ahead of reading it; no effect on any value.
  void prefetch(size_t i) const {
    __builtin_prefetch(source_ ? static_cast<const void*>(source_ + i) : static_cast<const void*>(moved_ + i));
  }
  // Reads in order, for range-for loops and copies (each position by value).
  class Iterator {
   public:
    using iterator_category = std::input_iterator_tag;
    using value_type = glm::dvec3;
    using difference_type = std::ptrdiff_t;
    using pointer = void;
    using reference = glm::dvec3;
    Iterator() = default;
    Iterator(const CutPositions* positions, size_t i) : positions_(positions), i_(i) {}
    glm::dvec3 operator*() const { return (*positions_)[i_]; }
    Iterator& operator++() {
      ++i_;
      return *this;
    }
    Iterator operator++(int) {
      Iterator before = *this;
      ++i_;
      return before;
    }
    bool operator==(const Iterator& other) const { return i_ == other.i_; }

   private:
    const CutPositions* positions_ = nullptr;
    size_t i_ = 0;
  };
  Iterator begin() const { return {this, 0}; }
  Iterator end() const { return {this, size_}; }
  // The source floats; empty unless isSource().
  std::span<const glm::vec3> source() const { return {source_, source_ ? size_ : 0}; }
  // The positions moved into cut space; empty while isSource().
  std::span<const glm::dvec3> moved() const { return {moved_, moved_ ? size_ : 0}; }
  // All positions as one array of doubles: the held array, or `scratch` filled from the source
  // floats (its capacity is reused). For callers whose functions take a span of doubles.
  std::span<const glm::dvec3> doubles(std::vector<glm::dvec3>& scratch) const {
    if (!source_) return {moved_, size_};
    scratch.assign(source_, source_ + size_);
    return scratch;
  }

 private:
  const glm::vec3* source_ = nullptr;
  const glm::dvec3* moved_ = nullptr;
  size_t size_ = 0;
};

}  // namespace cleave::geometry
