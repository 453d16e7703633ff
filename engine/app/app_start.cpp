// SPDX-License-Identifier: MIT
#include "cleave/app/app_start.h"

#include <cstdio>

#include "cleave_version.h"

namespace cleave::app {

std::optional<int> startApp(int argc, const char* const* argv, const AppStart& start, AppOptions& options, App& app) {
  options.sceneName = start.scene;
  const ParseResult parsed = parseAppOptions(argc, argv, options, start.gameOptions);
  if (!parsed.ok()) {
    std::fprintf(stderr, "%s: %s\n", start.program, parsed.message.c_str());
    return 2;
  }
  if (parsed.versionRequested) {
    std::printf("%s %s\n", start.program, kVersion);
    return 0;
  }
  if (parsed.helpRequested) {
    std::printf("usage: %s [options]\n\n%s%s", start.program, appOptionsUsage().c_str(), start.gameHelp.c_str());
    return 0;
  }
  if (const base::Status started = app.init(options, start.title); !started.ok()) {
    std::fprintf(stderr, "%s: %s\n", start.program, started.message.c_str());
    return 1;
  }
  return std::nullopt;
}

}  // namespace cleave::app
