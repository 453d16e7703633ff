// SPDX-License-Identifier: MIT
#include "cleave/app/app_options.h"

#include <charconv>
#include <cstdlib>
#include <cstring>

namespace cleave::app {

namespace {

bool parseInt(const std::string& text, int64_t& value) {
  const char* begin = text.data();
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(begin, end, value);
  return ec == std::errc() && ptr == end;
}

// "auto" (0) or a number in [0.25, 1].
bool parseRenderScale(const std::string& text, float& scale) {
  if (text == "auto") {
    scale = 0.f;
    return true;
  }
  char* end = nullptr;
  const float v = std::strtof(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !(v >= 0.25f && v <= 1.f)) return false;
  scale = v;
  return true;
}

}  // namespace

std::string appOptionsUsage() {
  return "engine options:\n"
         "  --version                  print the version and exit\n"
         "  --headless                 no window; ticks run as fast as they can\n"
         "  --replay FILE              play the input recorded in FILE\n"
         "  --record FILE              record this run's input to FILE\n"
         "  --scene FILE.json          load a data-driven scene\n"
         "  --ticks N                  stop after N ticks\n"
         "  --screenshot-dir DIR       write PNG screenshots to DIR\n"
         "  --screenshot-every N       a screenshot every N ticks\n"
         "  --dump-state FILE          write the entity state as JSON lines\n"
         "  --dump-every N             one state line every N ticks (default: last tick only)\n"
         "  --print-state-hash         print the final state hash\n"
         "  --resource-report          after the run, destroy every entity and print the bodies,\n"
         "                             shapes, joints, triggers and GPU meshes left, next to the\n"
         "                             figures from before the game was set up (leak check)\n"
         "  --width W --height H       frame size in pixels (default 1280x720)\n"
         "  --seed N                   seed for the scene's random choices\n"
         "  --render-scale S|auto      draw the 3D scene at S x the frame size (0.25 to 1) and the\n"
         "                             HUD at full size; auto (default): 0.35 to 0.6 by the frame\n"
         "                             time in a window on a software rasteriser (llvmpipe), else 1\n"
         "  --split-threads N          worker threads for split jobs (0: on the main thread;\n"
         "                             default: hardware threads minus one); results are the same\n";
}

ParseResult parseAppOptions(int argc, const char* const* argv, AppOptions& out,
                            const std::vector<std::pair<std::string, int>>& gameOptions) {
  ParseResult result;
  auto fail = [&](const std::string& message) {
    result.ok = false;
    result.error = message;
    return result;
  };
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&](std::string& into) -> bool {
      if (i + 1 >= argc) return false;
      into = argv[++i];
      return true;
    };
    auto number = [&](int64_t& into, int64_t minimum) -> bool {
      std::string text;
      if (!value(text)) return false;
      int64_t v = 0;
      if (!parseInt(text, v) || v < minimum) return false;
      into = v;
      return true;
    };
    if (arg == "--help" || arg == "-h") {
      result.helpRequested = true;
    } else if (arg == "--version") {
      result.versionRequested = true;
    } else if (arg == "--headless") {
      out.headless = true;
    } else if (arg == "--print-state-hash") {
      out.printStateHash = true;
    } else if (arg == "--resource-report") {
      out.resourceReport = true;
    } else if (arg == "--replay") {
      if (!value(out.replayPath)) return fail("--replay needs a file name");
    } else if (arg == "--record") {
      if (!value(out.recordPath)) return fail("--record needs a file name");
    } else if (arg == "--scene") {
      if (!value(out.scenePath)) return fail("--scene needs a file name");
    } else if (arg == "--screenshot-dir") {
      if (!value(out.screenshotDir)) return fail("--screenshot-dir needs a directory");
    } else if (arg == "--dump-state") {
      if (!value(out.dumpStatePath)) return fail("--dump-state needs a file name");
    } else if (arg == "--ticks") {
      if (!number(out.ticks, 0)) return fail("--ticks needs a whole number >= 0");
    } else if (arg == "--screenshot-every") {
      if (!number(out.screenshotEvery, 1)) return fail("--screenshot-every needs a whole number >= 1");
    } else if (arg == "--dump-every") {
      if (!number(out.dumpEvery, 1)) return fail("--dump-every needs a whole number >= 1");
    } else if (arg == "--width" || arg == "--height") {
      int64_t v = 0;
      if (!number(v, 16) || v > 8192) return fail(arg + " needs a size from 16 to 8192 pixels");
      (arg == "--width" ? out.width : out.height) = int(v);
    } else if (arg == "--seed") {
      int64_t v = 0;
      if (!number(v, 0)) return fail("--seed needs a whole number >= 0");
      out.seed = uint64_t(v);
    } else if (arg == "--render-scale") {
      std::string text;
      if (!value(text) || !parseRenderScale(text, out.renderScale))
        return fail("--render-scale needs 'auto' or a number from 0.25 to 1");
    } else if (arg == "--split-threads") {
      int64_t v = 0;
      if (!number(v, 0) || v > 64) return fail("--split-threads needs a whole number from 0 to 64");
      out.splitThreads = int(v);
    } else {
      bool known = false;
      for (const auto& [name, count] : gameOptions) {
        if (arg != name) continue;
        known = true;
        out.extra.push_back(arg);
        for (int k = 0; k < count; ++k) {
          if (i + 1 >= argc) return fail(arg + " needs " + std::to_string(count) + " value(s)");
          out.extra.push_back(argv[++i]);
        }
      }
      if (!known) return fail("unknown option '" + arg + "' (see --help)");
    }
  }
  return result;
}

}  // namespace cleave::app
