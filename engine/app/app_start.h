// SPDX-License-Identifier: MIT
// The start of a game's main(): its command line parsed, --version and --help answered, the App
// initialised. Both games start this way; so can a developer's own.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cleave/app/app.h"
#include "cleave/app/app_options.h"

namespace cleave::app {

struct AppStart {
  const char* program = "cleave";  // for messages and --version: "<program> <version>"
  const char* title = "Cleave";    // the window's title
  const char* scene = "";          // AppOptions::sceneName
  std::vector<std::pair<std::string, int>> gameOptions;  // the game's own options and their values
  std::string gameHelp;  // printed after the engine's options by --help (the game's options, keys)
};

// Parses argv into `options` and initialises `app`. Returns the exit code main should return now
// (0 after --version or --help, 2 for a bad option, 1 when the App cannot start, each with its line
// printed), or nothing when the game should go on.
std::optional<int> startApp(int argc, const char* const* argv, const AppStart& start, AppOptions& options, App& app);

}  // namespace cleave::app
