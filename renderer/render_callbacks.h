#pragma once

#include <atomic>
#include <functional>

namespace clipblur {

struct RenderCallbacks {
    std::function<void(long long done, long long total)> progress;  // called from worker threads, serialised
    const std::atomic<bool>* cancel = nullptr;                      // set by a signal handler to stop early
};

}  // namespace clipblur
