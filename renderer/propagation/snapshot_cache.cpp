#include "renderer/propagation/snapshot_cache.h"

namespace clipblur {

const MotionSnapshot& SnapshotCache::at(double time) const {
    {
        std::lock_guard lock(mutex_);
        const auto found = snapshots_.find(time);
        if (found != snapshots_.end()) return *found->second;
    }
    // Built outside the lock; a thread that loses the race to insert keeps the other's.
    auto built = std::make_unique<const MotionSnapshot>(*scene_, projection_, time);
    std::lock_guard lock(mutex_);
    return *snapshots_.try_emplace(time, std::move(built)).first->second;
}

}  // namespace clipblur
