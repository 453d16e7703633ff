// SPDX-License-Identifier: MIT
// A custom split handler: named by the crate's Splitable, called on the main thread at commit with
// the computed pieces, before anything is created. This one sends the upper piece up at 3 m/s and
// renames the lower one; a handler may also drop or add pieces, or keep the original whole.
#include <cstdio>

#include "crate_scene.h"

int main() {
  using namespace cleave;
  examples::CrateScene scene;
  auto printVelocities = [&scene](app::TickContext& c, const std::vector<components::SplitEvent>& events) {
    for (const components::SplitEvent& ev : events) {
      for (ecs::Entity piece : ev.pieces) {
        const auto& name = c.world.get<ecs::Name>(piece);
        const auto state = scene.sim->physics().bodyState(c.world.get<components::RigidBody>(piece).body);
        std::printf("%s: vertical velocity %.2f m/s\n", name.value.c_str(), state ? state->linearVelocity.y : 0.f);
      }
    }
  };
  if (!scene.start(30, printVelocities)) return 1;
  scene.sim->splits().registerHandler("kick-up", [](const components::SplitJob&, components::SplitOutcome& out) {
    for (components::PieceSpec& piece : out.pieces) {
      // The added velocity (world frame): at commit a piece moves with the parent's motion then,
      // plus this.
      if (piece.side > 0) {
        piece.impulse += glm::dvec3(0.0, 3.0, 0.0);
      } else {
        piece.name = "lower half";
      }
    }
    return components::HandlerDecision::Commit;
  });
  scene.app.world().get<components::Splitable>(scene.crate).handler = "kick-up";
  // A level cut through the crate's middle at tick 5.
  scene.addBladeAt(5, glm::vec3(0.f, 0.5f, 0.f), glm::quat(1.f, 0.f, 0.f, 0.f));
  return scene.app.run();
}
