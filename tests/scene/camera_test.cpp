#include <random>

#include <gtest/gtest.h>

#include "scene/camera.h"

namespace clipblur {

TEST(CameraFrame, OrthonormalRightHanded) {
    const CameraFrame f = makeCameraFrame({1, 2, 3}, {0, 0.1, 1}, {0.1, 1, 0});
    EXPECT_NEAR(glm::dot(f.e1, f.e3), 0.0, 1e-15);
    EXPECT_NEAR(glm::length(f.e1), 1.0, 1e-15);
    EXPECT_NEAR(glm::length(glm::cross(f.e1, f.e2) - f.e3), 0.0, 1e-15);
}

TEST(CameraFrame, RejectsUpParallelToView) {
    EXPECT_THROW(makeCameraFrame({0, 0, 0}, {0, 0, 1}, {0, 0, 2}), Error);
    EXPECT_THROW(makeCameraFrame({0, 0, 0}, {0, 0, 0}, {0, 1, 0}), Error);
}

TEST(Projection, RasterRoundTrip) {
    const Projection proj(640, 360, 40.0);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 0; i < 100; ++i) {
        const glm::dvec2 p(u(rng), u(rng));
        const glm::dvec2 back = proj.toImagePlane(proj.toRaster(p));
        EXPECT_NEAR(back.x, p.x, 1e-14);
        EXPECT_NEAR(back.y, p.y, 1e-14);
    }
    // The top edge of the image (y = 0) is p1 = tan(vfov/2).
    EXPECT_NEAR(proj.toImagePlane({320, 0}).x, std::tan(20.0 * M_PI / 180.0), 1e-15);
}

}  // namespace clipblur
