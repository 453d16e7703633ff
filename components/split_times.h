// SPDX-License-Identifier: MIT
// The time one split took, by stage, in wall-clock milliseconds. Measured and reported (split
// events, the split log, the HUDs, the inspector, the benchmarks); a deterministic budget never
// decides anything by them (it charges estimates: split_cost.h).
#pragma once

namespace cleave::components {

// The compute stage, on a worker (or inline with no workers).
struct ComputeTimes {
  double total = 0.0;
  double setup = 0.0;     // of which: container set-up (weld unless known, cut space)
  double geometry = 0.0;  // of which: cut, caps, islands, mass properties
  double collider = 0.0;  // of which: parts clipped or decomposed, hulls shrunk, ragdolls planned
};

struct SplitTimes {
  double prepare = 0.0;  // main thread
  double commit = 0.0;   // main thread, without the wait; of which:
  double shapes = 0.0;   //   physics shapes and bodies
  double uploads = 0.0;  //   GPU mesh uploads
  double wait = 0.0;     // main thread, waiting at commit for a compute not done yet
  ComputeTimes compute;

  double main() const { return prepare + commit; }          // the main thread's own work
  double total() const { return main() + compute.total; }   // the whole work of the split
};

}  // namespace cleave::components
