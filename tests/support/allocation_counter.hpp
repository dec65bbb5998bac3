#pragma once
// Counts heap allocations in a region of a test: the test binary replaces the global operator new
// (allocation_counter.cpp), which counts only while a CountAllocations object is alive.
#include <cstddef>

namespace tumble::test {

/// The number of operator new calls made while counting was on.
long allocations_counted();

/// Turns counting on for its lifetime (not reentrant; one at a time).
class CountAllocations {
 public:
  CountAllocations();
  ~CountAllocations();
  CountAllocations(const CountAllocations&) = delete;
  CountAllocations& operator=(const CountAllocations&) = delete;
  /// Allocations since construction.
  long count() const;
  /// Bytes requested by those allocations (whether freed since or not).
  long bytes() const;

 private:
  long start_, start_bytes_;
};

}  // namespace tumble::test
