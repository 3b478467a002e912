#include "renderer/clipped/error_target.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "renderer/clipped/clipped_renderer.h"
#include "renderer/clipped/time_error.h"
#include "renderer/stopwatch.h"

namespace clipblur {

namespace {

constexpr double kPilotSpacing = 1.0;  // px: where the estimate's order 2 holds (docs/performance.md)
constexpr int kPilotSubframes = 27;    // point subframes: 9 groups of three per segment-free shutter
constexpr double kMinSpacing = 0.01, kMaxSpacing = 1000.0;  // render.sweep_spacing's range
constexpr int kMaxCap = 4096;                                 // render.max_subframes' range
constexpr double kMeasuredRatio = 1.5;  // a render this much coarser than the pilot is measured against it
constexpr double kProbeRatio = 4.0;     // a sweep pilot with no estimate is compared with a render this coarser

// The pilot's job: the whole film, the given setting.
RenderJob pilotJob(const RenderJob& job, double spacing, int subframes) {
    RenderJob pilot = job;
    pilot.render.window.reset();
    pilot.render.error_target = 0.0;
    if (job.render.time_integration != TimeIntegration::Subframes)
        pilot.render.sweep_spacing = spacing;
    else
        pilot.render.subframes = subframes;
    return pilot;
}

// Whether two renders of one frame did the same integration work: re-clips and sweep positions.
bool sameWork(const ClippedStats& x, const ClippedStats& y) {
    return x.subframes_total == y.subframes_total && x.reclip.sweep_positions == y.reclip.sweep_positions;
}

// What the target tunes: sweep and auto the spacing in pixels (auto spaces its point subframes by it
// too), point subframes the count; both as an interval between samples (pixels, or the shutter over the
// subframes). `job` is the search's own copy: runPilot may raise its re-clip cap.
struct Tuning {
    RenderJob job;
    bool sweep = true;

    // p coarser than the pilot (error_target.h): 2 where exact sweep integrates time, else 1.
    double coarserOrder() const { return sweep && job.render.sweep_time == SweepTime::Exact ? 2.0 : 1.0; }

    double intervalOf(const RenderJob& j) const { return sweep ? j.render.sweep_spacing : 1.0 / j.render.subframes; }
    // The whole film at `interval`: every choice is made on whole-film renders, so shards choose alike.
    RenderJob at(double interval) const {
        RenderJob out = job;
        out.render.window.reset();
        out.render.error_target = 0.0;
        if (sweep)
            out.render.sweep_spacing = std::clamp(interval, kMinSpacing, kMaxSpacing);
        else
            out.render.subframes = std::clamp(static_cast<int>(std::ceil(1.0 / interval - 1e-9)), 1, job.render.max_subframes);
        return out;
    }
};

// An error known at an interval (pixels of sweep spacing, or 1 / subframes).
struct ErrorAt {
    double interval = 0.0, error = 0.0;
};

// The pilot and where the error model is anchored: an error known at an interval (the pilot's own
// estimate, or a coarser probe's measured difference from the pilot).
struct Pilot {
    RenderResult render;  // what renders well coarser are judged against
    double interval = 0.0, estimate = 0.0;
    double anchor_interval = 0.0, anchor_error = 0.0;
    double coarser_order = 0.0;  // > 0: measured between the anchor and a coarser probe (anchorOnRefinement)
    int renders = 0;
    std::optional<RenderResult> answer;  // a probe that is already the result
    bool second = false;  // finerPilot's: corrections stay where it judges them, and it is the answer over
};

// A sweep pilot with no estimate (every interval has fewer than 3 positions) against a render kProbeRatio
// coarser, the pilot the finer solution. Where both did the same work the spacing does not set the work
// (re-clips leave one position per interval) and the probe is the answer. Else their RMS difference
// anchors the model at the probe when the target's interval can be judged against the pilot; returns
// false where it is finer than that, so the pilot is refined instead.
bool probeCoarser(const Tuning& tuning, int frame, const RenderCallbacks& quiet, Pilot& pilot) {
    const RenderJob job = tuning.at(pilot.interval * kProbeRatio);
    RenderResult probe = renderClipped(job, frame, quiet);
    ++pilot.renders;
    const double difference = rmsDifference(pilot.render.image, probe.image);
    pilot.anchor_interval = tuning.intervalOf(job);
    pilot.anchor_error = difference;
    if (sameWork(pilot.render.stats.clipped(), probe.stats.clipped())) {
        pilot.answer = std::move(probe);
        return true;
    }
    return difference > 0.0 &&
           spacingForTarget(pilot.anchor_interval, difference, tuning.job.render.error_target, tuning.coarserOrder()) >=
               kMeasuredRatio * pilot.interval;
}

// A sweep pilot refined 4x that still has no estimate (re-clips follow the spacing, so they leave about
// as many positions per interval at every spacing): the refined render becomes the pilot, the finer
// solution, and the model is anchored at the coarser one by their difference, E(h) - E(h/4) = (3/4) E(h)
// at order 1, the re-clips' (error_target.h). With the coarser probe's error the order between the two
// is measured and serves targets between them. Where refining changed
// no pixel (or did the same work), no finer setting will: the coarser render is the answer.
void anchorOnRefinement(RenderResult& coarser, double coarser_interval, const ErrorAt& probe, Pilot& pilot) {
    const double difference = rmsDifference(pilot.render.image, coarser.image);
    pilot.anchor_interval = coarser_interval;
    if (!(difference > 0.0) || sameWork(pilot.render.stats.clipped(), coarser.stats.clipped())) {
        pilot.anchor_error = 0.0;
        pilot.answer = std::move(coarser);
        return;
    }
    pilot.anchor_error = difference / 0.75;
    if (probe.error > pilot.anchor_error && probe.interval > coarser_interval)
        pilot.coarser_order =
            std::clamp(std::log(probe.error / pilot.anchor_error) / std::log(probe.interval / coarser_interval), 1.0, 3.0);
}

// The pilot at kPilotSpacing (or kPilotSubframes). Where it has no estimate, a sweep pilot is probed
// coarser, then refined 4x once: it has an estimate there, or is anchored on the refinement
// (anchorOnRefinement). Point subframes are refined 4x, at most twice, until they have one. Where
// max_subframes caps the first sweep pilot's re-clips, it is no finer solution in those tiles, so renders
// judged against it would be judged against its capped error (near_plane at 160x90: 1.7e-4 from the
// reference at 1 px with the default 256, 2.7e-5 with 512): the cap is doubled for the whole search until
// that pilot has no capped tile, up to kMaxCap.
Pilot runPilot(Tuning& tuning, int frame, const RenderCallbacks& quiet) {
    Pilot pilot;
    double spacing = kPilotSpacing;
    int subframes = std::min(kPilotSubframes, tuning.job.render.max_subframes);
    std::optional<RenderResult> coarser;
    ErrorAt probe;  // the coarser probe's difference from the pilot
    for (int attempt = 0; attempt < 3; ++attempt) {
        if (attempt > 0) coarser = std::move(pilot.render);
        pilot.render = renderClipped(pilotJob(tuning.job, spacing, subframes), frame, quiet);
        ++pilot.renders;
        while (attempt == 0 && tuning.sweep && pilot.render.stats.clipped().capped_tiles > 0 &&
               tuning.job.render.max_subframes < kMaxCap) {
            tuning.job.render.max_subframes = std::min(kMaxCap, 2 * tuning.job.render.max_subframes);
            pilot.render = renderClipped(pilotJob(tuning.job, spacing, subframes), frame, quiet);
            ++pilot.renders;
        }
        const double coarser_interval = pilot.interval;
        pilot.interval = tuning.sweep ? spacing : 1.0 / subframes;
        pilot.estimate = pilot.render.stats.clipped().estimated_error;
        pilot.anchor_interval = pilot.interval;
        pilot.anchor_error = pilot.estimate;
        if (pilot.estimate > 0.0 || attempt == 2) break;
        if (tuning.sweep && attempt == 0) {
            if (probeCoarser(tuning, frame, quiet, pilot)) break;
            probe = {.interval = pilot.anchor_interval, .error = pilot.anchor_error};
        }
        if (tuning.sweep && attempt == 1) {
            anchorOnRefinement(*coarser, coarser_interval, probe, pilot);
            break;
        }
        spacing = std::max(kMinSpacing, spacing / 4.0);
        subframes = std::min(tuning.job.render.max_subframes, subframes * 4);
    }
    return pilot;
}

// A render and what it was judged to reach.
struct Choice {
    RenderJob job;
    RenderResult result;
    double reached = 0.0;
};

double reclipSpacing(const RenderJob& job) {
    return job.render.reclip_spacing > 0.0 ? job.render.reclip_spacing : job.render.sweep_spacing;
}

// A render of the re-clip check: the choice's job with re-clips at `spacing`.
struct ReclipRender {
    RenderJob job;
    RenderResult result;
    double count = 0.0, estimate = 0.0;  // re-clips, and the time error its estimate sees
};

ReclipRender renderReclips(const RenderJob& job, double spacing, int frame, const RenderCallbacks& quiet, int& renders) {
    ReclipRender r{job, {}};
    r.job.render.reclip_spacing = std::max(kMinSpacing, spacing);
    r.result = renderClipped(r.job, frame, quiet);
    ++renders;
    r.count = static_cast<double>(r.result.stats.clipped().subframes_total);
    r.estimate = r.result.stats.clipped().estimated_error;
    return r;
}

// How much two renders' re-clip errors differ: their RMS difference less, in quadrature, how much their
// estimated time errors differ (timeErrorDifference). Where re-clips at half the spacing keep the
// positions' times the two time errors are nearly one and cancel in the difference; where they re-lay
// them they are nearly independent and the difference holds both. The rules tried before this one are
// in docs/performance.md ("The re-clip check past a stepped count").
double reclipChange(const RenderResult& fine, const RenderResult& coarse) {
    const double d = rmsDifference(fine.image, coarse.image), t = timeErrorDifference(fine, coarse);
    return std::sqrt(std::max(0.0, d * d - t * t));
}

// The order p of a re-clip error E(c) ~ c^-p at which the changes measured over counts c1 < c2 < c3,
// d12 = E(c1) - E(c2) and d23 = E(c2) - E(c3), agree; held to [1, 2]. Order 2 is the midpoint rule's:
// visibility frozen at the middle of each interval over a coverage smooth between kinks
// (TimeError.ReclipErrorFallsAsTheReclipCountSquared); where visibility changes in ways that rule does
// not follow, the error falls slower; slower than order 1 (the bound the check accepts by) is taken as
// 1. Past 2 the error has left the asymptote: 2 is the safe side.
double reclipOrder(double c1, double c2, double c3, double d12, double d23) {
    const auto ratio = [&](double p) {
        return (std::pow(c1, -p) - std::pow(c2, -p)) / (std::pow(c2, -p) - std::pow(c3, -p));
    };
    double lo = 1.0, hi = 2.0;
    if (!(d23 > 0.0) || d12 >= d23 * ratio(hi)) return hi;
    if (d12 <= d23 * ratio(lo)) return lo;
    for (int i = 0; i < 40; ++i) {  // the ratio rises with p: bisection to well under 1e-6
        const double mid = 0.5 * (lo + hi);
        (d12 > d23 * ratio(mid) ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

// The error a sweep's estimate does not see: visibility frozen between re-clips and fragments carried
// rigidly over surfaces that turn under them. A render with re-clips at half the spacing measures its
// change (reclipChange). At order 1, the slowest the error falls with the re-clip count c (reclipOrder),
// E(c1) - E(c2) = E(c2) (c2 / c1 - 1): the largest error the change allows, so where the choice or the
// finer render meets the target by that, it does. Where neither does, a third render, re-clips halved
// again, measures the order, and the coarser of the two finer renders within 4/3 of the target at that
// order is the answer; where neither is, the re-clips are refined once more at that order, to what the
// time error leaves of the target, by the count's measured response to the spacing.
struct ReclipCheck {
    bool refined = false;  // the re-clip error was over the target: the re-clips were refined
    double order = 0.0;    // the order measured by a third render, where one was made
};

ReclipCheck checkReclips(const Tuning& tuning, int frame, const RenderCallbacks& quiet, Choice& choice, int& renders) {
    const double limit = tuning.job.render.error_target * 4.0 / 3.0;
    const ClippedStats& first = choice.result.stats.clipped();
    const double c1 = static_cast<double>(first.subframes_total), e1 = first.estimated_error;
    // Re-clip counts step with the spacing (a whole count per tile and interval): one halving can leave
    // them where they were (table1_spin: 15 at 1/2, 45 at 1/4), so a second one looks before giving up.
    ReclipRender second = renderReclips(choice.job, reclipSpacing(choice.job) / 2.0, frame, quiet, renders);
    if (!(second.count > c1) && c1 > 0.0)
        second = renderReclips(choice.job, reclipSpacing(choice.job) / 4.0, frame, quiet, renders);
    const double c2 = second.count, e2 = second.estimate;
    if (!(c2 > c1 && c1 > 0.0)) return {};  // the re-clips do not follow the spacing here: nothing to see
    const double d12 = reclipChange(second.result, choice.result);
    const double bound2 = d12 / (c2 / c1 - 1.0);  // E(c2) at order 1
    const double total1 = std::hypot(e1, bound2 * c2 / c1);
    if (total1 <= limit) {
        choice.reached = total1;
        return {};
    }
    choice = {second.job, std::move(second.result), std::hypot(e2, bound2)};
    if (choice.reached <= limit) return {true};
    ReclipRender third = renderReclips(choice.job, reclipSpacing(choice.job) / 2.0, frame, quiet, renders);
    const double c3 = third.count, e3 = third.estimate;
    if (!(c3 > c2)) return {true};  // capped or saturated: the finer render stands, judged at order 1
    const double d23 = reclipChange(third.result, choice.result);
    const double p = reclipOrder(c1, c2, c3, d12, d23);
    const double reclip3 = d23 / (std::pow(c3 / c2, p) - 1.0), total2 = std::hypot(e2, reclip3 + d23);
    if (total2 <= limit) {
        choice.reached = total2;
        return {true, p};
    }
    choice = {third.job, std::move(third.result), std::hypot(e3, reclip3)};
    if (choice.reached <= limit) return {true, p};
    const double target = tuning.job.render.error_target;
    const double budget = std::sqrt(std::max(target * target - e3 * e3, 0.25 * target * target));
    const double response = std::log(c3 / c2) / std::log(2.0);  // count ~ spacing^-response
    const double spacing = reclipSpacing(choice.job) / std::pow(reclip3 / budget, 1.0 / (p * response));
    ReclipRender fourth = renderReclips(choice.job, spacing, frame, quiet, renders);
    const double reclip4 = reclip3 * std::pow(c3 / std::max(1.0, fourth.count), p);
    choice = {fourth.job, std::move(fourth.result), std::hypot(fourth.estimate, reclip4)};
    return {true, p};
}

// Tiles whose re-clips max_subframes caps (counts.capped_tiles) hold visibility frozen longer than the
// spacing asks, and every render that chooses has the cap, the pilots too, so none sees that error
// (near_plane at 160x90, 1.93 px: 1.7e-4 at the default 256, 2.7e-5 at 1024). A render with the cap
// doubled measures it: their difference is E(c) - E(2c), and E(2c) is 0 where no tile is capped any more,
// else taken as E(c) - E(2c), the error falling as the re-clip count. The cap is doubled while the choice
// would miss the target by more than 4/3 beside what was seen.
void raiseCap(const Tuning& tuning, int frame, const RenderCallbacks& quiet, Choice& choice, int& renders) {
    const double limit = tuning.job.render.error_target * 4.0 / 3.0;
    const double seen = choice.reached;
    while (choice.result.stats.clipped().capped_tiles > 0 && choice.job.render.max_subframes < kMaxCap) {
        RenderJob raised = choice.job;
        raised.render.max_subframes = std::min(kMaxCap, 2 * choice.job.render.max_subframes);
        RenderResult result = renderClipped(raised, frame, quiet);
        ++renders;
        const double d = rmsDifference(result.image, choice.result.image);
        const double left = result.stats.clipped().capped_tiles > 0 ? d : 0.0;  // E(2c)
        if (std::hypot(seen, d + left) <= limit) {
            choice.reached = std::hypot(seen, d + left);
            return;
        }
        choice = {raised, std::move(result), std::hypot(seen, left)};
        if (choice.reached <= limit) return;
    }
}

// Each shutter segment (one per kAutoSegmentTurnDegrees of turn) adds two fragment sets and at least one
// re-clip per tile, so where the spacing's work has reached that floor, coarser spacings cost the same
// (shot_plain at 160x90: every spacing from 34 px up does 3 segments, 45 re-clips, 7e-4 from the
// reference) and a target far above the answer's error can only be met by fewer segments. Where the
// answer is under 3/4 of the target and the segments are auto, render.max_segments caps their count (the
// auto rule's deep tiles still keep what a longer segment hides at both ends). A render with fewer is
// judged against the answer, the finer solution: the error it adds is their difference d, taken as
// independent of the answer's own, so hypot(reached, d). The count is set from the error at the fewest
// segments judged within 4/3 of the target, at order 2 in the count until two renders measure it; up to
// kSegmentRenders renders, and the fewest within 4/3 is the answer.
void fewerSegments(const Tuning& tuning, int frame, const RenderCallbacks& quiet, Choice& choice, int& renders) {
    constexpr int kSegmentRenders = 3;
    const double target = tuning.job.render.error_target;
    const long long n = choice.result.stats.clipped().segments;
    if (tuning.job.render.segments != 0 || n < 2 || !(choice.reached < 0.75 * target)) return;
    Choice base = std::move(choice);
    std::optional<Choice> fewest;
    long long over = 0;  // the most segments judged over 4/3 of the target
    double order = 2.0;
    for (int k = 0; k < kSegmentRenders; ++k) {
        const Choice& within = fewest ? *fewest : base;
        const long long count = within.result.stats.clipped().segments;
        const double wanted = static_cast<double>(count) * std::pow(std::max(within.reached, 1e-12) / target, 1.0 / order);
        const long long m = std::max(over + 1, static_cast<long long>(std::ceil(wanted - 1e-9)));
        if (m >= count) break;
        RenderJob job = base.job;
        job.render.max_segments = static_cast<int>(m);
        RenderResult result = renderClipped(job, frame, quiet);
        ++renders;
        const long long got = result.stats.clipped().segments;
        if (got >= count) break;  // the cap did not lower the count (a shutter curve's pieces)
        const double reached = std::hypot(base.reached, rmsDifference(base.result.image, result.image));
        if (reached > target * 4.0 / 3.0) {
            over = std::max(over, got);
            continue;
        }
        if (reached > base.reached && base.reached > 0.0)
            order = std::clamp(std::log(reached / base.reached) / std::log(static_cast<double>(n) / got), 1.0, 3.0);
        fewest = Choice{job, std::move(result), reached};
        if (reached >= 0.75 * target) break;
    }
    choice = fewest ? std::move(*fewest) : std::move(base);
}

// A target finer than the pilot can judge: its render is judged by its own estimate, 0.3 .. 3x off there
// (coincident, fast_motion, seeded random scenes: docs/performance.md). A second pilot at half that
// render's interval judges it against an image instead, and its corrections down to 3/4 of it. The model
// is anchored at the first pilot by its difference from the second: sqrt(e1^2 + e2^2), within 1.2x of e1
// at order 1 and more. None where the setting cannot go finer (max_subframes, the spacing's floor).
std::optional<Pilot> finerPilot(const Tuning& tuning, int frame, const RenderCallbacks& quiet, const Pilot& first, double interval) {
    const RenderJob job = tuning.at(interval / 2.0);
    if (tuning.intervalOf(job) * kMeasuredRatio > interval) return std::nullopt;
    Pilot pilot;
    pilot.render = renderClipped(job, frame, quiet);
    pilot.renders = 1;
    pilot.interval = tuning.intervalOf(job);
    pilot.estimate = pilot.render.stats.clipped().estimated_error;
    pilot.anchor_interval = first.interval;
    pilot.anchor_error = rmsDifference(pilot.render.image, first.render.image);
    pilot.second = true;
    return pilot;
}

// The renders that choose after the pilot, each of the whole film, judged and counted. Those judged
// against the pilot bracket the setting sought: the coarsest within 4/3 of the target, the finest over.
class Search {
  public:
    Search(const Tuning& tuning, int frame, const RenderCallbacks& shown, const Pilot& pilot)
        : renders(pilot.renders), tuning_(tuning), frame_(frame), shown_(shown), pilot_(pilot),
          target_(tuning.job.render.error_target) {}

    int renders = 0, bisections = 0;  // renders: the pilot's too

    bool measured(const RenderJob& j) const { return tuning_.intervalOf(j) >= kMeasuredRatio * pilot_.interval; }
    bool over(double reached) const { return reached > target_ * 4.0 / 3.0; }
    bool within(double reached) const { return !over(reached) && reached >= target_ * 0.75; }

    // A render coarser than the pilot is judged against the pilot image: the two error fields are nearly
    // independent, so the difference is sqrt(e^2 + e_pilot^2), within 1.2x of the render's own e when the
    // pilot's is under 2/3 of it (order >= 1 at 1.5x the interval). Its own estimate falls 1.3-3x short
    // at coarse intervals (docs/performance.md). Error both share (the pilot's re-clips) is not seen.
    Choice render(const RenderJob& job) {
        RenderResult result = renderClipped(job, frame_, shown_);
        ++renders;
        return judge(job, std::move(result));
    }

    Choice judge(const RenderJob& job, RenderResult result) {
        const bool against_pilot = measured(job);
        const double reached = against_pilot ? rmsDifference(pilot_.render.image, result.image) : result.stats.clipped().estimated_error;
        Choice choice{job, std::move(result), reached};
        const double interval = tuning_.intervalOf(job);
        if (against_pilot && over(reached)) over_ = std::min(over_, interval);
        if (against_pilot && !over(reached) && interval > under_) {
            under_ = interval;
            best_ = choice;
        }
        return choice;
    }

    bool correct(Choice& choice);

    // The corrections, then bisection where they end outside 0.75 .. 4/3 of the target against the pilot;
    // the coarsest render within 4/3 replaces `choice`. Returns whether the pilot is the answer (correct).
    bool settle(Choice& choice) {
        const bool keep_pilot = correct(choice);
        if (!measured(choice.job) || within(choice.reached)) return keep_pilot;
        bisect();
        if (!best_) return keep_pilot || (pilot_.second && over(choice.reached));
        choice = std::move(*best_);
        return false;
    }

    // Where the error is no power of the interval (a staircase, a plateau: docs/performance.md, seeded
    // random scenes) the model's corrections can step over the target's setting. Between the coarsest
    // render judged within 4/3 of the target (the pilot before any) and the finest over it, bisection in
    // log interval finds it: up to kBisections renders, until one lands within 0.75 .. 4/3 of the target.
    // A midpoint too near the pilot to be judged against it is moved out to kMeasuredRatio of its interval.
    void bisect() {
        const double judged = kMeasuredRatio * pilot_.interval;
        for (int k = 0; k < kBisections && over_ < kNone; ++k) {
            const RenderJob mid = tuning_.at(std::max(std::sqrt(std::max(under_, pilot_.interval) * over_), judged));
            const double interval = tuning_.intervalOf(mid);
            if (!measured(mid) || interval <= under_ || interval >= over_) break;
            ++bisections;
            if (within(render(mid).reached)) break;
        }
    }

  private:
    static constexpr int kBisections = 3;
    static constexpr double kNone = std::numeric_limits<double>::infinity();
    const Tuning& tuning_;
    int frame_;
    const RenderCallbacks& shown_;
    const Pilot& pilot_;
    double target_;
    double under_ = 0.0, over_ = kNone;
    std::optional<Choice> best_;
};

// Corrections where the model missed by more than 4/3: the order measured between the anchor and this
// render (kept within [1, 3]) carries this render's error to the target. One where the render is finer
// than the pilot (renders are dear there), two where it is measured against it (they are cheap).
// A correction that did the work of the render before it (one sweep position per interval at every
// coarser spacing, as on the facade of many/building_dolly) shows a plateau: the setting no longer
// sets the work between the two. Under the target no coarser setting changes anything, so the
// corrections stop. Over it a finer one does: the order from the anchor to the plateau's error (now
// known at the finer of the two settings) carries it on once more. Returns whether the pilot, made
// already, is the answer where bisection finds none: where that still misses by more than 4/3, where
// the pilot has no estimate and a correction would leave the judgement against it (within
// kMeasuredRatio of the pilot's setting, or finer: nothing there could be judged), and where a render
// judged against the pilot is still twice the target while the pilot's own estimate meets it (the
// estimate sees time sampling alone, and a pilot refined until it had one may owe it to re-clips capped
// at max_subframes).
bool Search::correct(Choice& choice) {
    ClippedStats previous = pilot_.render.stats.clipped();
    bool plateau = false;
    for (int k = 0; k < (measured(choice.job) ? 2 : 1); ++k) {
        const double interval = tuning_.intervalOf(choice.job);
        if (sameWork(previous, choice.result.stats.clipped())) {
            plateau = k > 0;  // the first render repeating the pilot's work is no plateau of corrections
            if (!plateau || !over(choice.reached)) break;
        }
        if (!(choice.reached > 0.0 && pilot_.anchor_error > 0.0) || within(choice.reached) ||
            std::abs(std::log(interval / pilot_.anchor_interval)) <= 1e-6)
            break;
        const double order =
            std::clamp(std::log(choice.reached / pilot_.anchor_error) / std::log(interval / pilot_.anchor_interval), 1.0, 3.0);
        const double floor = pilot_.second ? kMeasuredRatio * pilot_.interval : 0.0;
        const RenderJob corrected = tuning_.at(std::max(floor, interval * std::pow(target_ / choice.reached, 1.0 / order)));
        if (tuning_.intervalOf(corrected) == interval) break;
        if (pilot_.estimate <= 0.0 && choice.reached > target_ && measured(choice.job) && !measured(corrected)) return true;
        previous = choice.result.stats.clipped();
        choice = render(corrected);
    }
    const bool far_over = choice.reached > 2.0 * target_ && pilot_.estimate > 0.0 && pilot_.estimate <= target_;
    return measured(choice.job) && ((plateau && over(choice.reached)) || far_over);
}

}  // namespace

double rmsDifference(const Image& fine, const Image& image) {
    double sum = 0.0;
    std::size_t n = 0;
    for (const char* name : {"R", "G", "B"}) {
        const Image::Channel* a = fine.find(name);
        const Image::Channel* b = image.find(name);
        if (!a || !b) continue;
        const PixelBounds& w = image.window;
        for (int y = w.y0; y < w.y1; ++y)
            for (int x = w.x0; x < w.x1; ++x) {
                const double d = double(b->values[image.index(x, y)]) - a->values[fine.index(x, y)];
                sum += d * d;
                ++n;
            }
    }
    return n > 0 ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
}

double timeErrorDifference(const RenderResult& fine, const RenderResult& result) {
    if (fine.level_differences.empty() || result.level_differences.empty()) return 0.0;
    const PixelBounds& w = result.image.window;
    double sum = 0.0;
    for (int y = w.y0; y < w.y1; ++y)
        for (int x = w.x0; x < w.x1; ++x) {
            const glm::vec4 d = result.level_differences[result.image.index(x, y)] - fine.level_differences[fine.image.index(x, y)];
            for (int c = 0; c < 3; ++c) sum += double(d[c]) * d[c];
        }
    return std::sqrt(sum / (3.0 * static_cast<double>(w.area()))) / levelsPerError();
}

double spacingForTarget(double setting, double estimate, double target, double coarser_order) {
    if (!(estimate > 0.0)) return setting;
    const double r = target / estimate;
    return setting * (r >= 1.0 ? std::pow(r, 1.0 / coarser_order) : std::sqrt(r));
}

RenderResult renderToErrorTarget(const RenderJob& job, int frame, const RenderCallbacks& callbacks) {
    const auto start = Clock::now();
    Tuning tuning{job, job.render.time_integration != TimeIntegration::Subframes};
    const RenderCallbacks quiet{nullptr, callbacks.cancel};
    // A shard's progress is its own window's render at the chosen setting, made last.
    const RenderCallbacks& shown = job.render.window ? quiet : callbacks;
    Pilot pilot = runPilot(tuning, frame, quiet);
    const double pilot_seconds = secondsSince(start);
    const double target = job.render.error_target;
    std::optional<Search> search;
    search.emplace(tuning, frame, shown, pilot);
    const double coarser_order = pilot.coarser_order > 0.0 ? pilot.coarser_order : tuning.coarserOrder();
    Choice choice = pilot.answer ? Choice{tuning.at(pilot.anchor_interval), std::move(*pilot.answer), pilot.anchor_error}
                                 : search->render(tuning.at(spacingForTarget(pilot.anchor_interval, pilot.anchor_error,
                                                                            target, coarser_order)));
    bool keep_pilot = !pilot.answer && search->settle(choice);
    int bisections = search->bisections;
    // A render judged by its own estimate has re-clip error the estimate does not see (checkReclips).
    // Where that is under the target, the time error, which the estimate sees 0.3 .. 3x off, sets the
    // error: a second pilot judges it. Where re-clips set it, their check has judged them and the
    // re-clips were refined; a pilot at a finer spacing would share their error and not see it.
    const bool by_estimate = !pilot.answer && !keep_pilot && !search->measured(choice.job);
    ReclipCheck reclips;
    if (by_estimate && tuning.sweep) reclips = checkReclips(tuning, frame, quiet, choice, search->renders);
    std::optional<Pilot> finer;
    if (by_estimate && !reclips.refined)
        finer = finerPilot(tuning, frame, quiet, pilot, tuning.intervalOf(choice.job));
    if (finer) {
        finer->renders += search->renders;
        search.emplace(tuning, frame, shown, *finer);
        choice = search->judge(choice.job, std::move(choice.result));
        keep_pilot = search->settle(choice);
        bisections += search->bisections;
    }
    Pilot& last = finer ? *finer : pilot;
    if (keep_pilot) choice = {tuning.at(last.interval), std::move(last.render), last.estimate};
    fewerSegments(tuning, frame, quiet, choice, search->renders);
    raiseCap(tuning, frame, quiet, choice, search->renders);
    if (job.render.window) {
        RenderJob shard = choice.job;
        shard.render.window = job.render.window;
        choice.result = renderClipped(shard, frame, callbacks);
        ++search->renders;
    }
    ClippedStats& stats = std::get<ClippedStats>(choice.result.stats.method);
    stats.target = ErrorTargetStats{.error_target = target,
                                    .pilot_estimated_error = pilot.estimate,
                                    .pilot_seconds = pilot_seconds,
                                    .renders = search->renders,
                                    .sweep_spacing = tuning.sweep ? choice.job.render.sweep_spacing : 0.0,
                                    .reclip_spacing = tuning.sweep ? choice.job.render.reclip_spacing : 0.0,
                                    .reclip_order = reclips.order,
                                    .subframes = tuning.sweep ? 0 : choice.job.render.subframes,
                                    .reached_error = choice.reached,
                                    .against_pilot = search->measured(choice.job),
                                    .pilot_kept = keep_pilot,
                                    .bisections = bisections,
                                    .finer_pilot = finer ? finer->interval : 0.0,
                                    .max_subframes = choice.job.render.max_subframes != job.render.max_subframes
                                                         ? choice.job.render.max_subframes : 0,
                                    .max_segments = choice.job.render.max_segments != job.render.max_segments
                                                        ? choice.job.render.max_segments : 0};
    return choice.result;
}

}  // namespace clipblur
