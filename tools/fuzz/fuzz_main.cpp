// SPDX-License-Identifier: MIT
// Standalone runner for a fuzz driver when libFuzzer is not used: a seeded mutation loop over the
// driver's built-in seeds, so CI can run a short deterministic smoke.
//
//   cleave-fuzz-<name> [--iterations N] [--seconds T] [--seed S] [--write-seeds DIR] [FILE...]
//
// --seconds T runs for T seconds of wall time (the long run; --iterations then only caps it, and is
// unlimited unless given).
// FILEs are run once each (to replay a crash input found by libFuzzer). --write-seeds writes the
// seeds as files into DIR (a starting corpus for libFuzzer) and exits. Mutations: bit flips,
// random and boundary bytes, inserted, erased, duplicated and truncated ranges, splices of two
// inputs. Mutated inputs that pass are kept in a small pool and mutated further.
#include <algorithm>
#include <charconv>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <string_view>

#include <fcntl.h>
#include <unistd.h>

#include "cleave_version.h"
#include "tools/fuzz/fuzz_driver.h"

namespace {

using Bytes = std::vector<uint8_t>;

// The input being run, written to "fuzz-crash-input" in the working folder if the driver aborts,
// so the failure can be replayed with `cleave-fuzz-<name> fuzz-crash-input`.
const Bytes* gCurrent = nullptr;

extern "C" void onAbort(int) {
  if (gCurrent != nullptr) {
    const int fd = ::open("fuzz-crash-input", O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      const ssize_t written = ::write(fd, gCurrent->data(), gCurrent->size());
      (void)written;
      ::close(fd);
    }
    static const char kNote[] = "the failing input was written to fuzz-crash-input\n";
    const ssize_t noted = ::write(2, kNote, sizeof(kNote) - 1);
    (void)noted;
  }
  std::signal(SIGABRT, SIG_DFL);
  std::raise(SIGABRT);
}

// True when the driver accepted the input.
bool runOne(const Bytes& input) {
  gCurrent = &input;
  const int status = LLVMFuzzerTestOneInput(input.data(), input.size());
  gCurrent = nullptr;
  return status == 0;
}

constexpr size_t kMaxInput = 1 << 16;
constexpr size_t kPoolSize = 64;

void mutate(Bytes& bytes, const std::vector<Bytes>& pool, std::mt19937_64& rng) {
  auto pick = [&rng](size_t n) { return n == 0 ? size_t{0} : static_cast<size_t>(rng() % n); };
  // Mostly one or two small changes: a valid file stays close to valid, where the deep paths are.
  int rounds = 1;
  while (rounds < 8 && rng() % 3 == 0) ++rounds;
  for (int r = 0; r < rounds; ++r) {
    switch (rng() % 8) {
      case 0:  // flip a bit
        if (!bytes.empty()) bytes[pick(bytes.size())] ^= static_cast<uint8_t>(1u << (rng() % 8));
        break;
      case 1:  // random byte
        if (!bytes.empty()) bytes[pick(bytes.size())] = static_cast<uint8_t>(rng());
        break;
      case 2: {  // boundary value
        static constexpr uint8_t kValues[] = {0x00, 0x01, 0x7f, 0x80, 0xff, '0', '9', '-', ' ', '\n', '/'};
        if (!bytes.empty()) bytes[pick(bytes.size())] = kValues[rng() % sizeof(kValues)];
        break;
      }
      case 3: {  // insert random bytes
        const size_t at = pick(bytes.size() + 1);
        const size_t count = 1 + pick(8);
        for (size_t i = 0; i < count; ++i) {
          bytes.insert(bytes.begin() + static_cast<std::ptrdiff_t>(at), static_cast<uint8_t>(rng()));
        }
        break;
      }
      case 4: {  // erase a range
        if (bytes.size() < 2) break;
        const size_t at = pick(bytes.size());
        const size_t count = 1 + pick(std::min<size_t>(16, bytes.size() - at));
        bytes.erase(bytes.begin() + static_cast<std::ptrdiff_t>(at),
                    bytes.begin() + static_cast<std::ptrdiff_t>(std::min(bytes.size(), at + count)));
        break;
      }
      case 5: {  // duplicate a range
        if (bytes.empty()) break;
        const size_t at = pick(bytes.size());
        const size_t count = 1 + pick(std::min<size_t>(32, bytes.size() - at));
        const Bytes chunk(bytes.begin() + static_cast<std::ptrdiff_t>(at),
                          bytes.begin() + static_cast<std::ptrdiff_t>(at + count));
        bytes.insert(bytes.begin() + static_cast<std::ptrdiff_t>(pick(bytes.size() + 1)), chunk.begin(),
                     chunk.end());
        break;
      }
      case 6:  // truncate
        if (!bytes.empty()) bytes.resize(pick(bytes.size()));
        break;
      case 7: {  // splice with another input
        if (pool.empty()) break;
        const Bytes& other = pool[pick(pool.size())];
        const size_t cut = pick(bytes.size() + 1);
        const size_t from = pick(other.size() + 1);
        bytes.resize(cut);
        bytes.insert(bytes.end(), other.begin() + static_cast<std::ptrdiff_t>(from), other.end());
        break;
      }
    }
  }
  if (bytes.size() > kMaxInput) bytes.resize(kMaxInput);
}

bool parseCount(std::string_view text, uint64_t& value) {
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && end == text.data() + text.size();
}

int usage(const char* program) {
  std::fprintf(stderr, "usage: %s [--iterations N] [--seconds T] [--seed S] [--write-seeds DIR] [FILE...]\n",
               program);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  uint64_t iterations = 10000;
  uint64_t seconds = 0;
  bool iterationsGiven = false;
  uint64_t seed = 1;
  std::string seedDir;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "--version") {
      std::printf("%s %s\n", argv[0], cleave::kVersion);
      return 0;
    }
    if ((arg == "--iterations" || arg == "--seed") && i + 1 < argc) {
      iterationsGiven = iterationsGiven || arg == "--iterations";
      if (!parseCount(argv[++i], arg == "--seed" ? seed : iterations)) return usage(argv[0]);
    } else if (arg == "--seconds" && i + 1 < argc) {
      if (!parseCount(argv[++i], seconds)) return usage(argv[0]);
    } else if (arg == "--write-seeds" && i + 1 < argc) {
      seedDir = argv[++i];
    } else if (arg == "--help" || arg == "-h" || arg.starts_with("-")) {
      return usage(argv[0]);
    } else {
      files.emplace_back(arg);
    }
  }

  const std::vector<Bytes> seeds = cleave::fuzz::fuzzSeeds();
  if (!seedDir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(seedDir, ec);
    for (size_t i = 0; i < seeds.size(); ++i) {
      const std::string path = (std::filesystem::path(seedDir) / ("seed_" + std::to_string(i))).string();
      std::ofstream out(path, std::ios::binary);
      out.write(reinterpret_cast<const char*>(seeds[i].data()), static_cast<std::streamsize>(seeds[i].size()));
      if (!out) {
        std::fprintf(stderr, "%s: cannot write\n", path.c_str());
        return 1;
      }
    }
    std::printf("wrote %zu seeds to %s\n", seeds.size(), seedDir.c_str());
    return 0;
  }
  if (!files.empty()) {
    for (const std::string& file : files) {
      std::ifstream in(file, std::ios::binary);
      if (!in) {
        std::fprintf(stderr, "%s: cannot open\n", file.c_str());
        return 1;
      }
      const Bytes bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      LLVMFuzzerTestOneInput(bytes.data(), bytes.size());
      std::printf("%s: ok\n", file.c_str());
    }
    return 0;
  }

  std::mt19937_64 rng(seed);
  std::vector<Bytes> pool = seeds;
  std::signal(SIGABRT, onAbort);
  for (const Bytes& s : seeds) runOne(s);
  uint64_t acceptedCount = 0;
  if (seconds > 0 && !iterationsGiven) iterations = UINT64_MAX;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
  uint64_t i = 0;
  for (; i < iterations; ++i) {
    if (seconds > 0 && i % 256 == 0 && std::chrono::steady_clock::now() >= deadline) break;
    Bytes input = pool[static_cast<size_t>(rng() % pool.size())];
    mutate(input, pool, rng);
    const bool accepted = runOne(input);
    acceptedCount += accepted ? 1 : 0;
    // Keep some accepted inputs so mutations compound; replace at random once the pool is full.
    if (accepted && rng() % 2 == 0) {
      if (pool.size() < kPoolSize) pool.push_back(std::move(input));
      else pool[seeds.size() + static_cast<size_t>(rng() % (kPoolSize - seeds.size()))] = std::move(input);
    }
  }
  std::printf("%llu mutated inputs from %zu seeds (seed %llu), %llu accepted: no invariant broken\n",
              static_cast<unsigned long long>(i), seeds.size(),
              static_cast<unsigned long long>(seed), static_cast<unsigned long long>(acceptedCount));
  return 0;
}
