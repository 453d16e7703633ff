// SPDX-License-Identifier: MIT
// SplitWorkers: where the compute stage of split jobs runs. A pool of worker threads of our own
// (std::thread), or a task callback the host supplies (its own job system), or inline on the
// calling thread (0 threads). Whichever runs a job, the outcome is the same: computeSplit is a pure
// function of the job, and each running task has its own scratch.
//
// Threads: submit, wait and the destructor are called from one thread (the main thread). A task
// given to a host executor must be run exactly once, on any thread, and may run after submit
// returns; the destructor waits for every submitted task.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "cleave/components/split_compute.h"
#include "cleave/components/split_job.h"

namespace cleave::components {

// A host's task system: runs `task` once, on any thread, soon (Box2D's enqueue-task style).
using SplitTaskExecutor = std::function<void(std::function<void()> task)>;

class SplitWorkers {
 public:
  // One job in flight: its outcome is valid once SplitWorkers::wait returned for it.
  struct Task {
    std::shared_ptr<const SplitJob> job;
    SplitOutcome outcome;
    double waitedMilliseconds = 0.0;  // how long the main thread waited for it (0: it was done)
    bool computedByCaller = false;    // the waiting thread ran it itself (it had not started)

   private:
    friend class SplitWorkers;
    std::mutex mutex;
    std::condition_variable doneSignal;
    bool started = false;
    bool done = false;
    std::thread::id submitter;  // the thread that submitted it
  };

  // `threads` workers of our own (0: compute inline in submit).
  explicit SplitWorkers(uint32_t threads = 0);
  ~SplitWorkers();
  SplitWorkers(const SplitWorkers&) = delete;
  SplitWorkers& operator=(const SplitWorkers&) = delete;

  uint32_t threads() const { return uint32_t(threads_.size()); }
  // Tasks computed on another thread than the one that submitted them, since the pool was made: the
  // proof that a run "on N threads" used them (0 with no threads, or when every task was run by its
  // waiting caller).
  uint64_t tasksRunElsewhere() const { return runElsewhere_.load(std::memory_order_relaxed); }
  // Hands tasks to the host instead of our threads (empty: back to our own). Waits for the tasks
  // in flight first.
  void setExecutor(SplitTaskExecutor executor);

  // Starts computing `job` and returns its task.
  std::shared_ptr<Task> submit(std::shared_ptr<const SplitJob> job);
  // Blocks until `task` is done. A task no thread has started yet is run by the caller, so waiting
  // never idles while work is queued.
  void wait(Task& task);
  // Waits for every task submitted so far.
  void waitAll();

 private:
  void run(Task& task);  // computes on a scratch of the pool
  void workerLoop();
  std::unique_ptr<SplitComputeScratch> takeScratch();
  void giveScratch(std::unique_ptr<SplitComputeScratch> scratch);

  std::vector<std::thread> threads_;
  SplitTaskExecutor executor_;
  std::mutex queueMutex_;
  std::condition_variable queueSignal_;
  std::deque<std::shared_ptr<Task>> queue_;  // our threads' work, oldest first
  std::vector<std::shared_ptr<Task>> inFlight_;  // submitted and not waited for
  bool stopping_ = false;
  std::atomic<uint64_t> runElsewhere_{0};
  std::mutex scratchMutex_;
  std::vector<std::unique_ptr<SplitComputeScratch>> scratches_;
};

}  // namespace cleave::components
