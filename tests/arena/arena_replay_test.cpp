// SPDX-License-Identifier: MIT
// The arena sample's bundled replays, run headless through the real executable: the match (menu,
// two waves of gladiators and skinned warriors, disc, sword and spin; the skinned ones fall as
// ragdoll halves), the burst of kills the split budget has to spread, the Quit
// cube, a first-time player's first two waves (grace period, arrivals one after another, the
// refill between waves), defeat (the enemies cheer, upright) and the clean arena of the next match,
// determinism (two runs, and a recorded-then-replayed run, give the same state hash) and golden
// frames (the match, and the view over the east wall).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include <nlohmann/json.hpp>

#include "cleave/render/renderer.h"
#include "tests/render/image_compare.h"
#include "tests/support/executable_run.h"

namespace {

namespace fs = std::filesystem;

const std::string kArena = std::string(CLEAVE_BINARY_DIR) + "/bin/cleave-arena";
const std::string kReplays = std::string(CLEAVE_SOURCE_DIR) + "/assets/replays";

using cleave::testing::expectEveryCutKeepsMass;
using cleave::testing::lastDumpLine;
using cleave::testing::RunResult;
using cleave::testing::stateHash;

RunResult run(const std::string& arguments) { return cleave::testing::runExecutable(kArena, arguments); }

fs::path scratchDir(const std::string& name) { return cleave::testing::scratchDir("arena", name); }

std::string replay(const std::string& name) { return "\"" + kReplays + "/" + name + "\""; }

// Every position finite and nothing under the sand (its top is y = 0).
void expectNothingBelowTheFloor(const nlohmann::json& dump) {
  for (const auto& e : dump.at("entities")) {
    for (int k = 0; k < 3; ++k) ASSERT_TRUE(std::isfinite(e.at("position")[k].get<double>())) << e.dump();
    EXPECT_GT(e.at("position")[1].get<double>(), -0.3) << "below the floor: " << e.dump();
  }
}

size_t countKind(const nlohmann::json& dump, const std::string& kind) {
  size_t n = 0;
  for (const auto& e : dump.at("entities"))
    if (e.value("kind", "") == kind) ++n;
  return n;
}

// Every line of a state dump (JSON lines).
std::vector<nlohmann::json> allDumpLines(const fs::path& path) {
  std::vector<nlohmann::json> lines;
  std::ifstream in(path);
  std::string text;
  while (std::getline(in, text))
    if (!text.empty()) lines.push_back(nlohmann::json::parse(text));
  return lines;
}

size_t countRagdollPieces(const nlohmann::json& dump) {
  size_t n = 0;
  for (const auto& e : dump.at("entities"))
    if (e.value("kind", "") == "piece" && e.value("ragdoll_bones", 0) > 0) ++n;
  return n;
}

size_t countCutsOf(const nlohmann::json& dump, const std::string& original) {
  size_t n = 0;
  for (const auto& s : dump.at("splits"))
    if (s.at("original") == original && s.at("status") == "Ok") ++n;
  return n;
}

TEST(ArenaReplay, MatchClearsTwoWavesWithBothWeapons) {
  const fs::path dir = scratchDir("match");
  const RunResult r = run("--headless --replay " + replay("arena_match.replay") + " --dump-state \"" +
                          (dir / "state.jsonl").string() + "\" --dump-every 20 --print-state-hash");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const nlohmann::json dump = lastDumpLine(dir / "state.jsonl");
  ASSERT_TRUE(dump.is_object());
  EXPECT_EQ(dump.at("tick"), 3099);
  const auto& arena = dump.at("arena");
  // The menu click cut the Start cube and started the match; wave 3 has begun, so waves 1 and 2
  // (4 + 2 and 8 + 3 gladiators and skinned warriors) were cleared, and the player lived through it.
  EXPECT_EQ(countCutsOf(dump, "start cube"), 1u);
  EXPECT_EQ(arena.at("state"), "playing");
  EXPECT_GE(arena.at("wave").get<int>(), 3);
  EXPECT_GE(arena.at("enemies_killed").get<int>(), 17) << arena.dump();
  EXPECT_EQ(arena.at("score"), arena.at("enemies_killed"));
  EXPECT_GT(arena.at("health").get<int>(), 0);
  // Both weapons and the spin were used, and each killed: the disc and sword kills of wave 1 come
  // before the spin, which met all eight of wave 2 in one step.
  EXPECT_GE(arena.at("disc_throws").get<int>(), 1);
  EXPECT_GE(arena.at("sword_swings").get<int>(), 2);
  EXPECT_GE(arena.at("spin_attacks").get<int>(), 1);
  EXPECT_GE(arena.at("max_enemies_hit_in_one_tick").get<int>(), 8);
  EXPECT_GE(countCutsOf(dump, "gladiator"), 12u);
  EXPECT_GE(arena.at("props_broken").get<int>(), 1);
  // A gladiator falls apart into its parts (islands): about nine pieces a kill.
  EXPECT_GE(arena.at("pieces_spawned").get<int>(), 90);
  for (const auto& s : dump.at("splits")) {
    if (s.at("original") != "gladiator" || s.at("status") != "Ok") continue;
    EXPECT_GE(s.at("pieces").get<int>(), 6) << s.dump();
  }
  expectEveryCutKeepsMass(dump);
  expectNothingBelowTheFloor(dump);
  EXPECT_EQ(dump.at("budget").at("queue"), 0) << "split requests left over";
  EXPECT_EQ(stateHash(r.output).size(), 16u);
}

TEST(ArenaReplay, SkinnedEnemiesFallAsRagdollHalves) {
  const fs::path dir = scratchDir("skinned");
  const RunResult r = run("--headless --replay " + replay("arena_match.replay") + " --dump-state \"" +
                          (dir / "state.jsonl").string() + "\" --dump-every 20");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const std::vector<nlohmann::json> lines = allDumpLines(dir / "state.jsonl");
  ASSERT_FALSE(lines.empty());
  const nlohmann::json& dump = lines.back();
  const auto& arena = dump.at("arena");
  // Kills are counted per kind and add up to the total; the five skinned warriors of waves 1 and 2
  // died, at least one to each weapon (disc, sword slash, spin).
  const auto& kills = arena.at("kills_by_kind");
  const auto& skinned = kills.at("skinned");
  EXPECT_EQ(kills.at("gladiator").at("total").get<int>() + skinned.at("total").get<int>(),
            arena.at("enemies_killed").get<int>())
      << kills.dump();
  EXPECT_GE(skinned.at("total").get<int>(), 5) << kills.dump();
  EXPECT_GE(skinned.at("disc").get<int>(), 1) << kills.dump();
  EXPECT_GE(skinned.at("sword").get<int>(), 1) << kills.dump();
  EXPECT_GE(skinned.at("spin").get<int>(), 1) << kills.dump();
  EXPECT_GE(kills.at("gladiator").at("total").get<int>(), 12) << kills.dump();
  // Each skinned kill is a cut of the whole character in its pose: at least two pieces that share
  // its mass (by posed volume) within 2e-6 relative. The masses add up by construction (each piece
  // takes its share of the parent's); the volumes are the check: the pieces' add up to the posed
  // character's, integrated on its own.
  size_t skinnedCuts = 0;
  for (const auto& s : dump.at("splits")) {
    if (s.at("original") != "skinned warrior" || s.at("status") != "Ok") continue;
    ++skinnedCuts;
    EXPECT_GE(s.at("pieces").get<int>(), 2) << s.dump();
    const double parent = s.at("parent_mass").get<double>();
    const double pieces = s.at("pieces_mass").get<double>();
    EXPECT_GT(parent, 30.0) << s.dump();  // a whole character (about 76 kg), not a scrap
    EXPECT_LE(std::abs(pieces - parent), 2e-6 * parent) << s.dump();
    ASSERT_TRUE(s.contains("posed_volume")) << s.dump();
    const double posed = s.at("posed_volume").get<double>();
    EXPECT_GT(posed, 0.03) << s.dump();  // about 76 litres
    EXPECT_NEAR(s.at("pieces_volume").get<double>() / posed, 1.0, 1e-6) << s.dump();
  }
  EXPECT_EQ(skinnedCuts, size_t(skinned.at("total").get<int>()));
  // The halves are ragdolls: they appear in the dump after the first skinned kill (with their bones),
  // are counted, and the first ones fade out and are removed with every bone body.
  int firstKillTick = -1;
  for (const auto& s : dump.at("splits"))
    if (s.at("original") == "skinned warrior" && s.at("status") == "Ok") {
      firstKillTick = s.at("tick").get<int>();
      break;
    }
  ASSERT_GE(firstKillTick, 0);
  // A half is a ragdoll of many bones (a hand or a shoulder cut off on the way is a small one of
  // one or two): right after the kill both halves are there.
  size_t mostRagdolls = 0;
  bool halvesRightAfterTheKill = false;
  for (const auto& line : lines) {
    mostRagdolls = std::max(mostRagdolls, countRagdollPieces(line));
    const int tick = line.at("tick").get<int>();
    if (tick <= firstKillTick || tick > firstKillTick + 40) continue;
    size_t halves = 0;
    for (const auto& e : line.at("entities"))
      if (e.value("kind", "") == "piece" && e.value("ragdoll_bones", 0) >= 6) ++halves;
    if (halves >= 2) halvesRightAfterTheKill = true;
  }
  EXPECT_TRUE(halvesRightAfterTheKill) << "no ragdoll halves after the kill at tick " << firstKillTick;
  EXPECT_GE(mostRagdolls, 4u);
  EXPECT_GE(arena.at("ragdoll_pieces_spawned").get<int>(), 2 * skinned.at("total").get<int>()) << arena.dump();
  EXPECT_GE(arena.at("ragdoll_pieces_removed").get<int>(), 4) << arena.dump();
  EXPECT_EQ(countRagdollPieces(dump), size_t(arena.at("ragdoll_pieces_spawned").get<int>() -
                                             arena.at("ragdoll_pieces_removed").get<int>() -
                                             arena.at("ragdoll_pieces_cut").get<int>()))
      << arena.dump();
  EXPECT_EQ(arena.at("ragdoll_bodies_leaked"), 0) << arena.dump();
}

TEST(ArenaReplay, BurstOfKillsIsSpreadByTheBudget) {
  const fs::path dir = scratchDir("burst");
  const RunResult r = run("--headless --replay " + replay("arena_burst.replay") + " --dump-state \"" +
                          (dir / "state.jsonl").string() + "\"");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const nlohmann::json dump = lastDumpLine(dir / "state.jsonl");
  ASSERT_TRUE(dump.is_object());
  const auto& arena = dump.at("arena");
  const auto& budget = dump.at("budget");
  // Three spins: 4, 8 and 12 enemies touched in one step each; the skinned stragglers go to the
  // disc and the sword, and all three waves (6 + 11 + 16) are cleared.
  EXPECT_EQ(arena.at("spin_attacks"), 3);
  EXPECT_GE(arena.at("max_enemies_hit_in_one_tick").get<int>(), 12) << arena.dump();
  EXPECT_GE(arena.at("enemies_killed").get<int>(), 33) << arena.dump();
  EXPECT_GE(arena.at("kills_by_kind").at("skinned").at("total").get<int>(), 9) << arena.dump();
  EXPECT_EQ(arena.at("ragdoll_bodies_leaked"), 0) << arena.dump();
  // The budget charges each split's main-thread estimate (the heavy work runs on workers) and takes
  // at most max_splits_per_tick a tick: twelve touched in one step do not all fall apart at once,
  // the rest wait in the queue, and no tick is charged more than its budget plus one split.
  const int perTick = budget.at("max_splits_per_tick").get<int>();
  EXPECT_LT(perTick, 12);
  EXPECT_LE(arena.at("max_kills_in_one_tick").get<int>(), perTick) << arena.dump();
  EXPECT_GE(budget.at("max_queue").get<int>(), 12) << budget.dump();
  EXPECT_GT(budget.at("deferred_total").get<int>(), 3) << budget.dump();
  EXPECT_EQ(budget.at("queue"), 0) << budget.dump();
  EXPECT_LE(budget.at("max_charged_ms_in_a_tick").get<double>(),
            budget.at("ms_per_tick").get<double>() + budget.at("max_estimate_ms").get<double>() + 1e-9)
      << budget.dump();
  std::map<uint64_t, int> cutsPerTick;
  for (const auto& s : dump.at("splits"))
    if (s.at("original") == "gladiator") ++cutsPerTick[s.at("tick").get<uint64_t>()];
  for (const auto& [tick, cuts] : cutsPerTick) EXPECT_LE(cuts, perTick) << "tick " << tick;
  expectEveryCutKeepsMass(dump);
  expectNothingBelowTheFloor(dump);
  // Pieces stay a while, then shrink and go: the first burst's pieces are gone by the end.
  EXPECT_GT(arena.at("pieces_removed").get<int>(), 30) << arena.dump();
  EXPECT_LT(countKind(dump, "piece"), size_t(arena.at("pieces_spawned").get<int>()));
}

// The hammer (E) shatters what it lands on into cells, as split jobs: gladiators (their parts), the
// skinned warriors (rigid cells of the pose) and a crate the wave pushed along; every shatter keeps
// the mass of what it broke and none fails.
TEST(ArenaReplay, HammerShattersGladiatorsWarriorsAndProps) {
  const fs::path dir = scratchDir("hammer");
  const RunResult r = run("--headless --replay " + replay("arena_hammer.replay") + " --dump-state \"" +
                          (dir / "state.jsonl").string() + "\"");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output.find("kept whole"), std::string::npos) << r.output;
  const nlohmann::json dump = lastDumpLine(dir / "state.jsonl");
  ASSERT_TRUE(dump.is_object());
  const auto& arena = dump.at("arena");
  EXPECT_EQ(arena.at("hammer_blows"), 6);
  const auto& kills = arena.at("kills_by_kind");
  EXPECT_GE(kills.at("gladiator").at("hammer").get<int>(), 3) << kills.dump();
  EXPECT_GE(kills.at("skinned").at("hammer").get<int>(), 2) << kills.dump();
  EXPECT_GE(arena.at("props_broken").get<int>(), 1) << arena.dump();
  size_t gladiators = 0, warriors = 0, props = 0;
  for (const auto& s : dump.at("splits")) {
    EXPECT_EQ(s.at("status"), "Ok") << s.dump();
    const std::string original = s.at("original");
    const int pieces = s.at("pieces").get<int>();
    if (original == "gladiator" && pieces >= 12) ++gladiators;          // cells of its parts
    if (original == "skinned warrior" && pieces >= 8) ++warriors;      // a cut gives two
    if (original == "crate" && pieces >= 6) ++props;
  }
  EXPECT_GE(gladiators, 3u);
  EXPECT_GE(warriors, 2u);
  EXPECT_GE(props, 1u);
  EXPECT_EQ(arena.at("ragdoll_bodies_leaked"), 0) << arena.dump();
  // The cells of a shattered skinned warrior are final (never shattered again): every shatter keeps
  // the mass of what it broke to rounding.
  for (const auto& s : dump.at("splits")) {
    EXPECT_NE(s.at("original").get<std::string>().rfind("skinned warrior/", 0), 0u) << s.dump();
  }
  expectEveryCutKeepsMass(dump);
  expectNothingBelowTheFloor(dump);
  EXPECT_EQ(dump.at("budget").at("queue"), 0) << "split requests left over";
}

TEST(ArenaReplay, QuitCubeEndsTheGame) {
  const fs::path dir = scratchDir("quit");
  const RunResult r = run("--headless --replay " + replay("arena_quit.replay") + " --dump-state \"" +
                          (dir / "state.jsonl").string() + "\" --dump-every 10");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const nlohmann::json dump = lastDumpLine(dir / "state.jsonl");
  ASSERT_TRUE(dump.is_object());
  EXPECT_EQ(countCutsOf(dump, "quit cube"), 1u);
  EXPECT_EQ(dump.at("arena").at("state"), "quitting");
  EXPECT_LT(dump.at("tick").get<int>(), 200) << "the game did not end after the Quit cube was cut";
}

TEST(ArenaReplay, SameReplayGivesTheSameState) {
  const std::string args = "--headless --replay " + replay("arena_match.replay") + " --ticks 1000 --print-state-hash";
  const RunResult a = run(args);
  // Garbage in fresh and freed memory, addresses not randomized: the same state.
  const RunResult b = cleave::testing::runExecutable(kArena, args, cleave::testing::kPerturbedRun);
  ASSERT_EQ(a.exitCode, 0) << a.output;
  ASSERT_EQ(b.exitCode, 0) << b.output;
  ASSERT_EQ(stateHash(a.output).size(), 16u) << a.output;
  EXPECT_EQ(stateHash(a.output), stateHash(b.output));
}

TEST(ArenaReplay, EveryReplayGivesTheSameStateOnZeroOneAndThreeSplitThreads) {
  cleave::testing::OffMainThread total;
  for (const char* name : {"arena_match.replay", "arena_burst.replay", "arena_quit.replay", "arena_newcomer.replay",
                           "arena_rematch.replay", "arena_east_wall.replay", "arena_hammer.replay"}) {
    const cleave::testing::OffMainThread off =
        cleave::testing::expectSameStateOnZeroOneAndThreeSplitThreads(run, "--headless --replay " + replay(name), name);
    total.one += off.one;
    total.three += off.three;
  }
  // The threads really ran: the workers computed some of the replays' jobs.
  EXPECT_GT(total.one, 0);
  EXPECT_GT(total.three, 0);
}

TEST(ArenaReplay, RecordedRunReplaysToTheSameState) {
  const fs::path dir = scratchDir("record");
  const fs::path recorded = dir / "recorded.replay";
  const RunResult original = run("--headless --replay " + replay("arena_match.replay") + " --ticks 700 --record \"" +
                                 recorded.string() + "\" --print-state-hash");
  ASSERT_EQ(original.exitCode, 0) << original.output;
  ASSERT_TRUE(fs::exists(recorded));
  const RunResult replayed = run("--headless --replay \"" + recorded.string() + "\" --print-state-hash");
  ASSERT_EQ(replayed.exitCode, 0) << replayed.output;
  EXPECT_EQ(stateHash(original.output), stateHash(replayed.output));
}

// The entities of a dump line whose "kind" is `kind`.
std::vector<nlohmann::json> entitiesOfKind(const nlohmann::json& line, const std::string& kind) {
  std::vector<nlohmann::json> out;
  for (const auto& e : line.at("entities"))
    if (e.value("kind", "") == kind) out.push_back(e);
  return out;
}

// The first line at or after `fromTick` whose match state is `state` (null when there is none).
const nlohmann::json* firstLineInState(const std::vector<nlohmann::json>& lines, const std::string& state,
                                       int fromTick = 0) {
  for (const auto& line : lines)
    if (line.at("tick").get<int>() >= fromTick && line.at("arena").at("state") == state) return &line;
  return nullptr;
}

// Plays the bundled replay `name` headless with a state dump every 10 ticks into scratch folder
// `scratch`; returns every line of the dump (empty, with a failure, when the run fails).
std::vector<nlohmann::json> dumpEveryTenTicks(const std::string& name, const std::string& scratch) {
  const fs::path dir = scratchDir(scratch);
  const RunResult r = run("--headless --replay " + replay(name) + " --dump-state \"" + (dir / "state.jsonl").string() +
                          "\" --dump-every 10");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  return r.exitCode == 0 ? allDumpLines(dir / "state.jsonl") : std::vector<nlohmann::json>{};
}

// A first-time player who never moves and only presses the spin attack every four seconds
// (arena_newcomer.replay). Nobody comes through a gate during the grace period after START; the
// enemies come one after another (never two within the tuned arrival gap) and at most
// max_attackers strike at once; wave 1 costs health but is survived; the pause after it fills the
// health bar up, so wave 2 begins at full health; wave 2 is survived too and wave 3 begins.
TEST(ArenaReplay, NewcomerStandingStillSurvivesTwoWaves) {
  const std::vector<nlohmann::json> lines = dumpEveryTenTicks("arena_newcomer.replay", "newcomer");
  ASSERT_FALSE(lines.empty());
  const auto& tuning = lines.front().at("arena").at("tuning");
  const int full = lines.front().at("arena").at("max_health").get<int>();
  const nlohmann::json* grace = firstLineInState(lines, "intermission");
  ASSERT_NE(grace, nullptr) << "no grace period after START";
  const int graceEnd = grace->at("tick").get<int>() + int(std::lround(tuning.at("grace_seconds").get<double>() * 60));
  std::map<uint64_t, std::pair<int, int>> arrivals;  // enemy id -> (wave, spawn tick)
  int firstDamage = -1, lowestInWave1 = full, healthAtWave1Cleared = -1, healthAtWave2 = -1, mostStriking = 0;
  for (const auto& line : lines) {
    const auto& arena = line.at("arena");
    const int tick = line.at("tick").get<int>(), wave = arena.at("wave").get<int>();
    const int health = arena.at("health").get<int>();
    const std::string state = arena.at("state");
    EXPECT_NE(state, "defeated") << "tick " << tick;
    if (health < full && firstDamage < 0) firstDamage = tick;
    if (wave == 1 && state == "playing") lowestInWave1 = std::min(lowestInWave1, health);
    if (wave == 1 && state == "intermission" && healthAtWave1Cleared < 0) healthAtWave1Cleared = health;
    if (wave == 2 && state == "playing" && healthAtWave2 < 0) healthAtWave2 = health;
    int striking = 0;
    for (const auto& e : entitiesOfKind(line, "enemy")) {
      arrivals.emplace(e.at("id").get<uint64_t>(), std::make_pair(wave, e.at("spawn_tick").get<int>()));
      if (e.at("behaviour") == "strike") ++striking;
    }
    mostStriking = std::max(mostStriking, striking);
  }
  // The grace period: no arrival and no blow before it is over, and the first blow not within 8 s.
  ASSERT_FALSE(arrivals.empty());
  for (const auto& [id, arrival] : arrivals) EXPECT_GE(arrival.second, graceEnd) << "enemy " << id;
  EXPECT_GE(firstDamage, graceEnd);
  EXPECT_GE(firstDamage - grace->at("tick").get<int>(), 8 * 60) << "struck within 8 s of START";
  // One after another: wave 1 (4 + 2) at arrival_seconds, wave 2 (8 + 3) at later_arrival_seconds.
  for (int wave : {1, 2}) {
    std::vector<int> ticks;
    for (const auto& [id, arrival] : arrivals)
      if (arrival.first == wave) ticks.push_back(arrival.second);
    std::sort(ticks.begin(), ticks.end());
    EXPECT_EQ(ticks.size(), wave == 1 ? 6u : 11u) << "wave " << wave;
    const double gap = tuning.at(wave == 1 ? "arrival_seconds" : "later_arrival_seconds").get<double>() * 60.0;
    for (size_t k = 1; k < ticks.size(); ++k)
      EXPECT_GE(ticks[k] - ticks[k - 1], std::max(30, int(std::lround(gap)) - 1))
          << "wave " << wave << " arrival " << k;
  }
  // Never surrounded: a few strike (never more than four), the others wait their turn.
  EXPECT_GE(mostStriking, 2);
  EXPECT_LE(mostStriking, std::min(4, tuning.at("max_attackers").get<int>()));
  // Wave 1 costs health; the refill brings it back before wave 2.
  EXPECT_LT(lowestInWave1, full);
  EXPECT_GT(lowestInWave1, 0);
  EXPECT_LT(healthAtWave1Cleared, full) << "nothing to refill: the check below would say nothing";
  EXPECT_EQ(healthAtWave2, full);
  const auto& last = lines.back().at("arena");
  EXPECT_GE(last.at("wave").get<int>(), 3) << last.dump();
  EXPECT_GT(last.at("health").get<int>(), 0);
  EXPECT_EQ(last.at("enemies_killed"), 17) << "waves 1 and 2: 6 + 11";
}

// Beaten (arena_rematch.replay: the player stands still after one disc throw): the player lasts
// far longer than the six seconds it took before the grace period and the staggered arrivals;
// then every enemy still standing cheers where it stands (behaviour "cheer", the skinned ones in
// their cheer clip), upright, hopping in place, for as long as the defeat is shown.
TEST(ArenaReplay, DefeatedPlayerIsCheeredByUprightEnemies) {
  const std::vector<nlohmann::json> lines = dumpEveryTenTicks("arena_rematch.replay", "defeat");
  ASSERT_FALSE(lines.empty());
  const nlohmann::json* starting = firstLineInState(lines, "starting");
  const nlohmann::json* defeat = firstLineInState(lines, "defeated");
  ASSERT_NE(starting, nullptr);
  ASSERT_NE(defeat, nullptr) << "the player was never beaten";
  const int defeatTick = defeat->at("tick").get<int>();
  EXPECT_GE(defeatTick - starting->at("tick").get<int>(), 20 * 60) << "beaten within 20 s of START";
  std::map<uint64_t, nlohmann::json> atDefeat;  // enemy id -> its line when the cheering began
  std::map<uint64_t, std::pair<double, double>> heights;  // id -> lowest and highest centre of mass
  size_t cheeringLines = 0;
  for (const auto& line : lines) {
    const int tick = line.at("tick").get<int>();
    if (line.at("arena").at("state") != "defeated" || tick < defeatTick + 30) continue;
    ++cheeringLines;
    const auto enemies = entitiesOfKind(line, "enemy");
    EXPECT_GE(enemies.size(), 3u) << "tick " << tick;
    for (const auto& e : enemies) {
      const uint64_t id = e.at("id").get<uint64_t>();
      EXPECT_EQ(e.at("behaviour"), "cheer") << e.dump();
      EXPECT_LT(e.at("tilt_deg").get<double>(), 12.0) << "toppled: " << e.dump();
      if (e.at("enemy_kind") == "skinned") {
        EXPECT_EQ(e.value("clip", ""), "cheer") << e.dump();
      }
      const double y = e.at("center_of_mass")[1].get<double>();
      EXPECT_GT(y, 0.6) << "lying on the sand: " << e.dump();
      auto [it, first] = atDefeat.emplace(id, e);
      if (!first) {
        const double dx = e.at("position")[0].get<double>() - it->second.at("position")[0].get<double>();
        const double dz = e.at("position")[2].get<double>() - it->second.at("position")[2].get<double>();
        EXPECT_LT(std::hypot(dx, dz), 0.3) << "walked off: " << e.dump();
      }
      auto& h = heights.try_emplace(id, y, y).first->second;
      h = {std::min(h.first, y), std::max(h.second, y)};
    }
  }
  EXPECT_GE(cheeringLines, 10u);
  // The gladiators hop as they cheer.
  size_t hopping = 0;
  for (const auto& [id, e] : atDefeat)
    if (e.at("enemy_kind") == "gladiator" && heights[id].second - heights[id].first > 0.05) ++hopping;
  EXPECT_GE(hopping, 2u);
}

// A new match starts from a clean arena (arena_rematch.replay: a crate, an urn and enemies cut,
// then defeat, Enter, and the Start cube again). Back in the menu every prop stands whole where it
// stood at the start, no piece is left (nor its body or GPU mesh: the engine's figures are back to
// those of the first menu), and the match's figures are zero; the second match's only pieces are
// those of its own Start cube.
TEST(ArenaReplay, NewMatchStartsOnACleanArena) {
  const std::vector<nlohmann::json> lines = dumpEveryTenTicks("arena_rematch.replay", "rematch");
  ASSERT_FALSE(lines.empty());
  const nlohmann::json& firstMenu = lines.front();
  ASSERT_EQ(firstMenu.at("arena").at("state"), "menu");
  const nlohmann::json* defeat = firstLineInState(lines, "defeated");
  ASSERT_NE(defeat, nullptr);
  const nlohmann::json* menu = firstLineInState(lines, "menu", defeat->at("tick").get<int>());
  ASSERT_NE(menu, nullptr) << "Enter did not go back to the menu";
  // The last match left something to clean up.
  const nlohmann::json* lastDefeated = nullptr;
  for (const auto& line : lines)
    if (line.at("arena").at("state") == "defeated") lastDefeated = &line;
  const auto& before = lastDefeated->at("arena");
  EXPECT_GE(before.at("enemies_killed").get<int>(), 1);
  EXPECT_GE(before.at("props_broken").get<int>(), 1);
  EXPECT_GE(countKind(*lastDefeated, "piece"), 1u);
  EXPECT_LT(countKind(*lastDefeated, "prop"), countKind(firstMenu, "prop"));
  // Props whole, where they stood: the same names, masses and places as in the first menu.
  auto props = [](const nlohmann::json& line) {
    std::vector<std::tuple<std::string, double, double, double>> out;
    for (const auto& e : entitiesOfKind(line, "prop")) {
      EXPECT_FALSE(e.contains("split_from")) << "a piece counted as a prop: " << e.dump();
      out.emplace_back(e.at("name"), e.at("mass").get<double>(), e.at("position")[0].get<double>(),
                       e.at("position")[2].get<double>());
    }
    std::sort(out.begin(), out.end());
    return out;
  };
  const auto original = props(firstMenu), restored = props(*menu);
  ASSERT_EQ(restored.size(), original.size());
  for (size_t k = 0; k < original.size(); ++k) {
    EXPECT_EQ(std::get<0>(restored[k]), std::get<0>(original[k]));
    EXPECT_NEAR(std::get<1>(restored[k]), std::get<1>(original[k]), 1e-9 * std::get<1>(original[k]));
    EXPECT_NEAR(std::get<2>(restored[k]), std::get<2>(original[k]), 1e-3);
    EXPECT_NEAR(std::get<3>(restored[k]), std::get<3>(original[k]), 1e-3);
  }
  EXPECT_EQ(countKind(*menu, "piece"), 0u);
  EXPECT_EQ(countKind(*menu, "enemy"), 0u);
  EXPECT_EQ(countKind(*menu, "menu_cube"), 2u);
  const auto& reset = menu->at("arena");
  for (const char* figure : {"score", "enemies_killed", "wave", "props_broken", "disc_throws", "enemies_alive"})
    EXPECT_EQ(reset.at(figure), 0) << figure;
  for (const auto& [kind, kills] : reset.at("kills_by_kind").items()) EXPECT_EQ(kills.at("total"), 0) << kind;
  EXPECT_EQ(reset.at("health"), reset.at("max_health"));
  EXPECT_EQ(reset.at("resources"), firstMenu.at("arena").at("resources")) << "left behind by the last match";
  EXPECT_EQ(reset.at("ragdoll_bodies_leaked"), 0);
  // The next match: started, at zero, and every piece on the sand is its own Start cube's.
  const nlohmann::json* next = nullptr;
  for (const auto& line : lines)
    if (line.at("arena").at("matches_started") == 2 && line.at("arena").at("state") == "intermission") next = &line;
  ASSERT_NE(next, nullptr) << "the second match did not start";
  EXPECT_EQ(next->at("arena").at("enemies_killed"), 0);
  EXPECT_EQ(next->at("arena").at("score"), 0);
  EXPECT_GE(countKind(*next, "piece"), 2u);
  for (const auto& piece : entitiesOfKind(*next, "piece"))
    EXPECT_GT(piece.at("born_tick").get<int>(), menu->at("tick").get<int>()) << "left over: " << piece.dump();
}

// Compares `frame` (a 640 x 360 screenshot in `dir`) with tests/arena/goldens/<prefix><frame>, with
// the golden tolerance (image_compare.h). Only the wall-clock text of the top-right HUD box is
// blanked (the FPS line, the split ms line and the graph: 2% of the frame). Goldens are refreshed
// with CLEAVE_UPDATE_GOLDENS=1.
void expectFrameMatchesGolden(const fs::path& dir, const std::string& frame, const std::string& prefix) {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;
  ASSERT_EQ(cleave::render::readPng((dir / frame).string(), width, height, rgba).message, "");
  ASSERT_EQ(width, 640);
  ASSERT_EQ(height, 360);
  // The HUD is laid out for 720 lines: at 360, half its units (drawBudgetPanel, box at x = W - 145).
  cleave::testing::maskRect(rgba, width, height, 498, 8, width, 18);    // FPS, tick ms
  cleave::testing::maskRect(rgba, width, height, 498, 26, width, 36);   // split ms
  cleave::testing::maskRect(rgba, width, height, 498, 36, width, 53);   // the split ms graph
  const std::string golden = std::string(CLEAVE_SOURCE_DIR) + "/tests/arena/goldens/" + prefix + frame;
  const auto comparison =
      cleave::testing::compareWithGolden(golden, width, height, rgba, cleave::testing::kGoldenTolerance);
  EXPECT_TRUE(comparison.ok) << frame << ": " << comparison.message;
}

// Frames of the match at 640 x 360 (the replay declares a 1280 x 720 window, so the clicks land on
// the same things): the disc's first kills (a skinned warrior's halves falling), wave 2 closing in
// (three gladiators strike, the others wait around the player), and the pieces after the spin (the
// skinned warriors of wave 2 still coming).
TEST(ArenaReplay, MatchFramesMatchGoldenImages) {
  const fs::path dir = scratchDir("golden");
  const RunResult r = run("--headless --replay " + replay("arena_match.replay") + " --ticks 2500 --width 640 --height 360 "
                          "--screenshot-dir \"" + dir.string() + "\" --screenshot-every 310");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* frame : {"frame_000620.png", "frame_002170.png", "frame_002499.png"})
    expectFrameMatchesGolden(dir, frame, "match_");
}

// The follow view at the east wall (arena_east_wall.replay): over the wall the stands, their crowd
// and the turf fill the frame; before them this view showed the sky's empty grey below the horizon.
TEST(ArenaReplay, EastWallViewShowsTheStandsNotTheVoid) {
  const fs::path dir = scratchDir("east_wall");
  const RunResult r = run("--headless --replay " + replay("arena_east_wall.replay") + " --width 640 --height 360 "
                          "--screenshot-dir \"" + dir.string() + "\" --screenshot-every 100000");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  expectFrameMatchesGolden(dir, "frame_000399.png", "east_wall_");
}

// F1 opens the inspector over the menu, showing the Splitable of the cube under the cursor (the
// QUIT cube); built without Dear ImGui it stays shut and the notice says why.
TEST(ArenaReplay, F1OpensTheInspectorOnTheCubeUnderTheCursor) {
  const fs::path dir = scratchDir("f1");
  const fs::path replayFile = dir / "f1.replay";
  std::ofstream(replayFile) << "cleave-replay 1\nscene arena\nseed 1\nticks 40\n0 rs:1280,720 mm:812,435,0,0\n"
                               "10 kd:f1\n11 ku:f1\n";
  const RunResult r = run("--headless --replay \"" + replayFile.string() + "\" --dump-state \"" +
                          (dir / "state.jsonl").string() + "\" --screenshot-every 1000 --screenshot-dir \"" +
                          dir.string() + "\"");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const nlohmann::json dump = lastDumpLine(dir / "state.jsonl");
  ASSERT_TRUE(dump.is_object());
  const nlohmann::json& inspector = dump.at("inspector");
  if (CLEAVE_HAVE_IMGUI) {
    EXPECT_TRUE(inspector.at("open").get<bool>());
    EXPECT_EQ(inspector.at("target"), "quit cube");
    EXPECT_FALSE(inspector.at("settings").is_null());
    EXPECT_EQ(inspector.at("notice"), "");
  } else {
    EXPECT_FALSE(inspector.at("open").get<bool>());
    EXPECT_NE(inspector.at("notice").get<std::string>().find("not built"), std::string::npos) << inspector.dump();
  }
}

}  // namespace
