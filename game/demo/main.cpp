// SPDX-License-Identifier: MIT
// cleave-demo: the tech demo. In a window: WASD, mouse look, hold Space and drag to cut. Headless:
// plays a replay and writes screenshots (see --help).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>

#include "cleave/app/app.h"
#include "cleave/app/app_start.h"
#include "game/demo/demo_game.h"

int main(int argc, char** argv) {
  cleave::app::AppStart start;
  start.program = "cleave-demo";
  start.title = "Cleave tech demo";
  start.scene = "demo";
  start.gameOptions = {{"--bench-splits", 1}, {"--bench-burst", 0}, {"--bench-session", 1}, {"--no-piece-budget", 0},
                       {"--json", 0}};
  start.gameHelp =
      "demo options:\n"
      "  --bench-splits N           cut each demo object N times, print median stage times\n"
      "  --bench-burst              cut 50 cubes, then 100 characters, each lot in one tick\n"
      "  --bench-session MINUTES    blades sweep 225 objects for MINUTES, then 30 s of quiet; per-minute\n"
      "                             pieces, tick p50/p99/max, physics and split time, memory\n"
      "  --no-piece-budget          retire no pieces (the piece budget off), to see what it buys\n"
      "  --json                     benchmarks print JSON instead of a table\n\n"
      "keys: WASD move, mouse look, hold Space and drag to cut, right button push, F shatter,\n"
      "  1-8 spawn, Q/E material, H help, F1 inspector, Esc free the mouse (twice: quit)\n";
  cleave::app::AppOptions options;
  cleave::app::App app;
  if (const std::optional<int> code = cleave::app::startApp(argc, argv, start, options, app)) return *code;
  cleave::demo::DemoGame game;
  // Before setup: the game's physics world does not exist yet (a new one holds nothing).
  const cleave::components::ResourceCounts before = cleave::components::countResources(nullptr, &app.renderer());
  if (const cleave::base::Status ready = game.setup(app); !ready.ok()) {
    std::fprintf(stderr, "cleave-demo: %s\n", ready.message.c_str());
    return 1;
  }
  const auto& extra = options.extra;
  const bool json = std::find(extra.begin(), extra.end(), "--json") != extra.end();
  if (std::find(extra.begin(), extra.end(), "--no-piece-budget") != extra.end()) {
    cleave::components::PieceBudgetSettings off = game.splits().pieces().settings();
    off.enabled = false;
    game.splits().pieces().setSettings(off);
  }
  for (size_t i = 0; i < extra.size(); ++i) {
    if (extra[i] == "--bench-session" && i + 1 < extra.size()) {
      const int minutes = std::atoi(extra[i + 1].c_str());
      if (minutes <= 0) {
        std::fprintf(stderr, "cleave-demo: --bench-session needs a positive number of minutes\n");
        return 2;
      }
      game.benchmarkSession(minutes, json);
      return 0;
    }
    if (extra[i] == "--bench-burst") {
      game.benchmarkBurst(json);
      return 0;
    }
    if (extra[i] != "--bench-splits" || i + 1 >= extra.size()) continue;
    const int repeats = std::atoi(extra[i + 1].c_str());
    if (repeats <= 0) {
      std::fprintf(stderr, "cleave-demo: --bench-splits needs a positive count\n");
      return 2;
    }
    game.benchmarkSplits(repeats, json);
    return 0;
  }
  // Mouse look from the start (the game frees the cursor for split mode, Escape and the inspector).
  if (!app.platform().headless()) app.platform().setCursorMode(cleave::app::CursorMode::Captured);
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
