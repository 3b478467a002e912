#pragma once

#include "renderer/render.h"

namespace clipblur {

// render.error_target: a pilot render of the whole film (so every shard of a frame chooses alike) at a
// pilot setting measures estimated_error e0 (time_error.h); the final render's sweep spacing (sweep, and
// auto, whose point subframes it spaces too), or point subframe count, is chosen so that the estimate
// reaches the target:
//     setting x (target / e0)^(1/p),  p = 2 finer than the pilot, p = 1 coarser,
// since positions closer than a pixel leave kinks (midpoint rule, h^2) and positions farther apart leave
// a pixel's value nearly a step (h). Exact sweep (render.sweep_time exact) has no steps: its error is the
// chords' distance from the paths, the square of the spacing either way, so p = 2 coarser too. Where a sweep pilot estimates 0 (fewer than 3 positions in every
// interval), a render 4x coarser is measured against it: where both did the same work that render is the
// answer, else their difference anchors the model at its interval. Where that cannot serve (a target finer
// than the pilot can judge, or point subframes), the pilot is refined 4x: point subframes at most twice,
// until they have an estimate (their setting kept if they never do); a sweep pilot once, and where it still
// has none (sweep re-clips follow the spacing, so every spacing leaves about as few positions per interval)
// the refined render becomes the pilot and the model is anchored at the coarser one, E = 4/3 of their
// difference, with the order to the coarser probe measured (the coarser render is the answer where the
// refinement changed no pixel). Where the render's own estimate then misses the
// target by more than 4/3, the order measured between pilot and render corrects it once (one more
// render). A render at an interval at least 1.5x the pilot's is judged instead by its RMS difference from
// the pilot image (the pilot is the finer solution) and corrected up to twice; a correction that does the
// work of the render before it (a plateau) is carried on finer where it is over the target, and ends the
// corrections where it is under. Where the corrections end on a render judged against the pilot outside
// 0.75 .. 4/3 of the target, the setting is bisected in log interval (up to three renders) between the
// coarsest render judged within 4/3 of it (the pilot before any) and the finest over it, and the coarsest
// within 4/3 is the answer; where there is none, the pilot is where the corrections ended on a plateau or
// twice over the target, else the render over it. Every render that chooses is of the whole film, so
// every shard of a frame chooses alike; a shard then renders its window at the chosen setting. Sweep's
// automatic re-clips are spaced by the spacing too (finer than a pixel as well), so a render coarser than the
// pilot is judged with its re-clip error; the pilot's own is not seen. A sweep
// render judged by its own estimate (which sees sweep positions, not re-clips) is checked against one
// with re-clips at half the spacing (render.reclip_spacing; a quarter where half leaves the count as it
// was): their difference, less in quadrature how much their estimated time errors differ per pixel
// (timeErrorDifference), is the change in re-clip error, bounded by order 1 in the re-clip count. The finer render is
// the answer where the first misses by more than 4/3 at that bound; where the finer one misses too, a
// third render, re-clips halved again, measures the order (1 .. 2: 2 is the midpoint rule's), the coarser
// of the two finer renders that meets the target at it is the answer, and where neither does, one more
// refines the re-clips at that order to what the time error leaves of the target. Where the check finds
// the re-clip error within the target, the time error sets it, and the estimate sees that 0.3 .. 3x
// off: a second pilot at half the render's interval judges the render against its image, and the search
// above runs again from it, its corrections kept where it judges them (1.5x its interval or coarser);
// where they end over the target, the second pilot is the answer. Last, where the answer has tiles whose re-clips max_subframes caps
// (every render that chose had the cap, so none saw that error), a render with the cap doubled measures
// it, and the cap is doubled (up to 4096) until the answer fits within 4/3 of the target beside it. Before
// that, where the answer is under 3/4 of the target with auto segments, fewer segments are tried
// (max_segments), judged against the answer, and the fewest within 4/3 kept: each costs two fragment sets
// and a re-clip per tile, which no coarser spacing removes.
// The first sweep pilot is the finer solution renders are judged against, so where max_subframes caps
// its re-clips the cap is doubled for the whole search until it caps none (up to 4096) before anything
// is judged.
RenderResult renderToErrorTarget(const RenderJob& job, int frame, const RenderCallbacks& callbacks);

// The setting that reaches `target` from a pilot's estimate `estimate` at `setting` (an interval
// between samples: pixels of sweep spacing, or 1 / subframes), by the model above; `coarser_order` is p
// coarser than the pilot (1, or 2 for exact sweep).
double spacingForTarget(double setting, double estimate, double target, double coarser_order = 1.0);

// RMS over R, G and B of `image` minus `fine` over image's window (fine's window must hold it).
double rmsDifference(const Image& fine, const Image& image);

// RMS over R, G and B of the difference of two renders' estimated time errors per pixel
// (RenderResult::level_differences / (3^p - 1), time_error.h) over result's window: near 0 where both
// sample time at the same positions, near the two estimates in quadrature where their positions
// differ. 0 where either has no levels.
double timeErrorDifference(const RenderResult& fine, const RenderResult& result);

}  // namespace clipblur
