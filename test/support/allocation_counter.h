#pragma once
// Counts heap allocations (global operator new) made by the calling thread, so tests can prove
// that a real-time function does not allocate. Linking this library replaces operator new.

#include <cstdint>

namespace teleop::test {

/// Counts the calling thread's allocations between construction and destruction.
class ScopedAllocationCounter {
 public:
  ScopedAllocationCounter();
  ~ScopedAllocationCounter();
  ScopedAllocationCounter(const ScopedAllocationCounter&) = delete;
  ScopedAllocationCounter& operator=(const ScopedAllocationCounter&) = delete;

  /// Allocations so far.
  uint64_t count() const;

 private:
  uint64_t start_;
  bool was_counting_;
};

}  // namespace teleop::test
