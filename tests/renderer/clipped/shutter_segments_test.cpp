#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/quaternion.hpp>

#include "renderer/clipped/shutter_segments.h"
#include "renderer/render.h"
#include "renderer/test_scenes.h"

namespace clipblur {

namespace {

glm::dquat aboutY(double degrees) {
    return glm::angleAxis(degrees * std::numbers::pi / 180.0, glm::dvec3(0, 1, 0));
}

}  // namespace

TEST(ShutterSegments, StillSceneIsOneSegment) {
    RenderJob job = test::squareFilmJob();
    job.scene.objects.push_back(test::rasterQuad(2, 2, 20, 20, 5.0));
    EXPECT_NEAR(FrameMotion(job.scene, 0.0, 1.0).largestTurn(), 0.0, 1e-12);
    EXPECT_EQ(shutterSegments(FrameMotion(job.scene, 0.0, 1.0), 0, 16), 1);
    EXPECT_EQ(shutterSegments(FrameMotion(job.scene, 0.0, 1.0), 4, 16), 4);   // requested counts are kept
    EXPECT_EQ(shutterSegments(FrameMotion(job.scene, 0.0, 1.0), 40, 16), 16);  // up to the cap
}

// An object turning 90 degrees in two keys of 45 (slerp is a constant-rate turn): the summed angle is
// 90 degrees whatever the sampling, so auto gives ceil(90 / 15) = 6 segments; half the shutter 3.
TEST(ShutterSegments, ObjectTurnSetsTheCount) {
    RenderJob job = test::squareFilmJob();
    Object quad = test::rasterQuad(2, 2, 20, 20, 5.0);
    quad.transform = {TransformKey{0.0, glm::dvec3(0.0), aboutY(0), glm::dvec3(1.0)},
                      TransformKey{0.5, glm::dvec3(0.0), aboutY(45), glm::dvec3(1.0)},
                      TransformKey{1.0, glm::dvec3(0.0), aboutY(90), glm::dvec3(1.0)}};
    job.scene.objects.push_back(quad);
    EXPECT_NEAR(FrameMotion(job.scene, 0.0, 1.0).largestTurn(), std::numbers::pi / 2, 1e-9);
    EXPECT_EQ(shutterSegments(FrameMotion(job.scene, 0.0, 1.0), 0, 16), 6);
    EXPECT_EQ(shutterSegments(FrameMotion(job.scene, 0.0, 0.5), 0, 16), 3);
}

// A camera yawing 100 degrees: the basis turns by the angle between the view directions.
TEST(ShutterSegments, CameraTurnSetsTheCount) {
    RenderJob job = test::squareFilmJob();
    job.scene.objects.push_back(test::rasterQuad(2, 2, 20, 20, 5.0));
    const double a = 100.0 * std::numbers::pi / 180.0;
    job.scene.camera.keys.push_back(
        CameraKey{1.0, glm::dvec3(0.0), glm::dvec3(std::sin(a), 0, std::cos(a)), glm::dvec3(0, 1, 0)});
    EXPECT_NEAR(FrameMotion(job.scene, 0.0, 1.0).largestTurn(), a, 1e-9);
    EXPECT_EQ(shutterSegments(FrameMotion(job.scene, 0.0, 1.0), 0, 16), 7);
}

// Neighbouring segments meet at one time, so the set closing one opens the next: S segments build S + 1
// fragment sets, and a still last segment builds none of its own.
TEST(ShutterSegments, NeighboursShareTheirEndSet) {
    RenderJob job = test::squareFilmJob();
    job.render.method = Method::Clipped;
    Object quad = test::rasterQuad(2, 2, 20, 20, 5.0);
    quad.transform = {TransformKey{0.0, glm::dvec3(0.0), aboutY(0), glm::dvec3(1.0)},
                      TransformKey{0.5, glm::dvec3(0.0), aboutY(20), glm::dvec3(1.0)}};
    job.scene.objects.push_back(quad);
    job.render.segments = 2;  // the second half of the shutter is still
    EXPECT_EQ(renderFrame(job, 0).stats.clipped().frame_sets, 2);
    job.scene.objects[0].transform.push_back(TransformKey{1.0, glm::dvec3(0.0), aboutY(40), glm::dvec3(1.0)});
    job.render.segments = 3;
    EXPECT_EQ(renderFrame(job, 0).stats.clipped().frame_sets, 4);
}

// Equal segments meet at one double and share the shutter equally.
TEST(ShutterSegments, EqualSegmentsTileTheShutter) {
    const std::vector<ShutterSegment> s = equalSegments(2.25, 3.0, 3);
    ASSERT_EQ(s.size(), 3u);
    EXPECT_EQ(s.front().begin, 2.25);
    EXPECT_EQ(s.back().end, 3.0);
    for (std::size_t i = 0; i < s.size(); ++i) {
        EXPECT_EQ(s[i].weight, 1.0 / 3.0);
        if (i > 0) {
            EXPECT_EQ(s[i].begin, s[i - 1].end);
        }
    }
}

// A surface seen only during [0.30, 0.35] is hidden at both ends of a segment [a, b] exactly when a < 0.30
// and b > 0.35. Bisecting [0, 1] by hand: [0, 0.5] hides it, [0, 0.25] does not, [0.25, 0.5] does,
// [0.25, 0.375] does, its halves [0.25, 0.3125] and [0.3125, 0.375] do not, nor do [0.375, 0.5] and
// [0.5, 1]: five segments, each weighted by its length.
TEST(ShutterSegments, SplitWhereHiddenBisectsUntilNothingIsHidden) {
    const auto hidden = [](const ShutterSegment& s) { return s.begin < 0.30 && s.end > 0.35 ? TileSet() : TileSet::none(); };
    int unsplit = -1;
    const std::vector<ShutterSegment> s = splitWhereHidden(equalSegments(0.0, 1.0, 1), 16, hidden, unsplit);
    const std::vector<double> ends{0.25, 0.3125, 0.375, 0.5, 1.0};
    ASSERT_EQ(s.size(), ends.size());
    double begin = 0.0;
    for (std::size_t i = 0; i < s.size(); ++i) {
        EXPECT_EQ(s[i].begin, begin);
        EXPECT_EQ(s[i].end, ends[i]);
        EXPECT_EQ(s[i].weight, ends[i] - begin);  // powers of two: exact
        EXPECT_TRUE(hidden(s[i]).empty());
        EXPECT_TRUE(s[i].tiles.every());
        begin = ends[i];
    }
    EXPECT_EQ(unsplit, 0);
}

// At the cap a segment that still hides something is kept and counted: [0, 1] and [0, 0.5] split (3
// segments), [0.25, 0.5] would be the fourth.
TEST(ShutterSegments, SplitWhereHiddenStopsAtTheCap) {
    const auto hidden = [](const ShutterSegment& s) { return s.begin < 0.30 && s.end > 0.35 ? TileSet() : TileSet::none(); };
    int unsplit = -1;
    const std::vector<ShutterSegment> s = splitWhereHidden(equalSegments(0.0, 1.0, 1), 3, hidden, unsplit);
    ASSERT_EQ(s.size(), 3u);
    EXPECT_EQ(s[1].begin, 0.25);
    EXPECT_EQ(s[1].end, 0.5);
    EXPECT_EQ(unsplit, 1);
    // Rotation segments already at the cap are checked but never split.
    const std::vector<ShutterSegment> full = splitWhereHidden(equalSegments(0.0, 1.0, 2), 2, hidden, unsplit);
    EXPECT_EQ(full.size(), 2u);
    EXPECT_EQ(unsplit, 1);
}

// A hole in one tile of a 4x2 grid: the split segment keeps the other tiles over its whole span, and
// that tile alone gets the halves, checked again over it alone. Every tile is then covered by segments
// whose spans partition the shutter, with weights that sum to 1.
TEST(ShutterSegments, SplitWhereHiddenSplitsOnlyTheTilesThatHide) {
    const TileGrid grid(64, 32, 16);
    const int hole = 5;
    std::vector<int> asked_tiles;
    const auto hidden = [&](const ShutterSegment& s) {
        asked_tiles.push_back(s.tiles.size(grid));
        TileSet where = TileSet::none();
        if (s.begin < 0.30 && s.end > 0.35 && s.tiles.contains(hole)) where.addOverlapping(grid, grid.tile(hole));
        return where;
    };
    int unsplit = -1;
    const std::vector<ShutterSegment> s = splitWhereHidden(equalSegments(0.0, 1.0, 1), 16, hidden, unsplit);
    EXPECT_EQ(unsplit, 0);
    ASSERT_EQ(s.size(), 6u);  // [0, 1] without the hole's tile, and the five of the whole-film test there
    EXPECT_EQ(s[0].begin, 0.0);
    EXPECT_EQ(s[0].end, 1.0);
    EXPECT_EQ(s[0].tiles.size(grid), 7);
    EXPECT_FALSE(s[0].tiles.contains(hole));
    EXPECT_EQ(asked_tiles.front(), 8);
    for (std::size_t i = 1; i < asked_tiles.size(); ++i) EXPECT_EQ(asked_tiles[i], 1);
    for (int tile = 0; tile < grid.count(); ++tile) {
        double weight = 0.0, end = 0.0;
        for (const ShutterSegment& segment : s) {
            if (!segment.tiles.contains(tile)) continue;
            EXPECT_EQ(segment.begin, end) << tile;  // in time order, no gap, no overlap
            end = segment.end;
            weight += segment.weight;
        }
        EXPECT_EQ(end, 1.0) << tile;
        EXPECT_EQ(weight, 1.0) << tile;  // powers of two: exact
    }
}

}  // namespace clipblur
