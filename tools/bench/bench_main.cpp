// SPDX-License-Identifier: MIT
// cleave-bench's entry point: Google Benchmark's, plus --version.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstring>

#include "cleave_version.h"

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--version") == 0) {
      std::printf("cleave-bench %s\n", cleave::kVersion);
      return 0;
    }
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
