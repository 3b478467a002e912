#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>
#include <utility>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace clipblur {

// The threads TBB runs a render's parallel loops on: the arena's concurrency capped by a
// global_control limit (render --threads), which this_task_arena::max_concurrency does not see.
inline int workerThreads() {
    const auto limit = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
    return static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(tbb::this_task_arena::max_concurrency()), limit));
}

// Starts TBB: its first parallel loop opens its allocator and thread-pool libraries (dlopen) and it
// creates worker threads as loops ask for them, both of which take the dynamic loader's process-wide lock.
// Done before a library loads in the background (the image module: ~0.4 s of dlopen), the render's Embree
// build and first loops do not wait for that load with one thread. Returns when every worker has run a
// task, or after 100 ms (a busy machine may not schedule one: it is then merely started late).
inline void startWorkerThreads() {
    const int threads = workerThreads();
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(100);
    std::atomic<int> arrived{0};
    tbb::enumerable_thread_specific<bool> seen(false);
    tbb::parallel_for(
        0, threads,
        [&](int) {
            if (!std::exchange(seen.local(), true)) ++arrived;
            while (arrived.load() < threads && std::chrono::steady_clock::now() < deadline) std::this_thread::yield();
        },
        tbb::simple_partitioner());
}

}  // namespace clipblur
