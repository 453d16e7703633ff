// SPDX-License-Identifier: MIT
// Status results of the physics layer: an error code plus a reason a person can act on.
//
// No call of the physics layer throws or crashes on bad input; data-dependent failures come back as
// a PhysicsStatus (with a message) or a Result<T>, and handle-taking queries return false or
// nullopt for stale handles.
#pragma once

#include <cassert>
#include <cstdint>
#include <string>
#include <utility>

namespace cleave::physics {

enum class PhysicsStatus : uint8_t {
  Ok = 0,
  InvalidArgument,         // NaN/Inf, negative size or mass, index out of range, empty arrays, ...
  StaleHandle,             // the handle is null, was destroyed, or belongs to a reused slot
  DegenerateShape,         // points are (nearly) coplanar/colinear, the mesh has no usable triangle
  UnsupportedCombination,  // e.g. a static triangle mesh on a dynamic body, a mesh as a trigger
};
const char* toString(PhysicsStatus status);

// A value or the reason there is none. T must be default-constructible (handles are).
template <class T>
class Result {
 public:
  static Result success(T value) {
    Result result;
    result.value_ = std::move(value);
    return result;
  }
  static Result failure(PhysicsStatus status, std::string reason) {
    assert(status != PhysicsStatus::Ok);
    Result result;
    result.status_ = status;
    result.reason_ = std::move(reason);
    return result;
  }

  bool ok() const { return status_ == PhysicsStatus::Ok; }
  explicit operator bool() const { return ok(); }
  // Precondition: ok(). A failed result holds a default-constructed (null) value.
  const T& value() const {
    assert(ok());
    return value_;
  }
  PhysicsStatus status() const { return status_; }
  const std::string& reason() const { return reason_; }  // empty when ok()

 private:
  T value_{};
  PhysicsStatus status_ = PhysicsStatus::Ok;
  std::string reason_;
};

}  // namespace cleave::physics
