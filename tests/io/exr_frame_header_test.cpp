#include <gtest/gtest.h>

#include "io/exr_frame_header.h"

namespace clipblur {

namespace {

// p M for a row vector p = (x, y, z, 1) and an Imath-layout matrix, with the homogeneous divide:
// how OpenEXR readers apply worldToCamera and worldToNDC.
glm::dvec3 rowTimes(const glm::dvec3& p, const ExrMatrix& m) {
    double out[4];
    for (int j = 0; j < 4; ++j)
        out[j] = p.x * m[static_cast<std::size_t>(j)] + p.y * m[static_cast<std::size_t>(4 + j)] +
                 p.z * m[static_cast<std::size_t>(8 + j)] + m[static_cast<std::size_t>(12 + j)];
    return glm::dvec3(out[0], out[1], out[2]) / out[3];
}

}  // namespace

// A camera at (0, 0, -1) looking along +z with +y up and a 90 degree vertical field of view on a
// 200 x 100 film. Right-handed world, so image right is -x. Hand values: the point (-1, 0.5, 1) is 2
// in front, 1 right and 0.5 up in OpenEXR camera space; at unit distance that is (0.5, 0.25), and with
// tan(45) = 1 the film spans [-2, 2] x [-1, 1] there: NDC x = (0.5 + 2) / 4, y = (1 - 0.25) / 2.
TEST(ExrFrameHeader, CameraMatricesFollowOpenExrConventions) {
    const CameraFrame camera = makeCameraFrame({0.0, 0.0, -1.0}, {0.0, 0.0, 1.0}, {0.0, 1.0, 0.0});
    const ExrCameraMatrices m = exrCameraMatrices(camera, Projection(200, 100, 90.0));
    const glm::dvec3 c = rowTimes({-1.0, 0.5, 1.0}, m.world_to_camera);
    EXPECT_NEAR(c.x, 1.0, 1e-6);
    EXPECT_NEAR(c.y, 0.5, 1e-6);
    EXPECT_NEAR(c.z, 2.0, 1e-6);
    const glm::dvec3 ndc = rowTimes({-1.0, 0.5, 1.0}, m.world_to_ndc);
    EXPECT_NEAR(ndc.x, 0.625, 1e-6);
    EXPECT_NEAR(ndc.y, 0.375, 1e-6);
    // The view axis hits the display window's centre; the upper-left corner's ray hits NDC (0, 0).
    const glm::dvec3 centre = rowTimes({0.0, 0.0, 5.0}, m.world_to_ndc);
    EXPECT_NEAR(centre.x, 0.5, 1e-6);
    EXPECT_NEAR(centre.y, 0.5, 1e-6);
    const glm::dvec3 corner = rowTimes({2.0, 1.0, 0.0}, m.world_to_ndc);  // 1 in front: left 2, up 1
    EXPECT_NEAR(corner.x, 0.0, 1e-6);
    EXPECT_NEAR(corner.y, 0.0, 1e-6);
}

TEST(ExrFrameHeader, FpsIsAnExactRational) {
    EXPECT_EQ(fpsRational(24.0), (std::array<int, 2>{24, 1}));
    EXPECT_EQ(fpsRational(24000.0 / 1001.0), (std::array<int, 2>{24000, 1001}));
    EXPECT_EQ(fpsRational(30000.0 / 1001.0), (std::array<int, 2>{30000, 1001}));
    EXPECT_EQ(fpsRational(12.5), (std::array<int, 2>{25, 2}));
}

}  // namespace clipblur

namespace clipblur {

// A centred shutter: the header's offsets are negative, expTime is the open length, the camera matrices
// are those at frame + open (before the frame), and the curve is written as time:weight pairs. The camera
// moves 1 along x per frame from x = 0 at frame 0, so at frame 2 - 0.25 the point (1.75, 0, 1) is straight
// ahead at distance 1 (camera x 0 in OpenEXR camera space).
TEST(ExrFrameHeader, CentredShutterWithCurve) {
    RenderJob job;
    job.frames.fps = 24.0;
    job.shutter = {-0.25, 0.25, {{-0.25, 0.0}, {-0.15, 1.0}, {0.15, 1.0}, {0.25, 0.0}}};
    job.scene.film.width = 200;
    job.scene.film.height = 100;
    job.scene.camera.vfov_degrees = 90.0;
    job.scene.camera.keys = {CameraKey{0.0, {0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, {0.0, 1.0, 0.0}},
                             CameraKey{4.0, {4.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, {0.0, 1.0, 0.0}}};
    const FrameHeader h = frameHeader(job, 2);
    EXPECT_EQ(h.shutter_open, -0.25);
    EXPECT_EQ(h.shutter_close, 0.25);
    EXPECT_DOUBLE_EQ(h.exposure_seconds, 0.5 / 24.0);
    EXPECT_EQ(h.shutter_curve, "-0.25:0 -0.15:1 0.15:1 0.25:0");
    const glm::dvec3 c = rowTimes({1.75, 0.0, 1.0}, h.world_to_camera);
    EXPECT_NEAR(c.x, 0.0, 1e-6);
    EXPECT_NEAR(c.z, 1.0, 1e-6);
    job.shutter.curve.clear();
    EXPECT_EQ(frameHeader(job, 2).shutter_curve, "") << "a box writes no curve attribute";
}

}  // namespace clipblur
