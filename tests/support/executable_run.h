// SPDX-License-Identifier: MIT
// Running the engine's executables from tests: capture the output and exit status, a clean scratch
// folder per test, the printed state hash (and its check over split thread counts), the last line of a JSON-lines state dump, and the
// per-cut mass check on a dump's split log (components/split_log.h).
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace cleave::testing {

struct RunResult {
  int exitCode = -1;
  std::string output;  // stdout and stderr
};

// Runs `executable arguments` through the shell with stderr folded into stdout; `prefix`, when
// given, goes before the executable (environment assignments, a wrapper such as setarch).
inline RunResult runExecutable(const std::string& executable, const std::string& arguments,
                               const std::string& prefix = {}) {
  RunResult result;
  const std::string command = prefix + (prefix.empty() ? "" : " ") + "\"" + executable + "\" " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer{};
  size_t n = 0;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

// A run under conditions that must not change a result: glibc fills every allocation and every
// freed block with a garbage byte (a read of memory never written then differs), and the process's
// addresses are laid out without randomization (an order taken from pointers then differs from a
// randomized run's). Compared against a plain run, it sees what running one binary twice cannot.
inline const char* kPerturbedRun = "MALLOC_PERTURB_=165 setarch \"$(uname -m)\" -R";

// build/test-output/<suite>/<name>, emptied.
inline std::filesystem::path scratchDir(const std::string& suite, const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(CLEAVE_BINARY_DIR) / "test-output" / suite / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// The 16 hex digits after the last "state-hash: " of a run's output ("" when absent).
inline std::string stateHash(const std::string& output) {
  const std::string key = "state-hash: ";
  const size_t at = output.rfind(key);
  if (at == std::string::npos) return {};
  return output.substr(at + key.size(), 16);
}

// The state hash each bundled replay ends with is recorded per build configuration (build type,
// compiler and version, processor: floating-point results may differ between them) in
// tests/support/state_hashes.txt, one "configuration replay hash" per line, so that a change that
// alters results is seen in review. A configuration without a record fails, with how to add one
// (CLEAVE_UPDATE_HASHES=1 rewrites the lines of this configuration with the hashes found, in a run
// that still compares 0, 1 and 3 threads): another compiler keeps a check that can fail. Sanitizer
// builds are the exception: they check within the build only.
inline std::filesystem::path stateHashFile() {
  return std::filesystem::path(CLEAVE_SOURCE_DIR) / "tests" / "support" / "state_hashes.txt";
}

inline void expectRecordedStateHash(const std::string& replay, const std::string& hash) {
  const std::string configuration = CLEAVE_BUILD_CONFIGURATION;
  std::vector<std::string> lines;
  std::string recorded;
  {
    std::ifstream in(stateHashFile());
    for (std::string line; std::getline(in, line);) {
      lines.push_back(line);
      const std::string key = configuration + " " + replay + " ";
      if (line.rfind(key, 0) == 0) recorded = line.substr(key.size());
    }
  }
  if (std::getenv("CLEAVE_UPDATE_HASHES")) {
    std::vector<std::string> kept;
    for (const std::string& line : lines)
      if (line.rfind(configuration + " " + replay + " ", 0) != 0) kept.push_back(line);
    kept.push_back(configuration + " " + replay + " " + hash);
    std::ofstream out(stateHashFile());
    for (const std::string& line : kept) out << line << "\n";
    return;
  }
  if (recorded.empty()) {
#if defined(CLEAVE_SANITIZE) || defined(CLEAVE_TSAN)
    // A sanitizer build looks for memory and thread errors; its results are checked within the build
    // (0, 1 and 3 threads, a recording against its replay) and the Release build keeps the record.
    std::printf("[hashes ] sanitizer build %s: %s not compared with a record\n", configuration.c_str(), replay.c_str());
    return;
#endif
    ADD_FAILURE() << "no recorded state hash of " << replay << " for the build configuration " << configuration
                  << " in " << stateHashFile() << " (this run ends in " << hash
                  << "): record this configuration's hashes with CLEAVE_UPDATE_HASHES=1 and ctest -j1, and "
                  << "commit them";
    return;
  }
  EXPECT_EQ(hash, recorded) << replay << " ends in another state than recorded for " << configuration
                            << " in " << stateHashFile() << ": if the change is meant, record it with "
                            << "CLEAVE_UPDATE_HASHES=1";
}

// The number after "split-jobs-off-main-thread: " in a run's output (-1 when absent).
inline long long splitJobsOffMainThread(const std::string& output) {
  const std::string key = "split-jobs-off-main-thread: ";
  const size_t at = output.rfind(key);
  return at == std::string::npos ? -1 : std::atoll(output.c_str() + at + key.size());
}

// Split jobs computed off the main thread in the runs on 1 and on 3 split threads.
struct OffMainThread {
  long long one = 0, three = 0;
};

// Runs `replayArguments` (a --replay and its options) with --split-threads 0, 1 and 3 through
// `run` and expects the same printed state hash each time: threads never change a result. Returns
// the jobs the runs on threads computed off the main thread (none on 0 threads, checked here): a
// caller checks that its replays, together, gave the threads work (a replay of one cut may not,
// when the main thread reaches the job first).
template <typename Run>
OffMainThread expectSameStateOnZeroOneAndThreeSplitThreads(const Run& run, const std::string& replayArguments,
                                                           const std::string& name) {
  std::vector<std::string> hashes;
  OffMainThread off;
  for (int threads : {0, 1, 3}) {
    const RunResult r = run(replayArguments + " --split-threads " + std::to_string(threads) + " --print-state-hash");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    hashes.push_back(stateHash(r.output));
    EXPECT_EQ(hashes.back().size(), 16u) << r.output;
    if (hashes.back().size() != 16u) return off;
    const long long jobs = splitJobsOffMainThread(r.output);
    EXPECT_GE(jobs, 0) << "no split-jobs-off-main-thread line: " << r.output;
    if (threads == 0) {
      EXPECT_EQ(jobs, 0) << name;
    } else {
      (threads == 1 ? off.one : off.three) += jobs;
    }
  }
  std::printf("[threads] %s: %s %s %s\n", name.c_str(), hashes[0].c_str(), hashes[1].c_str(), hashes[2].c_str());
  EXPECT_EQ(hashes[1], hashes[0]) << name;
  EXPECT_EQ(hashes[2], hashes[0]) << name;
  expectRecordedStateHash(name, hashes[0]);
  std::printf("[threads] %s: %lld and %lld jobs off the main thread on 1 and 3 threads\n", name.c_str(), off.one,
              off.three);
  return off;
}

inline nlohmann::json lastDumpLine(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  return last.empty() ? nlohmann::json() : nlohmann::json::parse(last);
}

// Every cut of the dump's split log kept the mass of what it cut (pieces with colliders and debris
// together) within `relative`. Piece masses come from world-space volumes, so float rounding of the
// world transform is the only error. A splitter may touch a collider's margin while its plane misses
// the mesh: those entries have nothing to check.
inline void expectEveryCutKeepsMass(const nlohmann::json& dump, double relative = 2e-6) {
  for (const auto& split : dump.at("splits")) {
    if (split.at("status") == "PlaneMissesMesh") continue;
    ASSERT_EQ(split.at("status"), "Ok") << split.dump();
    const double parent = split.at("parent_mass");
    const double pieces = split.at("pieces_mass");
    ASSERT_GT(parent, 0.0) << split.dump();
    EXPECT_NEAR(pieces / parent, 1.0, relative) << split.dump();
    EXPECT_GE(split.at("pieces").get<int>(), 2) << split.dump();
    // Skinned pieces share the parent's mass by volume, so the masses add up whatever the pieces
    // are: their volumes must add up to the posed character's, integrated on its own.
    if (split.contains("posed_volume")) {
      EXPECT_NEAR(split.at("pieces_volume").get<double>() / split.at("posed_volume").get<double>(), 1.0, 1e-6)
          << split.dump();
    }
  }
}

}  // namespace cleave::testing
