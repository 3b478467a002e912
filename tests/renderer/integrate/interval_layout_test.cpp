#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "renderer/integrate/interval_layout.h"
#include "support/motion_scenes.h"

namespace clipblur {

namespace {

using testing::referenceProjection;
using testing::stillCameraScene;
using testing::triangleObject;
using testing::addTransformKey;

// The positions one interval needs by its definition, from the test's own slow projection: the farthest
// a vertex gets from its interval-start position along the parabola through its exact positions at the
// interval's start, middle and end (chord + twice the middle's distance from the chord's midpoint bounds
// that parabola), at least the kink floor of that travel for the interval's share of the shutter,
// max(d, sqrt(kKinkMotion share d)), over the spacing, rounded up. Exact sweep's by its definition: n chords stray by
// sagitta / n^2 (the sagitta: the middle's distance from the chord's midpoint), so kBendTolerance x
// spacing^2 needs sqrt(sagitta / kBendTolerance) / spacing of them.
int expectedPositions(const Scene& scene, const Projection& projection, double t0, double t1, double spacing,
                      bool exact = false) {
    double farthest = 0.0;
    for (int v = 0; v < 3; ++v) {
        glm::dvec3 b(0.0);
        b[v] = 1.0;
        const glm::dvec2 a = referenceProjection(scene, projection, 0, 0, b, t0).raster;
        const glm::dvec2 m = referenceProjection(scene, projection, 0, 0, b, 0.5 * (t0 + t1)).raster;
        const glm::dvec2 e = referenceProjection(scene, projection, 0, 0, b, t1).raster;
        const double sagitta = glm::length(0.5 * (a + e) - m);
        farthest = std::max(farthest, exact ? std::sqrt(sagitta / kBendTolerance) : glm::length(e - a) + 2.0 * sagitta);
    }
    if (!exact) farthest = std::max(farthest, std::sqrt(kKinkMotion * (t1 - t0) * farthest));
    return std::max(1, static_cast<int>(std::ceil(farthest / spacing)));
}

// The open layer of one fragment triangle: object 0's triangle 0, whole.
struct WholeTriangle {
    std::vector<FragmentTriangle> triangles{{0, 0, {glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1)}}};
    FragmentLayers layers;
    WholeTriangle() { layers.triangles = {&triangles, nullptr}; }
    WholeTriangle(const WholeTriangle&) = delete;
    WholeTriangle& operator=(const WholeTriangle&) = delete;
};

// A still camera and a triangle with two vertices at depth 5 and the third at `third`, sliding 0.5
// world units along x over the shutter.
Scene slidingTriangleScene(const glm::dvec3& third) {
    Scene scene = stillCameraScene(640, 360, 40.0);
    scene.objects.push_back(triangleObject({-1, -1, 5}, {1, -1, 5}, third));
    addTransformKey(scene.objects[0], 0.0, {0, 0, 0});
    addTransformKey(scene.objects[0], 1.0, {0.5, 0, 0});
    return scene;
}

// The pinhole's focal length in pixels: a world length l across the view at depth z spans focal l / z px.
double focalPixels(const Scene& scene) {
    return 0.5 * scene.film.height / std::tan(0.5 * glm::radians(scene.camera.vfov_degrees));
}

// A camera dollying away (depth doubles over the shutter) from a triangle.
Scene dollyAwayScene() {
    Scene scene = stillCameraScene(640, 360, 40.0);
    scene.camera.keys.push_back({1.0, {0, 0, -10}, {0, 0, 1}, {0, 1, 0}});
    scene.objects.push_back(triangleObject({-3, -2, 10}, {3, -1.5, 10}, {0.5, 2.5, 12}));
    return scene;
}

}  // namespace

// A camera dollying away from a triangle: image speed falls as 1/depth^2, so the early intervals need
// more sweep positions than the late ones. Each interval gets what its own motion needs (checked
// against the independent projection), not what the fastest moment of the shutter needs.
TEST(SweepPositions, FollowEachIntervalsOwnMotion) {
    const Scene scene = dollyAwayScene();
    const Projection projection(scene.film.width, scene.film.height, scene.camera.vfov_degrees);
    const WholeTriangle whole;
    const FragmentLayers& layers = whole.layers;

    constexpr int kIntervals = 6;
    constexpr double kSpacing = 0.75;
    const std::vector<int> positions = sweepPositions(
        scene, projection, layers,
        {.t0 = 0.0, .t1 = 1.0, .intervals = kIntervals, .spacing = kSpacing, .max_positions = 1000});
    ASSERT_EQ(positions.size(), std::size_t(kIntervals));
    for (int k = 0; k < kIntervals; ++k)
        EXPECT_EQ(positions[k], expectedPositions(scene, projection, k / double(kIntervals), (k + 1) / double(kIntervals), kSpacing))
            << "interval " << k;
    // Depth doubles over the shutter, so the first interval moves about (z1 / z0)^2 = 4x the last, and
    // gets more than sqrt(4) x its positions where the kink floor (a square root of the travel) holds.
    EXPECT_GT(positions.front(), 2 * positions.back());
}

// Vertices behind the camera plane at any of an interval's three times are not swept, so they must not
// set the count: a triangle reaching through the camera plane counts only its vertices in front.
TEST(SweepPositions, IgnoreVerticesBehindTheCamera) {
    const Scene scene = slidingTriangleScene({0, 1, -3});
    const Projection projection(scene.film.width, scene.film.height, scene.camera.vfov_degrees);
    const WholeTriangle whole;
    const FragmentLayers& layers = whole.layers;
    // The two front vertices move 0.5 world units at depth 5: d = focal / 5 * 0.5 = 49.4 px, the same for
    // both, under kKinkMotion, so the count is the kink floor sqrt(kKinkMotion d) = 56.2.
    const double d = focalPixels(scene) / 5.0 * 0.5;
    const std::vector<int> positions = sweepPositions(
        scene, projection, layers, {.t0 = 0.0, .t1 = 1.0, .intervals = 1, .spacing = 1.0, .max_positions = 1000});
    EXPECT_EQ(positions[0], static_cast<int>(std::ceil(std::sqrt(kKinkMotion * d))));
}

// A vertex just in front of the camera plane travels thousands of pixels, but no tile sweeps a fragment
// that travels farther than its reach (SweepInterval::sweeps), so a vertex counts at most `reach`. Here
// the two far vertices travel focal / 5 x 0.5 = 49.4 px and the near one (depth 0.05) 100x that: without
// a reach it sets the count (4,945 positions), with a reach of 80 px the count is 80, and with 10 px,
// which all three exceed, the kink floor of a 10 px travel (kinkSamples): ceil(sqrt(kKinkMotion 10)) = 26.
// Exact sweep: the same triangle also coming 0.04 nearer (the near vertex from depth 0.05 to 0.01) bends
// the near vertex's path; a path of travel at most R strays at most R / 2 from its chord, so bends count
// up to sqrt(R / 2 / kBendTolerance): 16 positions for R = 8 (the far vertices' bends are under 2).
TEST(SweepPositions, VertexTravelCountsUpToTheReach) {
    const Scene scene = slidingTriangleScene({0, 0.02, 0.05});
    const Projection projection(scene.film.width, scene.film.height, scene.camera.vfov_degrees);
    const WholeTriangle whole;
    const FragmentLayers& layers = whole.layers;
    const double focal = focalPixels(scene);
    const auto count = [&](double reach) {
        return sweepPositions(scene, projection, layers,
                              {.t0 = 0.0, .t1 = 1.0, .intervals = 1, .spacing = 1.0, .max_positions = 100000, .reach = reach})[0];
    };
    EXPECT_EQ(count(std::numeric_limits<double>::infinity()), static_cast<int>(std::ceil(focal / 0.05 * 0.5)));
    EXPECT_EQ(count(80.0), 80);
    EXPECT_EQ(count(10.0), static_cast<int>(std::ceil(std::sqrt(kKinkMotion * 10.0))));

    Scene dolly = scene;
    dolly.objects[0].transform.back().translate = glm::dvec3(0.5, 0.0, -0.04);
    const auto exact = [&](double reach) {
        return sweepPositions(dolly, projection, layers,
                              {.t0 = 0.0, .t1 = 1.0, .intervals = 1, .spacing = 1.0, .max_positions = 100000, .exact = true, .reach = reach})[0];
    };
    EXPECT_GT(exact(std::numeric_limits<double>::infinity()), 100);
    EXPECT_EQ(exact(8.0), 16);
}

// The largest reach of a plan's tiles is sweepInterval's for each: 10 px over 4 re-clips reaches
// 2 x 10 / 4 + 1 = 6 px, 3 px over one 7 px; a still tile (no re-clips) reaches nothing.
TEST(IntervalLayout, LargestReachIsTheFarthestTiles) {
    std::vector<SubframePlan> tiles(3);
    tiles[0].count = 4;
    tiles[0].max_sweep_pixels = 10.0;
    tiles[1].count = 1;
    tiles[1].max_sweep_pixels = 3.0;
    tiles[2].count = 0;
    tiles[2].max_sweep_pixels = 100.0;
    EXPECT_DOUBLE_EQ(largestReach(tiles), 7.0);
}

// Exact sweep spaces positions by bend, not travel. The dolly away above: image speed falls as 1/depth^2
// and the paths bend in time as it changes, so the early intervals still need more positions than the late
// ones (about (z1 / z0)^1.5 = 2.8x for the sagitta's 8x), each what its own bend needs.
TEST(SweepPositions, ExactFollowEachIntervalsOwnBend) {
    const Scene scene = dollyAwayScene();
    const Projection projection(scene.film.width, scene.film.height, scene.camera.vfov_degrees);
    const WholeTriangle whole;
    const FragmentLayers& layers = whole.layers;
    constexpr int kIntervals = 6;
    constexpr double kSpacing = 0.1;
    const std::vector<int> positions = sweepPositions(
        scene, projection, layers,
        {.t0 = 0.0, .t1 = 1.0, .intervals = kIntervals, .spacing = kSpacing, .max_positions = 1000, .exact = true});
    ASSERT_EQ(positions.size(), std::size_t(kIntervals));
    for (int k = 0; k < kIntervals; ++k)
        EXPECT_EQ(positions[k], expectedPositions(scene, projection, k / double(kIntervals), (k + 1) / double(kIntervals), kSpacing, true))
            << "interval " << k;
    EXPECT_GT(positions.front(), 2 * positions.back());
}

// A pan (camera translation parallel to the film) moves every point along a straight line at a constant
// rate: nothing bends, one position however far it travels.
TEST(SweepPositions, ExactNeedOneWhereNothingBends) {
    Scene scene = stillCameraScene(640, 360, 40.0);
    scene.camera.keys.push_back({1.0, {4, 1, 0}, {0, 0, 1}, {0, 1, 0}});
    scene.objects.push_back(triangleObject({-1, -1, 5}, {1, -1, 5}, {0, 1, 7}));
    const Projection projection(scene.film.width, scene.film.height, scene.camera.vfov_degrees);
    const WholeTriangle whole;
    const FragmentLayers& layers = whole.layers;
    const std::vector<int> positions = sweepPositions(
        scene, projection, layers, {.t0 = 0.0, .t1 = 1.0, .intervals = 1, .spacing = 0.1, .max_positions = 1000, .exact = true});
    EXPECT_EQ(positions[0], 1);
    const std::vector<int> points = sweepPositions(
        scene, projection, layers, {.t0 = 0.0, .t1 = 1.0, .intervals = 1, .spacing = 0.1, .max_positions = 1000});
    EXPECT_GT(points[0], 100) << "the same pan under point positions: travel / spacing";
}

// The reach and apron rule by hand: 10 px of motion over 4 intervals gives reach 2 x 10 / 4 + 1 = 6 px
// and an apron of ceil(6 / 2) + 1 = 4 px. A corner tile re-clips the apron outside the film on its two
// film edges; an inner tile re-clips itself only; both reach an apron past what they re-clip.
TEST(IntervalLayout, ReachAndApronOfCornerAndInnerTiles) {
    const PixelBounds film = PixelBounds::corners(0, 0, 160, 90);
    const SweepInterval corner = sweepInterval(PixelBounds::corners(0, 0, 32, 32), 10.0, 4, film);
    EXPECT_EQ(corner.reach, 6.0);
    EXPECT_EQ(corner.resolve, PixelBounds::corners(-4, -4, 32, 32));
    EXPECT_EQ(corner.box, PixelBounds::corners(-8, -8, 36, 36));
    const SweepInterval inner = sweepInterval(PixelBounds::corners(32, 32, 64, 64), 10.0, 4, film);
    EXPECT_EQ(inner.resolve, PixelBounds::corners(32, 32, 64, 64));
    EXPECT_EQ(inner.box, PixelBounds::corners(28, 28, 68, 68));
    const SweepInterval last = sweepInterval(PixelBounds::corners(128, 64, 160, 90), 10.0, 4, film);
    EXPECT_EQ(last.resolve, PixelBounds::corners(128, 64, 164, 94));
}

// A straight path from -3 to +3 px travels 6 px: swept within a reach of 6, a point sample within 5.9.
TEST(IntervalLayout, PathTravelIsChordLengthForAStraightPath) {
    const SweepPath path = SweepPath::through({{-3.0, 0.0}, 1.0}, {{0.0, 0.0}, 1.0}, {{3.0, 0.0}, 1.0});
    EXPECT_DOUBLE_EQ(pathTravel(path), 6.0);
    SweepInterval interval;
    interval.reach = 6.0;
    EXPECT_TRUE(interval.sweeps(path));
    interval.reach = 5.9;
    EXPECT_FALSE(interval.sweeps(path));
}

// A shutter curve rising linearly from 1 to 3 over [0, 1], 4 subframes at 1/8, 3/8, 5/8, 7/8: its
// weights 1 + 2t there are 1.25, 1.75, 2.25, 2.75 against a mean of 2, and its slope over an interval
// of 1/4 relative to the weight is 2 x 0.25 / w. A box gives factors of exactly 1 and no tilt.
TEST(IntervalLayout, SubframeFactorsAndTiltsFollowALinearCurve) {
    const SubframeLayout curve = subframeLayout({.t0 = 0.0, .t1 = 1.0, .curve_begin = 1.0, .curve_end = 3.0}, 4);
    const std::vector<double> times{0.125, 0.375, 0.625, 0.875}, factors{0.625, 0.875, 1.125, 1.375};
    ASSERT_EQ(curve.times.size(), 4u);
    EXPECT_DOUBLE_EQ(curve.half, 0.125);
    for (std::size_t k = 0; k < 4; ++k) {
        EXPECT_DOUBLE_EQ(curve.times[k], times[k]);
        EXPECT_DOUBLE_EQ(curve.factors[k], factors[k]);
        EXPECT_DOUBLE_EQ(curve.tilts[k], 0.5 / (1.0 + 2.0 * times[k]));
    }
    const SubframeLayout box = subframeLayout({.t0 = 2.0, .t1 = 3.0}, 0);  // a still tile: one time, the middle
    ASSERT_EQ(box.times.size(), 1u);
    EXPECT_DOUBLE_EQ(box.times[0], 2.5);
    EXPECT_EQ(box.factors[0], 1.0);
    EXPECT_EQ(box.tilts[0], 0.0);
}

}  // namespace clipblur
