#pragma once

#include <utility>

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

#include "renderer/stopwatch.h"

namespace clipblur {

// The wall time a render's own thread spends in its parallel loops, so that the rest of its time, the
// serial part that bounds the speed-up on more cores (Amdahl), can be reported. A ledger is installed on
// the thread that runs the render, for its lifetime. Loops started through parallelFor, parallelInvoke and
// parallelReduce on that thread add their wall time, the outermost only (a nested loop the thread runs as
// a task of an outer one is already inside it); on any other thread (a TBB worker) they add nothing.
class ParallelLedger {
public:
    ParallelLedger() : previous_(std::exchange(current(), this)) {}
    ~ParallelLedger() { current() = previous_; }
    ParallelLedger(const ParallelLedger&) = delete;
    ParallelLedger& operator=(const ParallelLedger&) = delete;

    double seconds() const { return seconds_; }

    // Times one parallel loop on this thread's ledger, if it has one and is not already inside a loop.
    template <class Loop>
    static decltype(auto) time(Loop&& loop) {
        ParallelLedger* ledger = current();
        if (!ledger || ledger->depth_ > 0) return loop();
        ++ledger->depth_;
        const auto start = Clock::now();
        struct Close {  // also when the loop throws (a cancelled render)
            ParallelLedger* ledger;
            Clock::time_point start;
            ~Close() {
                ledger->seconds_ += secondsSince(start);
                --ledger->depth_;
            }
        } close{ledger, start};
        return loop();
    }

private:
    static ParallelLedger*& current() {
        thread_local ParallelLedger* ledger = nullptr;
        return ledger;
    }

    ParallelLedger* previous_;
    double seconds_ = 0.0;
    int depth_ = 0;
};

// tbb::parallel_for, tbb::parallel_invoke and tbb::parallel_reduce, timed on the render's ledger.
template <class... Args>
void parallelFor(Args&&... args) {
    ParallelLedger::time([&] { tbb::parallel_for(std::forward<Args>(args)...); });
}
template <class... Args>
void parallelInvoke(Args&&... args) {
    ParallelLedger::time([&] { tbb::parallel_invoke(std::forward<Args>(args)...); });
}
template <class... Args>
auto parallelReduce(Args&&... args) {
    return ParallelLedger::time([&] { return tbb::parallel_reduce(std::forward<Args>(args)...); });
}

}  // namespace clipblur
