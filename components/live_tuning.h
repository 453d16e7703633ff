// SPDX-License-Identifier: MIT
// Live tuning: the settings a person may change while the game runs (the games' inspector, F1),
// checked before they are written. A Splitable's settings are copied into a split job when it is
// prepared, so a change applies from the next split of that object (a split already in flight keeps
// what it was prepared with), and the pieces inherit the changed settings. The budget's settings
// apply from the next tick.
//
// Every edit goes through these functions, the inspector's and the tests' alike.
#pragma once

#include <string>

#include "cleave/base/status.h"
#include "cleave/components/split_budget.h"
#include "cleave/components/splitable.h"
#include "cleave/ecs/world.h"

namespace cleave::components {

// The Splitable fields the inspector shows and edits.
struct SplitableTuning {
  geometry::CapUvMode capUvMode = geometry::CapUvMode::WorldPlanar;
  double capUvPerMetre = 1.0;       // cap texture repeats per metre (WorldPlanar), > 0
  ColliderMode collider = ColliderMode::Auto;
  double density = 500.0;           // kg/m^3, > 0
  double splitImpulse = 0.0;        // m/s along the plane normal, away from the cut, >= 0
  bool separateIslands = true;      // false: each side stays one piece
  geometry::IslandMode islands = geometry::IslandMode::Touching;
  bool hollow = false;              // pieces are not capped (Splitable::cap = false)
  friend bool operator==(const SplitableTuning&, const SplitableTuning&) = default;
};

// Limits of the edits (the inspector's slider ranges too).
inline constexpr double kMaxCapUvPerMetre = 100.0;
inline constexpr double kMinDensity = 1.0;        // kg/m^3
inline constexpr double kMaxDensity = 50000.0;
inline constexpr double kMaxSplitImpulse = 50.0;  // m/s

// Ok, or InvalidArgument with a message naming the setting and the reason.
using TuningResult = base::Status;

SplitableTuning tuningOf(const Splitable& splitable);

// Writes `tuning` into the Splitable of `entity`. Fails, changing nothing, when the entity is gone
// or has no Splitable, or a value is out of its range or not finite.
TuningResult applySplitableTuning(ecs::World& world, ecs::Entity entity, const SplitableTuning& tuning);

// The budget settings the inspector edits: millisecondsPerTick, workerMillisecondsPerTick,
// maxSplitsPerTick, maxActivationsPerTick, maxQueueLength, deterministic and commitDelayTicks.
// The other fields of `settings` (the threads, the cost estimates) are kept as the budget has them.
// Fails, changing nothing, on a value out of range (milliseconds > 0 and finite, counts >= 1,
// commit delay <= 8 ticks).
TuningResult applyBudgetTuning(SplitBudget& budget, const SplitBudgetSettings& settings);

}  // namespace cleave::components
