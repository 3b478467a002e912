#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <tuple>
#include <vector>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "renderer/propagation/subframes.h"
#include "renderer/render.h"
#include "scene/primitives.h"
#include "renderer/test_scenes.h"

namespace clipblur {

namespace {

using test::movingQuad;
using test::rasterQuad;
using test::squareFilmJob;
using test::worldAtRaster;

const std::vector<float>& channel(const RenderResult& r, const char* name) { return r.image.find(name)->values; }

// A clipped job of two quads in motion over the black background (so neither is a still backdrop).
RenderJob twoMovingQuads(const Object& far, const Object& near) {
    RenderJob job = squareFilmJob();
    job.render.method = Method::Clipped;
    job.scene.objects.push_back(far);
    job.scene.objects.push_back(near);
    return job;
}

double maxDifference(const RenderResult& a, const RenderResult& b) {
    double worst = 0.0;
    for (const char* c : {"R", "G", "B", "A"})
        for (std::size_t i = 0; i < channel(a, c).size(); ++i)
            worst = std::max(worst, double(std::abs(channel(a, c)[i] - channel(b, c)[i])));
    return worst;
}

double rmsDifference(const RenderResult& a, const RenderResult& b) {
    double sum = 0.0;
    std::size_t n = 0;
    for (const char* c : {"R", "G", "B"})
        for (std::size_t i = 0; i < channel(a, c).size(); ++i, ++n)
            sum += std::pow(double(channel(a, c)[i] - channel(b, c)[i]), 2);
    return std::sqrt(sum / double(n));
}

// The auto re-clip count at sweep_spacing 1, and a sweep with that many re-clips and positions 0.05 px
// apart (fine enough that what re-clips change is all that is left) against 96 point subframes. Auto
// re-clips follow the spacing, so the count is taken at 1 px and then fixed.
struct AutoSweep {
    long long reclips;
    double rms, max;
};
AutoSweep autoSweepAgainstPointSubframes(RenderJob job) {
    job.render.subframes = 96;
    const RenderResult point = renderFrame(job, 0);
    job.render.time_integration = TimeIntegration::Sweep;
    job.render.subframes = 0;
    const long long reclips = renderFrame(job, 0).stats.clipped().subframes_max_per_tile;
    job.render.subframes = static_cast<int>(reclips);
    job.render.sweep_spacing = 0.05;
    const RenderResult sweep = renderFrame(job, 0);
    return {reclips, rmsDifference(sweep, point), maxDifference(sweep, point)};
}

// Sweep with `intervals` re-clips and exactly `positions` positions per interval for a quad moving by v.
RenderJob sweepJob(RenderJob job, glm::dvec2 v, int intervals, int positions) {
    job.render.time_integration = TimeIntegration::Sweep;
    job.render.subframes = intervals;
    // Each interval moves the quad by d = |v| / intervals and holds 1 / intervals of the shutter, so it
    // gets max(d, sqrt(kKinkMotion d / intervals)) / spacing positions (the kink floor, kinkSamples); a
    // spacing a hair above that over `positions` keeps the ceiling at `positions` despite rounding.
    const double d = glm::length(v) / intervals;
    job.render.sweep_spacing = std::max(d, std::sqrt(kKinkMotion * d / intervals)) / positions * (1.0 + 1e-9);
    return job;
}

// Vertex positions of a translating quad, and so every pixel's coverage, are the same whether a time is
// a subframe of its own or a sweep position of a subframe's interval: sweep with K intervals of M
// positions and point subframes at N = K M are the same midpoint rule (times (j + 1/2) / N), so the
// images agree to rounding. Float storage: 1e-6.
constexpr double kFloatTolerance = 1e-6;

// A clipped job whose material 1 is stripes across x, 0.8 px wide at depth 6 (a checker would also cut
// along z, and a quad's plane z = 6 would lie on a cell boundary, where rounding picks the colour).
RenderJob stripedJob() {
    RenderJob job = squareFilmJob();
    job.render.method = Method::Clipped;
    Material stripes;
    stripes.texture.kind = Texture::Kind::Stripe;
    stripes.texture.scale = 0.3;
    stripes.texture.color2 = glm::dvec3(0.2, 0.5, 0.0);
    job.scene.materials.push_back(stripes);
    return job;
}

// A striped quad at `depth` filling the film, the camera moving to `key` at t = 1: auto asks for one
// re-clip, and against 96 point subframes (positions 0.02 px apart, so only what re-clips change is
// left) the RMS error falls by at least 0.6 each time the re-clips grow (a first-order error halves).
void expectOneAutoReclipThenFallingError(const CameraKey& key, double depth, std::initializer_list<int> intervals) {
    RenderJob job = stripedJob();
    Object quad = rasterQuad(-8.0, -8.0, 40.0, 40.0, depth);
    quad.material = 1;
    job.scene.objects.push_back(quad);
    job.scene.camera.keys.push_back(key);
    job.render.subframes = 96;
    const RenderResult point = renderFrame(job, 0);
    job.render.time_integration = TimeIntegration::Sweep;
    job.render.subframes = 0;
    EXPECT_EQ(renderFrame(job, 0).stats.clipped().subframes_max_per_tile, 1);  // at sweep_spacing 1
    job.render.sweep_spacing = 0.02;
    double previous = 0.0;
    for (const int n : intervals) {
        job.render.subframes = n;
        const double error = rmsDifference(renderFrame(job, 0), point);
        if (n > *intervals.begin()) {
            EXPECT_LT(error, 0.6 * previous) << n;
        }
        previous = error;
    }
}

// A striped quad receding from depth 5 to 6 over the shutter.
RenderJob recedingStripedQuad() {
    RenderJob job = stripedJob();
    Object quad = rasterQuad(3.3, 5.2, 13.7, 28.9, 5.0);
    quad.material = 1;
    quad.transform.push_back(TransformKey{0.0, glm::dvec3(0.0), {1, 0, 0, 0}, glm::dvec3(1.0)});
    quad.transform.push_back(TransformKey{1.0, glm::dvec3(0, 0, 1), {1, 0, 0, 0}, glm::dvec3(1.0)});
    job.scene.objects.push_back(quad);
    return job;
}

// A quad filling the film under a camera rolling by 1 rad in one shutter segment, sweep integration.
RenderJob rollingCameraJob() {
    RenderJob roll = squareFilmJob();
    roll.render.method = Method::Clipped;
    roll.render.time_integration = TimeIntegration::Sweep;
    roll.render.segments = 1;
    roll.scene.objects.push_back(rasterQuad(-8.0, -8.0, 40.0, 40.0, 5.0));
    roll.scene.camera.keys.push_back(
        CameraKey{1.0, glm::dvec3(0.0), glm::dvec3(0, 0, 1), glm::dvec3(std::sin(1.0), std::cos(1.0), 0)});
    return roll;
}

}  // namespace

TEST(SweepIntegration, TranslationMatchesPointSubframesAtTheSameTimes) {
    const glm::dvec2 v(11.4, 3.7);
    RenderJob job = stripedJob();
    Object quad = movingQuad(4.3, 6.2, 14.7, 19.9, 6.0, v);
    quad.material = 1;  // texture edges inside fragments must move with the surface, not with the fragment
    job.scene.objects.push_back(quad);
    job.render.subframes = 12;
    const RenderResult point = renderFrame(job, 0);
    for (const auto& [intervals, positions] : {std::pair{1, 12}, {3, 4}, {12, 1}}) {
        const RenderResult sweep = renderFrame(sweepJob(job, v, intervals, positions), 0);
        EXPECT_EQ(sweep.stats.clipped().subframes_max_per_tile, intervals);
        EXPECT_LT(maxDifference(sweep, point), kFloatTolerance) << intervals << " x " << positions;
        EXPECT_EQ(sweep.stats.clipped().reclip.sweep_unswept, 0);
        if (positions > 1) {
            EXPECT_GT(sweep.stats.clipped().sweep_spilled_pixels, 0) << "8-pixel tiles";
        }
    }
}

// A pixel whose fragments are all of one object and fill an axis-aligned rectangle is swept as that
// rectangle (the quad's diagonal cuts pixels in two, and so may the two frames' triangulations), so the
// positions placed are positions x pixels. Quad A, flat white, moves 6.4 px right: at the re-clip
// (t = 1/2) it covers raster [6.5, 16.9] x [5.2, 28.9], columns 6..16 and rows 5..28, 264 pixels, and 4
// positions each. Quad B, nearer and moving down, covers [16.9, 22.3] x [6.0, 22.2] then, 7 x 17 pixels,
// and shares column 16 with A (rows 6..22): pixels where two objects meet keep one entry per fragment,
// so there are at least 4 x (264 + 119) positions, where merging them would give 4 x (264 + 119 - 17).
TEST(SweepIntegration, PixelsOfOneSurfaceSweepAsOneRectangle) {
    const glm::dvec2 v(6.4, 0.0);
    RenderJob job = squareFilmJob();
    job.render.method = Method::Clipped;
    job.scene.objects.push_back(movingQuad(3.3, 5.2, 13.7, 28.9, 10.0, v));
    const RenderResult one = renderFrame(sweepJob(job, v, 1, 4), 0);
    EXPECT_EQ(one.stats.clipped().reclip.sweep_positions, 4 * 264);
    EXPECT_GT(one.stats.clipped().reclip.fragments, 264) << "the diagonal cuts pixels: the test means something";

    job.scene.objects.push_back(movingQuad(16.9, 4.4, 22.3, 20.6, 8.0, glm::dvec2(0.0, 3.2)));
    const RenderResult two = renderFrame(sweepJob(job, v, 1, 4), 0);
    EXPECT_GE(two.stats.clipped().reclip.sweep_positions, 4 * (264 + 119));
}

// A striped quad receding from depth 5 to 6 shrinks toward the image centre by 5/6. A sweep follows each
// fragment's centroid on the homogeneous parabola, exact under translation (SweepPath::through), and
// stretches it by depth(t) / depth, exact for a surface facing the camera: so with fine positions one
// interval matches many point subframes up to quadrature alone. Bound: a pixel's coverage is piecewise
// smooth in t with a kink where an edge enters or leaves it; 96 midpoint subframes err by at most
// (slope jump) h^2 / 8 per kink, slope jumps <= 2 x the speed of an edge, <= 16 / 5 px per frame for
// x0 <= 16 px from the centre, a handful of kinks: 4 x 6.4 / 96^2 / 8 = 3.5e-4; positions 0.02 px apart
// err far less. The raster parabola used before missed a corner's path by up to 6.2e-3 px, and fragments
// moved without the stretch miss by 0.0086 even with three intervals.
TEST(SweepIntegration, DollyMatchesPointSubframes) {
    RenderJob job = recedingStripedQuad();
    job.render.subframes = 96;
    const RenderResult point = renderFrame(job, 0);
    job.render.time_integration = TimeIntegration::Sweep;
    job.render.sweep_spacing = 0.02;
    for (const int intervals : {1, 3}) {
        job.render.subframes = intervals;
        const RenderResult sweep = renderFrame(job, 0);
        EXPECT_LT(maxDifference(sweep, point), 3.5e-4) << intervals;
        EXPECT_EQ(sweep.stats.clipped().reclip.sweep_unswept, 0);
    }
}

// Auto re-clips with sweeps: a dolly is followed by the sweep itself (its paths exactly, as the
// homogeneous parabola is under translation; its stretch by the depth ratio), while a roll (which sweeps
// do not follow inside a fragment) needs one re-clip per 0.1 px a fragment's vertex strays.
// Dolly: depth 5 -> 10 halves the image about its centre; counting the stretch would ask for
// |1/2 - 1| / 0.1 = 5 re-clips, and a point x0 px from the centre, at x0 / (1 + t), is off the raster
// parabola through t = 0, 1/2, 1 by up to 0.0134 x0 <= 0.27 px for the quad's corners (cube rule at
// 0.1 px: 2 re-clips), but it is on the homogeneous one: 1. Roll by 1 rad in one shutter segment: J = R,
// whose columns have length 1, so all of R - I is left: |(R - I) e| / |e| = 2 sin(1/2) = 0.959, and a
// vertex half a pixel's diagonal from its fragment's centre strays by 0.959 x (sqrt 2 / 2) / 2 = 0.339 px
// at an interval's ends with one interval: ceil(3.39) = 4 re-clips. (Auto segments turn by at most 15
// degrees, 0.088 px by the same count: one re-clip.)
TEST(SweepIntegration, AutoReclipsFollowRollButNotStretch) {
    RenderJob dolly = squareFilmJob();
    dolly.render.method = Method::Clipped;
    dolly.render.time_integration = TimeIntegration::Sweep;
    Object quad = rasterQuad(2.0, 2.0, 30.0, 30.0, 5.0);
    quad.transform.push_back(TransformKey{0.0, glm::dvec3(0.0), {1, 0, 0, 0}, glm::dvec3(1.0)});
    quad.transform.push_back(TransformKey{1.0, glm::dvec3(0, 0, 5), {1, 0, 0, 0}, glm::dvec3(1.0)});
    dolly.scene.objects.push_back(quad);
    EXPECT_EQ(renderFrame(dolly, 0).stats.clipped().subframes_max_per_tile, 1);

    const RenderResult rolled = renderFrame(rollingCameraJob(), 0);
    EXPECT_EQ(rolled.stats.clipped().segments, 1);
    EXPECT_EQ(rolled.stats.clipped().subframes_max_per_tile, 4);
}

// A roll of 0.25 rad (within one auto segment) under a 0.8 px striped quad: auto asks for one re-clip, a
// fragment's vertex straying by up to 0.088 px (see above). Against 96 point subframes, with positions
// fine enough (0.02 px) that the turn is the only error left, the error falls steadily as re-clips are
// added, at least by 0.6 per doubling (a first-order error halves; measured 0.38: RMS 0.0032, 0.0012,
// 0.00047, 0.00019 at 1, 2, 4, 8).
TEST(SweepIntegration, RollErrorFallsWithReclips) {
    expectOneAutoReclipThenFallingError(
        CameraKey{1.0, glm::dvec3(0.0), glm::dvec3(0, 0, 1), glm::dvec3(std::sin(0.25), std::cos(0.25), 0)}, 6.0,
        {1, 2, 4, 8});
}

// A camera backing away (depth 5 -> 10) while it pans by 0.1 rad: with the camera's turn taken out of
// the paths and put back at each position (SweepPath::turns), every path is followed exactly, so auto
// asks for one re-clip. What is left against 96 point subframes (positions 0.02 px apart) is that
// fragments shear with the pan's homography but are not sheared, which more re-clips shrink: RMS 0.00094,
// 0.00040, 0.000078 at 1, 2, 8.
TEST(SweepIntegration, TurningDollyNeedsOneReclip) {
    expectOneAutoReclipThenFallingError(
        CameraKey{1.0, glm::dvec3(0, 0, -5), glm::dvec3(std::sin(0.1), 0, std::cos(0.1)), glm::dvec3(0, 1, 0)}, 5.0,
        {1, 2, 8});
}

// A box turned 20 degrees about y slides from x = -1.5 to 1.5 at depth 5 past the camera: its +x face
// (normal (cos 20, 0, -sin 20)) faces the camera while -n . (centre + 0.6 n) > 0, that is for x < 1.18,
// and turns away at t = 0.89. The sweep stretches that face with the signed stretch of its open-to-close
// map, which passes through 0 there, and leaves it out after; pixels where it meets the front face are
// not merged (the two stretch differently). So one re-clip matches 96 point subframes up to quadrature:
// the box moves 14 px, so slope jumps per kink are at most 2 x 15 / px per frame, and with a handful of
// kinks 4 x 30 / 96^2 / 8 = 0.0016. (Merging those pixels with one face's stretch gave RMS 0.0052.)
TEST(SweepIntegration, FaceTurningAwayLeavesWithItsStretch) {
    RenderJob job = squareFilmJob(48);
    job.render.method = Method::Clipped;
    Material stripes;
    stripes.base_color = glm::dvec3(0.2, 0.5, 0.9);
    stripes.texture.kind = Texture::Kind::Stripe;
    stripes.texture.scale = 0.5;
    stripes.texture.color2 = glm::dvec3(0.95);
    job.scene.materials.push_back(stripes);
    Object box;
    box.name = "box";
    box.material = 1;
    box.mesh = makeBox(glm::dvec3(1.2, 2.0, 0.5));
    const glm::dquat turn = glm::angleAxis(glm::radians(20.0), glm::dvec3(0, 1, 0));
    box.transform.push_back(TransformKey{0.0, glm::dvec3(-1.5, 0, 5), turn, glm::dvec3(1.0)});
    box.transform.push_back(TransformKey{1.0, glm::dvec3(1.5, 0, 5), turn, glm::dvec3(1.0)});
    job.scene.objects.push_back(box);
    const AutoSweep sweep = autoSweepAgainstPointSubframes(job);
    EXPECT_EQ(sweep.reclips, 1);
    EXPECT_LT(sweep.max, 0.0016);
}

// A tilt of 0.05 rad turns the image by a homography: every fragment shears by at most x/f x 0.05 <= 0.05
// (x/f <= 1 with a 90 degree field of view), half the 0.1 the gradient rule allows per re-clip, and a
// point's path is nearly a parabola (what the chord rule used before did not credit); so one re-clip.
TEST(SweepIntegration, AutoReclipsOnceForATilt) {
    RenderJob job = stripedJob();
    Object wall = rasterQuad(-40.0, -40.0, 104.0, 104.0, 10.0, 64);
    wall.material = 1;
    job.scene.film.width = job.scene.film.height = 64;
    job.scene.objects.push_back(wall);
    job.scene.camera.keys.push_back(
        CameraKey{1.0, glm::dvec3(0.0), glm::dvec3(0, std::sin(0.05), std::cos(0.05)), glm::dvec3(0, 1, 0)});
    job.render.time_integration = TimeIntegration::Sweep;
    const RenderResult tilted = renderFrame(job, 0);
    EXPECT_EQ(tilted.stats.clipped().segments, 1);
    EXPECT_EQ(tilted.stats.clipped().subframes_max_per_tile, 1);
}

// Where one moving surface slides over another, what is hidden changes within an interval and a sweep
// keeps visibility as it was at the re-clip: the error against point subframes at the same 48 times
// falls as re-clips are added, and auto picks enough. Both quads move, so neither is a still backdrop.
TEST(SweepIntegration, OcclusionErrorFallsWithReclips) {
    const glm::dvec2 v(11.4, 3.7), w(-4.1, 1.3);
    RenderJob job = twoMovingQuads(movingQuad(1.0, 1.0, 31.0, 31.0, 10.0, w), movingQuad(4.3, 6.2, 14.7, 19.9, 6.0, v));
    job.render.subframes = 48;
    const RenderResult reference = renderFrame(job, 0);  // point subframes, 48 times
    std::vector<double> errors;
    for (int intervals : {1, 4, 16}) {
        const RenderResult sweep = renderFrame(sweepJob(job, v, intervals, 48 / intervals), 0);
        EXPECT_EQ(sweep.stats.clipped().sweep_backdrop_tiles, 0);
        errors.push_back(maxDifference(sweep, reference));
    }
    EXPECT_GT(errors[0], 0.1) << "one re-clip for 16 px of relative motion must show it";
    EXPECT_LT(errors[1], errors[0]);
    EXPECT_LT(errors[2], errors[1]);
    job.render.subframes = 0;
    job.render.time_integration = TimeIntegration::Sweep;
    const RenderResult automatic = renderFrame(job, 0);
    // Relative motion |v - w| = 15.6 px: auto re-clips at least every pixel of it.
    EXPECT_GE(automatic.stats.clipped().subframes_max_per_tile, 16);
}

// Automatic re-clips are spaced like positions: at sweep_spacing s surfaces move s px relative to each
// other between re-clips, and the path tolerances (0.1 px at s = 1) are 0.1 s above a pixel and 0.1 s^2
// below. Relative motion |v - w| = |(15.5, 2.4)| = 15.7 px gives ceil(15.7 / s) re-clips: 63, 16, 8, 4 at
// s = 0.25, 1, 2, 4. A roll of 1 rad strays 0.339 px (AutoReclipsFollowRollButNotStretch):
// ceil(0.339 / 0.00625) = 55 at s = 0.25, then ceil(3.39 / s) = 4, 2, 1.
TEST(SweepIntegration, AutoReclipsFollowTheSpacing) {
    const glm::dvec2 v(11.4, 3.7), w(-4.1, 1.3);
    RenderJob passing = twoMovingQuads(movingQuad(1.0, 1.0, 31.0, 31.0, 10.0, w), movingQuad(4.3, 6.2, 14.7, 19.9, 6.0, v));
    passing.render.time_integration = TimeIntegration::Sweep;
    RenderJob roll = rollingCameraJob();
    for (const auto& [spacing, relative, rolled] : {std::tuple{0.25, 63, 55}, {1.0, 16, 4}, {2.0, 8, 2}, {4.0, 4, 1}}) {
        passing.render.sweep_spacing = roll.render.sweep_spacing = spacing;
        EXPECT_EQ(renderFrame(passing, 0).stats.clipped().subframes_max_per_tile, relative) << spacing;
        EXPECT_EQ(renderFrame(roll, 0).stats.clipped().subframes_max_per_tile, rolled) << spacing;
    }
}

// render.reclip_spacing reads the same re-clip rule at its own spacing, positions staying at
// sweep_spacing: the counts above at reclip_spacing, whatever sweep_spacing is, and the bits of the plain
// render where the two are equal.
TEST(SweepIntegration, ReclipSpacingSetsTheReclipsAlone) {
    const glm::dvec2 v(11.4, 3.7), w(-4.1, 1.3);
    RenderJob passing = twoMovingQuads(movingQuad(1.0, 1.0, 31.0, 31.0, 10.0, w), movingQuad(4.3, 6.2, 14.7, 19.9, 6.0, v));
    passing.render.time_integration = TimeIntegration::Sweep;
    passing.render.sweep_spacing = 2.0;
    const RenderResult plain = renderFrame(passing, 0);
    passing.render.reclip_spacing = 2.0;
    const RenderResult same = renderFrame(passing, 0);
    EXPECT_EQ(same.image.find("R")->values, plain.image.find("R")->values);
    for (const auto& [reclip, relative] : {std::tuple{0.25, 63}, {1.0, 16}, {4.0, 4}}) {
        passing.render.reclip_spacing = reclip;
        EXPECT_EQ(renderFrame(passing, 0).stats.clipped().subframes_max_per_tile, relative) << reclip;
    }
}

// Below a pixel, positions s px apart leave an error of order s^2 (midpoint rule), and a fragment that
// strays d px from its path (a roll turns it, the sweep does not) one of order d. Re-clips keep d under
// 0.1 s^2 there, so that the error keeps the positions' order: under a roll of 0.25 rad over a striped
// quad, against a sweep fine in everything (positions 1/32 px apart, 256 re-clips), halving the spacing
// from 0.25 to 0.125 px divides the error by at least 3 (order 2 would give 4). With the tolerance 0.1 s
// (order 1) it divided it by 2.4 (RMS 1.7e-4 to 6.9e-5); with 0.1 s^2, by 4.8 (1.1e-4 to 2.2e-5).
TEST(SweepIntegration, BelowAPixelErrorFallsWithTheSquareOfTheSpacing) {
    RenderJob job = stripedJob();
    Object quad = rasterQuad(-8.0, -8.0, 40.0, 40.0, 6.0);
    quad.material = 1;
    job.scene.objects.push_back(quad);
    job.scene.camera.keys.push_back(
        CameraKey{1.0, glm::dvec3(0.0), glm::dvec3(0, 0, 1), glm::dvec3(std::sin(0.25), std::cos(0.25), 0)});
    job.render.time_integration = TimeIntegration::Sweep;
    job.render.segments = 1;
    job.render.sweep_spacing = 1.0 / 32.0;
    job.render.subframes = 256;
    job.render.max_subframes = 256;
    const RenderResult reference = renderFrame(job, 0);
    job.render.subframes = 0;
    const auto error = [&](double spacing) {
        job.render.sweep_spacing = spacing;
        return rmsDifference(renderFrame(job, 0), reference);
    };
    const double coarse = error(0.25), fine = error(0.125);
    EXPECT_GT(fine, 0.0);
    EXPECT_GT(coarse, 3.0 * fine) << coarse << " " << fine;
}

// Two quads that pass each other in mid-shutter, apart at both ends: what one hides of the other changes
// only in the middle, where grouping objects by what was near a tile at the segment's ends saw no
// relative motion at all. Their swept boxes meet, and the relative motion there, |v - w| = 44 px, sets
// the count (eq. 24). Against point subframes at 96 times: one re-clip, at t = 1/2, finds the far quad
// wholly behind the near one and drops it, though a pixel on its path sees it for 6 / 22 = 0.27 of the
// shutter; auto's count (at sweep_spacing 1), swept with positions 0.05 px apart, does no worse than
// point subframes at that count.
TEST(SweepIntegration, ObjectsPassingInMidShutterReclipForTheirRelativeMotion) {
    const glm::dvec2 v(22.0, 0.0), w(-22.0, 0.0);
    RenderJob job = twoMovingQuads(movingQuad(24.0, 12.0, 30.0, 20.0, 10.0, w), movingQuad(2.0, 10.0, 8.0, 22.0, 6.0, v));
    job.render.subframes = 96;
    const RenderResult reference = renderFrame(job, 0);
    const double once = maxDifference(renderFrame(sweepJob(job, v, 1, 96), 0), reference);
    job.render.subframes = 0;
    job.render.time_integration = TimeIntegration::Sweep;
    const int count = static_cast<int>(renderFrame(job, 0).stats.clipped().subframes_max_per_tile);
    EXPECT_GE(count, 44);
    job.render.subframes = count;
    job.render.sweep_spacing = 0.05;
    const RenderResult automatic = renderFrame(job, 0);
    job.render.time_integration = TimeIntegration::Subframes;
    const double point = rmsDifference(renderFrame(job, 0), reference);
    const double sweep = rmsDifference(automatic, reference);
    EXPECT_GT(once, 0.25);
    EXPECT_LE(sweep, point);
}

// Two crossed bars turning together about the view axis (a propeller's blades, one object each) keep
// what one hides of the other: their image maps are the same turn, so the relative motion is 0 wherever
// they meet, and the turn alone sets the count (0.25 rad: 0.088 px of vertex stray, one re-clip). The
// error against 96 point subframes is then no more than each bar's error turning alone. Turning apart,
// they move relative to each other where they cross: at the corners of the 4 x 4 px square they share at
// the start, 2 sqrt 2 px from the axis, by 2 x 2 sin(0.25 / 2) x 2 sqrt 2 = 1.4 px, so at least 2.
TEST(SweepIntegration, BarsTurningTogetherNeedOneReclip) {
    const auto turning = [](Object bar, double angle) {
        bar.transform.push_back(TransformKey{0.0, glm::dvec3(0.0), {1, 0, 0, 0}, glm::dvec3(1.0)});
        bar.transform.push_back(TransformKey{1.0, glm::dvec3(0.0), glm::angleAxis(angle, glm::dvec3(0, 0, 1)), glm::dvec3(1.0)});
        return bar;
    };
    const auto job = [&](double angle_a, double angle_b, bool a, bool b) {
        RenderJob j = stripedJob();
        Object across = turning(rasterQuad(2.0, 14.0, 30.0, 18.0, 6.0), angle_a), down = turning(rasterQuad(14.0, 2.0, 18.0, 30.0, 5.0), angle_b);
        across.material = down.material = 1;
        if (a) j.scene.objects.push_back(across);
        if (b) j.scene.objects.push_back(down);
        j.render.segments = 1;
        return j;
    };
    const AutoSweep together = autoSweepAgainstPointSubframes(job(0.25, 0.25, true, true));
    const double alone_a = autoSweepAgainstPointSubframes(job(0.25, 0.25, true, false)).rms;
    const double alone_b = autoSweepAgainstPointSubframes(job(0.25, 0.25, false, true)).rms;
    EXPECT_EQ(together.reclips, 1);
    EXPECT_LE(together.rms, alone_a + alone_b);
    EXPECT_GE(autoSweepAgainstPointSubframes(job(0.25, -0.25, true, true)).reclips, 2);
}

// A striped quad at depth 4 before a white wall at depth 10, both still, under an eye moving 1.5 units
// sideways: the quad slides over the wall by k d (1/4 - 1/10) = 16 x 1.5 x 0.15 = 3.6 px (k = 16 px per
// unit at unit depth), at every pixel, so auto re-clips 4 times at sweep_spacing 1, whether the two are
// one object (their parallax, GroupParallax) or two (the difference of their displacements, 6 - 2.4 px).
// A turning camera slides nothing: one re-clip. Against 96 point subframes the auto count errs at most
// half as much as one re-clip, whose frozen visibility misses what the quad uncovers and covers.
TEST(SweepIntegration, StillSurfacesSlideOverEachOtherUnderAMovingEye) {
    const auto job = [](bool one_object, const CameraKey& key) {
        RenderJob j = stripedJob();
        Object wall = rasterQuad(-8.0, -8.0, 40.0, 40.0, 10.0), quad = rasterQuad(9.3, 6.1, 21.7, 25.4, 4.0);
        quad.material = 1;
        if (one_object) {
            const auto base = static_cast<std::uint32_t>(wall.mesh.positions.size());
            for (const glm::dvec3& p : quad.mesh.positions) wall.mesh.positions.push_back(p);
            for (const auto& t : quad.mesh.triangles) wall.mesh.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
            wall.material = 1;  // stripes across x on both: the wall's are 2.5 times as wide at depth 10
        }
        j.scene.objects.push_back(wall);
        if (!one_object) j.scene.objects.push_back(quad);
        j.scene.camera.keys.push_back(key);
        j.render.segments = 1;
        return j;
    };
    const CameraKey sideways{1.0, glm::dvec3(1.5, 0, 0), glm::dvec3(0, 0, 1), glm::dvec3(0, 1, 0)};
    const AutoSweep one = autoSweepAgainstPointSubframes(job(true, sideways));
    EXPECT_EQ(one.reclips, 4);
    EXPECT_EQ(autoSweepAgainstPointSubframes(job(false, sideways)).reclips, 4);
    const CameraKey turn{1.0, glm::dvec3(0.0), glm::dvec3(0.1, 0, 1), glm::dvec3(0, 1, 0)};
    RenderJob turning = job(true, turn);
    turning.render.time_integration = TimeIntegration::Sweep;
    EXPECT_EQ(renderFrame(turning, 0).stats.clipped().subframes_max_per_tile, 1);

    RenderJob frozen = job(true, sideways);
    frozen.render.subframes = 96;
    const RenderResult point = renderFrame(frozen, 0);
    frozen.render.time_integration = TimeIntegration::Sweep;
    frozen.render.subframes = 1;
    frozen.render.sweep_spacing = 0.05;
    EXPECT_LT(one.rms, 0.5 * rmsDifference(renderFrame(frozen, 0), point));
}

// A still backdrop behind everything that moves (a locked-off camera, an object passing a wall) is
// resolved once and seen through what the moving surfaces leave uncovered: pixel = front + (1 - its swept
// coverage) x backdrop, exact where the backdrop is uniform within the pixel. So one re-clip with 48
// positions equals point subframes at the same 48 times to float rounding, and auto needs one re-clip.
// A still surface in front of a moving one is not a backdrop: then the relative motion sets the count.
TEST(SweepIntegration, StillBackdropNeedsNoReclips) {
    const glm::dvec2 v(11.4, 3.7);
    RenderJob job = squareFilmJob();
    job.render.method = Method::Clipped;
    job.scene.objects.push_back(rasterQuad(1.0, 1.0, 31.0, 31.0, 10.0));
    job.scene.objects.push_back(movingQuad(4.3, 6.2, 14.7, 19.9, 6.0, v));
    job.render.subframes = 48;
    const RenderResult reference = renderFrame(job, 0);
    const RenderResult sweep = renderFrame(sweepJob(job, v, 1, 48), 0);
    EXPECT_GT(sweep.stats.clipped().sweep_backdrop_tiles, 0);
    EXPECT_LT(maxDifference(sweep, reference), kFloatTolerance);
    job.render.subframes = 0;
    job.render.time_integration = TimeIntegration::Sweep;
    EXPECT_EQ(renderFrame(job, 0).stats.clipped().subframes_max_per_tile, 1);

    RenderJob behind = squareFilmJob();
    behind.render.method = Method::Clipped;
    behind.render.time_integration = TimeIntegration::Sweep;
    behind.scene.objects.push_back(rasterQuad(1.0, 1.0, 12.0, 31.0, 6.0));
    behind.scene.objects.push_back(movingQuad(4.3, 6.2, 14.7, 19.9, 10.0, v));
    const RenderResult hidden = renderFrame(behind, 0);
    EXPECT_EQ(hidden.stats.clipped().sweep_backdrop_tiles, 0);
    EXPECT_GE(hidden.stats.clipped().subframes_max_per_tile, 12);
}

// A bar turning half a turn about the view axis in one segment lies on the same pixels at both ends, so
// the wall behind it is hidden in both fragment sets although it shows all through the middle of the
// shutter: the paper's frame-0 / frame-1 union has no wall there. The still backdrop is its own still
// frame of the wall alone, so it has it. Reference: the accumulation buffer (512 still clipped renders at
// equally spaced times), independent of both sweeps and fragment sets; its per-pixel error is at most one
// time step's coverage change (the bar's tip moves 44 px in 512 steps: < 0.1 px^2, so < 0.1 per pixel, far
// less in RMS). Point subframes with the same single segment miss the hidden wall: pixels near the bar's
// ends at t = 0 see the black background for most of the shutter instead of the white wall.
TEST(SweepIntegration, BackdropHasWhatBothFramesHide) {
    // The bar's bounding sphere about its pivot, the camera (its ends are |(5.25, 0.56, 6)| = 8.0 away),
    // reaches past a wall at 7.5 but not one at 10: per-tile backdrops (the bar itself stays at depth 6),
    // then one behind everything, which the fragment sets leave out.
    for (const auto& [wall_depth, behind_everything] : {std::pair{7.5, 0}, {10.0, 1}}) {
        RenderJob job = squareFilmJob();
        Material orange;
        orange.base_color = glm::dvec3(0.9, 0.5, 0.1);
        job.scene.materials.push_back(orange);
        job.scene.objects.push_back(rasterQuad(0.0, 0.0, 32.0, 32.0, wall_depth));
        Object bar = rasterQuad(2.0, 14.5, 30.0, 17.5, 6.0);
        bar.material = 1;
        const glm::dvec3 z(0, 0, 1);
        for (int k = 0; k <= 4; ++k)  // keys every 45 degrees: slerp between antipodal keys is undefined
            bar.transform.push_back(TransformKey{k / 4.0, glm::dvec3(0.0),
                                                 glm::angleAxis(k * 0.25 * glm::pi<double>(), z), glm::dvec3(1.0)});
        job.scene.objects.push_back(bar);
        job.render.method = Method::Accumulation;
        job.render.samples = 512;
        const RenderResult reference = renderFrame(job, 0);

        job.render.method = Method::Clipped;
        job.render.segments = 1;
        job.render.time_integration = TimeIntegration::Sweep;
        const RenderResult sweep = renderFrame(job, 0);
        EXPECT_GT(sweep.stats.clipped().sweep_backdrop_tiles, 0);
        EXPECT_EQ(sweep.stats.clipped().backdrop_behind_everything, behind_everything);
        EXPECT_LT(rmsDifference(sweep, reference), 0.01) << wall_depth;
        EXPECT_LT(maxDifference(sweep, reference), 0.1) << wall_depth;

        job.render.time_integration = TimeIntegration::Subframes;
        job.render.subframes = 64;
        const RenderResult point = renderFrame(job, 0);
        EXPECT_GT(maxDifference(point, reference), 0.3) << "the union of both frames misses the wall behind the bar";
    }
}

// A textured backdrop is where compositing by coverage is not exact: in a pixel holding both a moving
// edge and a stripe edge, the part the front covers is charged the pixel's mean backdrop colour instead
// of its own. At one time that errs by at most min(a, 1 - a) x the stripes' contrast (1, channel B) <= 0.5
// for covered fraction a, and only while an edge of the quad is inside the pixel: a horizontal edge
// moving 3.7 px down stays in a pixel row for 1/3.7 of the shutter, a vertical one in a column for 1/11.4.
// So no pixel errs by more than 0.5 / 3.7 = 0.135 against point subframes at the same times, and only
// pixels on the quad's path that also hold a stripe edge err at all.
TEST(SweepIntegration, TexturedBackdropErrsOnlyWhereEdgesMeet) {
    const glm::dvec2 v(11.4, 3.7);
    RenderJob job = stripedJob();
    Object back = rasterQuad(1.0, 1.0, 31.0, 31.0, 10.0);
    back.material = 1;
    job.scene.objects.push_back(back);
    job.scene.objects.push_back(movingQuad(4.3, 6.2, 14.7, 19.9, 6.0, v));
    job.render.subframes = 48;
    const RenderResult reference = renderFrame(job, 0);
    const RenderResult sweep = renderFrame(sweepJob(job, v, 1, 48), 0);
    const double worst = maxDifference(sweep, reference);
    EXPECT_LT(worst, 0.5 / 3.7);
    EXPECT_GT(worst, kFloatTolerance) << "stripe edges under moving edges: the approximation shows";
}

// Surfaces outside the film at a re-clip sweep into it: the film-edge tiles re-clip past the edge.
TEST(SweepIntegration, SurfacesSweepInAcrossTheFilmEdge) {
    const glm::dvec2 v(-9.0, 5.0);
    RenderJob job = squareFilmJob();
    job.render.method = Method::Clipped;
    job.scene.objects.push_back(movingQuad(26.0, -6.0, 38.0, 20.0, 6.0, v));
    job.render.subframes = 8;
    const RenderResult point = renderFrame(job, 0);
    const RenderResult sweep = renderFrame(sweepJob(job, v, 1, 8), 0);
    EXPECT_LT(maxDifference(sweep, point), kFloatTolerance);
}

// Both sweep times; exact with the quad receding too, so paths bend and there are levels to estimate.
TEST(SweepIntegration, BitIdenticalForOneAndTwoThreads) {
    for (const SweepTime time : {SweepTime::Points, SweepTime::Exact}) {
        RenderJob job = squareFilmJob();
        job.render.method = Method::Clipped;
        job.render.time_integration = TimeIntegration::Sweep;
        job.render.sweep_time = time;
        job.render.subframes = 2;  // few re-clips, so fragments sweep across tile borders
        Material checker;
        checker.texture.kind = Texture::Kind::Checker;
        checker.texture.scale = 0.3;
        job.scene.materials.push_back(checker);
        Object back = rasterQuad(0.5, 0.5, 31.5, 31.5, 10.0);
        back.material = 1;
        job.scene.objects.push_back(back);
        Object quad = movingQuad(4.0, 8.0, 12.0, 20.0, 4.0, {9.0, 5.0});
        if (time == SweepTime::Exact) quad.transform[1].translate.z = 1.0;
        job.scene.objects.push_back(quad);
        std::vector<RenderResult> results;
        for (int threads : {1, 2}) {
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
            results.push_back(renderFrame(job, 0));
        }
        for (std::size_t c = 0; c < results[0].image.channels.size(); ++c)
            EXPECT_EQ(results[0].image.channels[c].values, results[1].image.channels[c].values) << c;
        EXPECT_GT(results[0].stats.clipped().sweep_spilled_pixels, 0);
        EXPECT_EQ(results[0].stats.clipped().estimated_error, results[1].stats.clipped().estimated_error);
        if (time == SweepTime::Exact) {
            EXPECT_GT(results[0].stats.clipped().estimated_error, 0.0);
        }
    }
}

// Exact sweep (render.sweep_time exact): a translating striped quad (texture edges inside fragments move
// with the surface) is exact for any intervals and spacing, the same image to float storage (1e-6); point
// subframes converge to it within the midpoint rule's bound, h^2 / 8 x the slope jump (<= 2 |v|) at each
// of a pixel's kinks (<= 2 (|v.x| + |v.y| + 2) edges entering or leaving it), and about as h^2: 8x the
// subframes, at least 16x closer.
TEST(SweepIntegration, ExactSweepIsExactForTranslationWhateverTheIntervalsAndSpacing) {
    const glm::dvec2 v(11.4, 3.7);
    const auto bound = [&](int n) {
        return 2.0 * (std::abs(v.x) + std::abs(v.y) + 2.0) * 2.0 * glm::length(v) / (8.0 * n * n);
    };
    RenderJob job = stripedJob();
    Object quad = movingQuad(4.3, 6.2, 14.7, 19.9, 6.0, v);
    quad.material = 1;
    job.scene.objects.push_back(quad);
    job.render.subframes = 12;
    const RenderResult point = renderFrame(job, 0);
    job.render.subframes = 96;
    const RenderResult fine_point = renderFrame(job, 0);
    job.render.time_integration = TimeIntegration::Sweep;
    job.render.sweep_time = SweepTime::Exact;
    job.render.subframes = 1;
    const RenderResult exact = renderFrame(job, 0);
    // A path that does not bend needs one position: at most one per swept fragment.
    EXPECT_GT(exact.stats.clipped().reclip.sweep_positions, 0);
    EXPECT_LE(exact.stats.clipped().reclip.sweep_positions, exact.stats.clipped().reclip.fragments);
    EXPECT_LT(maxDifference(point, exact), bound(12));
    EXPECT_LT(maxDifference(fine_point, exact), bound(96));
    EXPECT_LT(maxDifference(fine_point, exact), maxDifference(point, exact) / 16.0);
    for (const auto& [intervals, spacing] : {std::pair{3, 1.0}, {12, 0.1}, {1, 50.0}}) {
        job.render.subframes = intervals;
        job.render.sweep_spacing = spacing;
        const RenderResult sweep = renderFrame(job, 0);
        EXPECT_EQ(sweep.stats.clipped().subframes_max_per_tile, intervals);
        EXPECT_LT(maxDifference(sweep, exact), kFloatTolerance) << intervals << " x " << spacing;
        EXPECT_EQ(sweep.stats.clipped().reclip.sweep_unswept, 0);
    }
}

// Exact sweep of the receding striped quad of DollyMatchesPointSubframes: its fragments stretch as it
// shrinks (linearly along each chord, the rectangles exactly), so at spacing 0.05 it matches 96 point
// subframes within their own quadrature bound (3.5e-4). At spacing 1 (3 positions for a corner's sagitta
// of 0.12 px) it errs less than point positions doing the same work do (spacing 4, whose kink floor
// gives no more positions; measured: 5.8e-3 with 660 against 2.4e-2 with 660).
TEST(SweepIntegration, ExactSweepFollowsAStretchingSurface) {
    RenderJob job = recedingStripedQuad();
    job.render.subframes = 96;
    const RenderResult point = renderFrame(job, 0);
    job.render.time_integration = TimeIntegration::Sweep;
    job.render.subframes = 1;
    job.render.sweep_spacing = 4.0;
    const RenderResult positions = renderFrame(job, 0);
    job.render.sweep_spacing = 1.0;
    job.render.sweep_time = SweepTime::Exact;
    const RenderResult chords = renderFrame(job, 0);
    EXPECT_LT(maxDifference(chords, point), maxDifference(positions, point));
    EXPECT_LE(chords.stats.clipped().reclip.sweep_positions, positions.stats.clipped().reclip.sweep_positions);
    job.render.sweep_spacing = 0.05;
    for (const int intervals : {1, 3}) {
        job.render.subframes = intervals;
        const RenderResult sweep = renderFrame(job, 0);
        EXPECT_LT(maxDifference(sweep, point), 3.5e-4) << intervals;
        EXPECT_EQ(sweep.stats.clipped().reclip.sweep_unswept, 0);
    }
}

}  // namespace clipblur
