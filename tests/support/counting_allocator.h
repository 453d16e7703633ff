// SPDX-License-Identifier: MIT
// Allocation counting for tests: the global operator new and delete (plain, array, nothrow, sized)
// replaced with malloc and free, counting allocations while cleave::testing::gCountAllocations is
// set. Every form is replaced, so that no allocation of the sanitizer's own operator new reaches
// this free (what AddressSanitizer reports as alloc-dealloc-mismatch).
// Include it in exactly one source file of a test binary: it defines the global operators.
#pragma once

#include <atomic>
#include <cstdlib>
#include <new>

namespace cleave::testing {
inline std::atomic<bool> gCountAllocations{false};
inline std::atomic<size_t> gAllocations{0};
inline void* countedAllocate(std::size_t size) {
  if (gCountAllocations.load(std::memory_order_relaxed)) gAllocations.fetch_add(1, std::memory_order_relaxed);
  void* p = std::malloc(size ? size : 1);
  if (!p) throw std::bad_alloc();
  return p;
}
inline void* countedAllocateOrNull(std::size_t size) noexcept {
  try {
    return countedAllocate(size);
  } catch (...) {
    return nullptr;
  }
}
}  // namespace cleave::testing

void* operator new(std::size_t size) { return cleave::testing::countedAllocate(size); }
void* operator new[](std::size_t size) { return cleave::testing::countedAllocate(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept { return cleave::testing::countedAllocateOrNull(size); }
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  return cleave::testing::countedAllocateOrNull(size);
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
