#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "renderer/propagation/subframes.h"
#include "renderer/render.h"
#include "renderer/test_scenes.h"

namespace clipblur {

namespace {

using test::movingQuad;
using test::rasterQuad;
using test::squareFilmJob;

// A clipped job on 8 px tiles, so a 32 px film has still and moving tiles.
RenderJob clippedJob(std::initializer_list<Object> objects, TimeIntegration integration) {
    RenderJob job = squareFilmJob();
    job.render.method = Method::Clipped;
    job.render.tile_size = 8;
    job.render.time_integration = integration;
    for (const Object& o : objects) job.scene.objects.push_back(o);
    return job;
}

bool sameBits(const RenderResult& a, const RenderResult& b) {
    if (a.image.channels.size() != b.image.channels.size()) return false;
    for (std::size_t c = 0; c < a.image.channels.size(); ++c)
        if (a.image.channels[c].values != b.image.channels[c].values) return false;
    return true;
}

struct Choice {
    long long points, sweep;
};
Choice choiceOf(const RenderResult& r) {
    return {r.stats.clipped().segments_points, r.stats.clipped().segments_sweep};
}

// The three motions below, each over the black background (nothing still, so no backdrop), with the
// answer read off the counts of the two plans rather than from the cost model's constants:
// (floored: the kink floor of a motion of d px, kinkSamples, computed here at kKinkMotion 64):
//   slow: a quad moving half a pixel: 6 point subframes (sqrt(64 x 0.5) = 5.7) and one sweep re-clip
//         with as many positions (the same floor), which costs less than 6 point re-clips, so sweep;
//   pan:  a quad moving 24 px alone: 40 point subframes on its tiles (sqrt(64 x 24) = 39.2), one sweep
//         re-clip (translation leaves no path bend and there is no relative motion), so sweep;
//   crossing: two quads passing each other 12 px each way: 28 point subframes (sqrt(64 x 12) = 27.7),
//         but 24 sweep re-clips (their relative motion, one a pixel) on every moving tile, so points.
int floored(double d) { return static_cast<int>(std::ceil(std::max(d, std::sqrt(kKinkMotion * d)))); }
Object slowQuad() { return movingQuad(8, 8, 20, 20, 4.0, {0.5, 0.0}); }
Object panQuad() { return movingQuad(2, 8, 12, 20, 4.0, {24.0, 0.0}); }
Object leftQuad() { return movingQuad(2, 6, 12, 16, 4.0, {12.0, 0.0}); }
Object rightQuad() { return movingQuad(20, 14, 30, 24, 5.0, {-12.0, 0.0}); }

struct AutoCase {
    const char* name;
    std::vector<Object> objects;
    TimeIntegration expected;
    int point_subframes, sweep_reclips;  // the counts above, per most moving tile
};

std::vector<AutoCase> cases() {
    return {{"slow", {slowQuad()}, TimeIntegration::Sweep, floored(0.5), 1},
            {"pan", {panQuad()}, TimeIntegration::Sweep, floored(24.0), 1},
            {"crossing", {leftQuad(), rightQuad()}, TimeIntegration::Subframes, floored(12.0), 24}};
}

// The premise of each case: the explicit methods' plans have the counts the case is built on.
TEST(AutoIntegration, CasesHaveTheirCounts) {
    for (const AutoCase& c : cases()) {
        SCOPED_TRACE(c.name);
        RenderJob job = clippedJob({}, TimeIntegration::Subframes);
        job.scene.objects = c.objects;
        EXPECT_EQ(renderFrame(job, 0).stats.clipped().subframes_max_per_tile, c.point_subframes);
        job.render.time_integration = TimeIntegration::Sweep;
        EXPECT_EQ(renderFrame(job, 0).stats.clipped().subframes_max_per_tile, c.sweep_reclips);
    }
}

TEST(AutoIntegration, PicksTheMethodTheCountsSayIsCheaperAndRendersItsBits) {
    for (const AutoCase& c : cases()) {
        SCOPED_TRACE(c.name);
        RenderJob job = clippedJob({}, TimeIntegration::Auto);
        job.scene.objects = c.objects;
        const RenderResult automatic = renderFrame(job, 0);
        job.render.time_integration = c.expected;
        const RenderResult chosen = renderFrame(job, 0);
        const Choice choice = choiceOf(automatic);
        if (c.expected == TimeIntegration::Sweep) {
            EXPECT_EQ(choice.sweep, 1);
            EXPECT_EQ(choice.points, 0);
        } else {
            EXPECT_EQ(choice.points, 1);
            EXPECT_EQ(choice.sweep, 0);
        }
        EXPECT_GT(automatic.stats.clipped().auto_cost_points, 0.0);
        EXPECT_GT(automatic.stats.clipped().auto_cost_sweep, 0.0);
        EXPECT_TRUE(sameBits(automatic, chosen));
    }
}

TEST(AutoIntegration, ExplicitChoicesCountTheirSegments) {
    RenderJob job = clippedJob({panQuad()}, TimeIntegration::Subframes);
    Choice c = choiceOf(renderFrame(job, 0));
    EXPECT_EQ(c.points, 1);
    EXPECT_EQ(c.sweep, 0);
    job.render.time_integration = TimeIntegration::Sweep;
    c = choiceOf(renderFrame(job, 0));
    EXPECT_EQ(c.points, 0);
    EXPECT_EQ(c.sweep, 1);
}

// A fixed subframe count is point subframes' count: auto renders the paper's method at it.
TEST(AutoIntegration, FixedSubframesMeanPointSubframes) {
    RenderJob job = clippedJob({panQuad()}, TimeIntegration::Auto);
    job.render.subframes = 5;
    const RenderResult automatic = renderFrame(job, 0);
    job.render.time_integration = TimeIntegration::Subframes;
    const RenderResult points = renderFrame(job, 0);
    EXPECT_EQ(choiceOf(automatic).points, 1);
    EXPECT_EQ(choiceOf(automatic).sweep, 0);
    EXPECT_TRUE(sameBits(automatic, points));
}

// A still quad behind two crossing ones under a still camera: a backdrop behind everything, left out of
// the fragment sets, which only sweep composites; auto sweeps though the crossing alone picks points.
TEST(AutoIntegration, BackdropBehindEverythingSweeps) {
    RenderJob job = clippedJob({rasterQuad(0, 0, 32, 32, 10.0), leftQuad(), rightQuad()}, TimeIntegration::Auto);
    const RenderResult automatic = renderFrame(job, 0);
    job.render.time_integration = TimeIntegration::Sweep;
    const RenderResult sweep = renderFrame(job, 0);
    EXPECT_TRUE(automatic.stats.clipped().backdrop_behind_everything);
    EXPECT_EQ(choiceOf(automatic).sweep, 1);
    EXPECT_EQ(choiceOf(automatic).points, 0);
    EXPECT_TRUE(sameBits(automatic, sweep));
}

TEST(AutoIntegration, SameBitsForOneAndTwoThreads) {
    for (const AutoCase& c : cases()) {
        SCOPED_TRACE(c.name);
        RenderJob job = clippedJob({}, TimeIntegration::Auto);
        job.scene.objects = c.objects;
        RenderResult one, two;
        {
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
            one = renderFrame(job, 0);
        }
        {
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
            two = renderFrame(job, 0);
        }
        EXPECT_TRUE(sameBits(one, two));
        EXPECT_EQ(choiceOf(one).sweep, choiceOf(two).sweep);
    }
}

// render.error_target under auto tunes the spacing both methods are placed by.
TEST(AutoIntegration, ErrorTargetPicksASpacing) {
    RenderJob job = clippedJob({panQuad()}, TimeIntegration::Auto);
    job.render.error_target = 1e-3;
    const RenderResult r = renderFrame(job, 0);
    ASSERT_TRUE(r.stats.clipped().target.has_value());
    EXPECT_GT(r.stats.clipped().target->sweep_spacing, 0.0);
    EXPECT_EQ(r.stats.clipped().target->subframes, 0);
}

}  // namespace

}  // namespace clipblur
