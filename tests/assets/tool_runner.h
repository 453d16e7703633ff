// SPDX-License-Identifier: MIT
// Test helpers that run programs: a shell command with its output captured, build/bin/cleave-split,
// and the Khronos glTF validator (tools/gltf-validate) when node and the npm package gltf-validator
// are there (./cleave test installs it into <build>/npm).
#pragma once

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <span>
#include <string>

#include <sys/wait.h>

#include "tests/assets/asset_test_files.h"

namespace cleave::assets::test {

// Runs a command, capturing stdout into `output`; returns the exit status (-1 when it did not run
// or did not exit).
inline int runCommand(const std::string& command, std::string& output) {
  output.clear();
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return -1;
  char buffer[4096];
  size_t got = 0;
  while ((got = std::fread(buffer, 1, sizeof(buffer), pipe)) > 0) output.append(buffer, got);
  const int status = pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The text in single quotes for the shell (the tests' paths hold no quote).
inline std::string quote(const std::string& text) { return "'" + text + "'"; }

inline std::string splitTool() { return std::string(CLEAVE_BINARY_DIR) + "/bin/cleave-split"; }

// The folder holding node_modules/gltf-validator: CLEAVE_GLTF_VALIDATOR_DIR, else the npm folder of
// the set-up (npmDir(), <build>/npm). Empty, with the reason in `why`, when the package is not
// there or node is missing.
inline std::string gltfValidatorDir(std::string& why) {
  const char* env = std::getenv("CLEAVE_GLTF_VALIDATOR_DIR");
  const std::filesystem::path dir =
      env != nullptr && *env != '\0' ? std::filesystem::path(env) : npmDir();
  std::error_code ec;
  const std::filesystem::path package = dir / "node_modules" / "gltf-validator";
  if (!std::filesystem::exists(package / "package.json", ec)) {
    why = "npm package gltf-validator not installed (no " + package.string() +
          "; tools/install-deps.sh installs it, see docs/cleave-split.md)";
    return {};
  }
  std::string output;
  if (runCommand("node --version 2>/dev/null", output) != 0) {
    why = "node not found on the path";
    return {};
  }
  return std::filesystem::absolute(dir, ec).string();
}

// Runs tools/gltf-validate on `files` with the validator in `validatorDir`; its exit status (0 when
// no file has an error) and, in `report`, one JSON line per file (and any error text).
inline int validateGltf(const std::string& validatorDir, std::span<const std::string> files,
                        std::string& report) {
  std::string command = "CLEAVE_GLTF_VALIDATOR_DIR=" + quote(validatorDir) + " node " +
                        quote(std::string(CLEAVE_SOURCE_DIR) + "/tools/gltf-validate/validate.cjs");
  for (const std::string& file : files) command += ' ' + quote(file);
  return runCommand(command + " 2>&1", report);
}

}  // namespace cleave::assets::test
