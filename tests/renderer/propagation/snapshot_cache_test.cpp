#include "renderer/propagation/snapshot_cache.h"

#include <atomic>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include "support/motion_scenes.h"

namespace clipblur {
namespace {

// Many threads asking for the same few times get one snapshot per time, and each is the snapshot
// built directly at that time: the same camera and every object's same motion state.
TEST(SnapshotCache, OneSnapshotPerTimeEqualToABuiltOne) {
    const Scene scene = testing::randomMovingScene(4, 5);
    const Projection projection(scene.film.width, scene.film.height, scene.camera.vfov_degrees);
    const SnapshotCache cache(scene, projection);
    const double times[] = {0.0, 0.125, 0.5, 1.0 / 3.0, 0.9};
    std::vector<std::atomic<const MotionSnapshot*>> first(std::size(times));
    for (auto& f : first) f = nullptr;
    std::atomic<int> mismatches{0};
    tbb::parallel_for(0, 2000, [&](int i) {
        const std::size_t k = static_cast<std::size_t>(i) % std::size(times);
        const MotionSnapshot* got = &cache.at(times[k]);
        const MotionSnapshot* expected = nullptr;
        if (!first[k].compare_exchange_strong(expected, got) && expected != got) ++mismatches;
    });
    EXPECT_EQ(mismatches, 0);
    for (std::size_t k = 0; k < std::size(times); ++k) {
        const MotionSnapshot direct(scene, projection, times[k]);
        const MotionSnapshot& cached = cache.at(times[k]);
        EXPECT_EQ(cached.time, times[k]);
        EXPECT_EQ(cached.camera.position, direct.camera.position);
        EXPECT_EQ(cached.camera.basis(), direct.camera.basis());
        EXPECT_EQ(cached.camera_velocity, direct.camera_velocity);
        ASSERT_EQ(cached.objects.size(), direct.objects.size());
        for (std::size_t o = 0; o < direct.objects.size(); ++o) {
            EXPECT_EQ(cached.objects[o].transform.translate, direct.objects[o].transform.translate);
            EXPECT_EQ(cached.objects[o].transform.rotate, direct.objects[o].transform.rotate);
            EXPECT_EQ(cached.objects[o].angular_velocity, direct.objects[o].angular_velocity);
            EXPECT_EQ(cached.objects[o].deform_weight, direct.objects[o].deform_weight);
        }
    }
}

}  // namespace
}  // namespace clipblur
