// SPDX-License-Identifier: MIT
// The contract between a fuzz driver and the standalone runner (fuzz_main.cpp). Each driver defines
// LLVMFuzzerTestOneInput (the libFuzzer entry point) and fuzzSeeds(), a few valid inputs to start
// mutating from. A driver aborts (so that libFuzzer or the runner reports it) when an invariant the
// library promises is broken. It returns 0 for input the library accepted and -1 for input it
// rejected (libFuzzer then keeps it out of the corpus; the runner mutates accepted input further).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace cleave::fuzz {

std::vector<std::vector<uint8_t>> fuzzSeeds();

// Prints the broken invariant on stderr and aborts.
[[noreturn]] inline void fail(const char* what) {
  std::fprintf(stderr, "fuzz invariant broken: %s\n", what);
  std::abort();
}

}  // namespace cleave::fuzz
