#include <cmath>

#include <gtest/gtest.h>

#include "renderer/render.h"
#include "renderer/test_scenes.h"

namespace clipblur {

namespace {

float at(const Image& image, const char* channel, int x, int y) {
    return image.find(channel)->values[image.index(x, y)];
}

// A quad at depth 5 over raster x [8.5, 12.5), y [8, 24) at shutter open, 10 px further right at close,
// so over [13.5, 17.5) at mid-shutter, in front of a wall at depth 10 that fills the film.
RenderJob passingQuadJob(Method method) {
    RenderJob job = test::squareFilmJob();
    job.render.method = method;
    job.scene.objects.push_back(test::rasterQuad(-4, -4, 36, 36, 10.0));
    Object quad = test::rasterQuad(8.5, 8, 12.5, 24, 5.0);
    const glm::dvec3 shift = test::worldAtRaster(18.5, 8, 5.0) - test::worldAtRaster(8.5, 8, 5.0);
    quad.transform = {TransformKey{0.0, glm::dvec3(0.0)}, TransformKey{1.0, shift}};
    job.scene.objects.push_back(quad);
    job.output.aov_depth = true;
    return job;
}

}  // namespace

class DepthAov : public ::testing::TestWithParam<Method> {};

// Z is the depth of what is seen at mid-shutter, area-weighted over the pixel: 5 where the quad covers the
// pixel then, 10 where only the wall does, whatever passed over the pixel earlier or later (a
// time-averaged depth would give 10 at x = 9-11, which the quad covers at open, and less than 10 at x =
// 18-21). Clipped and accumulation resolve the mid-shutter frame exactly (float storage: 1e-6 relative);
// the stochastic renderer's mid-shutter rays all hit the same plane in these pixels (Embree's float ray
// parameter: 1e-6 relative).
TEST_P(DepthAov, IsTheDepthSeenAtMidShutter) {
    RenderJob job = passingQuadJob(GetParam());
    const Image image = renderFrame(job, 0).image;
    for (int y = 9; y < 23; ++y) {
        for (int x = 14; x < 17; ++x) EXPECT_NEAR(at(image, "Z", x, y), 5.0f, 5e-6f) << x << "," << y;
        for (int x : {9, 10, 11, 18, 19, 20, 21}) EXPECT_NEAR(at(image, "Z", x, y), 10.0f, 1e-5f) << x << "," << y;
    }
    if (GetParam() != Method::Stochastic) {
        // Half of pixel 13 and half of pixel 17 are the quad at mid-shutter: (5 + 10) / 2.
        for (int y = 9; y < 23; ++y) {
            EXPECT_NEAR(at(image, "Z", 13, y), 7.5f, 1e-5f) << y;
            EXPECT_NEAR(at(image, "Z", 17, y), 7.5f, 1e-5f) << y;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Methods, DepthAov,
                         ::testing::Values(Method::Clipped, Method::Accumulation, Method::Stochastic),
                         [](const ::testing::TestParamInfo<Method>& info) { return std::string(methodName(info.param)); });

// With sweep integration too: the AOV does not depend on how the colour is integrated in time.
TEST(DepthAov, SweepIntegrationKeepsTheMidShutterDepth) {
    RenderJob job = passingQuadJob(Method::Clipped);
    job.render.time_integration = TimeIntegration::Sweep;
    const Image image = renderFrame(job, 0).image;
    for (int y = 9; y < 23; ++y) {
        EXPECT_NEAR(at(image, "Z", 15, y), 5.0f, 5e-6f) << y;
        EXPECT_NEAR(at(image, "Z", 10, y), 10.0f, 1e-5f) << y;
        EXPECT_NEAR(at(image, "Z", 13, y), 7.5f, 1e-5f) << y;
    }
}

}  // namespace clipblur
