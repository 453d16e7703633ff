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

// Runs one pass of `jobs` jobs in which job i checks and moves on the value that job i - 1 (mod
// jobs) moved on in the pass before, so that every pass reads what other threads wrote in the one
// before (run() returns only when every job has; a parked thread sees what was written before the
// pass started). A job slower than `slowFor` now and then when asked. Counts wrong reads in `wrong`
// (no assertion inside a job: a parked thread must not throw).
void rotatingPass(PassThreads& threads, std::vector<uint64_t>& values, uint64_t n, std::atomic<int>& wrong,
                  std::chrono::microseconds slowFor = {}) {
  const uint32_t jobs = static_cast<uint32_t>(values.size());
  threads.run(jobs, [&](uint32_t i) {
    uint64_t& value = values[(i + n) % jobs];
    if (value != n - 1) wrong.fetch_add(1);
    if (slowFor.count() > 0 && i == n % jobs) std::this_thread::sleep_for(slowFor);
    value = n;
  });
}

TEST(PassThreads, ManyShortPassesSeeEachOthersWrites) {
  PassThreads threads;
  std::vector<uint64_t> values(4, 0);
  std::atomic<int> wrong{0};
  for (uint64_t pass = 1; pass <= 2000; ++pass) rotatingPass(threads, values, pass, wrong);
  EXPECT_EQ(wrong.load(), 0);
  for (uint64_t v : values) EXPECT_EQ(v, 2000u);
}

TEST(PassThreads, HeldPassesSeeEachOthersWritesSlowJobsIncluded) {
  // Held, a thread that ran a job spins for the next pass and the caller spins for the jobs; a job
  // slower than the spin limit, or a pause between passes longer than it, sends them back to
  // sleeping on the condition variables. Every pass must still see the one before, held or not.
  PassThreads threads;
  std::vector<uint64_t> values(3, 0);
  std::atomic<int> wrong{0};
  uint64_t n = 0;
  {
    const PassThreads::Hold hold(threads);
    for (int k = 0; k < 600; ++k) {
      const bool slow = k % 200 == 199;
      rotatingPass(threads, values, ++n, wrong, slow ? PassThreads::kSpinLimit * 2 : std::chrono::microseconds{});
    }
    std::this_thread::sleep_for(PassThreads::kSpinLimit * 2);  // a pause past the spin limit
    for (int k = 0; k < 100; ++k) rotatingPass(threads, values, ++n, wrong);
    {
      const PassThreads::Hold nested(threads);  // held while any Hold lives
    }
    for (int k = 0; k < 100; ++k) rotatingPass(threads, values, ++n, wrong);
  }
  for (int k = 0; k < 100; ++k) rotatingPass(threads, values, ++n, wrong);  // no longer held
  {
    const PassThreads::Hold again(threads);
    rotatingPass(threads, values, ++n, wrong, PassThreads::kSpinLimit * 2);
    for (int k = 0; k < 100; ++k) rotatingPass(threads, values, ++n, wrong);
  }
  EXPECT_EQ(wrong.load(), 0);
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
