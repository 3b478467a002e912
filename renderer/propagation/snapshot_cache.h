#pragma once

#include <map>
#include <memory>
#include <mutex>

#include "renderer/propagation/surface_path.h"

namespace clipblur {

// A segment's MotionSnapshots by time, each built once. Its tiles re-clip at the same times (sweep's
// shared intervals; point subframes at (k + 1/2) / n of the segment), and a snapshot evaluates every
// object's motion: a slerp each for the particles' 500 objects, three snapshots per tile and re-clip.
// Thread-safe; a snapshot is the same value whichever thread builds it.
class SnapshotCache {
public:
    SnapshotCache(const Scene& scene, const Projection& projection) : scene_(&scene), projection_(projection) {}

    const MotionSnapshot& at(double time) const;

private:
    const Scene* scene_;
    Projection projection_;
    mutable std::mutex mutex_;
    mutable std::map<double, std::unique_ptr<const MotionSnapshot>> snapshots_;  // nodes never move
};

}  // namespace clipblur
