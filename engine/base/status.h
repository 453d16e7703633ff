// SPDX-License-Identifier: MIT
// The one error shape of every layer: a Status is a code plus a message a person can act on, and an
// Expected<T> is a value or the Status saying why there is none.
//
// The code enum is the layer's own where it has one (physics::PhysicsStatus, geometry::SplitStatus);
// the other layers use the layer-neutral StatusCode. Every code enum has an `Ok` enumerator, and a
// failure never carries Ok. Messages name the file, the place and the reason; an ok Status has an
// empty message. Nothing here throws: a failed Expected holds a default-constructed value, so T must
// be default-constructible.
//
// Standard library only; header-only (the layer below every other).
#pragma once

#include <cassert>
#include <cstdint>
#include <string>
#include <utility>

namespace cleave::base {

// The codes of the layers that have no enum of their own.
enum class StatusCode : uint8_t {
  Ok = 0,
  InvalidArgument,  // a value out of range, an unknown option, a malformed request
  NotFound,         // a file, entity, name or handle that is not there
  IoError,          // a file could not be read or written
  ParseError,       // the bytes are there but do not hold what they should
  Unavailable,      // a needed runtime resource is missing (display, GL context, GL functions)
};

inline const char* toString(StatusCode code) {
  switch (code) {
    case StatusCode::Ok: return "Ok";
    case StatusCode::InvalidArgument: return "InvalidArgument";
    case StatusCode::NotFound: return "NotFound";
    case StatusCode::IoError: return "IoError";
    case StatusCode::ParseError: return "ParseError";
    case StatusCode::Unavailable: return "Unavailable";
  }
  return "?";
}

// Ok, or a code with the reason. A result that has more to give than one value (warnings, the line
// of an error, a mesh's material names) derives from Status: `if (!read.ok()) ... read.message`.
template <class Code>
struct BasicStatus {
  Code code = Code::Ok;
  std::string message;  // empty when ok()

  static BasicStatus success() { return {}; }
  static BasicStatus failure(Code failureCode, std::string failureMessage) {
    assert(failureCode != Code::Ok);
    return BasicStatus{failureCode, std::move(failureMessage)};
  }
  bool ok() const { return code == Code::Ok; }
  explicit operator bool() const { return ok(); }
  // Turns this Status (or the result that carries it) into a failure.
  void setFailure(Code failureCode, std::string failureMessage) {
    assert(failureCode != Code::Ok);
    code = failureCode;
    message = std::move(failureMessage);
  }
};

using Status = BasicStatus<StatusCode>;

// A value, or the Status saying why there is none.
template <class T, class Code = StatusCode>
class Expected {
 public:
  using StatusType = BasicStatus<Code>;

  Expected() = default;  // ok, with a default-constructed value
  // A value converts implicitly (`return mesh;`), and so does a failed Status (`return status;`).
  Expected(T value) : value_(std::move(value)) {}  // NOLINT(google-explicit-constructor)
  Expected(StatusType status) : status_(std::move(status)) {  // NOLINT(google-explicit-constructor)
    assert(!status_.ok());
  }

  static Expected success(T value) { return Expected(std::move(value)); }
  static Expected failure(Code failureCode, std::string failureMessage) {
    return Expected(StatusType::failure(failureCode, std::move(failureMessage)));
  }

  bool ok() const { return status_.ok(); }
  explicit operator bool() const { return ok(); }

  // Precondition: ok(). A failed Expected holds a default-constructed value.
  const T& value() const& {
    assert(ok());
    return value_;
  }
  T& value() & {
    assert(ok());
    return value_;
  }
  T&& value() && {
    assert(ok());
    return std::move(value_);
  }
  // The value, or `fallback` when there is none (a null handle, say, where a caller has no use for
  // the reason).
  T valueOr(T fallback) const& { return ok() ? value_ : std::move(fallback); }
  const T& operator*() const& { return value(); }
  T& operator*() & { return value(); }
  const T* operator->() const { return &value(); }
  T* operator->() { return &value(); }

  const StatusType& status() const { return status_; }
  Code code() const { return status_.code; }
  const std::string& message() const { return status_.message; }  // empty when ok()

 private:
  T value_{};
  StatusType status_;
};

}  // namespace cleave::base
