// SPDX-License-Identifier: MIT
// PassThreads: every job of a pass runs exactly once, on as many threads as asked, pass after pass;
// threads are started on first use and kept, and spin between passes while held; the destructor
// joins them.
#include "cleave/geometry/pass_threads.h"

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <set>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace cleave::geometry::detail {
namespace {

TEST(PassThreads, EveryJobRunsOnceAndTheCallerRunsJobZero) {
  PassThreads threads;
  for (uint32_t count : {1u, 2u, 5u, 3u, 8u, 1u, 8u}) {
    std::vector<std::atomic<int>> runs(count);
    std::vector<std::thread::id> where(count);
    threads.run(count, [&](uint32_t i) {
      runs[i].fetch_add(1);
      where[i] = std::this_thread::get_id();
    });
    for (uint32_t i = 0; i < count; ++i) EXPECT_EQ(runs[i].load(), 1) << count << " jobs, job " << i;
    EXPECT_EQ(where[0], std::this_thread::get_id());
    std::set<std::thread::id> distinct(where.begin(), where.end());
    EXPECT_EQ(distinct.size(), count) << "one thread per job";
  }
  EXPECT_EQ(threads.started(), 7u) << "threads are kept: the most any pass asked for, less the caller";
}

TEST(PassThreads, ManyShortPassesSeeEachOthersWrites) {
  // Each pass reads what the pass before wrote on other threads: run() returns only when every job
  // has, and a parked thread sees what the caller wrote before the pass.
  PassThreads threads;
  std::vector<uint64_t> values(4, 0);
  for (uint64_t pass = 1; pass <= 2000; ++pass) {
    threads.run(4, [&](uint32_t i) {
      ASSERT_EQ(values[i], pass - 1);
      values[i] = pass;
    });
  }
  for (uint64_t v : values) EXPECT_EQ(v, 2000u);
}

TEST(PassThreads, HeldPassesSeeEachOthersWritesSlowJobsIncluded) {
  // Held, the threads spin between passes and the caller spins for them; a job slower than the spin
  // limit sends both back to sleeping. Every pass must still see the one before, held or not.
  PassThreads threads;
  std::vector<uint64_t> values(3, 0);
  auto pass = [&](uint64_t n, bool slow) {
    threads.run(3, [&](uint32_t i) {
      ASSERT_EQ(values[i], n - 1);
      if (slow && i == n % 3) std::this_thread::sleep_for(PassThreads::kSpinLimit * 2);
      values[i] = n;
    });
  };
  uint64_t n = 0;
  {
    const PassThreads::Hold hold(threads);
    for (int k = 0; k < 3000; ++k) pass(++n, k % 1000 == 999);
    // A pause longer than the spin limit between passes: the threads fall asleep and are woken.
    std::this_thread::sleep_for(PassThreads::kSpinLimit * 2);
    for (int k = 0; k < 100; ++k) pass(++n, false);
  }
  for (int k = 0; k < 100; ++k) pass(++n, false);  // no longer held: sleeping between passes
  {
    const PassThreads::Hold again(threads);
    for (int k = 0; k < 100; ++k) pass(++n, false);
  }
  for (uint64_t v : values) EXPECT_EQ(v, n);
}

TEST(PassThreads, AThrowOnTheCallingThreadWaitsForTheOthersThenPassesOn) {
  PassThreads threads;
  std::atomic<int> finished{0};
  EXPECT_THROW(threads.run(3,
                           [&](uint32_t i) {
                             if (i == 0) throw std::runtime_error("job 0");
                             std::this_thread::sleep_for(std::chrono::milliseconds(20));
                             finished.fetch_add(1);
                           }),
               std::runtime_error);
  EXPECT_EQ(finished.load(), 2) << "run() returned before the parked threads' jobs";
  // The threads are still usable.
  std::atomic<int> runs{0};
  threads.run(3, [&](uint32_t) { runs.fetch_add(1); });
  EXPECT_EQ(runs.load(), 3);
}

TEST(PassThreads, ZeroJobsRunNothingAndAnUnusedPoolStartsNoThread) {
  PassThreads threads;
  bool ran = false;
  threads.run(0, [&](uint32_t) { ran = true; });
  EXPECT_FALSE(ran);
  threads.run(1, [&](uint32_t) { ran = true; });
  EXPECT_TRUE(ran);
  EXPECT_EQ(threads.started(), 0u);
}

}  // namespace
}  // namespace cleave::geometry::detail
