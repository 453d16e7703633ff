// SPDX-License-Identifier: MIT
// The tech demo's bundled replays, run headless through the real executable: final state
// (pieces, mass kept by every cut, nothing lost through the floor), determinism (two runs and a
// recorded-then-replayed run give the same state hash), bad replay files, and golden frames.
#include <gtest/gtest.h>
#include <gtest/gtest-spi.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cleave/render/renderer.h"
#include "tests/render/image_compare.h"
#include "tests/support/executable_run.h"

namespace {

namespace fs = std::filesystem;

const std::string kDemo = std::string(CLEAVE_BINARY_DIR) + "/bin/cleave-demo";
const std::string kReplays = std::string(CLEAVE_SOURCE_DIR) + "/assets/replays";

using cleave::testing::expectEveryCutKeepsMass;
using cleave::testing::lastDumpLine;
using cleave::testing::RunResult;
using cleave::testing::stateHash;

RunResult run(const std::string& arguments) { return cleave::testing::runExecutable(kDemo, arguments); }

fs::path scratchDir(const std::string& name) { return cleave::testing::scratchDir("replay", name); }

// No entity lost: every position finite, and no body through the floor (top at y = 0): the lowest
// point of every mesh with mass lies above the floor's top, within 7 cm. That much is the collider's
// doing, not a fall: the collider of a round piece is a hull of at most 48 of its vertices, inside
// its surface, so the metal sphere (radius 0.5) and its pieces rest up to 6 cm into the floor.
void expectNothingLost(const nlohmann::json& dump) {
  size_t checked = 0;
  for (const auto& e : dump.at("entities")) {
    for (int k = 0; k < 3; ++k) ASSERT_TRUE(std::isfinite(e.at("position")[k].get<double>())) << e.dump();
    if (!e.contains("mass") || !e.contains("lowest_y")) continue;
    ++checked;
    EXPECT_GT(e.at("lowest_y").get<double>(), -0.07) << "through the floor: " << e.dump();
  }
  EXPECT_GT(checked, 0u) << "no body with a rigid mesh in the dump";
}

size_t countPieces(const nlohmann::json& dump) {
  size_t pieces = 0;
  for (const auto& e : dump.at("entities"))
    if (e.contains("split_from")) ++pieces;
  return pieces;
}

TEST(DemoReplay, TourCutsEveryObjectAndKeepsMass) {
  const fs::path dir = scratchDir("tour");
  const RunResult r = run("--headless --replay \"" + kReplays + "/demo_tour.replay\" --dump-state \"" +
                          (dir / "state.jsonl").string() + "\" --print-state-hash");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const nlohmann::json dump = lastDumpLine(dir / "state.jsonl");
  ASSERT_TRUE(dump.is_object());
  EXPECT_EQ(dump.at("tick"), 899);
  expectEveryCutKeepsMass(dump);
  expectNothingLost(dump);

  // Every one of the seven objects (the walking character included) was cut at least once, some
  // pieces were cut again, and the spawned objects were cut by the final sweep.
  std::vector<std::string> originals;
  size_t piecesOfPieces = 0;
  for (const auto& split : dump.at("splits")) {
    const std::string name = split.at("original");
    if (name.find('/') != std::string::npos) ++piecesOfPieces;
    originals.push_back(name.substr(0, name.find('/')));
  }
  for (const char* object : {"wooden cube", "metal sphere", "marble cylinder", "melon", "figure", "skinned character",
                             "torus"}) {
    EXPECT_NE(std::find(originals.begin(), originals.end(), object), originals.end())
        << object << " was never cut";
  }
  EXPECT_GE(piecesOfPieces, 3u);
  EXPECT_GE(dump.at("splits").size(), 9u);
  EXPECT_GE(countPieces(dump), 14u);
  EXPECT_EQ(dump.at("budget").at("queue"), 0) << "split requests left over at the end";
  // Q/E cycled an object through all seven looks.
  EXPECT_EQ(dump.at("looks_cycled").size(), 7u) << dump.at("looks_cycled").dump();
  EXPECT_EQ(stateHash(r.output).size(), 16u);
}

TEST(DemoReplay, BurstOfCutsIsSpreadByTheBudgetAndKeepsMass) {
  const fs::path dir = scratchDir("burst");
  const RunResult r = run("--headless --replay \"" + kReplays + "/demo_burst.replay\" --dump-state \"" +
                          (dir / "state.jsonl").string() + "\"");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const nlohmann::json dump = lastDumpLine(dir / "state.jsonl");
  expectEveryCutKeepsMass(dump);
  expectNothingLost(dump);
  const auto& budget = dump.at("budget");
  EXPECT_GT(budget.at("deferred_total").get<int>(), 0) << "the burst never had to wait: " << budget.dump();
  EXPECT_GE(budget.at("max_queue").get<int>(), 3) << budget.dump();
  EXPECT_EQ(budget.at("queue"), 0) << "requests left over: " << budget.dump();
  // The replay makes 19 cuts since pieces appear at the commit tick, one tick later (20 before).
  EXPECT_GE(dump.at("splits").size(), 19u);
}

// The positive control of the mass check every replay and arena test runs on its split log: it
// fails on a cut whose pieces miss mass, and on a skinned cut whose pieces' masses add up (as they
// do by construction) while their volumes do not add up to the posed character's.
// The shatter replay: F breaks four objects into cells (split jobs on workers), each keeping its
// mass; nothing falls through the floor; frames written.
TEST(DemoReplay, ShatterBreaksFourObjectsIntoCellsAndKeepsMass) {
  const fs::path dir = scratchDir("shatter");
  const RunResult r = run("--headless --replay \"" + kReplays + "/demo_shatter.replay\" --dump-state \"" +
                          (dir / "state.jsonl").string() + "\" --screenshot-dir \"" + dir.string() + "\"");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const nlohmann::json dump = lastDumpLine(dir / "state.jsonl");
  ASSERT_TRUE(dump.is_object());
  std::vector<std::string> shattered;
  for (const auto& split : dump.at("splits")) {
    EXPECT_GE(split.at("pieces").get<int>(), 10) << split.dump();
    shattered.push_back(split.at("original").get<std::string>());
  }
  const std::vector<std::string> expected = {"marble cylinder", "metal sphere", "wooden cube", "melon"};
  EXPECT_EQ(shattered, expected);
  expectEveryCutKeepsMass(dump);
  expectNothingLost(dump);
  EXPECT_GE(countPieces(dump), 50u);
  EXPECT_TRUE(fs::exists(dir / "frame_000479.png"));
}

TEST(DemoReplay, MassCheckFailsOnLostMassAndOnLostSkinnedVolume) {
  const auto logOf = [](const nlohmann::json& split) {
    nlohmann::json dump;
    dump["splits"] = nlohmann::json::array({split});
    return dump;
  };
  const nlohmann::json whole = {{"status", "Ok"}, {"pieces", 2}, {"parent_mass", 10.0}, {"pieces_mass", 10.0}};
  cleave::testing::expectEveryCutKeepsMass(logOf(whole));
  nlohmann::json lost = whole;
  lost["pieces_mass"] = 9.99;
  EXPECT_NONFATAL_FAILURE(cleave::testing::expectEveryCutKeepsMass(logOf(lost)), "pieces / parent");
  nlohmann::json skinned = whole;
  skinned["posed_volume"] = 0.08;
  skinned["pieces_volume"] = 0.079;
  EXPECT_NONFATAL_FAILURE(cleave::testing::expectEveryCutKeepsMass(logOf(skinned)), "posed_volume");
}

TEST(DemoReplay, SameReplayGivesTheSameState) {
  const std::string args = "--headless --replay \"" + kReplays + "/demo_tour.replay\" --ticks 420 --print-state-hash";
  const RunResult a = run(args);
  // Garbage in fresh and freed memory, addresses not randomized: the same state.
  const RunResult b = cleave::testing::runExecutable(kDemo, args, cleave::testing::kPerturbedRun);
  ASSERT_EQ(a.exitCode, 0) << a.output;
  ASSERT_EQ(b.exitCode, 0) << b.output;
  ASSERT_EQ(stateHash(a.output).size(), 16u) << a.output;
  EXPECT_EQ(stateHash(a.output), stateHash(b.output));
}

TEST(DemoReplay, EveryReplayGivesTheSameStateOnZeroOneAndThreeSplitThreads) {
  cleave::testing::OffMainThread total;
  for (const char* name : {"demo_tour.replay", "demo_burst.replay", "demo_shatter.replay"}) {
    const cleave::testing::OffMainThread off = cleave::testing::expectSameStateOnZeroOneAndThreeSplitThreads(
        run, "--headless --replay \"" + kReplays + "/" + name + "\"", name);
    total.one += off.one;
    total.three += off.three;
  }
  // The threads really ran: the workers computed some of the replays' jobs.
  EXPECT_GT(total.one, 0);
  EXPECT_GT(total.three, 0);
}

TEST(DemoReplay, RecordedRunReplaysToTheSameState) {
  const fs::path dir = scratchDir("record");
  const fs::path recorded = dir / "recorded.replay";
  const RunResult original = run("--headless --replay \"" + kReplays + "/demo_tour.replay\" --ticks 420 --record \"" +
                                 recorded.string() + "\" --print-state-hash");
  ASSERT_EQ(original.exitCode, 0) << original.output;
  ASSERT_TRUE(fs::exists(recorded));
  const RunResult replayed = run("--headless --replay \"" + recorded.string() + "\" --print-state-hash");
  ASSERT_EQ(replayed.exitCode, 0) << replayed.output;
  EXPECT_EQ(stateHash(original.output), stateHash(replayed.output));
}

// Escape frees the mouse, a second Escape quits: a replay of 600 ticks that presses it at ticks 20
// and 40 ends at tick 40, cleanly.
TEST(DemoReplay, EscapeTwiceQuits) {
  const fs::path dir = scratchDir("escape");
  const fs::path replayFile = dir / "escape.replay";
  std::ofstream(replayFile) << "cleave-replay 1\nscene demo\nseed 1\nticks 600\n20 kd:escape\n21 ku:escape\n"
                               "40 kd:escape\n41 ku:escape\n";
  const RunResult r = run("--headless --replay \"" + replayFile.string() + "\" --dump-state \"" +
                          (dir / "state.jsonl").string() + "\"");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const nlohmann::json dump = lastDumpLine(dir / "state.jsonl");
  ASSERT_TRUE(dump.is_object());
  EXPECT_LE(dump.at("tick").get<int>(), 42) << "the second Escape did not quit";
  EXPECT_GE(dump.at("tick").get<int>(), 40) << "the first Escape quit";
}

// Keys 1-7 spawn in front of the player at free spots: five cubes spawned one after another stand
// side by side on the floor (each at least a cube's width from the others), not piled at one point.
TEST(DemoReplay, SpawnedObjectsStandSideBySideInFrontOfThePlayer) {
  const fs::path dir = scratchDir("spawn");
  const fs::path replayFile = dir / "spawn.replay";
  std::ofstream replay(replayFile);
  replay << "cleave-replay 1\nscene demo\nseed 1\nticks 240\n";
  for (int k = 0; k < 5; ++k) replay << 10 + 12 * k << " kd:1\n" << 11 + 12 * k << " ku:1\n";
  replay.close();
  const RunResult r = run("--headless --replay \"" + replayFile.string() + "\" --dump-state \"" +
                          (dir / "state.jsonl").string() + "\"");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const nlohmann::json dump = lastDumpLine(dir / "state.jsonl");
  ASSERT_TRUE(dump.is_object());
  std::vector<std::array<double, 3>> cubes;
  for (const auto& e : dump.at("entities")) {
    if (e.value("name", "") != "wooden cube") continue;
    const auto& p = e.at("position");
    cubes.push_back({p[0].get<double>(), p[1].get<double>(), p[2].get<double>()});
  }
  ASSERT_EQ(cubes.size(), 6u) << "the line-up's cube and five spawned ones";
  // The spawned ones: in front of the camera (it starts at z = 7.5 looking along -z), resting.
  for (size_t a = 1; a < cubes.size(); ++a) {
    EXPECT_LT(cubes[a][2], 5.5) << "cube " << a << " is not in front of the player";
    EXPECT_NEAR(cubes[a][1], 0.5, 0.05) << "cube " << a << " does not stand on the floor";
    for (size_t b = 0; b < a; ++b) {
      const double dx = cubes[a][0] - cubes[b][0], dz = cubes[a][2] - cubes[b][2];
      EXPECT_GT(std::hypot(dx, dz), 1.0) << "cubes " << a << " and " << b << " overlap";
    }
  }
}

// Pieces come to rest and sleep: the burst replay run on for half a minute after its last cut
// leaves no body awake; right after the burst many are (the check sees awake bodies).
TEST(DemoReplay, PiecesSleepOnceTheyComeToRest) {
  const fs::path dir = scratchDir("sleep");
  const RunResult r = run("--headless --replay \"" + kReplays + "/demo_burst.replay\" --ticks 2200 --dump-every 300 "
                          "--dump-state \"" + (dir / "state.jsonl").string() + "\"");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::ifstream in(dir / "state.jsonl");
  std::string line;
  int awakeAfterBurst = -1, awakeAtEnd = -1;
  while (std::getline(in, line)) {
    const nlohmann::json dump = nlohmann::json::parse(line);
    int awake = 0;
    for (const auto& e : dump.at("entities")) awake += e.value("awake", false) ? 1 : 0;
    if (dump.at("tick").get<int>() == 300) awakeAfterBurst = awake;
    awakeAtEnd = awake;
  }
  EXPECT_GT(awakeAfterBurst, 5) << "nothing moving right after the burst: the check sees nothing";
  EXPECT_EQ(awakeAtEnd, 0) << "bodies still awake half a minute after the last cut";
}

// A drag that crosses nothing and a push at nothing say so under the crosshair (the dump's
// "notice"); a drag across the cube says nothing and cuts it.
TEST(DemoReplay, MissedCutsAndPushesGiveFeedback) {
  const fs::path dir = scratchDir("feedback");
  struct Case {
    const char* name;
    const char* events;
    const char* notice;
  };
  const Case cases[] = {
      {"push at the sky (after looking up)", "5 mm:640,160,0,-200\n10 md:right@640,160\n12 mu:right@640,160\n",
       "nothing to push under the crosshair"},
      {"push at the cylinder", "10 md:right@640,360\n12 mu:right@640,360\n", ""},
      {"drag across the sky", "10 kd:space\n14 md:left@200,100\n18 mm:500,100,300,0\n20 mu:left@500,100\n",
       "missed: the line crosses nothing to cut"},
      {"drag across the cube", "10 kd:space\n14 md:left@300,335\n18 mm:470,455,170,120\n20 mu:left@470,455\n", ""},
  };
  for (const Case& c : cases) {
    const fs::path replayFile = dir / "feedback.replay";
    std::ofstream(replayFile) << "cleave-replay 1\nscene demo\nseed 1\nticks 40\n" << c.events;
    const RunResult r = run("--headless --replay \"" + replayFile.string() + "\" --dump-state \"" +
                            (dir / "state.jsonl").string() + "\"");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const nlohmann::json dump = lastDumpLine(dir / "state.jsonl");
    ASSERT_TRUE(dump.is_object()) << c.name;
    EXPECT_EQ(dump.value("notice", "?"), c.notice) << c.name;
  }
}

// The HUD at any window size: its stats panel, the help box and the banners fit the frame, and
// every text fits the box it is drawn in (the dump's "hud" layout, in pixels). Help open, split
// mode on and a notice shown, so every box is there.
TEST(DemoReplay, HudTextFitsItsBoxesAtEveryFrameSize) {
  const fs::path dir = scratchDir("hud");
  const fs::path replayFile = dir / "hud.replay";
  std::ofstream(replayFile) << "cleave-replay 1\nscene demo\nseed 1\nticks 30\n5 kd:h\n6 ku:h\n"
                               "10 kd:space\n12 md:left@20,20\n14 mm:60,20,40,0\n16 mu:left@60,20\n";
  const std::pair<int, int> sizes[] = {{480, 270}, {640, 360}, {800, 600}, {1280, 720}, {1920, 1080}, {2560, 1080}};
  for (const auto& [w, h] : sizes) {
    const std::string size = std::to_string(w) + "x" + std::to_string(h);
    const RunResult r = run("--headless --width " + std::to_string(w) + " --height " + std::to_string(h) +
                            " --replay \"" + replayFile.string() + "\" --dump-state \"" + (dir / "state.jsonl").string() +
                            "\" --screenshot-dir \"" + (dir / size).string() + "\" --screenshot-every 1000");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const nlohmann::json dump = lastDumpLine(dir / "state.jsonl");
    ASSERT_TRUE(dump.is_object()) << size;
    const auto& items = dump.at("hud").at("items");
    std::set<std::string> kinds;
    for (const auto& item : items) {
      const std::string what = item.at("what").get<std::string>();
      kinds.insert(what);
      const auto box = item.at("box").get<std::array<double, 4>>();
      const auto text = item.at("text").get<std::array<double, 4>>();
      EXPECT_GE(box[0], 0.0) << size << " " << what;
      EXPECT_GE(box[1], 0.0) << size << " " << what;
      EXPECT_LE(box[0] + box[2], w) << size << " " << what << " runs out of the frame";
      EXPECT_LE(box[1] + box[3], h) << size << " " << what << " runs out of the frame";
      EXPECT_GE(text[0], box[0]) << size << " " << what;
      EXPECT_GE(text[1], box[1]) << size << " " << what;
      EXPECT_LE(text[0] + text[2], box[0] + box[2]) << size << " the text of " << what << " runs out of its box";
      EXPECT_LE(text[1] + text[3], box[1] + box[3]) << size << " the text of " << what << " runs out of its box";
    }
    EXPECT_TRUE(kinds.count("stats") && kinds.count("help") && kinds.count("text")) << size << ": boxes missing";
  }
}

TEST(DemoReplay, CorruptReplayIsReportedWithFileAndLine) {
  const fs::path dir = scratchDir("corrupt");
  const fs::path bad = dir / "bad.replay";
  std::ofstream(bad) << "cleave-replay 1\nscene demo\nseed 1\n12 kd:w\n7 kd:nosuchkey\n";
  const RunResult r = run("--headless --replay \"" + bad.string() + "\"");
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.output.find("bad.replay:5"), std::string::npos) << r.output;

  const RunResult missing = run("--headless --replay \"" + (dir / "missing.replay").string() + "\"");
  EXPECT_NE(missing.exitCode, 0);
  EXPECT_NE(missing.output.find("missing.replay"), std::string::npos) << missing.output;
}

// Frames of the tour against golden images, with the golden tolerance (image_compare.h). Only the
// HUD's wall-clock text is blanked before comparing (the FPS and tick line, the split ms line and
// the graph of split ms: 9% of the frame); its other lines and the panel are compared. Goldens are
// refreshed with CLEAVE_UPDATE_GOLDENS=1.
TEST(DemoReplay, TourFramesMatchGoldenImages) {
  const fs::path dir = scratchDir("golden");
  const RunResult r = run("--headless --replay \"" + kReplays + "/demo_tour.replay\" --width 1280 --height 720 "
                          "--screenshot-dir \"" + dir.string() + "\" --screenshot-every 300");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* frame : {"frame_000300.png", "frame_000600.png", "frame_000899.png"}) {
    int width = 0, height = 0;
    std::vector<uint8_t> rgba;
    ASSERT_EQ(cleave::render::readPng((dir / frame).string(), width, height, rgba).message, "");
    // The size the tour was recorded at: its drags cut what they cross there.
    ASSERT_EQ(width, 1280);
    ASSERT_EQ(height, 720);
    cleave::testing::maskRect(rgba, width, height, 14, 13, 338, 33);   // TPS, tick ms (drawHud, y = 14)
    cleave::testing::maskRect(rgba, width, height, 14, 53, 338, 73);   // split ms (y = 54)
    cleave::testing::maskRect(rgba, width, height, 14, 94, 258, 122);  // the split ms graph
    const cleave::testing::ImageTolerance tolerance = cleave::testing::kGoldenTolerance;
    const std::string golden = std::string(CLEAVE_SOURCE_DIR) + "/tests/replay/goldens/tour_" + frame;
    const auto comparison = cleave::testing::compareWithGolden(golden, width, height, rgba, tolerance);
    EXPECT_TRUE(comparison.ok) << frame << ": " << comparison.message;
  }
}

// The blanks of a frame with the inspector open: the HUD's wall-clock lines (as in the tour test)
// and every rectangle the inspector names as wall-clock in the dump (its times, its graph and the
// milliseconds column of the split log), a pixel wider on each side.
void maskWallClock(std::vector<uint8_t>& rgba, int width, int height, const nlohmann::json& inspector) {
  cleave::testing::maskRect(rgba, width, height, 14, 13, 338, 33);
  cleave::testing::maskRect(rgba, width, height, 14, 53, 338, 73);
  cleave::testing::maskRect(rgba, width, height, 14, 94, 258, 122);
  for (const auto& r : inspector.at("clock")) {
    const auto [x, y, w, h] = r.get<std::array<double, 4>>();
    cleave::testing::maskRect(rgba, width, height, int(std::floor(x)) - 1, int(std::floor(y)) - 1,
                              int(std::ceil(x + w)) + 1, int(std::ceil(y + h)) + 1);
  }
}

// --inspector: the inspector window over the HUD, drawn headless, against a golden image. It shows
// the marble cylinder's Splitable (under the crosshair), the budget, the times and the split log
// of the cuts the replay makes. Goldens are refreshed with CLEAVE_UPDATE_GOLDENS=1.
TEST(DemoReplay, InspectorFrameMatchesGoldenImage) {
  if (!CLEAVE_HAVE_IMGUI)
    GTEST_SKIP() << "built without Dear ImGui (libimgui-dev missing, or CLEAVE_INSPECTOR=OFF): no inspector";
  const fs::path dir = scratchDir("inspector");
  const RunResult r = run("--headless --inspector --replay \"" + kReplays + "/demo_inspector.replay\" --width 1280 "
                          "--height 720 --screenshot-dir \"" + dir.string() + "\" --screenshot-every 100000 "
                          "--dump-state \"" + (dir / "state.jsonl").string() + "\"");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const nlohmann::json dump = lastDumpLine(dir / "state.jsonl");
  ASSERT_TRUE(dump.is_object());
  const nlohmann::json& inspector = dump.at("inspector");
  EXPECT_TRUE(inspector.at("open").get<bool>());
  EXPECT_EQ(inspector.at("target"), "marble cylinder");
  EXPECT_GE(dump.at("splits").size(), 2u);
  // Its times, its graph and one milliseconds cell per row of the log are blanked, no more.
  EXPECT_EQ(inspector.at("clock").size(), 2 + std::min<size_t>(10, dump.at("splits").size()));
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;
  ASSERT_EQ(cleave::render::readPng((dir / "frame_000149.png").string(), width, height, rgba).message, "");
  ASSERT_EQ(width, 1280);
  ASSERT_EQ(height, 720);
  maskWallClock(rgba, width, height, inspector);
  const std::string golden = std::string(CLEAVE_SOURCE_DIR) + "/tests/replay/goldens/inspector_frame_000149.png";
  const auto comparison =
      cleave::testing::compareWithGolden(golden, width, height, rgba, cleave::testing::kGoldenTolerance);
  EXPECT_TRUE(comparison.ok) << comparison.message;
}

// F1 in a replay opens the inspector and a second F1 closes it (the dump says which); built
// without Dear ImGui it stays shut and the notice under the crosshair says why.
TEST(DemoReplay, F1OpensAndClosesTheInspector) {
  const fs::path dir = scratchDir("f1");
  const fs::path replayFile = dir / "f1.replay";
  auto runTo = [&](const char* events) {
    std::ofstream(replayFile) << "cleave-replay 1\nscene demo\nseed 1\nticks 40\n" << events;
    const RunResult r = run("--headless --replay \"" + replayFile.string() + "\" --dump-state \"" +
                            (dir / "state.jsonl").string() + "\" --screenshot-every 1000 --screenshot-dir \"" +
                            dir.string() + "\"");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    return lastDumpLine(dir / "state.jsonl");
  };
  const nlohmann::json opened = runTo("10 kd:f1\n11 ku:f1\n");
  const nlohmann::json closed = runTo("10 kd:f1\n11 ku:f1\n20 kd:f1\n21 ku:f1\n");
  ASSERT_TRUE(opened.is_object() && closed.is_object());
  EXPECT_FALSE(closed.at("inspector").at("open").get<bool>());
  if (CLEAVE_HAVE_IMGUI) {
    EXPECT_TRUE(opened.at("inspector").at("open").get<bool>());
    EXPECT_EQ(opened.at("inspector").at("target"), "marble cylinder");
    EXPECT_GT(opened.at("inspector").at("window")[2].get<double>(), 100.0);
    EXPECT_EQ(opened.value("notice", "?"), "");
  } else {
    EXPECT_FALSE(opened.at("inspector").at("open").get<bool>());
    EXPECT_NE(opened.value("notice", "").find("not built"), std::string::npos) << opened.dump();
  }
}

}  // namespace
