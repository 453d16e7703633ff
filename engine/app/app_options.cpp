// SPDX-License-Identifier: MIT
#include "cleave/app/app_options.h"

#include <charconv>
#include <cstdint>
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
         "                             default: hardware threads minus one); results are the same\n"
         "  --inspector                open the inspector (F1) at start: the Splitable under the\n"
         "                             crosshair, the split budget, the split log (Dear ImGui)\n";
}

namespace {

// One engine option: its name, whether a value follows, the message when the value is missing or
// refused, and what it sets (false: the value is refused).
struct OptionSpec {
  const char* name;
  bool takesValue;
  const char* need;
  bool (*apply)(const std::string& value, AppOptions& out, ParseResult& result);
};

bool wholeNumber(const std::string& text, int64_t lowest, int64_t highest, int64_t& value) {
  return parseInt(text, value) && value >= lowest && value <= highest;
}

constexpr int64_t kAny = INT64_MAX;

const OptionSpec kOptions[] = {
    {"--help", false, "", [](const std::string&, AppOptions&, ParseResult& r) { return r.helpRequested = true; }},
    {"-h", false, "", [](const std::string&, AppOptions&, ParseResult& r) { return r.helpRequested = true; }},
    {"--version", false, "", [](const std::string&, AppOptions&, ParseResult& r) { return r.versionRequested = true; }},
    {"--headless", false, "", [](const std::string&, AppOptions& o, ParseResult&) { return o.headless = true; }},
    {"--inspector", false, "", [](const std::string&, AppOptions& o, ParseResult&) { return o.inspector = true; }},
    {"--print-state-hash", false, "",
     [](const std::string&, AppOptions& o, ParseResult&) { return o.printStateHash = true; }},
    {"--resource-report", false, "",
     [](const std::string&, AppOptions& o, ParseResult&) { return o.resourceReport = true; }},
    {"--replay", true, "--replay needs a file name",
     [](const std::string& v, AppOptions& o, ParseResult&) { return o.replayPath = v, true; }},
    {"--record", true, "--record needs a file name",
     [](const std::string& v, AppOptions& o, ParseResult&) { return o.recordPath = v, true; }},
    {"--scene", true, "--scene needs a file name",
     [](const std::string& v, AppOptions& o, ParseResult&) { return o.scenePath = v, true; }},
    {"--screenshot-dir", true, "--screenshot-dir needs a directory",
     [](const std::string& v, AppOptions& o, ParseResult&) { return o.screenshotDir = v, true; }},
    {"--dump-state", true, "--dump-state needs a file name",
     [](const std::string& v, AppOptions& o, ParseResult&) { return o.dumpStatePath = v, true; }},
    {"--ticks", true, "--ticks needs a whole number >= 0",
     [](const std::string& v, AppOptions& o, ParseResult&) { return wholeNumber(v, 0, kAny, o.ticks); }},
    {"--screenshot-every", true, "--screenshot-every needs a whole number >= 1",
     [](const std::string& v, AppOptions& o, ParseResult&) { return wholeNumber(v, 1, kAny, o.screenshotEvery); }},
    {"--dump-every", true, "--dump-every needs a whole number >= 1",
     [](const std::string& v, AppOptions& o, ParseResult&) { return wholeNumber(v, 1, kAny, o.dumpEvery); }},
    {"--width", true, "--width needs a size from 16 to 8192 pixels",
     [](const std::string& v, AppOptions& o, ParseResult&) {
       int64_t n = 0;
       return wholeNumber(v, 16, 8192, n) && (o.width = int(n), true);
     }},
    {"--height", true, "--height needs a size from 16 to 8192 pixels",
     [](const std::string& v, AppOptions& o, ParseResult&) {
       int64_t n = 0;
       return wholeNumber(v, 16, 8192, n) && (o.height = int(n), true);
     }},
    {"--seed", true, "--seed needs a whole number >= 0",
     [](const std::string& v, AppOptions& o, ParseResult&) {
       int64_t n = 0;
       return wholeNumber(v, 0, kAny, n) && (o.seed = uint64_t(n), true);
     }},
    {"--render-scale", true, "--render-scale needs 'auto' or a number from 0.25 to 1",
     [](const std::string& v, AppOptions& o, ParseResult&) { return parseRenderScale(v, o.renderScale); }},
    {"--split-threads", true, "--split-threads needs a whole number from 0 to 64",
     [](const std::string& v, AppOptions& o, ParseResult&) {
       int64_t n = 0;
       return wholeNumber(v, 0, 64, n) && (o.splitThreads = int(n), true);
     }},
};

const OptionSpec* findOption(const std::string& name) {
  for (const OptionSpec& spec : kOptions) {
    if (name == spec.name) return &spec;
  }
  return nullptr;
}

}  // namespace

ParseResult parseAppOptions(int argc, const char* const* argv, AppOptions& out,
                            const std::vector<std::pair<std::string, int>>& gameOptions) {
  ParseResult result;
  auto fail = [&](const std::string& message) {
    result.setFailure(base::StatusCode::InvalidArgument, message);
    return result;
  };
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (const OptionSpec* spec = findOption(arg)) {
      std::string value;
      if (spec->takesValue) {
        if (i + 1 >= argc) return fail(spec->need);
        value = argv[++i];
      }
      if (!spec->apply(value, out, result)) return fail(spec->need);
      continue;
    }
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
  return result;
}

}  // namespace cleave::app
