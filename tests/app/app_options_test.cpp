// SPDX-License-Identifier: MIT
// The engine's command line (engine/app/app_options.h): every option sets what it names, values are
// checked against their ranges with a message naming the option, the game's own options are passed
// through with their values, and anything else is refused.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cleave/app/app_options.h"

namespace cleave::app {
namespace {

struct Parsed {
  ParseResult result;
  AppOptions options;
};

Parsed parse(std::vector<const char*> args, const std::vector<std::pair<std::string, int>>& game = {}) {
  args.insert(args.begin(), "cleave-test");
  Parsed p;
  p.result = parseAppOptions(int(args.size()), args.data(), p.options, game);
  return p;
}

TEST(AppOptions, EveryOptionSetsWhatItNames) {
  const Parsed p = parse({"--headless", "--inspector", "--print-state-hash", "--resource-report", "--replay", "r.replay", "--record",
                          "out.replay", "--scene", "s.json", "--screenshot-dir", "shots", "--dump-state", "d.jsonl",
                          "--ticks", "120", "--screenshot-every", "30", "--dump-every", "10", "--width", "640",
                          "--height", "360", "--seed", "7", "--render-scale", "0.5", "--split-threads", "0"});
  ASSERT_TRUE(p.result.ok()) << p.result.message;
  const AppOptions& o = p.options;
  EXPECT_TRUE(o.headless);
  EXPECT_TRUE(o.inspector);
  EXPECT_TRUE(o.printStateHash);
  EXPECT_TRUE(o.resourceReport);
  EXPECT_EQ(o.replayPath, "r.replay");
  EXPECT_EQ(o.recordPath, "out.replay");
  EXPECT_EQ(o.scenePath, "s.json");
  EXPECT_EQ(o.screenshotDir, "shots");
  EXPECT_EQ(o.dumpStatePath, "d.jsonl");
  EXPECT_EQ(o.ticks, 120);
  EXPECT_EQ(o.screenshotEvery, 30);
  EXPECT_EQ(o.dumpEvery, 10);
  EXPECT_EQ(o.width, 640);
  EXPECT_EQ(o.height, 360);
  EXPECT_EQ(o.seed, 7u);
  EXPECT_FLOAT_EQ(o.renderScale, 0.5f);
  EXPECT_EQ(o.splitThreads, 0);
  EXPECT_FALSE(p.result.helpRequested);
  EXPECT_FALSE(p.result.versionRequested);
}

TEST(AppOptions, DefaultsWithoutOptionsAndHelpAndVersionAreRequests) {
  const Parsed none = parse({});
  ASSERT_TRUE(none.result.ok());
  EXPECT_FALSE(none.options.headless);
  EXPECT_EQ(none.options.width, 1280);
  EXPECT_EQ(none.options.ticks, -1);
  EXPECT_TRUE(parse({"--help"}).result.helpRequested);
  EXPECT_TRUE(parse({"-h"}).result.helpRequested);
  EXPECT_TRUE(parse({"--version"}).result.versionRequested);
  EXPECT_FLOAT_EQ(parse({"--render-scale", "auto"}).options.renderScale, 0.f);
}

TEST(AppOptions, BadValuesAreRefusedWithTheOptionNamed) {
  struct Case {
    std::vector<const char*> args;
    std::string message;
  };
  const Case cases[] = {
      {{"--replay"}, "--replay needs a file name"},
      {{"--ticks", "-1"}, "--ticks needs a whole number >= 0"},
      {{"--ticks", "12x"}, "--ticks needs a whole number >= 0"},
      {{"--screenshot-every", "0"}, "--screenshot-every needs a whole number >= 1"},
      {{"--dump-every"}, "--dump-every needs a whole number >= 1"},
      {{"--width", "15"}, "--width needs a size from 16 to 8192 pixels"},
      {{"--height", "8193"}, "--height needs a size from 16 to 8192 pixels"},
      {{"--seed", "x"}, "--seed needs a whole number >= 0"},
      {{"--render-scale", "0.2"}, "--render-scale needs 'auto' or a number from 0.25 to 1"},
      {{"--render-scale", "1.5"}, "--render-scale needs 'auto' or a number from 0.25 to 1"},
      {{"--split-threads", "65"}, "--split-threads needs a whole number from 0 to 64"},
      {{"--frobnicate"}, "unknown option '--frobnicate' (see --help)"},
  };
  for (const Case& c : cases) {
    const Parsed p = parse(c.args);
    EXPECT_FALSE(p.result.ok()) << c.message;
    EXPECT_EQ(p.result.message, c.message);
  }
}

TEST(AppOptions, GameOptionsPassThroughWithTheirValues) {
  const Parsed p = parse({"--bench-splits", "20", "--headless", "--quiet"}, {{"--bench-splits", 1}, {"--quiet", 0}});
  ASSERT_TRUE(p.result.ok()) << p.result.message;
  EXPECT_TRUE(p.options.headless);
  EXPECT_EQ(p.options.extra, (std::vector<std::string>{"--bench-splits", "20", "--quiet"}));
  const Parsed missing = parse({"--bench-splits"}, {{"--bench-splits", 1}});
  EXPECT_FALSE(missing.result.ok());
  EXPECT_EQ(missing.result.message, "--bench-splits needs 1 value(s)");
}

}  // namespace
}  // namespace cleave::app
