#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/clipped/fragment_triangle.h"
#include "renderer/geometry/swept_footprint.h"
#include "renderer/propagation/subframes.h"
#include "renderer/propagation/surface_path.h"
#include "renderer/tiles.h"

namespace clipblur {

// How far a point on `path` travels over its sweep interval: twice its reach from the interval's middle
// (SweepPath::reach). The reach rule is stated in this one measure: sweepPositions spaces an interval's
// positions by it, a re-clip sweeps a fragment only while it stays within its interval's reach
// (SweepInterval::sweeps), and sweepInterval sizes a tile's reach and apron by the plan's bound on it.
inline double pathTravel(const SweepPath& path) { return 2.0 * path.reach(); }

// A turning camera over a sweep interval [begin, end]: its turn from the middle to each of `positions`
// equally spaced times (the midpoints, as the sweep places fragments) and the inverse turns at begin and
// end; no turns when its orientation is the same at all positions. The same for every tile of the interval.
struct IntervalTurns {
    std::vector<glm::dmat3> at_positions;
    glm::dmat3 unturn_begin{1.0}, unturn_end{1.0};
};
IntervalTurns intervalTurns(const Scene& scene, const Projection& projection, double begin, double end, int positions);

// Sweep integration (render.time_integration: sweep): the subframe at time t stands for the interval
// [begin, end] around it. Each re-clipped fragment is moved along the path of the surface point under its
// centroid (the parabola through its exact positions at begin, t and end), stretched along the raster axes
// as the surface under it stretches (a dolly), and placed at `positions` equally spaced times, the same
// times for every fragment of the interval: fragments sampled at different
// times would open cracks and overlaps along their shared edges. Visibility stays as resolved at t, so for
// what moves in the image without changing what it hides this equals point subframes at all those times;
// that is why re-clips can be spaced by relative motion and path curvature alone.
struct SweepInterval {
    const MotionSnapshot* begin = nullptr;
    const MotionSnapshot* end = nullptr;
    int positions = 1;
    // A path travelling farther than reach (px, pathTravel) is not swept: the fragment stays a point sample
    // at t. The tile plan bounds every path by it; only paths it could not measure (camera plane) exceed it.
    double reach = 0.0;
    PixelBounds resolve;  // the pixels to re-clip: the tile, grown past the film edge by what can sweep in
    PixelBounds box;      // the pixels the sweep can reach: resolve grown by reach / 2 + 1
    // A turning camera's turns over the interval, shared by its tiles; null when it does not turn.
    const IntervalTurns* turns = nullptr;
    // Per object, its motion group (MotionPlan::groups): a pixel's fragments of one group move alike.
    std::span<const std::uint32_t> groups;
    double tilt = 0.0;  // the shutter curve over the interval (SweepPath::tilt); 0 for a box
    bool exact = false;  // render.sweep_time exact: chords integrated exactly (chord_sweep.h), else positions

    bool sweeps(const SweepPath& path) const { return pathTravel(path) <= reach; }
};

// The sweep interval layout of a moving tile with n re-clips: its fragments travel at most reach pixels
// during an interval (the plan bounds speed x interval by max_sweep_pixels / n; twice that allows for the
// peak speed falling between the plan's samples), so they land up to the apron, reach / 2 + 1 pixels, past
// where they are re-clipped. Tiles on the film edge also re-clip that far outside it, where nothing else
// would, because surfaces there sweep into the film. The snapshots, positions, turns, groups and tilt are
// the caller's.
SweepInterval sweepInterval(const PixelBounds& tile, double max_sweep_pixels, int n, const PixelBounds& film);

// How sweep positions are laid out: `intervals` equal intervals of [t0, t1], at most `spacing` pixels and
// at most `max_positions` positions apart; `exact` for render.sweep_time exact. `reach`: the largest reach
// of a tile over an interval (largestReach); a fragment travelling farther is swept by no tile.
struct SweepLayout {
    double t0 = 0.0, t1 = 1.0;
    int intervals = 1;
    double spacing = 1.0;
    int max_positions = 1;
    bool exact = false;
    double reach = std::numeric_limits<double>::infinity();
    double shutter_share = 1.0;  // the layout's share of the frame's shutter (kinkSamples)
};

// Sweep integration: the positions of each of the layout's equal intervals of [t0, t1], shared by every fragment
// (equal times keep shared edges closed) and spaced so that no fragment vertex travels more than `spacing`
// pixels between them during that interval (pathTravel: along the parabola through its positions at the
// interval's ends and middle, as a swept fragment moves), and at least kinkSamples' floor for the
// interval's share of the shutter: positions are midpoint samples in time as point subframes are, and
// a short travel errs as much at a pixel an edge crosses. An interval where things move slowly (the end of
// a dolly away) gets fewer positions than one where they move fast. Vertices at or behind the camera plane
// are left out (they are not swept, see SweepInterval::reach), and a vertex counts a travel of at most
// `reach`: only what travels no farther is swept (a piece of a triangle reaching the camera plane, cut to
// a pixel where it is on a tile), so the positions follow what is swept, not a vertex far off the image.
// Exact sweep integrates each fragment exactly along the chords between positions, so they serve only to
// follow how paths bend: a path whose chord over the interval strays by d pixels at the middle (its
// sagitta: the middle position's distance from the ends' midpoint, which also sees a speed that changes
// along a straight path) strays by d / n^2 with n chords. There an interval gets bendLength / spacing
// positions over the vertices' largest bendLength: no chord strays more than kBendTolerance spacing^2
// pixels, and a path that does not bend needs one position however far it travels. A path that travels
// at most `reach` strays at most reach / 2 from its chord, so bends count up to that.
std::vector<int> sweepPositions(const Scene& scene, const Projection& projection, const FragmentLayers& layers,
                                const SweepLayout& layout);

// Exact sweep: at sweep_spacing 1 no chord strays farther than this from its path (px).
inline constexpr double kBendTolerance = 1.0 / 64.0;

// Exact sweep's measure of a path through a, m and b at an interval's start, middle and end:
// sqrt(sagitta / kBendTolerance), in pixels, so that positions = bendLength / spacing.
double bendLength(const glm::dvec2& a, const glm::dvec2& m, const glm::dvec2& b);

// The intervals a segment's moving tiles share under sweep (planMotion gives them one count): the largest
// tile count, at least 1.
int sharedIntervals(std::span<const SubframePlan> tiles);

// The largest reach (SweepInterval::reach) of a moving tile of the plan under sweep: sweepInterval's for
// the tile's count.
double largestReach(std::span<const SubframePlan> tiles);

// A turning camera's turns over each of positions.size() equal intervals of [t0, t1], at that interval's
// positions (intervalTurns).
std::vector<IntervalTurns> turnsPerInterval(const Scene& scene, const Projection& projection, double t0, double t1,
                                            std::span<const int> positions);

// The sweep intervals a segment's moving tiles share: their count (sharedIntervals) and per interval its
// positions (sweepPositions) and a turning camera's turns (turnsPerInterval).
struct SweepSchedule {
    int intervals = 1;
    std::vector<int> positions;
    std::vector<IntervalTurns> turns;
    bool exact = false;  // render.sweep_time exact
};

// A shutter segment's span and the shutter curve's weight at its ends (ShutterSegment; equal for a box).
struct SegmentSpan {
    double t0 = 0.0, t1 = 1.0;
    double curve_begin = 1.0, curve_end = 1.0;
};

// A tile's n subframes over a segment: their times (the midpoints, subframeTimes; one when n is 0), half
// an interval, and per subframe the shutter curve's weight relative to its mean over the segment (linear
// there, so the midpoints' factors average to 1 exactly in exact arithmetic) and, for sweep, the curve's
// slope over the interval relative to its weight at the interval's middle (SweepPath::tilt). A box gives
// factors of exactly 1 and tilts of 0.
struct SubframeLayout {
    std::vector<double> times;
    double half = 0.0;
    std::vector<double> factors;
    std::vector<double> tilts;
};
SubframeLayout subframeLayout(const SegmentSpan& span, int n);

}  // namespace clipblur
