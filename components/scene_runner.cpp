// SPDX-License-Identifier: MIT
// Running a loaded scene (scene_loader.h): its scheduled splitters appear, move and go on their
// ticks; runSceneTick is one whole tick without an App.
#include "cleave/components/scene_loader.h"

#include "cleave/components/scene_components.h"
#include "cleave/components/simulation.h"

namespace cleave::components {

void SceneRunner::update(SplitWorld& w, uint64_t tick, double dt) {
  for (ScheduledSplitter& s : splitters_) {
    if (s.schedule == SplitterSchedule::OneTick) {
      if (!s.created && tick == s.fireTick) {
        s.entity = createSplitterEntity(w, s);
        s.created = true;
        s.createdTick = tick;
      }
      continue;
    }
    const bool due = tick >= s.startTick && (!s.endTick || tick < *s.endTick);
    if (!s.created && due) {
      s.entity = createSplitterEntity(w, s);
      s.created = true;
      s.createdTick = tick;
    }
    if (!w.world.alive(s.entity)) continue;
    if (s.endTick && tick >= *s.endTick) {
      w.world.destroy(s.entity);
      s.entity = {};
      continue;
    }
    if (s.velocity != glm::vec3(0.f)) {
      const double elapsed = double(tick - s.createdTick) * dt;
      const glm::vec3 position = glm::vec3(glm::dvec3(s.position) + glm::dvec3(s.velocity) * elapsed);
      auto& t = w.world.get<ecs::Transform>(s.entity);
      t.position = position;
      w.world.get<ecs::WorldTransform>(s.entity).matrix = ecs::localMatrix(t);
      if (const auto* sp = w.world.tryGet<Splitter>(s.entity))
        w.physics.setTriggerTransform(sp->trigger, physics::BodyTransform{position, s.rotation});
    }
  }
}

void runSceneTick(SplitWorld& w, SplitSystem& splits, SceneRunner& runner, uint64_t tick, double dt,
                  const glm::dvec3& cameraPosition) {
  runner.update(w, tick, dt);  // Gameplay
  for (const TickStageInfo& s : kTickOrder) runTickStage(s.stage, w, splits, tick, dt, cameraPosition);
}

}  // namespace cleave::components
