// SPDX-License-Identifier: MIT
// Hello, engine: a headless App with splitting installed, one splittable crate, and a one-tick
// splitter that cuts it at tick 5. The split is prepared in the next tick, computed on a worker and
// committed at a fixed tick; the pieces become rigid bodies with exact masses.
#include <cstdio>

#include "crate_scene.h"

namespace {

using namespace cleave;

void printPieces(app::TickContext& c, const std::vector<components::SplitEvent>& events) {
  for (const components::SplitEvent& ev : events) {
    std::printf("tick %llu: %s cut into %zu pieces (%s)\n", static_cast<unsigned long long>(ev.tick),
                ev.originalName.c_str(), ev.pieces.size(), geometry::toString(ev.status));
    double total = 0.0;
    for (ecs::Entity piece : ev.pieces) {
      const auto& mass = c.world.get<components::MassInfo>(piece);
      std::printf("  %s: %.1f kg, %.4f m^3\n", c.world.get<ecs::Name>(piece).value.c_str(), mass.mass, mass.volume);
      total += mass.mass;
    }
    std::printf("  total %.1f kg (the crate had %.1f kg)\n", total, ev.parentMass);
  }
}

}  // namespace

int main() {
  examples::CrateScene scene;
  if (!scene.start(30, printPieces)) return 1;
  // The blade: tilted 30 degrees about z, through the crate's centre.
  scene.addBladeAt(5, glm::vec3(0.f, 0.5f, 0.f), glm::angleAxis(glm::radians(30.f), glm::vec3(0, 0, 1)));
  return scene.app.run();
}
