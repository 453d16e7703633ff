// SPDX-License-Identifier: MIT
#include "cleave/components/live_tuning.h"

#include <cmath>

namespace cleave::components {

namespace {

TuningResult fail(std::string reason) {
  return TuningResult::failure(base::StatusCode::InvalidArgument, std::move(reason));
}

bool inRange(double v, double lo, double hi) { return std::isfinite(v) && v >= lo && v <= hi; }

}  // namespace

SplitableTuning tuningOf(const Splitable& s) {
  SplitableTuning t;
  t.capUvMode = s.capUvMode;
  t.capUvPerMetre = s.capUvPerMetre;
  t.collider = s.collider;
  t.density = s.density;
  t.splitImpulse = s.splitImpulse;
  t.separateIslands = s.separateIslands;
  t.islands = s.islands;
  t.hollow = !s.cap;
  return t;
}

TuningResult applySplitableTuning(ecs::World& world, ecs::Entity entity, const SplitableTuning& t) {
  Splitable* s = world.alive(entity) ? world.tryGet<Splitable>(entity) : nullptr;
  if (!s) return fail("splitable tuning: the entity is gone or has no Splitable");
  if (!(std::isfinite(t.capUvPerMetre) && t.capUvPerMetre > 0.0 && t.capUvPerMetre <= kMaxCapUvPerMetre))
    return fail("splitable tuning: cap UV scale must be above 0 and at most 100 per metre");
  if (!inRange(t.density, kMinDensity, kMaxDensity))
    return fail("splitable tuning: density must be from 1 to 50000 kg/m^3");
  if (!inRange(t.splitImpulse, 0.0, kMaxSplitImpulse))
    return fail("splitable tuning: split impulse must be from 0 to 50 m/s");
  if (int(t.collider) > int(ColliderMode::ConcaveMesh) ||
      int(t.capUvMode) > int(geometry::CapUvMode::NormalizedBounds) ||
      int(t.islands) > int(geometry::IslandMode::Connected))
    return fail("splitable tuning: unknown collider, cap UV or island mode");
  s->capUvMode = t.capUvMode;
  s->capUvPerMetre = t.capUvPerMetre;
  s->collider = t.collider;
  s->density = t.density;
  s->splitImpulse = t.splitImpulse;
  s->separateIslands = t.separateIslands;
  s->islands = t.islands;
  s->cap = !t.hollow;
  return {};
}

TuningResult applyBudgetTuning(SplitBudget& budget, const SplitBudgetSettings& in) {
  if (!inRange(in.millisecondsPerTick, 1e-3, 1000.0) || !inRange(in.workerMillisecondsPerTick, 1e-3, 1000.0))
    return fail("budget tuning: milliseconds per tick must be above 0 and at most 1000");
  if (in.maxSplitsPerTick < 1 || in.maxActivationsPerTick < 1 || in.maxQueueLength < 1)
    return fail("budget tuning: the splits, activations and queue length per tick must be at least 1");
  if (in.commitDelayTicks > 8) return fail("budget tuning: the commit delay must be at most 8 ticks");
  SplitBudgetSettings s = budget.settings();
  s.millisecondsPerTick = in.millisecondsPerTick;
  s.workerMillisecondsPerTick = in.workerMillisecondsPerTick;
  s.maxSplitsPerTick = in.maxSplitsPerTick;
  s.maxActivationsPerTick = in.maxActivationsPerTick;
  s.maxQueueLength = in.maxQueueLength;
  s.deterministic = in.deterministic;
  s.commitDelayTicks = in.commitDelayTicks;
  budget.setSettings(s);
  return {};
}

}  // namespace cleave::components
