#include <algorithm>
#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "renderer/camera_path.h"
#include "renderer/sampling/hash_rng.h"

namespace clipblur {

namespace {

// Three keys that move, roll, pan and tilt, with the turn changing axis and rate at t = 1.
Camera threeKeyCamera() {
    Camera camera;
    camera.keys = {CameraKey{0.0, {0, 2, -8}, {0, -1.5, 8}, {0, 1, 0}},
                   CameraKey{1.0, {0.5, 2, -8}, {0.3, -1.5, 8}, {0.1, 1, 0}},
                   CameraKey{2.5, {1, 3, -7}, {-0.4, -1, 8}, {0, 1, 0.2}}};
    return camera;
}

}  // namespace

TEST(CameraPath, MatchesEvalCameraBitForBit) {
    const Camera camera = threeKeyCamera();
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

// The table against the exact path at random times: inside a key segment the interpolated basis is
// off its arc by at most (angle step)^2 / 8; across the key at t = 1, where the turn changes axis and
// rate, by at most half the angle step. Bounds from the keys' own turn rates, 2x margin for rounding.
TEST(CameraTable, FollowsThePathWithinTheInterpolationBound) {
    const Camera camera = threeKeyCamera();
    const CameraPath path(camera);
    const int steps = 1024;
    const double t0 = 0.25, t1 = 2.0;
    const CameraTable table(path, t0, t1, steps);
    const double dt = (t1 - t0) / steps;
    const auto turn = [&](double a, double b) {  // angle between the bases at two times
        const CameraFrame fa = path.at(a), fb = path.at(b);
        return std::acos(std::clamp((glm::dot(fa.e1, fb.e1) + glm::dot(fa.e2, fb.e2) + glm::dot(fa.e3, fb.e3) - 1.0) / 2.0, -1.0, 1.0));
    };
    const double step_angle = std::max(turn(0.5, 0.5 + dt), turn(1.5, 1.5 + dt));
    const double smooth_bound = 2.0 * step_angle * step_angle / 8.0;
    const double kink_bound = 2.0 * step_angle / 2.0;
    // Position is linear in each segment: exact there; across the key a chord of two segments, off by at
    // most dt |v_after - v_before| / 4.
    const glm::dvec3 v_before = (camera.keys[1].position - camera.keys[0].position) / 1.0;
    const glm::dvec3 v_after = (camera.keys[2].position - camera.keys[1].position) / 1.5;
    const double kink_position_bound = 2.0 * dt * glm::length(v_after - v_before) / 4.0;
    const HashRng rng = HashRng::forKey(5, 0);
    double worst_smooth = 0.0, worst_kink = 0.0;
    for (int i = 0; i < 4000; ++i) {
        const double t = t0 + (t1 - t0) * rng.uniform(static_cast<std::uint64_t>(i));
        const CameraFrame a = table.at(t), b = path.at(t);
        const double d = std::max({glm::length(a.e1 - b.e1), glm::length(a.e2 - b.e2), glm::length(a.e3 - b.e3)});
        const bool across_key = std::fabs(t - 1.0) < dt;
        EXPECT_LE(glm::length(a.position - b.position), across_key ? kink_position_bound : 1e-12) << "t = " << t;
        double& worst = across_key ? worst_kink : worst_smooth;
        worst = std::max(worst, d);
    }
    EXPECT_LE(worst_smooth, smooth_bound);
    EXPECT_LE(worst_kink, kink_bound);
    EXPECT_GT(worst_smooth, 0.0);  // the table does interpolate: not the path itself
    // Exact at the window's ends, and held outside it.
    const CameraFrame end = table.at(t1), exact = path.at(t1);
    EXPECT_EQ(std::memcmp(&end, &exact, sizeof end), 0);
    const CameraFrame before = table.at(t0 - 1.0), start = path.at(t0);
    EXPECT_EQ(std::memcmp(&before, &start, sizeof before), 0);
}

}  // namespace clipblur
