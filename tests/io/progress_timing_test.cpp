#include <gtest/gtest.h>

#include "io/progress_timing.h"

namespace clipblur {

TEST(ProgressTiming, DurationsReadInTheirUnit) {
    EXPECT_EQ(formatDuration(0.0), "0.0 s");
    EXPECT_EQ(formatDuration(42.04), "42.0 s");
    EXPECT_EQ(formatDuration(187.0), "3 min 07 s");
    EXPECT_EQ(formatDuration(7500.0), "2 h 05 min");
}

// A quarter done after 10 s leaves three quarters: 30 s at the same rate.
TEST(ProgressTiming, EtaExtrapolatesTheMeanRate) {
    EXPECT_EQ(progressTiming(10.0, 25, 100), "10.0 s elapsed, ETA 30.0 s");
    EXPECT_EQ(progressTiming(10.0, 100, 100), "10.0 s elapsed, ETA 0.0 s");
    EXPECT_EQ(progressTiming(0.5, 0, 100), "0.5 s elapsed, ETA ?");
}

}  // namespace clipblur
