// SPDX-License-Identifier: MIT
// Threads for the passes of a split (SplitOptions::threads). Internal to the geometry library.
//
// A split runs a handful of passes on threads (classification, the cut, the join, both sides'
// islands and pieces). Starting a thread per pass costs about 40 microseconds here, a few per cent
// of a million-triangle split on two threads; PassThreads starts its threads on first use and parks
// them between passes, so a pass only wakes them.
//
// Ownership: the threads belong to the PassThreads object and are joined by its destructor. One
// caller at a time: run() is not re-entrant and must not be called from two threads at once (each
// splitter owns one, used by the thread that calls split()).
#pragma once

#include <algorithm>
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

  // Threads started so far (for tests).
  size_t started() const { return threads_.size(); }

 private:
  using Call = void (*)(void*, uint32_t);
  void runErased(uint32_t count, void* job, Call call);
  // Thread `index` (1, 2, ...): waits for a pass after `seen`, runs its job, and again until stop_.
  void park(uint32_t index, uint64_t seen);

  std::vector<std::thread> threads_;  // threads_[i - 1] runs job(i)
  std::mutex mutex_;
  std::condition_variable wake_;  // a pass started, or stop_
  std::condition_variable done_;  // pending_ reached 0
  uint64_t pass_ = 0;             // counts passes: a parked thread runs when it changes
  uint32_t count_ = 0;            // the current pass's job count
  uint32_t pending_ = 0;          // parked threads still running the current pass
  void* job_ = nullptr;
  Call call_ = nullptr;
  bool stop_ = false;
};

}  // namespace cleave::geometry::detail
