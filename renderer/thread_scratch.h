#pragma once

#include <memory>
#include <mutex>
#include <vector>

namespace clipblur {

// Per-thread scratch of type T (one per thread and T; give each use its own T), kept until the process
// ends. Instead of `thread_local T`: glibc registers a thread_local's destructor on each thread's first use
// under the dynamic loader's lock (__cxa_thread_atexit_impl), so a thread's first use waits for any
// dlopen in progress (the image module's takes 0.15-0.4 s; it once loaded beside every render). Here
// the thread_local is a raw pointer, which has no destructor, and one registry per T owns the objects.
template <class T>
T& threadScratch() {
    struct Registry {
        std::mutex mutex;
        std::vector<std::unique_ptr<T>> owned;
    };
    thread_local T* mine = nullptr;
    if (!mine) {
        static Registry registry;
        std::lock_guard lock(registry.mutex);
        mine = registry.owned.emplace_back(std::make_unique<T>()).get();
    }
    return *mine;
}

}  // namespace clipblur
