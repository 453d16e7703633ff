// SPDX-License-Identifier: MIT
// cleave-arena: the gladiator arena sample. In a window: click the Start cube, then WASD to move,
// the mouse to aim, left button for the sword, right button for the disc, Space for a spin attack.
// Headless: plays a replay and writes screenshots and state dumps (see --help).
#include <cstdio>
#include <string>

#include "cleave_version.h"
#include "cleave/app/app.h"
#include "game/arena/arena_game.h"

int main(int argc, char** argv) {
  cleave::app::AppOptions options;
  options.sceneName = "arena";
  const auto parsed = cleave::app::parseAppOptions(argc, argv, options);
  if (!parsed.ok) {
    std::fprintf(stderr, "cleave-arena: %s\n", parsed.error.c_str());
    return 2;
  }
  if (parsed.versionRequested) {
    std::printf("cleave-arena %s\n", cleave::kVersion);
    return 0;
  }
  if (parsed.helpRequested) {
    std::printf("usage: cleave-arena [options]\n\n%s", cleave::app::appOptionsUsage().c_str());
    std::printf("\nkeys: click START (or QUIT) to begin; WASD move, mouse aim, left button sword, right button\n"
                "  disc, Space spin, Enter back to the menu after a defeat, F1 inspector\n");
    return 0;
  }
  cleave::app::App app;
  std::string error;
  if (!app.init(options, "Cleave arena", &error)) {
    std::fprintf(stderr, "cleave-arena: %s\n", error.c_str());
    return 1;
  }
  cleave::arena::ArenaGame game;
  // Before setup: the game's physics world does not exist yet (a new one holds nothing).
  const cleave::components::ResourceCounts before = cleave::components::countResources(nullptr, &app.renderer());
  if (!game.setup(app, &error)) {
    std::fprintf(stderr, "cleave-arena: %s\n", error.c_str());
    return 1;
  }
  const int code = app.run();
  if (options.resourceReport) {
    // Every entity goes, and with it (through its destroy hooks) what it held: what is left leaked.
    game.releaseAll();
    std::printf("resources-before: %s\nresources-after: %s\n", cleave::components::toString(before).c_str(),
                cleave::components::toString(game.resources()).c_str());
  }
  return code;
}
