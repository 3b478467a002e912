#include <cstring>

#include <gtest/gtest.h>

#include "renderer/camera_path.h"
#include "renderer/sampling/hash_rng.h"

namespace clipblur {

TEST(CameraPath, MatchesEvalCameraBitForBit) {
    Camera camera;
    camera.keys = {CameraKey{0.0, {0, 2, -8}, {0, -1.5, 8}, {0, 1, 0}},
                   CameraKey{1.0, {0.5, 2, -8}, {0.3, -1.5, 8}, {0.1, 1, 0}},
                   CameraKey{2.5, {1, 3, -7}, {-0.4, -1, 8}, {0, 1, 0.2}}};
    const CameraPath path(camera);
    const HashRng rng = HashRng::forKey(3, 0);
    for (int i = 0; i < 500; ++i) {
        const double t = -0.5 + 3.5 * rng.uniform(static_cast<std::uint64_t>(i));
        const CameraFrame a = path.at(t);
        const CameraFrame b = evalCamera(camera, t);
        EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0) << "t = " << t;
    }
    for (double t : {0.0, 1.0, 2.5}) {
        const CameraFrame a = path.at(t);
        const CameraFrame b = evalCamera(camera, t);
        EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0) << "t = " << t;
    }
}

}  // namespace clipblur
