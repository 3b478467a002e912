#include <gtest/gtest.h>

#include "renderer/check.h"

namespace clipblur {

// The sanitizer build checks invariants (CLIPBLUR_CHECKS); the release build compiles them out, and
// must not evaluate the condition at all (no side effects, no cost).
TEST(Check, FailingInvariantAbortsInTheCheckedBuildOnly) {
    int evaluated = 0;
    const auto touch = [&] { return ++evaluated > 0; };
    CLIPBLUR_DCHECK(touch());
#ifdef CLIPBLUR_CHECKS
    EXPECT_EQ(evaluated, 1);
    EXPECT_DEATH(CLIPBLUR_DCHECK(evaluated == 0), "invariant failed: evaluated == 0");
#else
    EXPECT_EQ(evaluated, 0) << "compiled out: the condition is not evaluated";
#endif
}

}  // namespace clipblur
