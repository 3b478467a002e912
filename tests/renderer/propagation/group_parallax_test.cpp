#include "renderer/propagation/group_parallax.h"

#include <cmath>

#include <gtest/gtest.h>

#include "renderer/test_scenes.h"
#include "scene/object_motion.h"

namespace clipblur {

namespace {

// squareFilmJob's camera (at the origin, looking along +z, 16 pixels per image-plane unit on its 32x32
// film) moving to `eye` over the shutter [0, 1] and looking along `view` at its end, over one still quad.
Scene movingEye(const glm::dvec3& eye, const glm::dvec3& view = {0, 0, 1}) {
    RenderJob job = test::squareFilmJob();
    job.scene.camera.keys.push_back(CameraKey{1.0, eye, view, glm::dvec3(0, 1, 0)});
    job.scene.objects.push_back(test::rasterQuad(0, 0, 32, 32, 10.0));
    return job.scene;
}

constexpr double kPixelsPerUnit = 16.0;

}  // namespace

// An eye moving d sideways shifts a point at depth z by k d / z pixels (k pixels per unit at unit depth),
// the same at every pixel: two points on one ray part by k d |1/za - 1/zb|.
TEST(GroupParallax, SidewaysEyePartsDepthsByTheirInverseDifference) {
    const double d = 0.3;
    const Scene scene = movingEye({d, 0, 0});
    const FrameMotion motion(scene, 0.0, 1.0);
    const Projection projection(32, 32, 90.0);
    const GroupParallax parallax(motion, projection, motion.shutter(), motionGroups(scene, 0.0, 1.0));
    ASSERT_TRUE(parallax.slides(0));
    for (const glm::dvec2 x : {glm::dvec2(16, 16), glm::dvec2(3.5, 28.25), glm::dvec2(31, 0)}) {
        for (const auto& [za, zb] : {std::pair{2.0, 8.0}, {5.0, 5.5}, {10.0, 1.5}}) {
            const double expected = kPixelsPerUnit * d * std::abs(1.0 / za - 1.0 / zb);
            EXPECT_NEAR(parallax.between(0, x, 1.0 / za, 1.0 / zb), expected, 1e-9) << x.x << "," << x.y << " " << za;
        }
        EXPECT_EQ(parallax.between(0, x, 0.25, 0.25), 0.0);  // one surface point: nothing to part
    }
}

// An eye moving s forward along its view: a point at image-plane distance u from the centre and depth z
// goes to u z / (z - s), so two depths on one ray part by k |u| |za / (za - s) - zb / (zb - s)|; nothing
// parts at the centre.
TEST(GroupParallax, DollyPartsDepthsAwayFromTheCentre) {
    const double s = 0.5;
    const Scene scene = movingEye({0, 0, s});
    const FrameMotion motion(scene, 0.0, 1.0);
    const Projection projection(32, 32, 90.0);
    const GroupParallax parallax(motion, projection, motion.shutter(), motionGroups(scene, 0.0, 1.0));
    const double za = 2.0, zb = 6.0;
    for (const glm::dvec2 x : {glm::dvec2(16, 16), glm::dvec2(24, 16), glm::dvec2(4, 30)}) {
        const double u = glm::length(x - glm::dvec2(16.0)) / kPixelsPerUnit;
        const double expected = kPixelsPerUnit * u * std::abs(za / (za - s) - zb / (zb - s));
        EXPECT_NEAR(parallax.between(0, x, 1.0 / za, 1.0 / zb), expected, 1e-9) << x.x << "," << x.y;
    }
    // A point that the eye passes is not in front of it at the end: no parallax is measured there.
    EXPECT_EQ(parallax.between(0, glm::dvec2(20, 20), 1.0 / 0.25, 1.0 / zb), 0.0);
}

// What keeps the eye's place relative to a group slides nothing of it: a camera that only turns, and a
// group that rides along with a moving camera (while a still one beside it slides).
TEST(GroupParallax, TurningOrRidingAlongSlidesNothing) {
    const Scene turning = movingEye({0, 0, 0}, {0.3, 0.1, 1});
    const FrameMotion turn(turning, 0.0, 1.0);
    const Projection projection(32, 32, 90.0);
    EXPECT_FALSE(GroupParallax(turn, projection, turn.shutter(), motionGroups(turning, 0.0, 1.0)).slides(0));

    const glm::dvec3 eye(0.4, -0.2, 0.3);
    Scene riding = movingEye(eye);
    Object rider = test::rasterQuad(8, 8, 16, 16, 4.0);
    rider.transform = {TransformKey{0.0, glm::dvec3(0.0)}, TransformKey{1.0, eye}};
    riding.objects.push_back(rider);
    const FrameMotion ride(riding, 0.0, 1.0);
    const std::vector<std::uint32_t> groups = motionGroups(riding, 0.0, 1.0);
    ASSERT_EQ(groups, (std::vector<std::uint32_t>{0, 1}));
    const GroupParallax parallax(ride, projection, ride.shutter(), groups);
    EXPECT_TRUE(parallax.slides(0));
    EXPECT_FALSE(parallax.slides(1));
}

}  // namespace clipblur
