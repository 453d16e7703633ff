// SPDX-License-Identifier: MIT
#include "cleave/components/split_workers.h"
#include "cleave/components/split_clock.h"

#include <algorithm>
#include <exception>
#include <string>

#ifdef __linux__
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace cleave::components {
SplitWorkers::SplitWorkers(uint32_t threads) {
  threads_.reserve(threads);
  for (uint32_t i = 0; i < threads; ++i) threads_.emplace_back([this] { workerLoop(); });
}

SplitWorkers::~SplitWorkers() {
  waitAll();
  {
    std::lock_guard<std::mutex> lock(queueMutex_);
    stopping_ = true;
  }
  queueSignal_.notify_all();
  for (std::thread& t : threads_) t.join();
}

void SplitWorkers::setExecutor(SplitTaskExecutor executor) {
  waitAll();
  executor_ = std::move(executor);
}

std::unique_ptr<SplitComputeScratch> SplitWorkers::takeScratch() {
  {
    std::lock_guard<std::mutex> lock(scratchMutex_);
    if (!scratches_.empty()) {
      auto scratch = std::move(scratches_.back());
      scratches_.pop_back();
      return scratch;
    }
  }
  return std::make_unique<SplitComputeScratch>();
}

void SplitWorkers::giveScratch(std::unique_ptr<SplitComputeScratch> scratch) {
  std::lock_guard<std::mutex> lock(scratchMutex_);
  scratches_.push_back(std::move(scratch));
}

void SplitWorkers::run(Task& task) {
  if (std::this_thread::get_id() != task.submitter) runElsewhere_.fetch_add(1, std::memory_order_relaxed);
  auto scratch = takeScratch();
  try {
    computeSplit(*task.job, *scratch, task.outcome);
    giveScratch(std::move(scratch));
  } catch (const std::exception& e) {  // out of memory, say: the split fails, the game goes on
    task.outcome = SplitOutcome{};
    task.outcome.status = geometry::SplitStatus::InvalidInput;
    task.outcome.message = std::string("the split could not be computed: ") + e.what();
  }
  {
    std::lock_guard<std::mutex> lock(task.mutex);
    task.done = true;
  }
  task.doneSignal.notify_all();
}

void SplitWorkers::workerLoop() {
#ifdef __linux__
  // Workers yield to the main thread when there are more threads than cores: a commit waits for
  // late jobs anyway, and the main thread's frame is what the player sees.
  setpriority(PRIO_PROCESS, pid_t(syscall(SYS_gettid)), 10);
#endif
  for (;;) {
    std::shared_ptr<Task> task;
    {
      std::unique_lock<std::mutex> lock(queueMutex_);
      queueSignal_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) return;  // stopping with nothing left
      task = std::move(queue_.front());
      queue_.pop_front();
      std::lock_guard<std::mutex> taskLock(task->mutex);
      task->started = true;
    }
    run(*task);
  }
}

std::shared_ptr<SplitWorkers::Task> SplitWorkers::submit(std::shared_ptr<const SplitJob> job) {
  auto task = std::make_shared<Task>();
  task->job = std::move(job);
  task->submitter = std::this_thread::get_id();
  inFlight_.push_back(task);
  if (executor_) {
    // A weak pointer: a task the host runs late, after it was waited for, keeps nothing alive.
    executor_([this, weak = std::weak_ptr<Task>(task)] {
      const std::shared_ptr<Task> task = weak.lock();
      if (!task) return;
      {
        std::lock_guard<std::mutex> lock(task->mutex);
        if (task->started) return;  // the waiting thread took it
        task->started = true;
      }
      run(*task);
    });
  } else if (threads_.empty()) {
    task->started = true;
    run(*task);
  } else {
    {
      std::lock_guard<std::mutex> lock(queueMutex_);
      queue_.push_back(task);
    }
    queueSignal_.notify_one();
  }
  return task;
}

void SplitWorkers::wait(Task& task) {
  const double start = nowMilliseconds();
  bool runHere = false;
  {
    // Our queue first (a worker takes a task under the queue lock), then the task's own flag (a
    // host executor's task checks it before running).
    std::lock_guard<std::mutex> queueLock(queueMutex_);
    std::lock_guard<std::mutex> lock(task.mutex);
    if (!task.started) {
      task.started = true;
      runHere = true;
      const auto it = std::find_if(queue_.begin(), queue_.end(), [&](const auto& t) { return t.get() == &task; });
      if (it != queue_.end()) queue_.erase(it);
    }
  }
  if (runHere) {
    task.computedByCaller = true;
    run(task);
  } else {
    std::unique_lock<std::mutex> lock(task.mutex);
    task.doneSignal.wait(lock, [&] { return task.done; });
  }
  task.waitedMilliseconds = nowMilliseconds() - start;
  std::erase_if(inFlight_, [&](const auto& t) { return t.get() == &task; });
}

void SplitWorkers::waitAll() {
  while (!inFlight_.empty()) {
    std::shared_ptr<Task> task = inFlight_.front();
    wait(*task);
  }
}

}  // namespace cleave::components
