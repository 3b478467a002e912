#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "renderer/propagation/subframes.h"
#include "renderer/render.h"
#include "renderer/test_scenes.h"

namespace clipblur {

namespace {

using test::rasterQuad;
using test::squareFilmJob;
using test::worldAtRaster;

// A quad over raster x [left, left + width), y [8, 24) at depth 6 at time `at`, translating in +x at v
// pixels per frame from key time `at - 2` to `at + 2` (constant speed all that time).
Object slidingQuad(double left, double width, double v, double at) {
    Object quad = rasterQuad(left, 8.0, left + width, 24.0, 6.0);
    const glm::dvec3 step = worldAtRaster(left + 2.0 * v, 8.0, 6.0) - worldAtRaster(left, 8.0, 6.0);
    quad.transform.push_back(TransformKey{at - 2.0, -step, {1, 0, 0, 0}, glm::dvec3(1.0)});
    quad.transform.push_back(TransformKey{at + 2.0, step, {1, 0, 0, 0}, glm::dvec3(1.0)});
    return quad;
}

RenderJob jobWith(Method method, TimeIntegration integration) {
    RenderJob job = squareFilmJob();
    job.render.method = method;
    job.render.time_integration = integration;
    return job;
}

struct MethodCase {
    const char* name;
    Method method;
    TimeIntegration integration;
};

const MethodCase kMethods[] = {{"clipped subframes", Method::Clipped, TimeIntegration::Subframes},
                               {"clipped sweep", Method::Clipped, TimeIntegration::Sweep},
                               {"stochastic", Method::Stochastic, TimeIntegration::Subframes},
                               {"accumulation", Method::Accumulation, TimeIntegration::Subframes}};

// Pixel value of one moving edge (the quad's part right of it, or left: sign) under a shutter density.
// The pixel column [x, x + 1] sees R(e(tau) - x) of the edge e(tau) = e0 + v tau, R(s) = clamp(s, 0, 1):
// 0 before a = (x - e0) / v, v (tau - a) until b = a + 1 / v, 1 after. So
//   integral rho R = v [M1(b') - M1(a') - a (F(b') - F(a'))] + 1 - F(b'),
// a', b' clamped to [0, T], F(s) = integral_0^s rho and M1(s) = integral_0^s tau rho.
struct Density {
    double T = 0.5;
    bool triangle = true;
    // Triangle 0 -> peak at T/2 -> 0: rho = 4 tau / T^2 below T/2, 4 (T - tau) / T^2 above.
    //   F(s) = 2 s^2 / T^2 (s <= T/2),  1 - 2 (T - s)^2 / T^2 above;
    //   M1(s) = 4 s^3 / (3 T^2) (s <= T/2),  T/6 + (4 / T^2) [T tau^2 / 2 - tau^3 / 3] from T/2 to s above.
    // Box: rho = 1 / T, F(s) = s / T, M1(s) = s^2 / (2 T).
    double F(double s) const {
        if (!triangle) return s / T;
        return s <= 0.5 * T ? 2.0 * s * s / (T * T) : 1.0 - 2.0 * (T - s) * (T - s) / (T * T);
    }
    double M1(double s) const {
        if (!triangle) return s * s / (2.0 * T);
        if (s <= 0.5 * T) return 4.0 * s * s * s / (3.0 * T * T);
        const auto g = [&](double u) { return 0.5 * T * u * u - u * u * u / 3.0; };
        return T / 6.0 + 4.0 / (T * T) * (g(s) - g(0.5 * T));
    }
    double edge(double e0, double v, double x) const {
        const double a = (x - e0) / v, b = a + 1.0 / v;
        const double a1 = std::clamp(a, 0.0, T), b1 = std::clamp(b, 0.0, T);
        return v * (M1(b1) - M1(a1) - a * (F(b1) - F(a1))) + 1.0 - F(b1);
    }
};

// Expected red channel of slidingQuad(left, width, v, at = open) over a shutter of length T at open: in
// rows 8..23, R(right edge) - R(left edge) (the quad is wider than its motion, so no pixel sees both
// edges move through it); 0 elsewhere.
std::vector<double> analytic(const Density& rho, double left, double width, double v) {
    std::vector<double> out(32 * 32, 0.0);
    for (int y = 8; y < 24; ++y)
        for (int x = 0; x < 32; ++x)
            out[y * 32 + x] = rho.edge(left + width, v, x) - rho.edge(left, v, x);
    return out;
}

double maxError(const RenderResult& r, const std::vector<double>& expected) {
    const auto& red = r.image.find("R")->values;
    double worst = 0.0;
    for (std::size_t i = 0; i < expected.size(); ++i) worst = std::max(worst, std::abs(red[i] - expected[i]));
    return worst;
}

bool sameBits(const RenderResult& a, const RenderResult& b) {
    if (a.image.channels.size() != b.image.channels.size()) return false;
    for (std::size_t c = 0; c < a.image.channels.size(); ++c) {
        const auto& x = a.image.channels[c].values;
        const auto& y = b.image.channels[c].values;
        if (x.size() != y.size() || std::memcmp(x.data(), y.data(), x.size() * sizeof(float)) != 0) return false;
    }
    return true;
}

const std::vector<ShutterPoint> kTriangle{{0.0, 0.0}, {0.25, 1.0}, {0.5, 0.0}};

}  // namespace

// A centred 180-degree shutter (-0.25 .. 0.25) is the 0 .. 0.5 shutter of the same motion a quarter frame
// later: camera and quad keys at negative times, guard band, hidden probes, motion, depth and coverage
// AOVs all see the same times. 1e-6: both renders compute the same positions from times that differ in
// their last bits (t + 0.25), then store floats (6e-8 at values <= 1); motion vectors are pixels (up to
// 8), so 1e-6 relative.
TEST(ShutterCurveRender, CentredShutterIsTheLaterShutterShiftedByAQuarterFrame) {
    for (const MethodCase& m : kMethods) {
        RenderJob centred = jobWith(m.method, m.integration);
        centred.shutter = {-0.25, 0.25, {}};
        centred.output.aov_depth = centred.output.aov_coverage = centred.output.aov_motion = true;
        RenderJob later = centred;
        later.shutter = {0.0, 0.5, {}};
        for (auto [job, at] : {std::pair{&centred, -0.25}, std::pair{&later, 0.0}}) {
            job->scene.objects.push_back(slidingQuad(4.3, 12.25, 16.0, at));
            // The camera slides too, keyed around the shutter's opening.
            job->scene.camera.keys = {CameraKey{at - 2.0, glm::dvec3(-0.1, 0.0, 0.0), glm::dvec3(0, 0, 1), glm::dvec3(0, 1, 0)},
                                      CameraKey{at + 2.0, glm::dvec3(0.1, 0.0, 0.0), glm::dvec3(0, 0, 1), glm::dvec3(0, 1, 0)}};
        }
        const RenderResult a = renderFrame(centred, 0), b = renderFrame(later, 0);
        for (const auto& channel : a.image.channels) {
            const auto& x = channel.values;
            const auto& y = b.image.find(channel.name)->values;
            double worst = 0.0, scale = 1.0;
            for (std::size_t i = 0; i < x.size(); ++i) {
                if (std::isinf(x[i]) || std::isinf(y[i])) {
                    EXPECT_EQ(x[i], y[i]) << m.name << " " << channel.name;
                    continue;
                }
                worst = std::max(worst, static_cast<double>(std::abs(x[i] - y[i])));
                scale = std::max(scale, static_cast<double>(std::abs(x[i])));
            }
            EXPECT_LT(worst, 1e-6 * scale) << m.name << " channel " << channel.name;
        }
        if (m.method == Method::Clipped) {
            EXPECT_EQ(a.stats.clipped().segments, b.stats.clipped().segments) << m.name;
        }
    }
}

// Shards: a window of a centred-shutter render (the sweep's spills from neighbouring tiles included) has
// the whole film's pixels, bit for bit, with and without a curve.
TEST(ShutterCurveRender, CentredShutterWindowHasTheWholeFilmsPixels) {
    for (const MethodCase& m : kMethods) {
        for (bool curve : {false, true}) {
            RenderJob job = jobWith(m.method, m.integration);
            job.shutter = {-0.25, 0.25, {}};
            if (curve) job.shutter.curve = {{-0.25, 0.0}, {-0.15, 1.0}, {0.15, 1.0}, {0.25, 0.0}};
            job.scene.objects.push_back(slidingQuad(4.3, 12.25, 16.0, -0.25));
            const RenderResult whole = renderFrame(job, 0);
            job.render.window = PixelBounds::corners(9, 5, 23, 27);
            const RenderResult part = renderFrame(job, 0);
            const auto& a = whole.image.find("R")->values;
            const auto& b = part.image.find("R")->values;
            int different = 0;
            for (int y = 5; y < 27; ++y)
                for (int x = 9; x < 23; ++x)
                    different += a[whole.image.index(x, y)] == b[part.image.index(x, y)] ? 0 : 1;
            EXPECT_EQ(different, 0) << m.name << (curve ? " with curve" : "");
        }
    }
}

// A triangle shutter curve (0 at open and close, peak mid-shutter) on a quad sliding 16 px per frame over a
// 180-degree shutter, against the closed form above. Point subframes: the shutter is cut at the peak and
// each half's midpoint rule weights subframe k by w(t_k) / mean(w), which integrates the piecewise-linear w
// exactly, and c(t) w(t) with the midpoint rule's error: per unit time at most h^2 |f''| / 24 with
// f'' = 2 c' w' (|c'| <= v, |w'| = 4 / T^2 normalised) and h^2 / 8 x the jump in f' (v x peak density 2 / T)
// at each of a pixel's two coverage kinks, so at most (1/3 + 1/2) h^2 v / T. The order must be about 2.
TEST(ShutterCurveRender, TriangleCurveMatchesTheClosedFormWithPointSubframes) {
    const double left = 4.3, width = 12.25, v = 16.0, T = 0.5;
    const std::vector<double> expected = analytic({T, true}, left, width, v);
    const std::vector<double> box = analytic({T, false}, left, width, v);
    double curve_matters = 0.0;
    for (std::size_t i = 0; i < box.size(); ++i) curve_matters = std::max(curve_matters, std::abs(box[i] - expected[i]));
    EXPECT_GT(curve_matters, 0.1) << "the triangle must differ from the box for this test to see the curve";
    std::vector<double> errors;
    for (int n : {8, 16, 32, 64}) {
        RenderJob job = jobWith(Method::Clipped, TimeIntegration::Subframes);
        job.shutter = {0.0, T, kTriangle};
        job.scene.objects.push_back(slidingQuad(left, width, v, 0.0));
        job.render.subframes = n;  // shared by the two halves: n / 2 each, h = T / n
        const RenderResult r = renderFrame(job, 0);
        EXPECT_EQ(r.stats.clipped().segments, 2) << "cut at the curve's peak";
        errors.push_back(maxError(r, expected));
        const double h = T / n;
        EXPECT_LT(errors.back(), (1.0 / 3.0 + 0.5) * h * h * v / T + 1e-6) << "n " << n;
    }
    const double order = std::log2(errors.front() / errors.back()) / 3.0;
    EXPECT_GT(order, 1.6) << errors[0] << " " << errors[1] << " " << errors[2] << " " << errors[3];
}

// Sweep integration: each position s of an interval counts 1 + tilt s, the curve's linear weight there, so
// for pure translation the sweep is point subframes at its position times with the curve's weights: the
// bound above with h the time between positions. Each half moves the quad d = T v / 2 = 4 px and holds
// half the shutter, so it gets max(d, sqrt(kKinkMotion d / 2)) / spacing = 11.3 / spacing positions,
// rounded up (the kink floor, kinkSamples), not eq. 24's 4 / spacing.
TEST(ShutterCurveRender, TriangleCurveMatchesTheClosedFormWithSweep) {
    const double left = 4.3, width = 12.25, v = 16.0, T = 0.5;
    const std::vector<double> expected = analytic({T, true}, left, width, v);
    const double d = 0.5 * T * v;
    for (double spacing : {0.25, 0.05}) {
        RenderJob job = jobWith(Method::Clipped, TimeIntegration::Sweep);
        job.shutter = {0.0, T, kTriangle};
        job.scene.objects.push_back(slidingQuad(left, width, v, 0.0));
        job.render.sweep_spacing = spacing;
        const RenderResult r = renderFrame(job, 0);
        const int n =
            2 * static_cast<int>(std::ceil(std::max(d, std::sqrt(kKinkMotion * d / 2.0)) / spacing - 1e-6));
        const double h = T / n;
        EXPECT_LT(maxError(r, expected), (1.0 / 3.0 + 0.5) * h * h * v / T + 1e-6) << "spacing " << spacing;
        // The same times as n point subframes (one re-clip per half, its positions h apart): the same
        // image up to float storage (1e-6, as above).
        RenderJob points = jobWith(Method::Clipped, TimeIntegration::Subframes);
        points.shutter = job.shutter;
        points.scene.objects = job.scene.objects;
        points.render.subframes = n;
        const RenderResult point_render = renderFrame(points, 0);
        const auto& point_red = point_render.image.find("R")->values;
        const std::vector<double> point_image(point_red.begin(), point_red.end());
        EXPECT_LT(maxError(r, point_image), 1e-6) << "spacing " << spacing;
    }
}

// Exact sweep: over each chord the curve's weight is linear (1 + tilt s within a segment) and the chord's
// coverage is integrated against it in closed form, so the translating quad is exact under the triangle
// curve whatever the spacing: float storage alone (1e-6).
TEST(ShutterCurveRender, TriangleCurveIsExactUnderExactSweep) {
    const double left = 4.3, width = 12.25, v = 16.0, T = 0.5;
    const std::vector<double> expected = analytic({T, true}, left, width, v);
    for (double spacing : {8.0, 1.0, 0.25}) {
        RenderJob job = jobWith(Method::Clipped, TimeIntegration::Sweep);
        job.render.sweep_time = SweepTime::Exact;
        job.shutter = {0.0, T, kTriangle};
        job.scene.objects.push_back(slidingQuad(left, width, v, 0.0));
        job.render.sweep_spacing = spacing;
        const RenderResult r = renderFrame(job, 0);
        EXPECT_EQ(r.stats.clipped().segments, 2) << "cut at the curve's peak";
        EXPECT_LT(maxError(r, expected), 1e-6) << "spacing " << spacing;
    }
}

// The stochastic method draws times from the curve (its inverse CDF), stratified. Per pixel the estimate
// is a mean of spp coverage samples with mean p (the closed form): its standard error is at most
// sqrt(p (1 - p) / spp) for independent samples, and Latin-hypercube stratification raises a variance by
// at most spp / (spp - 1) (Owen 1997), so 5 of those bound every pixel of the 32 x 32 film. The box's
// closed form must fall outside that band somewhere, or the test could not see a wrong time density.
TEST(ShutterCurveRender, TriangleCurveMatchesTheClosedFormStochastically) {
    const double left = 4.3, width = 12.25, v = 16.0, T = 0.5;
    const int spp = 4096;
    const std::vector<double> expected = analytic({T, true}, left, width, v);
    const std::vector<double> box = analytic({T, false}, left, width, v);
    RenderJob job = jobWith(Method::Stochastic, TimeIntegration::Subframes);
    job.shutter = {0.0, T, kTriangle};
    job.scene.objects.push_back(slidingQuad(left, width, v, 0.0));
    job.render.samples = spp;
    const RenderResult r = renderFrame(job, 0);
    const auto& red = r.image.find("R")->values;
    int box_outside = 0;
    for (std::size_t i = 0; i < expected.size(); ++i) {
        const double p = expected[i];
        const double band = 5.0 * std::sqrt(p * (1.0 - p) / spp * spp / (spp - 1.0)) + 1e-6;
        EXPECT_LT(std::abs(red[i] - p), band) << "pixel " << i % 32 << ", " << i / 32;
        box_outside += std::abs(red[i] - box[i]) > band ? 1 : 0;
    }
    EXPECT_GT(box_outside, 0);
}

// The accumulation buffer renders at the curve's quantiles (k + 1/2) / n, with equal weights: the midpoint
// rule in u of c(t(u)). Where the density is 0 (the triangle's ends) t(u) has a square-root end,
// t - open = T sqrt(u / 2), so the first and last interval in u carry an error up to (1/n) v T sqrt(1 / (2n))
// (the coverage changes by v dt there) and the interior is second order: 1.5e-3 at n = 256, v = 16.
TEST(ShutterCurveRender, TriangleCurveMatchesTheClosedFormByAccumulation) {
    const double left = 4.3, width = 12.25, v = 16.0, T = 0.5;
    const int n = 256;
    RenderJob job = jobWith(Method::Accumulation, TimeIntegration::Subframes);
    job.shutter = {0.0, T, kTriangle};
    job.scene.objects.push_back(slidingQuad(left, width, v, 0.0));
    job.render.samples = n;
    const double bound = 2.0 * v * T / n * std::sqrt(1.0 / (2.0 * n)) + 1e-6;
    EXPECT_LT(maxError(renderFrame(job, 0), analytic({T, true}, left, width, v)), bound);
}

// A curve whose weights are all equal is a box: the renderers keep the box code, bit for bit.
TEST(ShutterCurveRender, BoxCurveGivesTheBitsOfNoCurve) {
    for (const MethodCase& m : kMethods) {
        RenderJob plain = jobWith(m.method, m.integration);
        plain.shutter = {-0.25, 0.25, {}};
        plain.output.aov_depth = plain.output.aov_coverage = plain.output.aov_motion = true;
        plain.scene.objects.push_back(slidingQuad(4.3, 12.25, 16.0, -0.25));
        RenderJob boxed = plain;
        boxed.shutter.curve = {{-0.25, 3.0}, {0.1, 3.0}, {0.25, 3.0}};
        EXPECT_TRUE(sameBits(renderFrame(plain, 0), renderFrame(boxed, 0))) << m.name;
    }
}

// A trapezoid (open ramps of 0.1 frame on a 180-degree centred shutter, the docs' example) splits the
// clipped method's shutter into its three linear pieces, each weighted by its share of the curve's
// integral (0.05 / 0.4, 0.3 / 0.4, 0.05 / 0.4), and matches the stochastic method within its noise.
TEST(ShutterCurveRender, TrapezoidCurveAgreesAcrossMethods) {
    RenderJob job = jobWith(Method::Clipped, TimeIntegration::Subframes);
    job.shutter = {-0.25, 0.25, {{-0.25, 0.0}, {-0.15, 1.0}, {0.15, 1.0}, {0.25, 0.0}}};
    job.scene.objects.push_back(slidingQuad(4.3, 12.25, 16.0, -0.25));
    job.render.subframes = 64;
    const RenderResult clipped = renderFrame(job, 0);
    EXPECT_EQ(clipped.stats.clipped().segments, 3);
    job.render.method = Method::Stochastic;
    job.render.samples = 4096;
    const RenderResult stochastic = renderFrame(job, 0);
    const auto& a = clipped.image.find("R")->values;
    const auto& b = stochastic.image.find("R")->values;
    for (std::size_t i = 0; i < a.size(); ++i) {
        // The clipped value stands in for the mean (the stochastic test's band), plus the clipped
        // quadrature's bound with 8 subframes on a 0.1-frame ramp: (5/6) h^2 v / T = 4.2e-3.
        const double p = a[i];
        EXPECT_LT(std::abs(a[i] - b[i]), 5.0 * std::sqrt(p * (1.0 - p) / 4095.0) + 4.2e-3) << "pixel " << i;
    }
}

}  // namespace clipblur
