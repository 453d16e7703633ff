// SPDX-License-Identifier: MIT
// Command-line options shared by every Cleave executable that runs the engine loop (the tech demo,
// the arena, the replay runner).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cleave/base/status.h"

namespace cleave::app {

struct AppOptions {
  bool headless = false;           // --headless: no window, ticks as fast as possible
  std::string replayPath;          // --replay FILE: input comes from a recorded replay
  std::string recordPath;          // --record FILE: write the input of this run as a replay
  std::string scenePath;           // --scene FILE.json: data-driven scene instead of the built-in one
  int64_t ticks = -1;              // --ticks N: stop after N ticks (-1: replay length, or forever in a window)
  std::string screenshotDir;       // --screenshot-dir DIR: write PNG screenshots there
  int64_t screenshotEvery = 0;     // --screenshot-every N: a screenshot every N ticks (0: replay marks + last)
  std::string dumpStatePath;       // --dump-state FILE: JSON lines of the entity state
  int64_t dumpEvery = 0;           // --dump-every N: a line every N ticks (0: only the last tick)
  bool printStateHash = false;     // --print-state-hash: print the final state hash
  bool resourceReport = false;     // --resource-report: after the run, destroy every entity and print
                                   // what physics and the renderer hold, before setup and after
  int width = 1280;                // --width, --height: window or offscreen size in pixels
  int height = 720;
  uint64_t seed = 1;               // --seed N: for anything random in the scene
  int splitThreads = -1;           // --split-threads N: split worker threads (-1: the engine's default)
  float renderScale = 0.f;         // --render-scale S: the 3D scene drawn at S x the frame size (0.25 to
                                   // 1), the HUD at full size; 0 (auto): in a window on a CPU
                                   // rasteriser (llvmpipe, ...) a dynamic scale from 0.35 to 0.6 by
                                   // the frame time (render/dynamic_scale.h), 1 otherwise
  bool inspector = false;          // --inspector: the game opens its inspector (F1) at start
  std::string sceneName = "default";  // the scene word written into recorded replays (set by the game)
  std::vector<std::string> extra;  // arguments the engine does not know, for the game to read
};

// A Status (InvalidArgument with a message naming the option and the reason) and what was asked.
struct ParseResult : base::Status {
  bool helpRequested = false;
  bool versionRequested = false;  // --version: print the name and kVersion (cleave_version.h), exit
};

// Parses argv[1..argc). Unknown options starting with "--" that the caller lists in `gameOptions`
// (with their value count) go to `extra`; anything else unknown is an error.
ParseResult parseAppOptions(int argc, const char* const* argv, AppOptions& out,
                            const std::vector<std::pair<std::string, int>>& gameOptions = {});

// The usage text for the engine options.
std::string appOptionsUsage();

}  // namespace cleave::app
