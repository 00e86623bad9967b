// SLUT_CHECK stays on in every build (this suite is built RelWithDebInfo, with NDEBUG):
// a violated invariant stops the process with the condition, both operands and file:line.
// Reference: kernels/slut_compat.h's contract. Death tests run the call in a child process.
#include <gtest/gtest.h>

#include <cmath>

extern "C" {
#include "slut_nearlight.h"
}

namespace {

// slut_distant_light_factor's precondition r ≥ 0: callers validate user input, so a negative r
// is a bug in the caller, reported with the value it got.
TEST(Checks, StayOnWithNdebugAndPrintOperandsAndPlace) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_DEATH(slut_distant_light_factor(-0.5, 1.0),
                 "scatterlut: check failed at .*slut_nearlight_approx\\.h:[0-9]+: r >= 0\\.0 \\(r = -0\\.5, 0\\.0 = 0\\)");
    // NaN fails a check too (every comparison with NaN is false).
    EXPECT_DEATH(slut_nl_E_thin(1.0, std::nan("")), "check failed at .*: S >= 0\\.0 \\(S = nan, 0\\.0 = 0\\)");
}

TEST(Checks, SilentWhenTheInvariantHolds) {
    EXPECT_EQ(slut_distant_light_factor(0.0, 1.0), 0.0); // r = 0: no light enters (a limit, not an error)
    EXPECT_GT(slut_nl_E_thin(1.0, 1.0), 0.0);
}

#ifdef NDEBUG
// The debug-only checks vanish under NDEBUG, operands unevaluated: nothing here may run.
TEST(Checks, DebugChecksVanishUnderNdebug) {
    int evaluated = 0;
    SLUT_DCHECK_GT((++evaluated, -1.0), 0.0);
    EXPECT_EQ(evaluated, 0);
}
#endif

} // namespace
