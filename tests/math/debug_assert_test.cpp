// The debug-assert tier (tumble/debug_assert.hpp): where compiled in (Debug, sanitize), a broken
// invariant stops the program with its description and place; where not (release), the condition is
// not even evaluated, so the engine pays nothing.
#include <gtest/gtest.h>

#include "tumble/debug_assert.hpp"

namespace tumble {
namespace {

TEST(DebugAssert, ABrokenInvariantAbortsWithItsPlaceOnlyWhereCompiledIn) {
  int evaluated = 0;
  const auto broken = [&] {
    ++evaluated;
    return false;
  };
#if defined(TUMBLE_DEBUG_ASSERTS)
  EXPECT_DEATH(TUMBLE_DEBUG_ASSERT(broken(), "the invariant under test"),
               "tumble: internal error at .*debug_assert_test.cpp:[0-9]+: the invariant under test");
  TUMBLE_DEBUG_ASSERT(evaluated == 0, "a kept invariant passes");  // the death test ran in a child
#else
  TUMBLE_DEBUG_ASSERT(broken(), "the invariant under test");
  EXPECT_EQ(evaluated, 0);
#endif
}

}  // namespace
}  // namespace tumble
