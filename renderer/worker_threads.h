#pragma once

#include <algorithm>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

namespace clipblur {

// The threads TBB runs a render's parallel loops on: the arena's concurrency capped by a
// global_control limit (render --threads), which this_task_arena::max_concurrency does not see.
inline int workerThreads() {
    const auto limit = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
    return static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(tbb::this_task_arena::max_concurrency()), limit));
}

}  // namespace clipblur
