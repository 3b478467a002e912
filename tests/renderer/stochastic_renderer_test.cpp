#include <atomic>
#include <cmath>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "renderer/render.h"
#include "renderer/sampling/pixel_samples.h"
#include "scene/error.h"
#include "tests/renderer/test_scenes.h"

namespace clipblur {

namespace {

float at(const Image& image, const char* channel, int x, int y) {
    return image.find(channel)->values[static_cast<std::size_t>(y * image.window.width() + x)];
}

// Exact area of the unit pixel [x, x+1) x [y, y+1) where a*px + b*py + c > 0: Sutherland-Hodgman clip of
// the square against the half-plane, then the shoelace formula.
double halfPlaneCoverage(int x, int y, double a, double b, double c) {
    const std::vector<glm::dvec2> square{{x, y}, {x + 1, y}, {x + 1, y + 1}, {x, y + 1}};
    std::vector<glm::dvec2> clipped;
    auto f = [&](const glm::dvec2& p) { return a * p.x + b * p.y + c; };
    for (std::size_t i = 0; i < square.size(); ++i) {
        const glm::dvec2 p = square[i];
        const glm::dvec2 q = square[(i + 1) % square.size()];
        const double fp = f(p);
        const double fq = f(q);
        if (fp >= 0) clipped.push_back(p);
        if ((fp >= 0) != (fq >= 0)) clipped.push_back(p + (q - p) * (fp / (fp - fq)));
    }
    double area = 0.0;
    for (std::size_t i = 0; i < clipped.size(); ++i) {
        const glm::dvec2 p = clipped[i];
        const glm::dvec2 q = clipped[(i + 1) % clipped.size()];
        area += p.x * q.y - q.x * p.y;
    }
    return std::fabs(0.5 * area);
}

// Half-plane y > 0.37 x + 5.3 (raster) as a triangle much larger than the 32 x 32 film.
RenderJob diagonalEdgeJob(int samples) {
    RenderJob job = test::squareFilmJob();
    job.render.samples = samples;
    const double slope = 0.37;
    const double offset = 5.3;
    Object tri;
    tri.name = "edge";
    tri.mesh.positions = {test::worldAtRaster(-100, slope * -100 + offset, 5.0),
                          test::worldAtRaster(200, slope * 200 + offset, 5.0), test::worldAtRaster(50, 600, 5.0)};
    tri.mesh.triangles = {{0, 1, 2}};
    job.scene.objects.push_back(tri);
    return job;
}

// Moving quad: raster x in [8, 12), y in [8, 24) at shutter open, translated +10 px in x by close.
RenderJob movingQuadJob(int samples) {
    RenderJob job = test::squareFilmJob();
    job.render.samples = samples;
    Object quad = test::rasterQuad(8, 8, 12, 24, 5.0);
    const glm::dvec3 shift = test::worldAtRaster(18, 8, 5.0) - test::worldAtRaster(8, 8, 5.0);
    quad.transform = {TransformKey{0.0, glm::dvec3(0.0)}, TransformKey{1.0, shift}};
    job.scene.objects.push_back(quad);
    job.output.aov_depth = true;
    job.output.aov_coverage = true;
    job.output.aov_motion = true;
    return job;
}

}  // namespace

TEST(StochasticRenderer, SquareCoversExactlyItsPixels) {
    RenderJob job = test::squareFilmJob();
    job.scene.objects.push_back(test::rasterQuad(10, 10, 20, 20, 5.0));
    job.output.aov_depth = true;
    const Image image = renderFrame(job, 0).image;
    ASSERT_EQ(image.channels.size(), 5u);
    for (int y = 0; y < 32; ++y) {
        for (int x = 0; x < 32; ++x) {
            const bool inside = x >= 10 && x < 20 && y >= 10 && y < 20;
            // Ambient 1, white albedo, no lights: every covered sample is exactly 1.
            ASSERT_EQ(at(image, "R", x, y), inside ? 1.0f : 0.0f) << x << "," << y;
            ASSERT_EQ(at(image, "A", x, y), inside ? 1.0f : 0.0f) << x << "," << y;
            if (inside)
                ASSERT_NEAR(at(image, "Z", x, y), 5.0f, 5.0f * 1e-6f);  // Embree's float ray parameter
            else
                ASSERT_TRUE(std::isinf(at(image, "Z", x, y)));
        }
    }
}

TEST(StochasticRenderer, HalfPixelEdgeGivesHalfCoverage) {
    RenderJob job = test::squareFilmJob();
    job.scene.objects.push_back(test::rasterQuad(10.5, 10, 20, 20, 5.0));
    for (int samples : {4, 16, 36}) {
        job.render.samples = samples;
        const Image image = renderFrame(job, 0).image;
        // The x offsets are N-rooks stratified: one sample in each of the N strata [k/N, (k+1)/N). For
        // even N the edge at 0.5 is a stratum boundary, so exactly N/2 samples are covered.
        for (int y = 10; y < 20; ++y) EXPECT_EQ(at(image, "A", 10, y), 0.5f) << "N = " << samples;
    }
}

TEST(StochasticRenderer, DiagonalEdgeStaysWithinTheStratifiedBoundAndConverges) {
    std::vector<double> rms;
    for (int samples : {4, 16, 64, 256}) {
        const Image image = renderFrame(diagonalEdgeJob(samples), 0).image;
        const StrataShape shape = strataShape(samples);
        // A straight edge crosses at most m + n - 1 cells of the m x n grid; every other cell lies wholly
        // on one side and its one sample is right, a crossed cell is off by at most 1/N.
        const double bound = (shape.columns + shape.rows - 1.0) / samples;
        double sum2 = 0.0;
        for (int y = 0; y < 32; ++y) {
            for (int x = 0; x < 32; ++x) {
                const double exact = halfPlaneCoverage(x, y, -0.37, 1.0, -5.3);
                const double err = at(image, "A", x, y) - exact;
                EXPECT_LE(std::fabs(err), bound + 1e-6) << x << "," << y << " N = " << samples;
                sum2 += err * err;
            }
        }
        rms.push_back(std::sqrt(sum2 / (32 * 32)));
    }
    for (std::size_t i = 1; i < rms.size(); ++i) EXPECT_LT(rms[i], rms[i - 1]) << i;
    // Plain Monte Carlo would fall as 1/sqrt(N), a factor 8 from 4 to 256 samples; stratification must
    // do at least that well.
    EXPECT_LT(rms.back(), rms.front() / 8.0) << rms.front() << " -> " << rms.back();
}

TEST(StochasticRenderer, MovingQuadTimeAveragedCoverageMatchesAnalytic) {
    const int samples = 16;
    const Image image = renderFrame(movingQuadJob(samples), 0).image;
    for (int x = 0; x < 32; ++x) {
        // Coverage of column x over time: overlap of [8 + 10t, 12 + 10t] with [x, x+1], averaged over t by
        // the midpoint rule (the integrand is piecewise linear; 1e5 steps give ~1e-9 error).
        const int steps = 100000;
        double exact = 0.0;
        for (int i = 0; i < steps; ++i) {
            const double t = (i + 0.5) / steps;
            exact += std::max(0.0, std::min(12 + 10 * t, x + 1.0) - std::max(8 + 10 * t, double(x)));
        }
        exact /= steps;
        // Latin-hypercube time strata have variance at most N/(N-1) times plain Monte Carlo's c(1-c)/N
        // (Owen 1997). Per pixel allow 4 sigma; the mean of the 16 rows (independent streams), 4 sigma/4.
        const double sigma = std::sqrt(exact * (1 - exact) / samples * samples / (samples - 1.0));
        double mean = 0.0;
        for (int y = 8; y < 24; ++y) {
            const double c = at(image, "A", x, y);
            if (exact == 0.0) {
                EXPECT_EQ(c, 0.0) << x;
            }
            EXPECT_NEAR(c, exact, 4 * sigma + 1e-6) << x << "," << y;
            mean += c / 16.0;
        }
        EXPECT_NEAR(mean, exact, sigma + 1e-6) << x;
        EXPECT_EQ(at(image, "A", x, 7), 0.0f);
        EXPECT_EQ(at(image, "coverage", x, 12), at(image, "A", x, 12));
    }
}

TEST(StochasticRenderer, MotionAovIsTheScreenSpaceDisplacement) {
    const Image image = renderFrame(movingQuadJob(16), 0).image;
    // Pure lateral translation at constant depth projects to a uniform 10 px shift in +x. Columns 10..19
    // are wholly covered for at least a fifth of the shutter, which holds 3 of the 16 time strata, so
    // each has covered samples.
    for (int x = 10; x < 20; ++x) {
        ASSERT_GT(at(image, "A", x, 12), 0.0f);
        EXPECT_NEAR(at(image, "motion.x", x, 12), 10.0f, 1e-4f) << x;
        EXPECT_NEAR(at(image, "motion.y", x, 12), 0.0f, 1e-4f) << x;
        // Depth is what is seen at mid-shutter, when the quad covers x in [13, 17) and nothing else is.
        if (x >= 13 && x < 17)
            EXPECT_NEAR(at(image, "Z", x, 12), 5.0f, 5e-6f) << x;
        else
            EXPECT_TRUE(std::isinf(at(image, "Z", x, 12))) << x;
    }
    EXPECT_EQ(at(image, "motion.x", 30, 12), 0.0f);
}

TEST(StochasticRenderer, BitIdenticalForOneAndTwoThreads) {
    RenderJob job = movingQuadJob(9);
    job.scene.film.width = 48;
    job.render.tile_size = 5;
    job.render.shadows = true;
    Object spinner = test::rasterQuad(20, 2, 30, 30, 4.0);
    spinner.transform = {TransformKey{0.0, glm::dvec3(0.0)},
                         TransformKey{1.0, glm::dvec3(0.2, 0.1, 0.3), glm::angleAxis(0.7, glm::dvec3(0.3, 0.4, 0.86))}};
    job.scene.objects.push_back(spinner);
    Material checker;
    checker.texture = {Texture::Kind::Checker, glm::dvec3(0.2, 0.5, 0.1), 0.3};
    job.scene.materials.push_back(checker);
    job.scene.objects.back().material = 1;
    Light light;
    light.kind = Light::Kind::Point;
    light.position = {1.0, 2.0, -1.0};
    job.scene.lights.push_back(light);
    job.scene.ambient = glm::dvec3(0.1);

    RenderResult one;
    RenderResult two;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = renderFrame(job, 2);
    }
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
        two = renderFrame(job, 2);
    }
    ASSERT_EQ(one.image.channels.size(), two.image.channels.size());
    for (std::size_t c = 0; c < one.image.channels.size(); ++c) {
        const auto& a = one.image.channels[c].values;
        const auto& b = two.image.channels[c].values;
        ASSERT_EQ(a.size(), b.size());
        EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0) << one.image.channels[c].name;
    }
    EXPECT_EQ(one.stats.stochastic().rays(), two.stats.stochastic().rays());
    EXPECT_GT(one.stats.stochastic().shadow_rays, 0);
    EXPECT_EQ(one.stats.stochastic().primary_rays, 48LL * 32 * 9);
}

TEST(StochasticRenderer, ReportsProgressPerTileAndStopsWhenCancelled) {
    RenderJob job = test::squareFilmJob();
    job.scene.objects.push_back(test::rasterQuad(10, 10, 20, 20, 5.0));
    long long calls = 0;
    long long last_total = 0;
    RenderCallbacks callbacks;
    callbacks.progress = [&](long long, long long total) {
        ++calls;
        last_total = total;
    };
    renderFrame(job, 0, callbacks);
    EXPECT_EQ(calls, 16);  // 32 x 32 in 8 x 8 tiles
    EXPECT_EQ(last_total, 16);

    std::atomic<bool> cancel{true};
    callbacks.cancel = &cancel;
    try {
        renderFrame(job, 0, callbacks);
        FAIL() << "expected cancellation";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::Interrupted);
    }
}

}  // namespace clipblur
