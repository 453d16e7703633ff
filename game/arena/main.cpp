// SPDX-License-Identifier: MIT
// cleave-arena: the gladiator arena sample. In a window: click the Start cube, then WASD to move,
// the mouse to aim, left button for the sword, right button for the disc, Space for a spin attack,
// E for the hammer.
// Headless: plays a replay and writes screenshots and state dumps (see --help).
#include <cstdio>
#include <optional>
#include <string>

#include "cleave/app/app.h"
#include "cleave/app/app_start.h"
#include "game/arena/arena_game.h"

int main(int argc, char** argv) {
  cleave::app::AppStart start;
  start.program = "cleave-arena";
  start.title = "Cleave arena";
  start.scene = "arena";
  start.gameHelp =
      "\nkeys: click START (or QUIT) to begin; WASD move, mouse aim, left button sword, right button\n"
      "  disc, Space spin, E hammer, Enter back to the menu after a defeat, F1 inspector\n";
  cleave::app::AppOptions options;
  cleave::app::App app;
  if (const std::optional<int> code = cleave::app::startApp(argc, argv, start, options, app)) return *code;
  cleave::arena::ArenaGame game;
  // Before setup: the game's physics world does not exist yet (a new one holds nothing).
  const cleave::components::ResourceCounts before = cleave::components::countResources(nullptr, &app.renderer());
  if (const cleave::base::Status ready = game.setup(app); !ready.ok()) {
    std::fprintf(stderr, "cleave-arena: %s\n", ready.message.c_str());
    return 1;
  }
  const int code = app.run();
  // Beside the state hash: a run on N split threads shows its workers computed jobs.
  if (options.printStateHash)
    std::printf("split-jobs-off-main-thread: %llu\n", static_cast<unsigned long long>(game.splitJobsOffMainThread()));
  if (options.resourceReport) {
    // Every entity goes, and with it (through its destroy hooks) what it held: what is left leaked.
    game.releaseAll();
    std::fputs(cleave::components::resourceReport(before, game.resources()).c_str(), stdout);
  }
  return code;
}
