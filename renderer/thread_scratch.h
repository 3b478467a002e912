#pragma once

#include <memory>
#include <mutex>
#include <vector>

namespace clipblur {

// Per-thread scratch of type T (one per thread and T; give each use its own T), kept until the process
// ends. Instead of `thread_local T`: glibc registers a thread_local's destructor on each thread's first use
// under the dynamic loader's lock (__cxa_thread_atexit_impl), and the image module's background dlopen
// holds that lock for about 0.4 s, so every render thread's first shading waited for the whole load. Here
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
