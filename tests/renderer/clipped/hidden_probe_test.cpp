#include "renderer/clipped/hidden_probe.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "renderer/render.h"
#include "renderer/test_scenes.h"
#include "support/test_frame.h"

namespace clipblur {

namespace {

using test::movingQuad;
using test::rasterQuad;

// A white wall over the whole 32x32 film at depth 10 and two white quads over rows [8, 24): A at depth 5
// moves from columns [4, 12) to [20, 28), B at depth 6 from [20, 28) to [4, 12). Each ends where the other
// started, so the wall behind [4, 12) and [20, 28) is hidden at shutter open (by A, then B) and at close
// (by B, then A), and shows in the middle of the shutter, when both quads are over [12, 20). Point
// subframes: under sweep the wall is a still backdrop, rendered on its own, and nothing is hidden.
RenderJob crossingJob() {
    RenderJob job = test::squareFilmJob();
    job.render.method = Method::Clipped;
    job.render.time_integration = TimeIntegration::Subframes;
    job.scene.objects.push_back(rasterQuad(-8.0, -8.0, 40.0, 40.0, 10.0));
    job.scene.objects.push_back(movingQuad(4.0, 8.0, 12.0, 24.0, 5.0, {16.0, 0.0}));
    job.scene.objects.push_back(movingQuad(20.0, 8.0, 28.0, 24.0, 6.0, {-16.0, 0.0}));
    return job;
}

// A fixed reach for hiddenTiles.
std::function<int()> within(int pixels) {
    return [pixels] { return pixels; };
}

// The segment [a, b].
ShutterSegment segment(double a, double b) { return {a, b, b - a, 1.0, 1.0}; }

// Hidden points the three probes of [a, b] find over the whole film, each run on its own.
long long threeProbeHits(const Scene& scene, double a, double b) {
    const test::TestFrame frame(scene, a, b);
    long long hits = 0;
    for (const auto& [at, offset] : {std::pair{0.5, 0}, {0.25, 1}, {0.75, 2}})
        hits += probeHiddenAtBothEnds(frame.setup(), a, b, a + (b - a) * at, offset).hidden;
    return hits;
}

}  // namespace

// At t = 0.5 the wall shows over columns [4, 12) and [20, 28) of rows [8, 24), hidden at both ends. The
// probe's points in a 2x2 cell are at +0.5 (offset 0) or +1.5 (offset 1) in both axes: 4 columns and 8
// rows of each region, 64 points, of the 16 x 16 that all hit the wall or a quad.
TEST(HiddenProbe, CountsTheWallTwoCrossingQuadsHideAtBothEnds) {
    const RenderJob job = crossingJob();
    const test::TestFrame frame(job.scene, 0.0, 1.0);
    for (int offset : {0, 1}) {
        const HiddenProbe probe = probeHiddenAtBothEnds(frame.setup(), 0.0, 1.0, 0.5, offset);
        EXPECT_EQ(probe.samples, 256) << "offset " << offset;
        EXPECT_EQ(probe.hidden, 64) << "offset " << offset;
    }
    // All three probe times run, each counted; at 0.25 and 0.75 the wall shows too (at 0.25 over [4, 8),
    // which A hides at open and B at close), so the total is the three probes' sum.
    HiddenProbe total;
    EXPECT_FALSE(hiddenTiles(frame.setup(), segment(0.0, 1.0), within(0), total).empty());
    long long expected = 0;
    for (const auto& [at, offset] : {std::pair{0.5, 0}, {0.25, 1}, {0.75, 2}})
        expected += probeHiddenAtBothEnds(frame.setup(), 0.0, 1.0, at, offset).hidden;
    EXPECT_EQ(total.hidden, expected);
    EXPECT_GT(expected, 64);
    // Split at the middle, each half has the hole at one of its ends: at 0.5 nothing hidden at 0 is hidden
    // (the quads are both over [12, 20)), so nothing is hidden at both ends of [0, 0.5] or [0.5, 1].
    total = {};
    EXPECT_TRUE(hiddenTiles(frame.setup(), segment(0.0, 0.5), within(0), total).empty());
    EXPECT_TRUE(hiddenTiles(frame.setup(), segment(0.5, 1.0), within(0), total).empty());
    EXPECT_EQ(total.samples, 6 * 256);
    EXPECT_EQ(total.hidden, 0);
}

// The crossing quads of the test above on a 64x64 film of 8x8 tiles, in its top-left quarter: the deep
// tiles are those within reach (plus a probe cell) of a hidden point, and none of the tiles far from the
// hole.
TEST(HiddenProbe, HiddenTilesAreWhereTheHoleIs) {
    RenderJob job = test::squareFilmJob(64);
    job.scene.objects.push_back(rasterQuad(-8.0, -8.0, 72.0, 72.0, 10.0, 64));
    job.scene.objects.push_back(test::movingQuad(4.0, 8.0, 12.0, 24.0, 5.0, {16.0, 0.0}, 64));
    job.scene.objects.push_back(test::movingQuad(20.0, 8.0, 28.0, 24.0, 6.0, {-16.0, 0.0}, 64));
    const test::TestFrame frame(job.scene, 0.0, 1.0, 8);
    const TileGrid& grid = frame.setup().grid;
    ASSERT_EQ(grid.columns(), 8);
    HiddenProbe total;
    for (const int reach : {0, 5}) {
        const TileSet where = hiddenTiles(frame.setup(), segment(0.0, 1.0), within(reach), total);
        // The wall shows in columns [4, 12) and [20, 28) of rows [8, 24) at 0.5: tile columns 0-3, rows 1-2.
        for (int ty = 1; ty <= 2; ++ty)
            for (int tx : {0, 1, 2, 3}) EXPECT_TRUE(where.contains(ty * 8 + tx)) << tx << "," << ty << " reach " << reach;
        // Every hidden point lies in [4, 28) x [8, 24): nothing past reach + 2 (a probe cell) from there.
        const PixelBounds near = PixelBounds::corners(4 - reach - 2, 8 - reach - 2, 28 + reach + 3, 24 + reach + 3);
        for (int i = 0; i < grid.count(); ++i)
            if (!grid.tile(i).overlaps(near)) {
                EXPECT_FALSE(where.contains(i)) << i << " reach " << reach;
            }
        EXPECT_LT(where.size(grid), grid.count() / 2);
    }
}

// One convex quad translating in the image plane cannot hide a point at both ends that it uncovers in
// between: a point under both its start and end footprints is under its middle one (the footprint at
// (1 - s) a + s b contains the matching blend of two points of the shape). Seeded random quads, sizes and
// moves over the wall: the probe must report nothing, whatever the depth tolerance meets at the edges.
TEST(HiddenProbe, OneTranslatingQuadHidesNothingAtBothEnds) {
    std::mt19937 rng(20261123);
    std::uniform_real_distribution<double> corner(0.0, 24.0), size(2.0, 12.0), move(-20.0, 20.0), depth(3.0, 8.0);
    for (int trial = 0; trial < 20; ++trial) {
        RenderJob job = test::squareFilmJob();
        job.scene.objects.push_back(rasterQuad(-8.0, -8.0, 40.0, 40.0, 10.0));
        const double x0 = corner(rng), y0 = corner(rng);
        job.scene.objects.push_back(movingQuad(x0, y0, x0 + size(rng), y0 + size(rng), depth(rng), {move(rng), move(rng)}));
        const test::TestFrame frame(job.scene, 0.0, 1.0);
        HiddenProbe total;
        int asked = 0;  // the reach scans the scene: it is measured only for a hidden point
        const auto reach = [&] {
            ++asked;
            return 4;
        };
        EXPECT_TRUE(hiddenTiles(frame.setup(), segment(0.0, 1.0), reach, total).empty()) << trial;
        EXPECT_EQ(asked, 0) << trial;
        EXPECT_EQ(total.samples, 3 * 256) << trial;
    }
}

TEST(HiddenProbe, VisibilityChangesOnlyWhenTheEyeOrAnObjectMoves) {
    RenderJob job = test::squareFilmJob();
    job.scene.objects.push_back(rasterQuad(4.0, 4.0, 20.0, 20.0, 5.0));
    EXPECT_FALSE(visibilityCanChange(FrameMotion(job.scene, 0.0, 1.0).shutter()));
    // Turning on the spot: the same surfaces from the same point.
    job.scene.camera.keys.push_back(CameraKey{1.0, glm::dvec3(0.0), glm::dvec3(0.1, 0, 1), glm::dvec3(0.1, 1, 0)});
    EXPECT_FALSE(visibilityCanChange(FrameMotion(job.scene, 0.0, 1.0).shutter()));
    // An eye that leaves and comes back within the shutter.
    job.scene.camera.keys.back().time = 0.5;
    job.scene.camera.keys.back().position = glm::dvec3(0.0, 0.0, 1.0);
    job.scene.camera.keys.push_back(CameraKey{1.0, glm::dvec3(0.0), glm::dvec3(0, 0, 1), glm::dvec3(0, 1, 0)});
    EXPECT_TRUE(visibilityCanChange(FrameMotion(job.scene, 0.0, 1.0).shutter()));
    EXPECT_FALSE(visibilityCanChange(FrameMotion(job.scene, 1.0, 2.0).shutter()));  // held after its last key
    job.scene.camera.keys.resize(1);
    job.scene.objects.push_back(movingQuad(4.0, 4.0, 8.0, 8.0, 4.0, {3.0, 0.0}));
    EXPECT_TRUE(visibilityCanChange(FrameMotion(job.scene, 0.0, 1.0).shutter()));
}

// Every surface is white over a white wall that fills the film, so the exact motion-blurred image is 1
// in every pixel. The paper's single segment has no wall over [4, 12) and [20, 28): there a pixel at
// column x shows the black background for as long as neither quad covers it, (23 - 2x) / 16 of the
// shutter at the pixel's centre for x in 4..11 (A leaves x at (x - 4) / 16, B arrives at (20 - x) / 16;
// linear in x, so the pixel's mean) and mirrored over [20, 28). Over 16 rows and both regions the mean
// squared error is 2 x 16 x (1 + 9 + ... + 225) / 256 / 1024 = 0.0830, RMSE 0.288. Auto keeps the one
// segment and every layer of the tiles near the hole (the probe test above), and draws the wall.
TEST(HiddenProbe, DeepTilesDrawTheWallBothEndsHide) {
    RenderJob job = crossingJob();
    job.render.segments = 1;
    const RenderResult one = renderFrame(job, 0);
    job.render.segments = 0;
    const RenderResult automatic = renderFrame(job, 0);
    const ClippedStats& stats = automatic.stats.clipped();
    EXPECT_EQ(stats.segments, 1);
    EXPECT_EQ(stats.hidden_probe_hits, threeProbeHits(job.scene, 0.0, 1.0));
    EXPECT_GT(stats.open.deep_tiles, 0);
    EXPECT_EQ(stats.open.deep_tiles, stats.close.deep_tiles);
    EXPECT_EQ(one.stats.clipped().open.deep_tiles, 0);  // a fixed count probes nothing
    const auto error = [](const RenderResult& r) {
        double squared = 0.0, worst = 0.0;
        for (const char* name : {"R", "G", "B"}) {
            for (float v : r.image.find(name)->values) {
                squared += (v - 1.0) * (v - 1.0);
                worst = std::max(worst, std::abs(v - 1.0));
            }
        }
        return std::pair{std::sqrt(squared / (3.0 * 32 * 32)), worst};
    };
    const auto [rmse_one, worst_one] = error(one);
    RecordProperty("rmse_one_segment", std::to_string(rmse_one));
    // The single segment's subframes sample each pixel's hole time at points: 5% covers that.
    EXPECT_NEAR(rmse_one, 0.288, 0.015);
    EXPECT_GT(worst_one, 0.85);  // 15/16 at columns 4 and 27
    // Each covered pixel's areas sum to one up to float rounding of the coverage sums.
    EXPECT_LT(error(automatic).second, 1e-5);
    // max_segments no longer matters: no segment is left hiding the wall.
    job.render.max_segments = 1;
    const RenderResult capped = renderFrame(job, 0);
    EXPECT_TRUE(capped.stats.warnings.empty());
    EXPECT_EQ(capped.image.find("R")->values, automatic.image.find("R")->values);
}

// The same crossing a centred shutter sees: every key half a frame earlier and the shutter -0.5 .. 0.5.
// The probes run at negative times and find the same hole; the deep tiles draw the wall.
TEST(HiddenProbe, CentredShutterFindsTheSameHole) {
    RenderJob job = crossingJob();
    for (Object& o : job.scene.objects)
        for (TransformKey& k : o.transform) k.time -= 0.5;
    job.shutter = {-0.5, 0.5, {}};
    const RenderResult r = renderFrame(job, 0);
    EXPECT_EQ(r.stats.clipped().segments, 1);
    EXPECT_EQ(r.stats.clipped().hidden_probe_hits, threeProbeHits(job.scene, -0.5, 0.5));
    EXPECT_EQ(r.stats.clipped().hidden_probe_hits, threeProbeHits(crossingJob().scene, 0.0, 1.0));
    double worst = 0.0;
    for (float v : r.image.find("R")->values) worst = std::max(worst, std::abs(v - 1.0));
    EXPECT_LT(worst, 1e-5);  // as DeepTilesDrawTheWallBothEndsHide: coverage sums to 1 to float rounding
}

// The crossing quads in the top-left corner of a 256x256 film of 8x8 tiles, over a wall that drifts 1 px
// (so sweep keeps it in the fragment sets rather than as a still backdrop). With point subframes every
// surface is white, so the exact image is 1 (as in DeepTilesDrawTheWallBothEndsHide), where the render
// without the probe has the hole. The deep tiles are only those near the hole (under an eighth of the
// film's), and a tile far from them re-clips what it did without them: its pixels are bit-identical to
// that render's. A shard whose window holds part of the hole has the whole film's pixels, under point
// subframes and under sweep (whose tiles spill over their edges).
TEST(HiddenProbe, DeepTilesAreLocalAndTheRestRendersAsWithout) {
    constexpr int kSize = 256;
    RenderJob job = test::squareFilmJob(kSize);
    job.render.method = Method::Clipped;
    job.render.tile_size = 8;
    job.scene.objects.push_back(test::movingQuad(-8.0, -8.0, 264.0, 264.0, 10.0, {1.0, 0.0}, kSize));
    job.scene.objects.push_back(test::movingQuad(4.0, 8.0, 12.0, 24.0, 5.0, {16.0, 0.0}, kSize));
    job.scene.objects.push_back(test::movingQuad(20.0, 8.0, 28.0, 24.0, 6.0, {-16.0, 0.0}, kSize));
    Material checker;
    checker.texture = {Texture::Kind::Checker, glm::dvec3(0.3), 0.7};
    for (const TimeIntegration integration : {TimeIntegration::Subframes, TimeIntegration::Sweep}) {
        const bool sweep = integration == TimeIntegration::Sweep;
        SCOPED_TRACE(sweep ? "sweep" : "subframes");
        RenderJob j = job;
        j.render.time_integration = integration;
        if (sweep) {
            j.render.subframes = 3;  // re-clips: their footprints reach past tiles
            j.scene.materials.push_back(checker);
            j.scene.objects[0].material = 1;
        }
        j.render.segments = 0;
        const RenderResult deep = renderFrame(j, 0);
        const ClippedStats& stats = deep.stats.clipped();
        EXPECT_EQ(stats.segments, 1);
        EXPECT_GT(stats.open.deep_tiles, 0);
        EXPECT_LT(stats.open.deep_tiles, 1024 / 8);
        if (!sweep) {
            j.render.segments = 1;  // as many segments, no probe, no deep tiles
            const RenderResult without = renderFrame(j, 0);
            double worst_deep = 0.0, worst_without = 0.0;
            for (int y = 0; y < kSize; ++y) {
                for (int x = 0; x < kSize; ++x) {
                    const std::size_t i = static_cast<std::size_t>(y * kSize + x);
                    const float got = deep.image.find("R")->values[i], other = without.image.find("R")->values[i];
                    if (x >= 64 || y >= 64) {
                        EXPECT_EQ(got, other) << x << "," << y;
                    }
                    worst_deep = std::max(worst_deep, std::abs(got - 1.0));
                    worst_without = std::max(worst_without, std::abs(other - 1.0));
                }
            }
            EXPECT_LT(worst_deep, 1e-5);
            EXPECT_GT(worst_without, 0.5);  // the hole the deep tiles draw
            j.render.segments = 0;
        }
        j.render.window = PixelBounds::corners(2, 10, 90, 70);
        const RenderResult shard = renderFrame(j, 0);
        int different = 0;
        for (int y = 10; y < 70; ++y)
            for (int x = 2; x < 90; ++x)
                different += deep.image.find("R")->values[deep.image.index(x, y)] ==
                                     shard.image.find("R")->values[shard.image.index(x, y)]
                                 ? 0
                                 : 1;
        EXPECT_EQ(different, 0);
    }
}

// The probe's counts are integers summed in row order, so the deep tiles and the image do not depend on
// the thread count.
TEST(HiddenProbe, SameDeepTilesForOneAndTwoThreads) {
    const RenderJob job = crossingJob();
    std::vector<RenderResult> results;
    for (int threads : {1, 2}) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        results.push_back(renderFrame(job, 0));
    }
    const ClippedStats& one = results[0].stats.clipped();
    const ClippedStats& two = results[1].stats.clipped();
    EXPECT_EQ(one.open.deep_tiles, two.open.deep_tiles);
    EXPECT_EQ(one.hidden_probe_samples, two.hidden_probe_samples);
    EXPECT_EQ(one.hidden_probe_hits, two.hidden_probe_hits);
    for (std::size_t c = 0; c < results[0].image.channels.size(); ++c)
        EXPECT_EQ(results[0].image.channels[c].values, results[1].image.channels[c].values) << c;
}

// A 16 px square centred on the optical axis (raster [24, 40)^2 of a 64 px film, 8 px tiles) turning
// about the view direction: over 90 degrees its corners sweep the disc of radius 8 sqrt(2) = 11.3 px
// about (32, 32), reached on the axes at 45 degrees (a sampled time, 4 of 8), so its box is
// [20.7, 43.3]^2: tile columns and rows 2 to 5, and with a reach of 5 px [15.7, 48.3]^2, 1 to 6. Turned
// 10 degrees (under 15) it marks nothing; crossing the camera plane, every tile.
TEST(HiddenProbe, TurningObjectTilesAreItsSweptFootprint) {
    RenderJob job = test::squareFilmJob(64);
    Object quad = rasterQuad(24.0, 24.0, 40.0, 40.0, 10.0, 64);
    const auto turned = [&](double degrees) -> const Scene& {  // the frame keeps a reference to it
        const glm::dquat q = glm::angleAxis(glm::radians(degrees), glm::dvec3(0, 0, 1));
        quad.transform = {TransformKey{0.0, glm::dvec3(0.0), glm::dquat(1, 0, 0, 0), glm::dvec3(1.0)},
                          TransformKey{1.0, glm::dvec3(0.0), q, glm::dvec3(1.0)}};
        job.scene.objects = {quad};
        return job.scene;
    };
    const auto expectSquare = [](const TileSet& where, const TileGrid& grid, int first, int last) {
        for (int i = 0; i < grid.count(); ++i) {
            const int tx = i % grid.columns(), ty = i / grid.columns();
            EXPECT_EQ(where.contains(i), tx >= first && tx <= last && ty >= first && ty <= last) << tx << "," << ty;
        }
    };
    {
        const test::TestFrame frame(turned(90.0), 0.0, 1.0, 8);
        ASSERT_EQ(frame.setup().grid.columns(), 8);
        expectSquare(turningObjectTiles(frame.setup(), segment(0.0, 1.0), within(0)), frame.setup().grid, 2, 5);
        expectSquare(turningObjectTiles(frame.setup(), segment(0.0, 1.0), within(5)), frame.setup().grid, 1, 6);
    }
    {
        const test::TestFrame frame(turned(10.0), 0.0, 1.0, 8);
        int asked = 0;  // the band scans the scene: not measured where nothing turns far
        EXPECT_TRUE(turningObjectTiles(frame.setup(), segment(0.0, 1.0), [&] { return ++asked; }).empty());
        EXPECT_EQ(asked, 0);
    }
    {
        quad.mesh.positions[0].z = -1.0;  // behind the eye
        const test::TestFrame frame(turned(90.0), 0.0, 1.0, 8);
        EXPECT_TRUE(turningObjectTiles(frame.setup(), segment(0.0, 1.0), within(0)).every());
    }
}

}  // namespace clipblur
