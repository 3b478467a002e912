#include <random>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "renderer/fragments/screen_triangle.h"

namespace clipblur {

namespace {

// A pinhole camera looking down +z: raster = focal * (x, y) / z + centre.
glm::dvec2 project(const glm::dvec3& p) {
    const double focal = 800.0;
    return glm::dvec2(focal * p.x / p.z + 640.0, focal * p.y / p.z + 360.0);
}

}  // namespace

TEST(ScreenTriangle, PerspectiveCorrectBarycentricsMatchExactProjection) {
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> xy(-3.0, 3.0);
    std::uniform_real_distribution<double> z(1.0, 50.0);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int i = 0; i < 1000; ++i) {
        std::array<glm::dvec3, 3> p;
        ScreenTriangle t;
        for (int k = 0; k < 3; ++k) {
            p[k] = glm::dvec3(xy(rng), xy(rng), z(rng));
            t.raster[k] = project(p[k]);
            t.inv_depth[k] = 1.0 / p[k].z;
        }
        // Skip nearly edge-on triangles: the raster -> surface map is then ill-conditioned by design.
        const glm::dvec2 e1 = t.raster[1] - t.raster[0], e2 = t.raster[2] - t.raster[0];
        if (std::abs(e1.x * e2.y - e1.y * e2.x) < 1.0) continue;
        double b1 = u(rng), b2 = u(rng);
        if (b1 + b2 > 1.0) {
            b1 = 1.0 - b1;
            b2 = 1.0 - b2;
        }
        const std::array<double, 3> b{1.0 - b1 - b2, b1, b2};
        const glm::dvec3 point = b[0] * p[0] + b[1] * p[1] + b[2] * p[2];
        const glm::dvec2 raster = project(point);

        SourceSample s;
        ASSERT_TRUE(evalSource(t, raster, s));
        // Double-precision raster positions near 1000 px carry ~1e-13 px of rounding; through the
        // raster -> barycentric map (scale ~1/|triangle| >= 1e-3 here) that is ~1e-10 at worst.
        EXPECT_NEAR(s.inv_depth * point.z, 1.0, 1e-9) << i;
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(s.bary[k], b[k], 1e-9) << i;

        DepthPlane plane;
        const glm::dvec2 origin = glm::floor(raster);
        ASSERT_TRUE(inverseDepthPlane(t, origin, plane));
        EXPECT_NEAR(plane(raster - origin) * point.z, 1.0, 1e-9) << i;
    }
}

TEST(ScreenTriangle, ValidityChecks) {
    ScreenTriangle t;
    t.raster = {glm::dvec2(0, 0), glm::dvec2(4, 0), glm::dvec2(0, 4)};
    t.inv_depth = {1.0, 0.5, 0.25};
    EXPECT_TRUE(validScreenTriangle(t));
    t.inv_depth[1] = -0.5;  // behind the eye
    EXPECT_FALSE(validScreenTriangle(t));
    t.inv_depth[1] = 0.5;
    t.raster[2] = glm::dvec2(8, 0);  // collinear
    EXPECT_FALSE(validScreenTriangle(t));
    t.raster[2] = glm::dvec2(NAN, 0);
    EXPECT_FALSE(validScreenTriangle(t));
}

// The tolerance is relative to the larger inverse depth, so the same relative gap decides at any distance,
// and the test is antisymmetric: swapping the surfaces swaps nearer and farther.
TEST(ScreenTriangle, DepthComparisonIsRelativeAndAntisymmetric) {
    const double rel = 1e-6;
    for (double w : {1e-4, 1.0, 1e4}) {
        EXPECT_EQ(compareDepth(w, w * (1.0 + 0.5e-6), rel), DepthOrder::Coincident) << w;
        EXPECT_EQ(compareDepth(w * (1.0 + 2e-6), w, rel), DepthOrder::Nearer) << w;
        EXPECT_EQ(compareDepth(w, w * (1.0 + 2e-6), rel), DepthOrder::Farther) << w;
    }
    EXPECT_EQ(compareDepth(0.0, 0.0, rel), DepthOrder::Coincident);
}

}  // namespace clipblur
