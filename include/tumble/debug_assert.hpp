#pragma once
// Invariants that tumble itself keeps, checked in debug builds: a body's Λ positive and its U a proper
// rotation, unit quaternions where a step or a closed form returns one. Compiled in when
// TUMBLE_DEBUG_ASSERTS is defined (CMAKE_BUILD_TYPE=Debug, and the sanitize preset, so that CI's second
// run of every test checks them); compiled out of release builds, where the engine runs. A failure is a
// bug in tumble, not bad input (bad input gets an error from the readers and constructors): it prints
// the invariant and the place, and aborts.
#include <cstdio>
#include <cstdlib>

#if defined(TUMBLE_DEBUG_ASSERTS)
#define TUMBLE_DEBUG_ASSERT(condition, what) \
  ((condition) ? void(0) : ::tumble::detail::debug_assert_failed(#condition, what, __FILE__, __LINE__))
#else
// Not evaluated (sizeof), but still compiled: an assert cannot rot in release builds.
#define TUMBLE_DEBUG_ASSERT(condition, what) static_cast<void>(sizeof((condition) ? 1 : 0))
#endif

namespace tumble::detail {

[[noreturn]] inline void debug_assert_failed(const char* condition, const char* what, const char* file,
                                             int line) {
  std::fprintf(stderr, "tumble: internal error at %s:%d: %s (%s does not hold); please report it\n", file,
               line, what, condition);
  std::abort();
}

}  // namespace tumble::detail
