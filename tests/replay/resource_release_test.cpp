// SPDX-License-Identifier: MIT
// Entities own what their components hold: every bundled replay (assets/replays/*.replay, the demo's
// through cleave-demo, the arena's through cleave-arena, chosen by the replay's scene line) is played
// headless with --resource-report, which destroys every entity after the last tick and prints the
// bodies, shapes, joints, triggers and GPU meshes left next to the figures from before the game was
// set up. Anything a destroy hook missed (resource_hooks.h) is left over and fails the test. The run
// must also end in its recorded state: the report changes nothing before it.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/support/executable_run.h"

namespace {

namespace fs = std::filesystem;

const std::string kBin = std::string(CLEAVE_BINARY_DIR) + "/bin/";
const fs::path kReplays = fs::path(CLEAVE_SOURCE_DIR) / "assets" / "replays";

// The text after "<key>: " on the line that starts with it ("" when absent).
std::string lineAfter(const std::string& output, const std::string& key) {
  const std::string prefix = key + ": ";
  size_t at = output.rfind(prefix);
  if (at == std::string::npos || (at > 0 && output[at - 1] != '\n')) return {};
  at += prefix.size();
  return output.substr(at, output.find('\n', at) - at);
}

// The word after "scene " in a replay's header ("" when it has none).
std::string sceneOf(const fs::path& replay) {
  std::ifstream in(replay);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("scene ", 0) == 0) return line.substr(6);
  return {};
}

std::vector<fs::path> bundledReplays() {
  std::vector<fs::path> replays;
  for (const auto& entry : fs::directory_iterator(kReplays))
    if (entry.path().extension() == ".replay") replays.push_back(entry.path());
  std::sort(replays.begin(), replays.end());
  return replays;
}

TEST(ResourceRelease, LineParsingFindsOnlyWholeLines) {
  EXPECT_EQ(lineAfter("x\nresources-after: bodies=1\n", "resources-after"), "bodies=1");
  EXPECT_EQ(lineAfter("no-resources-after: bodies=1\n", "resources-after"), "");
  EXPECT_EQ(lineAfter("nothing\n", "resources-after"), "");
}

TEST(ResourceRelease, EveryBundledReplayLeavesNothingBehindItsEntities) {
  const std::vector<fs::path> replays = bundledReplays();
  ASSERT_GE(replays.size(), 9u) << "bundled replays missing from " << kReplays;
  for (const fs::path& replay : replays) {
    SCOPED_TRACE(replay.filename().string());
    const std::string scene = sceneOf(replay);
    ASSERT_TRUE(scene == "demo" || scene == "arena") << "unknown scene '" << scene << "'";
    const cleave::testing::RunResult r = cleave::testing::runExecutable(
        kBin + "cleave-" + scene, "--headless --replay \"" + replay.string() + "\" --print-state-hash --resource-report");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::string before = lineAfter(r.output, "resources-before");
    const std::string after = lineAfter(r.output, "resources-after");
    ASSERT_NE(before.find("bodies=0 shapes=0 joints=0 triggers=0"), std::string::npos) << r.output;
    ASSERT_FALSE(after.empty()) << r.output;
    std::printf("[resources] %s: before %s, after %s\n", replay.filename().c_str(), before.c_str(), after.c_str());
    EXPECT_EQ(after, before) << "left over after every entity was destroyed";
    cleave::testing::expectRecordedStateHash(replay.filename().string(), cleave::testing::stateHash(r.output));
  }
}

}  // namespace
