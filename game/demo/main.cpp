// cleave-demo: the tech demo. In a window: WASD, mouse look, hold Space and drag to cut. Headless:
// plays a replay and writes screenshots (see --help).
#include <cstdio>
#include <cstdlib>
#include <string>

#include "engine/app/app.h"
#include "game/demo/demo_game.h"

int main(int argc, char** argv) {
  cleave::app::AppOptions options;
  options.sceneName = "demo";
  const auto parsed = cleave::app::parseAppOptions(argc, argv, options, {{"--bench-splits", 1}});
  if (!parsed.ok) {
    std::fprintf(stderr, "cleave-demo: %s\n", parsed.error.c_str());
    return 2;
  }
  if (parsed.helpRequested) {
    std::printf("usage: cleave-demo [options]\n\n%s", cleave::app::appOptionsUsage().c_str());
    return 0;
  }
  cleave::app::App app;
  std::string error;
  if (!app.init(options, "Cleave tech demo", &error)) {
    std::fprintf(stderr, "cleave-demo: %s\n", error.c_str());
    return 1;
  }
  cleave::demo::DemoGame game;
  if (!game.setup(app, &error)) {
    std::fprintf(stderr, "cleave-demo: %s\n", error.c_str());
    return 1;
  }
  for (size_t i = 0; i + 1 < options.extra.size(); ++i) {
    if (options.extra[i] != "--bench-splits") continue;
    const int repeats = std::atoi(options.extra[i + 1].c_str());
    if (repeats <= 0) {
      std::fprintf(stderr, "cleave-demo: --bench-splits needs a positive count\n");
      return 2;
    }
    game.benchmarkSplits(repeats);
    return 0;
  }
  if (!app.platform().headless()) app.platform().setCursorMode(cleave::app::CursorMode::Captured);
  return app.run();
}
