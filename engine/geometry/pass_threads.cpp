// SPDX-License-Identifier: MIT
#include "cleave/geometry/pass_threads.h"

#include <exception>
#include <system_error>
#include <thread>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace cleave::geometry::detail {

namespace {

void cpuPause() {  // a hint to the core that this is a wait loop
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#elif defined(__aarch64__)
  asm volatile("yield");
#endif
}

// Spins until done() or `limit` has passed. The clock is read once per 64 pauses (a pause is a few
// to tens of nanoseconds), and the thread then offers its core to any other thread waiting for one
// (a yield returns at once when none is): with more threads than cores, the thread a spin waits
// for may be the one waiting.
template <class Done>
void spinUntil(Done&& done, std::chrono::microseconds limit) {
  const auto end = std::chrono::steady_clock::now() + limit;
  for (;;) {
    for (int i = 0; i < 64; ++i) {
      if (done()) return;
      cpuPause();
    }
    if (std::chrono::steady_clock::now() >= end) return;
    std::this_thread::yield();
  }
}

// How many parked threads may spin at once: one per core beside the caller's.
uint32_t spinningThreads() {
  static const uint32_t cores = std::thread::hardware_concurrency();
  return cores > 1 ? cores - 1 : 0;
}

std::atomic<uint64_t> parkedJobs{0};  // see jobsRunOnParkedThreads

}  // namespace

uint64_t PassThreads::jobsRunOnParkedThreads() { return parkedJobs.load(std::memory_order_relaxed); }

PassThreads::~PassThreads() {
  {
    std::lock_guard lock(mutex_);
    stop_.store(true);
  }
  wake_.notify_all();
  for (std::thread& thread : threads_) thread.join();
}

void PassThreads::runErased(uint32_t count, void* job, Call call) {
  if (count == 0) return;
  // Start what this pass needs and is not running yet; stop at the first failure.
  try {
    while (threads_.size() + 1 < count) {
      const uint32_t index = static_cast<uint32_t>(threads_.size()) + 1;
      const uint64_t seen = pass_;  // only this thread changes pass_: the new one waits for the next
      threads_.emplace_back([this, index, seen] { park(index, seen); });
    }
  } catch (const std::system_error&) {
  }
  const uint32_t onThreads = std::min<uint32_t>(count - 1, static_cast<uint32_t>(threads_.size()));
  if (onThreads > 0) {
    {
      std::lock_guard lock(mutex_);
      job_ = job;
      call_ = call;
      count_ = onThreads + 1;
      pending_ = onThreads;
      pass_.fetch_add(1, std::memory_order_release);
    }
    wake_.notify_all();
  }
  // A job here that throws (a failed allocation) must not leave while the parked threads still run
  // theirs, which reach into the caller's frame: wait for them, then pass the exception on.
  std::exception_ptr failure;
  try {
    call(job, 0);
    for (uint32_t index = onThreads + 1; index < count; ++index) call(job, index);
  } catch (...) {
    failure = std::current_exception();
  }
  if (onThreads > 0) {
    if (holds_.load(std::memory_order_relaxed) != 0) {
      spinUntil([this] { return pending_.load(std::memory_order_acquire) == 0; }, kSpinLimit);
    }
    std::unique_lock lock(mutex_);
    done_.wait(lock, [this] { return pending_ == 0; });
    job_ = nullptr;
    call_ = nullptr;
  }
  if (failure) std::rethrow_exception(failure);
}

// Held, a thread that ran a job in the pass before spins for the next one, if it is among the first
// spinningThreads(); one without a job (a pass of fewer chunks) or past them sleeps at once.
void PassThreads::park(uint32_t index, uint64_t seen) {
  bool ran = false;
  for (;;) {
    void* job = nullptr;
    Call call = nullptr;
    if (ran && index <= spinningThreads() && holds_.load(std::memory_order_relaxed) != 0) {
      spinUntil(
          [&] {
            return pass_.load(std::memory_order_acquire) != seen || holds_.load(std::memory_order_relaxed) == 0 ||
                   stop_.load(std::memory_order_relaxed);
          },
          kSpinLimit);
    }
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || pass_ != seen; });
      if (stop_) return;
      seen = pass_;
      ran = index < count_;
      if (!ran) continue;
      job = job_;
      call = call_;
    }
    call(job, index);
    parkedJobs.fetch_add(1, std::memory_order_relaxed);
    std::lock_guard lock(mutex_);
    if (--pending_ == 0) done_.notify_one();
  }
}

}  // namespace cleave::geometry::detail
