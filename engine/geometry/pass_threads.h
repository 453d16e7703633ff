// SPDX-License-Identifier: MIT
// Threads for the passes of a split (SplitOptions::threads). Internal to the geometry library.
//
// A split runs a handful of passes on threads (classification, the cut, the join, both sides'
// islands and pieces). Starting a thread per pass costs about 40 microseconds here, a few per cent
// of a million-triangle split on two threads; PassThreads starts its threads on first use and parks
// them between passes, so a pass only wakes them.
//
// Waking a sleeping thread costs far more on a virtual machine, where the idle core is halted and
// the wake goes through the host (tens to hundreds of microseconds). So while a caller holds the
// threads (Hold, for the length of one split), a thread that finished a job spins, briefly
// pausing, for the next pass instead of sleeping, and the caller spins for the jobs it waits on.
// Only as many threads spin as there are cores beside the caller's; a thread that had no job in a
// pass sleeps; a spin offers its core to other threads now and then. Both spins are bounded
// (kSpinLimit); past it, or once the hold ends, they sleep as before. A held pool keeps its
// threads' cores busy between passes: hold it only across passes that follow each other closely.
//
// Ownership: the threads belong to the PassThreads object and are joined by its destructor. One
// caller at a time: run() is not re-entrant and must not be called from two threads at once (each
// splitter owns one, used by the thread that calls split()).
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <type_traits>
#include <vector>

namespace cleave::geometry::detail {

class PassThreads {
 public:
  PassThreads() = default;
  ~PassThreads();
  PassThreads(const PassThreads&) = delete;
  PassThreads& operator=(const PassThreads&) = delete;

  // Runs job(i) for every i in [0, count) and returns when all have returned: job(0) on the
  // calling thread, the others on parked threads (started on first use). Where a thread cannot be
  // started, its jobs run on the calling thread, after job(0). A job on the calling thread may
  // throw: run() waits for the parked threads' jobs, then rethrows. One on a parked thread must not
  // (it ends the program, as an exception leaving any std::thread does).
  template <class Job>
  void run(uint32_t count, Job&& job) {
    using Stored = std::remove_reference_t<Job>;
    runErased(count, const_cast<void*>(static_cast<const void*>(&job)),
              [](void* stored, uint32_t index) { (*static_cast<Stored*>(stored))(index); });
  }

  // Holds the threads for a run of passes (see the header's comment): constructed before the
  // first, destroyed after the last; the threads are held while any Hold lives. Made by the owner
  // of run(), on its thread.
  class Hold {
   public:
    explicit Hold(PassThreads& threads) : threads_(threads) { threads_.holds_.fetch_add(1, std::memory_order_relaxed); }
    ~Hold() { threads_.holds_.fetch_sub(1, std::memory_order_relaxed); }
    Hold(const Hold&) = delete;
    Hold& operator=(const Hold&) = delete;

   private:
    PassThreads& threads_;
  };

  // How long a spin waits at most before it sleeps.
  static constexpr std::chrono::microseconds kSpinLimit{2000};

  // Threads started so far (for tests).
  size_t started() const { return threads_.size(); }

  // Jobs run on parked threads by every PassThreads of the process, since it started: a test of
  // "the same bytes on N threads" checks that it grew, so the threads really took part.
  static uint64_t jobsRunOnParkedThreads();

 private:
  using Call = void (*)(void*, uint32_t);
  void runErased(uint32_t count, void* job, Call call);
  // Thread `index` (1, 2, ...): waits for a pass after `seen`, runs its job, and again until stop_.
  void park(uint32_t index, uint64_t seen);

  std::vector<std::thread> threads_;  // threads_[i - 1] runs job(i)
  std::mutex mutex_;
  std::condition_variable wake_;  // a pass started, or stop_
  std::condition_variable done_;  // pending_ reached 0
  // Read outside the mutex by spinning threads: atomics. Written under the mutex (but holds_).
  std::atomic<uint64_t> pass_{0};  // counts passes: a parked thread runs when it changes
  uint32_t count_ = 0;            // the current pass's job count
  std::atomic<uint32_t> pending_{0};  // parked threads still running the current pass
  void* job_ = nullptr;
  Call call_ = nullptr;
  std::atomic<bool> stop_{false};
  std::atomic<uint32_t> holds_{0};  // Holds alive: spin between passes while not 0
};

}  // namespace cleave::geometry::detail
