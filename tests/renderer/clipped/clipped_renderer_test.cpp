#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "renderer/propagation/subframes.h"
#include "renderer/render.h"
#include "renderer/test_scenes.h"
#include "support/translating_coverage.h"

namespace clipblur {

namespace {

using test::movingQuad;
using test::rasterQuad;
using test::squareFilmJob;
using test::worldAtRaster;

const std::vector<float>& channel(const RenderResult& r, const char* name) { return r.image.find(name)->values; }

double overlap(double a0, double a1, double b0, double b1) { return std::max(0.0, std::min(a1, b1) - std::max(a0, b0)); }

// Exact coverage of pixel (x, y) by the axis-aligned raster rectangle [x0, x1) x [y0, y1).
double rectCoverage(int x, int y, double x0, double y0, double x1, double y1) {
    return overlap(x, x + 1, x0, x1) * overlap(y, y + 1, y0, y1);
}

RenderJob clippedJob() {
    RenderJob job = squareFilmJob();
    job.render.method = Method::Clipped;
    return job;
}

double maxError(const RenderResult& r, const std::vector<double>& expected) {
    const auto& red = channel(r, "R");
    double worst = 0.0;
    for (std::size_t i = 0; i < expected.size(); ++i) worst = std::max(worst, std::abs(red[i] - expected[i]));
    return worst;
}

std::vector<double> translatingExpected(double x0, double y0, double x1, double y1, glm::dvec2 v) {
    const std::vector<glm::dvec2> quad{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    std::vector<double> expected(32 * 32);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) expected[y * 32 + x] = testing::translatingPixelCoverage(quad, v, x, y);
    return expected;
}

}  // namespace

// Values are stored as float: 1e-6 covers float rounding of values <= 1 (6e-8) with margin, and is
// far below any coverage mistake the clipper could make.
constexpr double kFloatTolerance = 1e-6;

TEST(ClippedRenderer, StillRectangleHasExactPixelCoverage) {
    RenderJob job = clippedJob();
    const double x0 = 3.25, y0 = 4.5, x1 = 20.75, y1 = 17.125;
    job.scene.objects.push_back(rasterQuad(x0, y0, x1, y1, 5.0));
    const RenderResult r = renderFrame(job, 0);
    std::vector<double> expected(32 * 32);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) expected[y * 32 + x] = rectCoverage(x, y, x0, y0, x1, y1);
    EXPECT_LT(maxError(r, expected), kFloatTolerance);
    EXPECT_EQ(r.stats.clipped().subframes_total, 0) << "nothing moves: no subframes";
}

TEST(ClippedRenderer, StillTriangleMatchesIndependentPolygonClip) {
    RenderJob job = clippedJob();
    const std::vector<glm::dvec2> raster{{2.3, 3.1}, {29.6, 11.7}, {9.2, 27.9}};
    Object tri;
    for (const auto& p : raster) tri.mesh.positions.push_back(worldAtRaster(p.x, p.y, 4.0));
    tri.mesh.triangles = {{0, 1, 2}};
    job.scene.objects.push_back(tri);
    const RenderResult r = renderFrame(job, 0);
    std::vector<double> expected(32 * 32);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x)
            expected[y * 32 + x] = testing::translatingPixelCoverage(raster, glm::dvec2(0.0), x, y);
    EXPECT_LT(maxError(r, expected), kFloatTolerance);
}

TEST(ClippedRenderer, FrontQuadHidesBackQuadExactly) {
    RenderJob job = clippedJob();
    Material red;
    red.base_color = glm::dvec3(1, 0, 0);
    job.scene.materials.push_back(red);  // material 1
    Object back = rasterQuad(2.5, 2.5, 25.5, 25.5, 8.0);
    back.material = 1;
    job.scene.objects.push_back(back);
    job.scene.objects.push_back(rasterQuad(10.25, 6.75, 30.5, 20.5, 4.0));  // white, in front
    const RenderResult r = renderFrame(job, 0);
    const auto& g = channel(r, "G");  // only the white front quad has green
    const auto& red_ch = channel(r, "R");
    for (int y = 0; y < 32; ++y) {
        for (int x = 0; x < 32; ++x) {
            const double front = rectCoverage(x, y, 10.25, 6.75, 30.5, 20.5);
            const double back_all = rectCoverage(x, y, 2.5, 2.5, 25.5, 25.5);
            const double both = overlap(x, x + 1, 10.25, 25.5) * overlap(y, y + 1, 6.75, 20.5);
            EXPECT_NEAR(g[y * 32 + x], front, kFloatTolerance);
            EXPECT_NEAR(red_ch[y * 32 + x], front + back_all - both, kFloatTolerance);
        }
    }
}

// Section 3 against the exact time-integrated coverage of a quad sliding parallel to the image plane.
// A pixel's covered area is piecewise linear in shutter time s for this motion, with a kink whenever a
// quad edge enters or leaves the pixel; the slope jumps there by at most the edge's speed |v_x| or |v_y|
// (px per shutter). The midpoint rule with step h = 1/N is exact on linear pieces and errs by at most
// jump * h^2 / 8 at a kink, and a pixel meets at most 4 kinks per axis, so the a-priori bound is
// (|v_x| + |v_y|) / (2 N^2). The measured order must also be close to 2.
TEST(ClippedRenderer, TranslatingQuadConvergesToExactTimeIntegratedCoverage) {
    const double x0 = 4.3, y0 = 6.2, x1 = 14.7, y1 = 19.9;
    const glm::dvec2 v(11.4, 3.7);
    const std::vector<double> expected = translatingExpected(x0, y0, x1, y1, v);
    std::vector<double> errors;
    for (int n : {3, 6, 12, 24}) {
        RenderJob job = clippedJob();
        job.scene.objects.push_back(movingQuad(x0, y0, x1, y1, 6.0, v));
        job.render.subframes = n;
        errors.push_back(maxError(renderFrame(job, 0), expected));
    }
    const double order = std::log2(errors.front() / errors.back()) / 3.0;
    EXPECT_GT(order, 1.6) << "errors " << errors[0] << " " << errors[1] << " " << errors[2] << " " << errors[3];
    const auto bound = [&](int n) { return (std::abs(v.x) + std::abs(v.y)) / (2.0 * n * n); };
    EXPECT_LT(errors.back(), bound(24));
    EXPECT_LT(errors.front(), bound(3));

    RenderJob job = clippedJob();
    job.scene.objects.push_back(movingQuad(x0, y0, x1, y1, 6.0, v));
    job.render.time_integration = TimeIntegration::Subframes;  // the automatic count
    const RenderResult r = renderFrame(job, 0);
    // Eq. 24 would take ceil(|v|) = 12; the kink floor (kinkSamples) sqrt(kKinkMotion |v|) = 27.7.
    const int n = static_cast<int>(std::ceil(std::sqrt(kKinkMotion * glm::length(v))));
    EXPECT_EQ(r.stats.clipped().subframes_max_per_tile, n);
    EXPECT_LT(maxError(r, expected), bound(n));
}

// An edge that moves a few pixels: eq. 24's count (one subframe a pixel) leaves the pixels it crosses
// up to 1 / (8 |v|) off, a step of 1/24 of the contrast here, visible at 8 bits. The automatic count of
// point subframes, and of sweep positions, holds it to 1/512 (kinkSamples). 1e-6: float storage.
TEST(ClippedRenderer, ShortMotionStepsNoMoreThanA512thOfTheContrast) {
    const double x0 = 6.3, y0 = 5.2, x1 = 19.6, y1 = 24.9;
    const glm::dvec2 v(3.0, 0.0);
    const std::vector<double> expected = translatingExpected(x0, y0, x1, y1, v);
    const auto quadJob = [&] {
        RenderJob job = clippedJob();
        job.scene.objects.push_back(movingQuad(x0, y0, x1, y1, 6.0, v));
        return job;
    };
    for (const TimeIntegration integration : {TimeIntegration::Subframes, TimeIntegration::Sweep}) {
        RenderJob job = quadJob();
        job.render.time_integration = integration;
        const RenderResult r = renderFrame(job, 0);
        EXPECT_LT(maxError(r, expected), 1.0 / 512.0 + 1e-6) << static_cast<int>(integration);
        if (integration == TimeIntegration::Sweep) {
            EXPECT_EQ(r.stats.clipped().subframes_max_per_tile, 1) << "one re-clip: the positions alone";
        }
    }
    RenderJob job = quadJob();
    job.render.subframes = 3;  // eq. 24's count
    // Up to 1/24 where an edge starts; this quad's start at 0.3 and 0.6 of a pixel gives 0.027.
    EXPECT_GT(maxError(renderFrame(job, 0), expected), 6.0 / 256.0) << "the step the floor removes";
}

TEST(ClippedRenderer, StaticSceneIsTheSameWithAnySubframeCount) {
    RenderJob job = clippedJob();
    job.scene.objects.push_back(rasterQuad(3.3, 2.7, 27.1, 22.9, 5.0));
    job.scene.objects.push_back(rasterQuad(8.2, 9.9, 16.4, 30.2, 3.0));
    const RenderResult still = renderFrame(job, 0);
    // Nothing moves: one fragment set at shutter open, no closing set, no subframes anywhere.
    EXPECT_GT(still.stats.clipped().open.fragments, 0);
    EXPECT_EQ(still.stats.clipped().close.fragments, 0);
    EXPECT_EQ(still.stats.clipped().subframes_total, 0);
    EXPECT_EQ(still.stats.clipped().still_tiles, still.stats.clipped().tiles);
    for (int n : {1, 2, 5}) {
        job.render.subframes = n;
        const RenderResult r = renderFrame(job, 0);
        for (const char* c : {"R", "G", "B", "A"})
            for (std::size_t i = 0; i < 32 * 32; ++i)
                ASSERT_NEAR(channel(r, c)[i], channel(still, c)[i], kFloatTolerance) << c << " pixel " << i << " N " << n;
    }
}

// A quad sweeping over a still background quad: at every instant the background covers its whole
// rectangle, so coverage there is 1. Frame 0's set lacks the background hidden at shutter open, so the
// frame-0-only ablation opens gaps that the union with frame 1 fills.
TEST(ClippedRenderer, DisocclusionHasNoGapsButFrame0OnlyDoes) {
    RenderJob job = clippedJob();
    job.scene.objects.push_back(rasterQuad(1.0, 1.0, 31.0, 31.0, 10.0));
    job.scene.objects.push_back(movingQuad(4.0, 8.0, 12.0, 20.0, 4.0, {14.0, 0.0}));
    const RenderResult clipped = renderFrame(job, 0);
    job.render.method = Method::Frame0Only;
    const RenderResult frame0 = renderFrame(job, 0);
    double worst_clipped = 1.0, worst_frame0 = 1.0;
    for (int y = 1; y < 31; ++y) {
        for (int x = 1; x < 31; ++x) {
            worst_clipped = std::min<double>(worst_clipped, channel(clipped, "A")[y * 32 + x]);
            worst_frame0 = std::min<double>(worst_frame0, channel(frame0, "A")[y * 32 + x]);
        }
    }
    EXPECT_NEAR(worst_clipped, 1.0, 1e-5);
    EXPECT_LT(worst_frame0, 0.5) << "the frame-0-only ablation should show the revealed gap";
}

TEST(ClippedRenderer, BitIdenticalForOneAndTwoThreads) {
    RenderJob job = clippedJob();
    Material checker;
    checker.texture.kind = Texture::Kind::Checker;
    checker.texture.scale = 0.3;
    job.scene.materials.push_back(checker);
    Object back = rasterQuad(0.5, 0.5, 31.5, 31.5, 10.0);
    back.material = 1;
    job.scene.objects.push_back(back);
    job.scene.objects.push_back(movingQuad(4.0, 8.0, 12.0, 20.0, 4.0, {9.0, 5.0}));
    job.scene.lights.push_back(Light{});
    std::vector<RenderResult> results;
    for (int threads : {1, 2}) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        results.push_back(renderFrame(job, 0));
    }
    for (std::size_t c = 0; c < results[0].image.channels.size(); ++c)
        EXPECT_EQ(results[0].image.channels[c].values, results[1].image.channels[c].values) << c;
    // squareFilmJob turns the fragment audit on: every frame and subframe tile was checked.
    EXPECT_GE(results[0].stats.clipped().audit->pixels, 3 * 32 * 32);
    EXPECT_GT(results[0].stats.clipped().audit->union_pixels, 0);
    EXPECT_EQ(results[0].stats.clipped().audit->violations, 0);
    // The serial seconds are the render's time outside its parallel loops: a part of the total, and
    // positive (a loop counted twice, e.g. a nested one, could take it below zero).
    for (const RenderResult& r : results) {
        EXPECT_GT(r.stats.clipped().seconds.serial, 0.0);
        EXPECT_LT(r.stats.clipped().seconds.serial, r.stats.total_seconds);
    }
}

}  // namespace clipblur

namespace clipblur {

namespace {

// Raster position of world point w for the camera of squareFilmJob: worldAtRaster inverted by hand.
glm::dvec2 rasterOf(const glm::dvec3& w, int size = 32) {
    const double k = 0.5 * size;
    return {0.5 * size - k * w.x / w.z, 0.5 * size - k * w.y / w.z};
}

glm::dvec3 turnAboutZ(const glm::dvec3& w, double angle) {
    return {w.x * std::cos(angle) - w.y * std::sin(angle), w.x * std::sin(angle) + w.y * std::cos(angle), w.z};
}

}  // namespace

// A wall three films wide at depth 6 turns by 0.3 rad about the optical axis over the shutter, covering
// every pixel throughout. What pixel (x, y) sees at time t is the wall's point turned back by 0.3 t from
// worldAtRaster there; its open-to-close displacement is linear in raster position at each t (one depth),
// so the pixel's mean is its value at the centre, averaged here over 2000 instants. The motion AOV must
// follow each surface point, however the fragment sets cut the wall (whole tiles of it are one fragment
// triangle, whose centroid moves up to 2 px differently from a pixel in it).
TEST(ClippedRenderer, MotionAovOfATurningWallIsEachPointsDisplacement) {
    constexpr double kTurn = 0.3;
    for (const TimeIntegration integration : {TimeIntegration::Subframes, TimeIntegration::Sweep}) {
        RenderJob job = clippedJob();
        job.render.time_integration = integration;
        if (integration == TimeIntegration::Subframes) job.render.subframes = 16;
        job.output.aov_motion = true;
        Object wall = rasterQuad(-32.0, -32.0, 64.0, 64.0, 6.0);
        wall.transform.push_back(TransformKey{0.0, glm::dvec3(0.0), {1, 0, 0, 0}, glm::dvec3(1.0)});
        wall.transform.push_back(TransformKey{1.0, glm::dvec3(0.0), {std::cos(kTurn / 2), 0, 0, std::sin(kTurn / 2)}, glm::dvec3(1.0)});
        job.scene.objects.push_back(wall);
        const RenderResult r = renderFrame(job, 0);
        const auto& u = channel(r, "motion.x");  // raster px over the shutter, y down
        const auto& v = channel(r, "motion.y");
        double worst = 0.0;
        for (int y = 0; y < 32; ++y) {
            for (int x = 0; x < 32; ++x) {
                constexpr int kInstants = 2000;
                glm::dvec2 mean(0.0);
                for (int i = 0; i < kInstants; ++i) {
                    const double t = (i + 0.5) / kInstants;
                    const glm::dvec3 open = turnAboutZ(worldAtRaster(x + 0.5, y + 0.5, 6.0), -kTurn * t);
                    mean += (rasterOf(turnAboutZ(open, kTurn)) - rasterOf(open)) / double(kInstants);
                }
                const std::size_t i = static_cast<std::size_t>(y * 32 + x);
                worst = std::max({worst, std::abs(u[i] - mean.x), std::abs(v[i] - mean.y)});
            }
        }
        // Displacements reach 6.8 px. 16 subframes average over instants whose midpoint-rule error on a
        // displacement turning by 0.3 rad is below 0.3^2 / (24 x 16^2) x 6.8 px = 1e-4 px; floats add
        // 1e-6 px. The sweep moves a piece without turning it, which puts its points up to 0.1 px
        // (motion_plan.cpp's kChordTolerance) from where they are, and the displacement changes by at
        // most |R(0.3) - I| = 0.3 px per px: 0.03 px.
        if (integration == TimeIntegration::Sweep)
            EXPECT_LT(worst, 0.03) << "sweep";
        else
            EXPECT_LT(worst, 2e-3) << "subframes";
    }
}

}  // namespace clipblur
