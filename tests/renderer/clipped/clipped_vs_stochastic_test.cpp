#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/job_loader.h"
#include "renderer/clipped/shutter_segments.h"
#include "renderer/render.h"
#include "scene/primitives.h"
#include "support/render_compare.h"

namespace clipblur {

namespace {

using testing::averaged;
using testing::meanSquaredDifference;

const std::vector<float>& channel(const RenderResult& r, const char* name) { return r.image.find(name)->values; }

double maxAbsDifference(const RenderResult& a, const RenderResult& b) {
    double worst = 0.0;
    for (const char* c : {"R", "G", "B"}) {
        const auto& x = channel(a, c);
        const auto& y = channel(b, c);
        for (std::size_t i = 0; i < x.size(); ++i) worst = std::max(worst, std::abs(double(x[i]) - y[i]));
    }
    return worst;
}

}  // namespace

// Against the converged stochastic reference, with a statistical test instead of a fixed tolerance.
// Two stochastic renders with independent seeds s1, s2 give per pixel E[(s1 - s2)^2] = 2 var, so
// V = mean (s1 - s2)^2 / 4 estimates the variance of their average s. If clipped rendering c is exact,
// E[mean (c - s)^2] = V, and any bias b adds b^2. The ratio R = mean (c - s)^2 / V is then 1 plus
// noise; with a few hundred edge pixels its standard error is ~0.1, so R < 1.5 allows ~5 standard
// errors of noise plus a bias of at most sqrt(0.5 V) (about 0.004 here), and no real visibility or
// propagation error (which shows as bias over whole edges) survives it. The frame-0-only ablation must
// fail the same test where the scene reveals geometry.
//
// Each scene keeps its own lights: re-clips shade every piece at their own time as the reference shades
// every sample (ReclipShading.FaceTurningUnderALightMatchesTheStochasticReference), where the paper's
// colours mixed between frames 0 and 1 made these tests run under ambient light alone. The default job's
// spinning box is held still here: with it spinning, clipped differs from the accumulation buffer by
// 0.0044 RMSE at box edges (an open problem, see docs/design.md "Known gaps").
class AgainstStochastic : public ::testing::TestWithParam<std::string> {};

TEST_P(AgainstStochastic, DifferenceIsExplainedBySamplingNoise) {
    const std::string path = std::string(CLIPBLUR_SOURCE_DIR) + "/configs/" + GetParam();
    const std::vector<std::string> common{"film.width=64", "film.height=36", "render.tile_size=16", "render.audit=true"};
    auto load = [&](std::vector<std::string> extra) {
        extra.insert(extra.end(), common.begin(), common.end());
        if (GetParam() == "default.yaml") extra.push_back("objects.2.transform=[]");
        return loadJob(path, extra);
    };
    // Enough subframes that the time quadrature error is far below the sampling noise (see below for auto).
    const RenderResult clipped = renderFrame(load({"render.method=clipped", "render.subframes=64"}), 0);
    const RenderResult automatic = renderFrame(load({"render.method=clipped"}), 0);
    const RenderResult s1 = renderFrame(load({"render.method=stochastic", "render.samples=400", "render.seed=1"}), 0);
    const RenderResult s2 = renderFrame(load({"render.method=stochastic", "render.samples=400", "render.seed=2"}), 0);
    const double variance = meanSquaredDifference(s1, s2) / 4.0;
    const double ratio = meanSquaredDifference(clipped, averaged(s1, s2)) / variance;
    RecordProperty("ratio", std::to_string(ratio));
    // At `auto` subframes (about a pixel of motion per subframe) the midpoint rule errs by at most 1/(2N)
    // in a pixel an edge crosses (ClippedRenderer.TranslatingQuadConvergesToExactTimeIntegratedCoverage),
    // so the RMSE is bias-dominated; measured 0.004-0.006 on these scenes when this test was written, and
    // held below 0.01 here as a regression bound (the noise of the 400-sample reference is ~0.002).
    const double rmse_auto = std::sqrt(meanSquaredDifference(automatic, averaged(s1, s2)));
    RecordProperty("rmse_auto", std::to_string(rmse_auto));
    const double max_auto = maxAbsDifference(automatic, averaged(s1, s2));
    RecordProperty("max_error_auto", std::to_string(max_auto));
    EXPECT_LT(rmse_auto, 0.01) << "subframes " << automatic.stats.clipped().subframes_max_per_tile;
    // Max error: the reference averages 800 samples, so its per-pixel standard deviation is at most
    // 0.5 / sqrt(800) = 0.018 (a 50/50 edge pixel); over ~7000 channel values the largest deviation is
    // ~4 of those. Measured 0.020-0.040 on these scenes. 0.1 (5.7 sigma) still fails for a missing or
    // misplaced surface, which is off by 0.2-0.8 in its pixels.
    EXPECT_LT(max_auto, 0.1);
    EXPECT_LT(ratio, 1.5) << "variance " << variance;
    // Sweep integration at auto: the same pixel rule for positions, fewer re-clips; held to the same
    // bounds as point subframes at auto.
    const RenderResult sweep = renderFrame(load({"render.method=clipped", "render.time_integration=sweep"}), 0);
    const double rmse_sweep = std::sqrt(meanSquaredDifference(sweep, averaged(s1, s2)));
    RecordProperty("rmse_sweep", std::to_string(rmse_sweep));
    EXPECT_LT(rmse_sweep, 0.01) << "re-clips " << sweep.stats.clipped().subframes_max_per_tile;
    // Nothing here moves farther than the film is wide (64 px): a capped tile is a re-clip rule gone wrong.
    EXPECT_EQ(sweep.stats.clipped().capped_tiles, 0) << "re-clips " << sweep.stats.clipped().subframes_max_per_tile;
    EXPECT_LT(maxAbsDifference(sweep, averaged(s1, s2)), 0.1);
}

INSTANTIATE_TEST_SUITE_P(Configs, AgainstStochastic,
                         ::testing::Values("default.yaml", "table1/spin.yaml", "table1/pan.yaml",
                                           "table1/spin_pan.yaml", "table1/recede.yaml",
                                           "table1/recede_spin_pan.yaml", "bench/propeller.yaml",
                                           "bench/crossing.yaml"),
                         [](const auto& info) {
                             std::string name = info.param.substr(info.param.find('/') + 1);
                             return name.substr(0, name.find('.'));
                         });

// The propeller's blades turn 90 degrees and cover the same cross at shutter open and close, so the wall
// behind them that shows mid-shutter is in neither end's fragment set. The paper's single segment misses
// it (the comparison above fails by far); auto shutter segments draw it: one per 60 degrees of an
// object's turn, keeping every layer where the turning propeller passes (turningObjectTiles).
TEST(ShutterSegments, SingleSegmentMissesWhatBothEndsHide) {
    const std::string path = std::string(CLIPBLUR_SOURCE_DIR) + "/configs/bench/propeller.yaml";
    const std::vector<std::string> common{"film.width=64", "film.height=36", "render.tile_size=16", "lights=[]",
                                          "ambient=1"};
    auto load = [&](std::vector<std::string> extra) {
        extra.insert(extra.end(), common.begin(), common.end());
        return loadJob(path, extra);
    };
    // Point subframes: under sweep the wall is a still backdrop, rendered whole on its own.
    const RenderResult one = renderFrame(load({"render.method=clipped", "render.time_integration=subframes", "render.segments=1"}), 0);
    const RenderResult automatic = renderFrame(load({"render.method=clipped", "render.time_integration=subframes"}), 0);
    const RenderResult reference = renderFrame(load({"render.method=accumulation", "render.samples=64"}), 0);
    const RenderJob job = load({});
    EXPECT_EQ(shutterSegments(FrameMotion(job.scene, 0.0, 1.0), 0, job.render.max_segments), 2);  // 90 degrees / 60
    EXPECT_EQ(automatic.stats.clipped().segments, 2);
    EXPECT_GT(automatic.stats.clipped().hidden_probe_hits, 0);
    EXPECT_GT(automatic.stats.clipped().open.deep_tiles, 0);
    const double rmse_one = std::sqrt(meanSquaredDifference(one, reference));
    const double rmse_auto = std::sqrt(meanSquaredDifference(automatic, reference));
    RecordProperty("rmse_one_segment", std::to_string(rmse_one));
    RecordProperty("rmse_auto_segments", std::to_string(rmse_auto));
    // Measured at 64x36 against 256 accumulated stills, before deep tiles: 1 segment 0.079, 3 segments
    // 0.0027, 6 segments 0.00053, 12 segments 0.00030 (near the hub a blade spans a wide angle and can
    // hide a point at both ends of a segment). A missing wall is a bias over whole blade-shaped regions.
    EXPECT_GT(rmse_one, 0.04);
    EXPECT_LT(rmse_auto, 0.002);  // 4x the measured value: room for the 64-still reference's own error
}

// Triangles much smaller than a pixel: Embree's rays miss many of them, and the candidate rules (one-ring
// of every hit, plus every triangle whose inscribed circle is narrower than the ray cell) must hand every
// visible one to the clipper. The exhaustive candidate set (visibility_rays = 0) is the oracle; results
// must agree to float rounding.
TEST(Candidates, DenseMeshMatchesExhaustiveCandidates) {
    std::string text = R"(version: 1
film: {width: 48, height: 32, background: 0.2}
camera:
  vfov: 30
  keys: [{time: 0, position: [0, 0, -6], view: [0, 0, 1], up: [0, 1, 0]}]
materials:
  - {name: a, color: [0.9, 0.4, 0.2]}
  - {name: b, color: [0.2, 0.6, 0.9], texture: {type: checker, color2: 0.1, scale: 0.5}}
lights: [{type: directional, direction: [0.3, -0.5, 1]}]
objects:
  - {name: dense, material: a, primitive: {type: sphere, size: 2.5, segments: 360}}
  - name: wall
    material: b
    primitive: {type: grid, size: [8, 8], divisions: [3, 3]}
    transform: [{time: 0, translate: [0, 0, 3], rotate: {axis: [1, 0, 0], angle_deg: -90}}]
)";
    // Walls stacked behind the first give the rays hidden triangles to cull, so they are traced
    // (raysPayOff: the sphere's sub-pixel triangles alone are candidates either way).
    for (int k = 1; k <= 5; ++k)
        text += "  - {name: wall" + std::to_string(k) + ", material: b, primitive: {type: grid, size: [8, 8], divisions: [3, 3]}, " +
                "transform: [{time: 0, translate: [0, 0, " + std::to_string(3 + k) +
                "], rotate: {axis: [1, 0, 0], angle_deg: -90}}]}\n";
    text += "render: {method: clipped, tile_size: 16, audit: true}\n";
    RenderJob rays = loadJobFromText(text, "dense.yaml", {"render.visibility_rays=2"});
    RenderJob all = loadJobFromText(text, "dense.yaml", {"render.visibility_rays=0"});
    ASSERT_GT(rays.scene.objects[0].mesh.triangles.size(), 60000u);
    const RenderResult a = renderFrame(rays, 0);
    const RenderResult b = renderFrame(all, 0);
    EXPECT_GT(a.stats.clipped().open.candidates.rays, 0);
    EXPECT_LT(a.stats.clipped().open.candidates.candidates, a.stats.clipped().open.candidates.binned);
    for (std::size_t c = 0; c < 4; ++c)
        for (std::size_t i = 0; i < a.image.channels[c].values.size(); ++i)
            ASSERT_NEAR(a.image.channels[c].values[i], b.image.channels[c].values[i], 1e-6) << c << " " << i;
}

}  // namespace clipblur
