#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "io/job_loader.h"
#include "renderer/clipped/error_target.h"
#include "renderer/clipped/time_error.h"
#include "renderer/propagation/subframes.h"
#include "renderer/render.h"
#include "renderer/test_scenes.h"
#include "support/translating_coverage.h"

namespace clipblur {

namespace {

using test::movingQuad;
using test::squareFilmJob;

// A white quad under ambient 1 translating by v over the black film: every pixel's R, G and B are its
// time-averaged coverage, known exactly (translatingPixelCoverage, an oracle sharing no code with the
// renderer). Returns the render's RMS error over R, G, B against that, and its own estimate.
struct Measured {
    double true_error = 0.0, estimated = 0.0;
};

constexpr double kX0 = 4.3, kY0 = 6.2, kX1 = 14.7, kY1 = 19.9;
const glm::dvec2 kVelocity(11.4, 3.7);

Measured measure(RenderJob job) {
    job.render.method = Method::Clipped;
    job.scene.objects.push_back(movingQuad(kX0, kY0, kX1, kY1, 6.0, kVelocity));
    const RenderResult r = renderFrame(job, 0);
    const std::vector<glm::dvec2> quad{{kX0, kY0}, {kX1, kY0}, {kX1, kY1}, {kX0, kY1}};
    double sum = 0.0;
    for (const char* c : {"R", "G", "B"}) {
        const std::vector<float>& values = r.image.find(c)->values;
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x)
                sum += std::pow(values[static_cast<std::size_t>(y * 32 + x)] -
                                    testing::translatingPixelCoverage(quad, kVelocity, x, y),
                                2);
    }
    return {std::sqrt(sum / (3.0 * 32 * 32)), r.stats.clipped().estimated_error};
}

// Richardson over the nested 3h rule with the order fixed at 2 (time_error.h) against the exact answer,
// over spacings from 2 px down to 0.06 px. One translating quad is the hardest case for a single scalar
// estimate: all its edges move alike, so the kink errors (D h^2 g(u), g in [0, 1/8] by phase) of all its
// pixels fall in or out of phase together; at 12 positions (0.95 px along x) they nearly cancel. Per
// spacing the estimate must be within 4x either way (measured 0.57 .. 3.4); over the spacings its
// geometric mean ratio within 1.5x (measured 1.26): no bias beyond what phase luck spreads.
void expectTracksExactError(const std::vector<int>& samples, bool sweep) {
    double log_sum = 0.0;
    for (const int n : samples) {
        RenderJob job = squareFilmJob();
        job.render.max_subframes = 256;
        if (sweep) {
            job.render.time_integration = TimeIntegration::Sweep;
            job.render.subframes = 1;
            job.render.sweep_spacing = glm::length(kVelocity) / n * (1.0 + 1e-9);  // exactly n positions
        } else {
            job.render.subframes = n;
        }
        const Measured m = measure(job);
        ASSERT_GT(m.true_error, 0.0) << n;
        const double ratio = m.estimated / m.true_error;
        EXPECT_GT(ratio, 0.25) << n << (sweep ? " positions" : " subframes");
        EXPECT_LT(ratio, 4.0) << n << (sweep ? " positions" : " subframes");
        log_sum += std::log(ratio);
    }
    const double mean = std::exp(log_sum / static_cast<double>(samples.size()));
    EXPECT_GT(mean, 1.0 / 1.5);
    EXPECT_LT(mean, 1.5);
}

// A white quad coming toward the camera (depth 7 -> 4) while sliding, and its reference: 2048 point
// subframes (midpoint error about 1e-6 here).
struct ApproachingQuad {
    RenderJob job;
    RenderResult reference;

    ApproachingQuad() : job(squareFilmJob()) {
        job.render.method = Method::Clipped;
        job.render.max_subframes = 2048;
        Object quad = test::rasterQuad(9.3, 8.2, 19.7, 21.9, 7.0);
        quad.transform.push_back(TransformKey{0.0, glm::dvec3(0.0), {1, 0, 0, 0}, glm::dvec3(1.0)});
        quad.transform.push_back(TransformKey{1.0, glm::dvec3(2.0, 1.0, -3.0), {1, 0, 0, 0}, glm::dvec3(1.0)});
        job.scene.objects.push_back(quad);
        job.render.subframes = 2048;
        reference = renderFrame(job, 0);
    }
    // Exact sweep with auto re-clips.
    RenderJob exactSweep() const {
        RenderJob out = job;
        out.render.time_integration = TimeIntegration::Sweep;
        out.render.sweep_time = SweepTime::Exact;
        out.render.subframes = 0;
        return out;
    }
    double trueError(const RenderResult& r) const {
        double sum = 0.0;
        for (const char* c : {"R", "G", "B"}) {
            const auto& a = r.image.find(c)->values;
            const auto& b = reference.image.find(c)->values;
            for (std::size_t i = 0; i < a.size(); ++i) sum += std::pow(double(a[i]) - b[i], 2);
        }
        return std::sqrt(sum / (3.0 * 32 * 32));
    }
};

}  // namespace

TEST(TimeError, SweepEstimateTracksExactErrorOfTranslatingQuad) {
    expectTracksExactError({6, 9, 12, 18, 24, 36, 48, 96, 192}, true);
}

// Exact sweep integrates a translating quad exactly in time whatever its positions (chords of a straight path
// are the path): the error is float storage alone, and the estimate, the nested rule's difference, 0.
TEST(TimeError, ExactSweepIsExactOnATranslatingQuadAndEstimatesZero) {
    for (const int n : {1, 6, 12, 96}) {
        RenderJob job = squareFilmJob();
        job.render.max_subframes = 256;
        job.render.time_integration = TimeIntegration::Sweep;
        job.render.sweep_time = SweepTime::Exact;
        job.render.subframes = 1;
        job.render.sweep_spacing = 1.0 / n;
        const Measured m = measure(job);
        EXPECT_LT(m.true_error, 1e-7) << n;  // float storage of values <= 1: 6e-8 at most per value
        // Depths equal to rounding make some paths not exactly translations: their two rules then agree
        // to rounding, not bit for bit.
        EXPECT_LT(m.estimated, 1e-12) << n;
    }
}

// Where paths bend, exact sweep's error is the chords' distance from them, O(h^2) in the spacing (chord
// sagitta falls as its square), and the nested estimate serves. A white quad coming toward the camera
// (depth 7 -> 4) while sliding: its corners' raster paths bend in time and it grows. One re-clip;
// reference: 2048 point subframes (their midpoint error, about 1e-6 here, is far below the errors
// measured). Per spacing the estimate must be within 4x of the true error either way, and over the
// spacings the geometric mean within 1.5x. Measured (spacing 2 .. 0.25): true 1.6e-3, 3.8e-4, 9.1e-5,
// 2.3e-5 (4x per halving); ratios 1.42, 1.21, 1.13, 1.04.
TEST(TimeError, ExactSweepEstimateTracksExactErrorOfAnApproachingQuad) {
    const ApproachingQuad scene;
    RenderJob job = scene.exactSweep();
    double log_sum = 0.0;
    int count = 0;
    for (const double spacing : {2.0, 1.0, 0.5, 0.25}) {
        job.render.sweep_spacing = spacing;
        const RenderResult r = renderFrame(job, 0);
        const double ratio = r.stats.clipped().estimated_error / scene.trueError(r);
        EXPECT_GT(ratio, 0.25) << spacing;
        EXPECT_LT(ratio, 4.0) << spacing;
        log_sum += std::log(ratio);
        ++count;
    }
    const double mean = std::exp(log_sum / count);
    EXPECT_GT(mean, 1.0 / 1.5);
    EXPECT_LT(mean, 1.5);
}

// render.error_target with exact sweep on the approaching quad: the spacing model takes order 2 both
// ways (error_target.h), so the true error lands within the issue's 0.5 .. 1.5 of the target on either
// side of the pilot (its estimate at 1 px: 4.6e-4). Order 1 coarser, as for point positions, put
// table1_recede's 3e-4 target at 5.5e-4 (docs/performance.md, "Exact time integration").
TEST(ErrorTarget, ExactSweepMeetsTargetsOnBothSidesOfThePilot) {
    const ApproachingQuad scene;
    for (const double target : {1e-3, 3e-4}) {
        RenderJob job = scene.exactSweep();
        job.render.error_target = target;
        const RenderResult r = renderFrame(job, 0);
        EXPECT_GT(scene.trueError(r), 0.5 * target) << target;
        EXPECT_LT(scene.trueError(r), 1.5 * target) << target;
    }
}

// Point subframes are the same midpoint rule over the segment, so the same estimate serves them.
TEST(TimeError, SubframeEstimateTracksExactErrorOfTranslatingQuad) { expectTracksExactError({9, 18, 36, 48}, false); }

// Too few samples for a coarser rule (fewer than 3) and a still scene contribute 0.
TEST(TimeError, NoCoarserRuleEstimatesZero) {
    RenderJob job = squareFilmJob();
    job.render.subframes = 2;
    EXPECT_EQ(measure(job).estimated, 0.0);
    RenderJob still = squareFilmJob();
    still.render.method = Method::Clipped;
    still.scene.objects.push_back(test::rasterQuad(kX0, kY0, kX1, kY1, 6.0));
    EXPECT_EQ(renderFrame(still, 0).stats.clipped().estimated_error, 0.0);
}

// The nested rule: per whole group of three, the middle sample counts 3 and the others 0; what is left
// after the last group keeps its fine weight. So both rules weigh every interval's samples to m.
TEST(TimeError, NestedRuleIsACompositeMidpointRule) {
    const NestedRule seven(7);
    const std::vector<double> expected{-1, 2, -1, -1, 2, -1, 0};
    EXPECT_EQ(seven.to3, expected);
    EXPECT_EQ(NestedRule(2).to3, (std::vector<double>{0, 0}));
}

// The spacing model: p = 2 below the pilot's spacing (4x less error, half the spacing), p = 1 above it.
TEST(ErrorTarget, SpacingFollowsOrderTwoBelowAndOneAbove) {
    EXPECT_DOUBLE_EQ(spacingForTarget(1.0, 4e-3, 1e-3), 0.5);
    EXPECT_DOUBLE_EQ(spacingForTarget(1.0, 4e-3, 8e-3), 2.0);
    EXPECT_DOUBLE_EQ(spacingForTarget(1.0, 0.0, 1e-3), 1.0) << "no estimate: the pilot's setting stays";
}

// render.error_target on the translating quad, sweep and point subframes, at targets finer than the
// pilot's error: the exact error of what it renders within the issue's 0.5 .. 1.5 of the target. The
// render's own estimate is 4x off either way on this phase-coherent scene (TimeError above), so a render
// finer than the pilot is judged against a second pilot at half its interval. Judged by the estimate
// they were 0.27 .. 1.84 (five of six outside 0.5 .. 1.5); measured now 0.90 .. 1.04.
TEST(ErrorTarget, TargetsFinerThanThePilotAreJudgedAgainstAFinerPilot) {
    for (const double target : {1e-3, 3e-4, 1e-4}) {
        for (const bool sweep : {true, false}) {
            RenderJob job = squareFilmJob();
            job.render.max_subframes = 1024;
            job.render.error_target = target;
            job.render.time_integration = sweep ? TimeIntegration::Sweep : TimeIntegration::Subframes;
            const Measured m = measure(job);
            EXPECT_GT(m.true_error, 0.5 * target) << target << (sweep ? " sweep" : " subframes");
            EXPECT_LT(m.true_error, 1.5 * target) << target << (sweep ? " sweep" : " subframes");
        }
    }
}

// Targets well above the pilot's error: renders coarser than the pilot are judged against the pilot
// image, not by their own estimate, so the exact error must land within the issue's 0.5 .. 1.5 of the
// target under every time integration (auto tunes the spacing as sweep does). Measured 0.67 .. 1.30.
TEST(ErrorTarget, CoarseTargetsAreMeasuredAgainstThePilot) {
    for (const double target : {2e-2, 6e-3}) {
        for (const TimeIntegration integration : {TimeIntegration::Sweep, TimeIntegration::Subframes, TimeIntegration::Auto}) {
            RenderJob job = squareFilmJob();
            job.render.max_subframes = 1024;
            job.render.error_target = target;
            job.render.time_integration = integration;
            job.render.method = Method::Clipped;
            job.scene.objects.push_back(movingQuad(kX0, kY0, kX1, kY1, 6.0, kVelocity));
            const RenderResult r = renderFrame(job, 0);
            const ErrorTargetStats& stats = *r.stats.clipped().target;
            job.render.error_target = 0.0;
            job.scene.objects.pop_back();
            const Measured m = measure(stats.sweep_spacing > 0.0 ? [&] { job.render.sweep_spacing = stats.sweep_spacing; return job; }()
                                                                 : [&] { job.render.subframes = static_cast<int>(stats.subframes); return job; }());
            EXPECT_GT(m.true_error, 0.5 * target) << target << " integration " << static_cast<int>(integration);
            EXPECT_LT(m.true_error, 1.5 * target) << target << " integration " << static_cast<int>(integration);
        }
    }
}

// A quad moving 0.013 px over the shutter, under the 1 / kKinkMotion px that the kink floor (kinkSamples)
// gives a second position: one sweep position per interval at the pilot's 1 px, so the pilot has no
// estimate, and a render 4x coarser does the same work. That render is the answer: two renders in all
// (no refined pilot), and the bits of a plain render at the default spacing.
TEST(ErrorTarget, ProbeThatDoesThePilotsWorkIsTheAnswer) {
    RenderJob job = squareFilmJob();
    job.render.method = Method::Clipped;
    job.render.time_integration = TimeIntegration::Sweep;
    job.scene.objects.push_back(movingQuad(kX0, kY0, kX1, kY1, 6.0, glm::dvec2(0.012, 0.006)));
    const RenderResult plain = renderFrame(job, 0);
    ASSERT_EQ(plain.stats.clipped().estimated_error, 0.0) << "the scene must leave the pilot without an estimate";
    job.render.error_target = 1e-2;
    const RenderResult r = renderFrame(job, 0);
    const ErrorTargetStats& stats = *r.stats.clipped().target;
    EXPECT_EQ(stats.renders, 2);
    EXPECT_EQ(stats.sweep_spacing, 4.0);
    for (const char* c : {"R", "G", "B", "A"}) EXPECT_EQ(r.image.find(c)->values, plain.image.find(c)->values) << c;
}

// A quad moving 0.048 px: the kink floor (kinkSamples) gives it sqrt(kKinkMotion 0.048) = 1.76 px
// of travel, so at the pilot's 1 px two sweep positions per interval (no estimate; its exact error is
// 6.2e-7), at every spacing from 1.76 px one (2.5e-6). For a target of 6e-7 every render coarser than
// that misses by 4x, and the correction from the first one, at order 1, lands below the pilot's spacing,
// where nothing is judged against the pilot any more. Bisection between the pilot and that render finds
// only spacings under 1.76 px, which do the pilot's work: the answer has the pilot's bits and an exact
// error within the issue's 0.5 .. 1.5 of the target.
TEST(ErrorTarget, EveryCoarserSpacingMissingTheTargetLeavesThePilotsWork) {
    constexpr double kTarget = 6e-7;
    const glm::dvec2 v(0.0474, 0.01);
    RenderJob job = squareFilmJob();
    job.render.method = Method::Clipped;
    job.render.time_integration = TimeIntegration::Sweep;
    job.scene.objects.push_back(movingQuad(kX0, kY0, kX1, kY1, 6.0, v));
    const RenderResult plain = renderFrame(job, 0);
    job.render.error_target = kTarget;
    const RenderResult r = renderFrame(job, 0);
    const ErrorTargetStats& stats = *r.stats.clipped().target;
    EXPECT_LT(stats.sweep_spacing, std::sqrt(kKinkMotion * glm::length(v)));
    for (const char* c : {"R", "G", "B", "A"}) EXPECT_EQ(r.image.find(c)->values, plain.image.find(c)->values) << c;
    const std::vector<glm::dvec2> quad{{kX0, kY0}, {kX1, kY0}, {kX1, kY1}, {kX0, kY1}};
    double sum = 0.0;
    const std::vector<float>& red = r.image.find("R")->values;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x)
            sum += std::pow(red[static_cast<std::size_t>(y * 32 + x)] - testing::translatingPixelCoverage(quad, v, x, y), 2);
    const double error = std::sqrt(sum / (32.0 * 32.0));  // R = G = B: white under ambient 1
    EXPECT_GT(error, 0.5 * kTarget);
    EXPECT_LT(error, 1.5 * kTarget);
}

// many/deforming at 160x90 under a target of 1e-2: the pilot (1 px) has no estimate, the probe 4x
// coarser anchors the model, and the first correction (19.7 px) does the work of the render before it
// (28.6 px), 1.6e-2 against the pilot: a plateau over the target. A finer setting changes the work there,
// so one more correction is made (14.4 px, 8.0e-3 against the reference below) instead of giving way to
// the pilot, whose error (3e-5) is 300x under the target: 0.5 .. 1.5 of the target, as issue 20 asks.
TEST(ErrorTarget, PlateauOverTheTargetIsCorrectedFinerNotAnsweredByThePilot) {
    constexpr double kTarget = 1e-2;
    const std::string path = std::string(CLIPBLUR_SOURCE_DIR) + "/configs/bench/many/deforming.yaml";
    RenderJob job = loadJob(path, {"film.width=160", "film.height=90", "render.time_integration=sweep"});
    job.render.sweep_spacing = 0.5;  // error 3e-5 at 1 px: a reference 300x finer than the target
    const RenderResult reference = renderFrame(job, 0);
    job.render.error_target = kTarget;
    job.render.sweep_spacing = 1.0;
    const RenderResult r = renderFrame(job, 0);
    const ErrorTargetStats& stats = *r.stats.clipped().target;
    EXPECT_FALSE(stats.pilot_kept);
    EXPECT_GT(stats.sweep_spacing, 4.0);
    const double error = rmsDifference(reference.image, r.image);
    EXPECT_GT(error, 0.5 * kTarget);
    EXPECT_LT(error, 1.5 * kTarget);
}

namespace {

// A bench scene at 160x90 under `target`, its error against a sweep at 0.1 px (re-clips following it,
// 6e-6 from the same at 0.05 px on both scenes below): the re-clip check refined the re-clips, and the
// answer is within 0.5 .. 1.5 of the target, as issue 20 asks.
void expectReclipsRefinedToTarget(const std::string& scene, double target) {
    const std::string path = std::string(CLIPBLUR_SOURCE_DIR) + "/configs/bench/" + scene + ".yaml";
    RenderJob job = loadJob(path, {"film.width=160", "film.height=90", "render.time_integration=sweep"});
    job.render.sweep_spacing = 0.1;
    job.render.max_subframes = 4096;
    const RenderResult reference = renderFrame(job, 0);
    job.render.max_subframes = 256;
    job.render.sweep_spacing = 1.0;
    job.render.error_target = target;
    const RenderResult r = renderFrame(job, 0);
    const ErrorTargetStats& stats = *r.stats.clipped().target;
    EXPECT_GT(stats.reclip_spacing, 0.0);
    EXPECT_LT(stats.reclip_spacing, stats.sweep_spacing);
    const double error = rmsDifference(reference.image, r.image);
    EXPECT_GT(error, 0.5 * target);
    EXPECT_LT(error, 1.5 * target);
}

}  // namespace

// Two renders' time errors e_a and e_b per pixel, their levels 8 e (Q_3h - Q_h = (3^2 - 1) e): the
// difference timeErrorDifference sees is 0 where they are one error (common positions) and the RMS of
// e_b - e_a where they are two (re-laid positions); without levels it is 0.
TEST(ErrorTarget, TimeErrorDifferenceIsThatOfTheEstimatesPerPixel) {
    const auto result = [](const std::vector<float>& error) {
        RenderResult r;
        r.image = Image::make(4, 1, {"R", "G", "B", "A"});
        for (const float e : error) r.level_differences.emplace_back(8.0f * e, 8.0f * e, 8.0f * e, 0.0f);
        return r;
    };
    const std::vector<float> ea{0.03f, -0.01f, 0.02f, 0.0f}, eb{-0.02f, 0.04f, 0.0f, 0.01f};
    EXPECT_EQ(timeErrorDifference(result(ea), result(ea)), 0.0);
    double sum = 0.0;
    for (std::size_t i = 0; i < ea.size(); ++i) sum += (double(eb[i]) - ea[i]) * (double(eb[i]) - ea[i]);
    // Float rounding of the levels (8 e in float, then / 8): 1e-8 of values near 0.05.
    EXPECT_NEAR(timeErrorDifference(result(ea), result(eb)), std::sqrt(sum / 4.0), 1e-8);
    RenderResult plain = result(eb);
    plain.level_differences.clear();
    EXPECT_EQ(timeErrorDifference(result(ea), plain), 0.0);
}

// A clipped render's levels are what its estimated_error sums (point subframes: a translating sweep is
// exact and has none).
TEST(ErrorTarget, RenderKeepsTheLevelsItsEstimateSums) {
    RenderJob job = squareFilmJob();
    job.render.method = Method::Clipped;
    job.render.time_integration = TimeIntegration::Subframes;
    job.render.subframes = 9;
    job.scene.objects.push_back(movingQuad(4.0, 6.0, 14.0, 20.0, 6.0, glm::dvec2(9.0, 2.0)));
    job.scene.objects.push_back(movingQuad(10.0, 8.0, 22.0, 16.0, 8.0, glm::dvec2(-7.0, 1.0)));
    const RenderResult r = renderFrame(job, 0);
    ASSERT_EQ(r.level_differences.size(), r.image.window.area());
    EXPECT_GT(r.stats.clipped().estimated_error, 0.0);
    EXPECT_EQ(estimateTimeError(r.level_differences), r.stats.clipped().estimated_error);
}

// table1_spin at 160x90 under a target of 3e-4: the spacing chosen (1.45 px) estimates 3.3e-4 and has
// 15 re-clips, and its re-clip error (4.3e-4 at 1 px against 7.3e-5 with reclip_spacing 0.1) is not in
// the estimate. Re-clips at half the spacing are 15 too, at a quarter 45, so the check looks past the
// first halving; and as they keep the positions' times, the two renders' time errors are nearly one
// error, which taking both estimates off the difference in quadrature took for the whole change (1.71 of
// the target before). Only how much the estimates differ per pixel is taken off now.
TEST(ErrorTarget, ReclipErrorBehindASteppedCountIsMeasured) {
    expectReclipsRefinedToTarget("table1_spin", 3e-4);
}

// table1_recede_spin_pan at 160x90 under a target of 1e-4: the chosen spacing (0.6 px) estimates
// 7.7e-5, but the wall rolls under its fragments, which sweep carries rigidly between the 15 re-clips, and
// that error the estimate does not see: 2.8e-4 against the reference below without the re-clip check.
// A render with re-clips at half the spacing measures it (error_target.cpp, checkReclips) and the
// re-clips are refined until it fits beside the time error.
TEST(ErrorTarget, ReclipErrorTheEstimateDoesNotSeeIsMeasuredAndRefined) {
    expectReclipsRefinedToTarget("table1_recede_spin_pan", 1e-4);
}

// Two quads passing each other (44 px of relative motion) with re-clips capped at 16: the pilot at 1 px
// caps them in its tiles, so it was no finer solution there. Before the pilot's cap was raised, its
// refinement to 0.25 px had an estimate (2.5e-4) only because the cap left several sweep positions per
// interval, the corrections stopped at 1.53 px (6.4e-3), and bisection toward the pilot answered 0.62 px
// (4.3e-4: under half the target). Now the cap is doubled for the whole search until the 1 px pilot has
// no capped tile (error_target.cpp, runPilot): cap 64, 1.72 px, 7 renders, and the answer's error against
// 2048 point subframes must be within the issue's 0.5 .. 1.5 of the target (measured 1.26).
TEST(ErrorTarget, PilotWithCappedReclipsHasTheCapRaisedFirst) {
    constexpr double kTarget = 1e-3;
    RenderJob job = squareFilmJob();
    job.render.method = Method::Clipped;
    job.render.max_subframes = 2048;
    job.scene.objects.push_back(movingQuad(24.0, 12.0, 30.0, 20.0, 10.0, glm::dvec2(-22.0, 0.0)));
    job.scene.objects.push_back(movingQuad(2.0, 10.0, 8.0, 22.0, 6.0, glm::dvec2(22.0, 0.0)));
    job.render.subframes = 2048;
    const RenderResult reference = renderFrame(job, 0);
    job.render.subframes = 0;
    job.render.max_subframes = 16;
    job.render.time_integration = TimeIntegration::Sweep;
    job.render.sweep_spacing = 1.0;
    ASSERT_GT(renderFrame(job, 0).stats.clipped().capped_tiles, 0);  // the pilot's setting is capped
    job.render.error_target = kTarget;
    const RenderResult r = renderFrame(job, 0);
    const ErrorTargetStats& stats = *r.stats.clipped().target;
    EXPECT_GT(stats.max_subframes, 16);
    EXPECT_EQ(r.stats.clipped().capped_tiles, 0);
    const double error = rmsDifference(reference.image, r.image);
    EXPECT_GT(error, 0.5 * kTarget);
    EXPECT_LT(error, 1.5 * kTarget);
}

// Two quads passing each other, 44 px apart in speed along x (and 0.4 px along y), and their reference,
// 2048 point subframes. With sweep integration their re-clips follow the spacing, so every spacing leaves
// about one sweep position per interval: no render has an estimate of its own.
struct PassingQuads {
    RenderJob job;
    RenderResult reference;
};
PassingQuads passingQuads(double vy_far, double vy_near) {
    RenderJob job = squareFilmJob();
    job.render.method = Method::Clipped;
    job.render.max_subframes = 2048;
    job.scene.objects.push_back(movingQuad(24.0, 12.0, 30.0, 20.0, 10.0, glm::dvec2(-22.0, vy_far)));
    job.scene.objects.push_back(movingQuad(2.0, 10.0, 8.0, 22.0, 6.0, glm::dvec2(22.0, vy_near)));
    job.render.subframes = 2048;
    RenderResult reference = renderFrame(job, 0);
    job.render.subframes = 0;
    job.render.time_integration = TimeIntegration::Sweep;
    return {job, std::move(reference)};
}

// The re-clip check's model (error_target.cpp, reclipOrder): visibility frozen at the middle of each
// re-clip interval is a midpoint rule in time over a coverage that is smooth between the intervals'
// kinks, so the re-clip error falls as the re-clip count squared. Positions fixed at 0.02 px (time
// error under 2e-6) and re-clips at 2 px down to 0.125 px over quads passing at 44 px: the order between
// successive halvings, in the count, must lie within 1.8 .. 2.2 (measured 1.99 .. 2.00), where the rule
// the check used before, order 1, would be off by a whole order.
TEST(TimeError, ReclipErrorFallsAsTheReclipCountSquared) {
    PassingQuads scene = passingQuads(0.7, 0.3);
    scene.job.render.sweep_spacing = 0.02;
    double count = 0.0, error = 0.0;
    for (const double spacing : {2.0, 1.0, 0.5, 0.25, 0.125}) {
        scene.job.render.reclip_spacing = spacing;
        const RenderResult r = renderFrame(scene.job, 0);
        const double c = static_cast<double>(r.stats.clipped().subframes_total);
        const double e = rmsDifference(scene.reference.image, r.image);
        if (count > 0.0) {
            ASSERT_GT(c, count) << spacing;
            const double order = std::log(error / e) / std::log(c / count);
            EXPECT_GT(order, 1.8) << spacing;
            EXPECT_LT(order, 2.2) << spacing;
        }
        count = c;
        error = e;
    }
}

// A pilot without an estimate, refined 4x without one, is anchored on the refinement: E(1) = 4/3 of
// their difference, and the order up to the coarser probe (4 px) measured (errors here: 1.4e-2, 1.3e-4
// and 8.2e-6 at 4, 1 and 0.25 px, order 3.4 then 2). Refined twice instead, the pilot of 0.0625 px cost
// 4x the renders' re-clips; taken at order 1 from the anchor, the render landed 7x over a 1e-3 target.
TEST(ErrorTarget, PilotWithoutAnEstimateIsAnchoredOnItsRefinement) {
    constexpr double kTarget = 1e-3;
    PassingQuads scene = passingQuads(0.7, 0.3);
    ASSERT_EQ(renderFrame(scene.job, 0).stats.clipped().estimated_error, 0.0);
    scene.job.render.error_target = kTarget;
    const RenderResult r = renderFrame(scene.job, 0);
    const ErrorTargetStats& stats = *r.stats.clipped().target;
    EXPECT_LE(stats.renders, 4);  // pilot, coarser probe, refinement, the render
    const double error = rmsDifference(scene.reference.image, r.image);
    EXPECT_GT(error, 0.5 * kTarget);
    EXPECT_LT(error, 1.5 * kTarget);
}

// Quads passing along x alone, 22 px each: at 1 px and at 0.25 px the render matches 2048 point
// subframes to float rounding, so the refinement changes no pixel. Then no finer setting will: the pilot
// at 1 px is the answer, after three renders (pilot, coarser probe, refinement).
TEST(ErrorTarget, RefinementThatChangesNothingLeavesThePilot) {
    PassingQuads scene = passingQuads(0.0, 0.0);
    const RenderResult plain = renderFrame(scene.job, 0);
    scene.job.render.error_target = 1e-4;
    const RenderResult r = renderFrame(scene.job, 0);
    const ErrorTargetStats& stats = *r.stats.clipped().target;
    EXPECT_EQ(stats.renders, 3);
    EXPECT_EQ(stats.sweep_spacing, 1.0);
    for (const char* c : {"R", "G", "B", "A"}) EXPECT_EQ(r.image.find(c)->values, plain.image.find(c)->values) << c;
    EXPECT_LT(rmsDifference(scene.reference.image, r.image), 1e-6);
}

// Quads passing each other: their error is a staircase in the spacing (re-clips following it leave one
// or two sweep positions per interval), so the model's corrections can step over a target's setting. At
// targets from 1e-2 to 3e-4 the error against 2048 point subframes must lie within the issue's 0.5 .. 1.5
// of the target. Before bisection between renders under and over the target: 0.50 at 1e-2,
// 506 at 5e-4 (corrections ended at 54.6 px) and 0.03 at 3e-4 (the refined pilot kept); along x alone,
// 4.2 at 3e-3 and 3e-5 at 5e-3 (the pilot kept, exact: a coarser render meets the target).
TEST(ErrorTarget, StaircaseErrorMeetsEveryTargetByBisection) {
    const std::vector<std::pair<glm::dvec2, std::vector<double>>> cases{
        {{0.7, 0.3}, {1e-2, 3e-3, 1e-3, 5e-4, 3e-4}}, {{0.0, 0.0}, {1e-2, 5e-3, 3e-3}}};
    int bisected = 0;
    for (const auto& [vy, targets] : cases) {
        PassingQuads scene = passingQuads(vy.x, vy.y);
        for (const double target : targets) {
            scene.job.render.error_target = target;
            const RenderResult r = renderFrame(scene.job, 0);
            bisected += r.stats.clipped().target->bisections > 0 ? 1 : 0;
            const double error = rmsDifference(scene.reference.image, r.image);
            EXPECT_GT(error, 0.5 * target) << vy.x << " " << target;
            EXPECT_LT(error, 1.5 * target) << vy.x << " " << target;
        }
    }
    EXPECT_GT(bisected, 0);
}

// Quads passing each other with re-clips capped at 4 per tile: every render that chooses, the pilots too,
// has the cap, so the error it leaves is seen by none (before raiseCap: 8.5x, 25x and 85x the target,
// reported as 0). A render with the cap doubled measures it, and the cap is raised until the choice fits:
// within the issue's 0.5 .. 1.5 of the target against 2048 point subframes (measured 0.66, 0.56, 1.09).
TEST(ErrorTarget, ErrorOfCappedReclipsIsMeasuredAndTheCapRaised) {
    PassingQuads scene = passingQuads(0.7, 0.3);
    scene.job.render.max_subframes = 4;
    for (const double target : {3e-3, 1e-3, 3e-4}) {
        scene.job.render.error_target = target;
        const RenderResult r = renderFrame(scene.job, 0);
        EXPECT_GT(r.stats.clipped().target->max_subframes, 4) << target;
        const double error = rmsDifference(scene.reference.image, r.image);
        EXPECT_GT(error, 0.5 * target) << target;
        EXPECT_LT(error, 1.5 * target) << target;
    }
}

// A camera yawing 40 degrees over two quads: auto makes ceil(40 / 15) = 3 shutter segments, 44 re-clips at
// the pilot's 1 px. Under a target far above what 3 segments leave at a coarse spacing (0.47 of 0.2 against
// the pilot), fewer segments meet it at less work (error_target.cpp, fewerSegments): the answer has fewer
// segments and re-clips, and its error against a render fine in spacing and re-clips with 3 segments is
// within 4/3 of the target (measured 0.34 with 2). The shot that needs it: ShippedShot.
TEST(ErrorTarget, LooseTargetOnATurningCameraTakesFewerSegments) {
    constexpr double kTarget = 0.2;
    RenderJob job = squareFilmJob();
    job.render.method = Method::Clipped;
    job.render.time_integration = TimeIntegration::Sweep;
    job.scene.objects.push_back(test::rasterQuad(2.0, 4.0, 30.0, 28.0, 8.0));
    job.scene.objects.push_back(test::rasterQuad(12.0, 10.0, 20.0, 22.0, 4.0));
    const double yaw = 40.0 * std::numbers::pi / 180.0;
    job.scene.camera.keys.push_back(
        CameraKey{1.0, glm::dvec3(0.0), glm::dvec3(std::sin(yaw), 0, std::cos(yaw)), glm::dvec3(0, 1, 0)});
    job.render.sweep_spacing = 0.25;
    job.render.max_subframes = 4096;
    const RenderResult reference = renderFrame(job, 0);
    ASSERT_EQ(reference.stats.clipped().segments, 3);
    job.render.sweep_spacing = 1.0;
    job.render.max_subframes = 256;
    const long long reclips = renderFrame(job, 0).stats.clipped().subframes_total;
    job.render.error_target = kTarget;
    const RenderResult r = renderFrame(job, 0);
    const ClippedStats& stats = r.stats.clipped();
    EXPECT_LT(stats.segments, 3);
    EXPECT_EQ(stats.target->max_segments, stats.segments);
    EXPECT_LT(stats.subframes_total, reclips);
    EXPECT_LT(rmsDifference(reference.image, r.image), kTarget * 4.0 / 3.0);
}

// Shards of one frame choose one setting: every render that chooses is of the whole film. A window over
// the quad and one beside it (nothing there, so its own error would be 0) must both get the whole film's
// spacing, and their pixels the whole film's bits. The target is one the quad's first render misses, so
// the choice is corrected by renders measured against the pilot.
TEST(ErrorTarget, ShardsOfAFrameChooseAlike) {
    RenderJob job = squareFilmJob();
    job.render.method = Method::Clipped;
    job.render.time_integration = TimeIntegration::Sweep;
    job.render.max_subframes = 1024;
    job.render.error_target = 2e-2;
    job.scene.objects.push_back(movingQuad(kX0, kY0, kX1, kY1, 6.0, kVelocity));
    const RenderResult whole = renderFrame(job, 0);
    const double spacing = whole.stats.clipped().target->sweep_spacing;
    for (const PixelBounds window : {PixelBounds::sized(0, 0, 32, 24), PixelBounds::sized(0, 26, 32, 6)}) {
        job.render.window = window;
        const RenderResult shard = renderFrame(job, 0);
        EXPECT_EQ(shard.stats.clipped().target->sweep_spacing, spacing) << window.y0;
        const Image::Channel& a = *whole.image.find("R");
        const Image::Channel& b = *shard.image.find("R");
        for (int y = window.y0; y < window.y1; ++y)
            for (int x = window.x0; x < window.x1; ++x)
                ASSERT_EQ(b.values[shard.image.index(x, y)], a.values[whole.image.index(x, y)]) << x << ", " << y;
    }
}

}  // namespace clipblur
