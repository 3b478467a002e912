#include "renderer/parallel_time.h"

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>

#include <gtest/gtest.h>

#include "renderer/stopwatch.h"

namespace clipblur {
namespace {

using std::chrono::milliseconds;

void sleepFor(int ms) { std::this_thread::sleep_for(milliseconds(ms)); }

// A loop's wall time is on the ledger and serial time around it is not: the ledger lies between the
// loop's sleep and the wall time measured around the loop alone.
TEST(ParallelLedgerTest, CountsLoopsNotSerialCode) {
    const ParallelLedger ledger;
    sleepFor(30);  // serial
    const auto start = Clock::now();
    parallelFor(0, 1, [](int) { sleepFor(20); });
    const double loop_wall = secondsSince(start);
    sleepFor(30);  // serial
    EXPECT_GE(ledger.seconds(), 0.020);
    EXPECT_LE(ledger.seconds(), loop_wall);
}

// A loop nested in another (run by this thread as the outer loop's task) is inside the outer one's time:
// counting it again would put more on the ledger than the outer loop's wall time.
TEST(ParallelLedgerTest, NestedLoopsCountOnce) {
    const ParallelLedger ledger;
    const auto start = Clock::now();
    parallelFor(0, 1, [](int) {
        sleepFor(20);
        parallelFor(0, 1, [](int) { sleepFor(20); });
    });
    const double wall = secondsSince(start);
    EXPECT_GE(ledger.seconds(), 0.040);
    EXPECT_LE(ledger.seconds(), wall);
}

TEST(ParallelLedgerTest, ReduceIsCountedAndReturnsItsValue) {
    const ParallelLedger ledger;
    const int sum = parallelReduce(
        tbb::blocked_range<int>(0, 100), 0,
        [](const tbb::blocked_range<int>& r, int s) {
            sleepFor(1);
            for (int i = r.begin(); i != r.end(); ++i) s += i;
            return s;
        },
        [](int a, int b) { return a + b; });
    EXPECT_EQ(sum, 4950);
    EXPECT_GE(ledger.seconds(), 0.001);
}

// Loops on a thread without a ledger (another render, a worker) add nothing to this thread's.
TEST(ParallelLedgerTest, OtherThreadsLoopsAreNotCounted) {
    const ParallelLedger ledger;
    std::thread other([] { parallelFor(0, 1, [](int) { sleepFor(20); }); });
    other.join();
    EXPECT_EQ(ledger.seconds(), 0.0);
}

// An inner ledger takes the loops while it lives, and the outer one gets them back after.
TEST(ParallelLedgerTest, InnerLedgerRestoresTheOuter) {
    const ParallelLedger outer;
    {
        const ParallelLedger inner;
        parallelFor(0, 1, [](int) { sleepFor(20); });
        EXPECT_GE(inner.seconds(), 0.020);
    }
    EXPECT_EQ(outer.seconds(), 0.0);
    parallelFor(0, 1, [](int) { sleepFor(20); });
    EXPECT_GE(outer.seconds(), 0.020);
}

// A loop that throws (a cancelled render) is counted and leaves the ledger able to count the next one.
TEST(ParallelLedgerTest, ThrowingLoopClosesItsSpan) {
    const ParallelLedger ledger;
    EXPECT_THROW(parallelFor(0, 1,
                             [](int) {
                                 sleepFor(10);
                                 throw std::runtime_error("cancelled");
                             }),
                 std::runtime_error);
    const double after_throw = ledger.seconds();
    EXPECT_GE(after_throw, 0.010);
    parallelFor(0, 1, [](int) { sleepFor(20); });
    EXPECT_GE(ledger.seconds() - after_throw, 0.020);
}

}  // namespace
}  // namespace clipblur
