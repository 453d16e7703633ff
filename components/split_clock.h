// SPDX-License-Identifier: MIT
// The clock the split stages report their times with (milliseconds, steady). Times are reported,
// never used to decide anything in deterministic scheduling.
#pragma once

#include <chrono>

namespace cleave::components {

inline double nowMilliseconds() {
  using namespace std::chrono;
  return duration<double, std::milli>(steady_clock::now().time_since_epoch()).count();
}

}  // namespace cleave::components
