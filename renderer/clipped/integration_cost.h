#pragma once

#include <span>

#include "renderer/clipped/motion_plan.h"

namespace clipblur {

// time_integration auto: the tile stage's cost of one shutter segment under point subframes and under
// sweep, estimated from the two plans' counts alone (no render), in units of propagating one fragment
// triangle in one re-clip. At equal sample spacing the two reach about the same time-sampling error
// (point subframes put vertices `spacing` pixels apart as sweep positions do), so the cheaper plan is the
// cheaper at equal error (both take kinkSamples' floor where motion is short). Per moving tile
// (max_sweep_pixels > 0) with F fragment triangles and R pixels resolved per re-clip (MotionPlan::resolved):
//     points  n (F + kPixelCost R)                                            n: its point subframes
//     sweep   N kSweepReclipCost (F + kPixelCost R) + kPositionCost P R       N: re-clips, P: positions
// A re-clip costs per triangle propagated and per pixel resolved; a sweep re-clip resolves an apron too
// and keeps per-pixel sweep state; a sweep position costs per resolved pixel moved and rasterised.
// Sweep's N is the segment's shared re-clip count, its R without a still backdrop split off. The
// constants are fitted to measured tile-stage seconds (docs/performance.md, "time_integration auto").
struct IntegrationCost {
    double points = 0.0, sweep = 0.0;
};
IntegrationCost integrationCost(const MotionPlan& points, const MotionPlan& sweep, std::span<const int> positions);

// The points half of integrationCost.
double pointsCost(const MotionPlan& points);

// The least sweep can cost on the tiles of a point-subframe plan: one re-clip per moving tile and no
// positions. Sweep's tiles hold the same fragments where no still backdrop is split off, so where this is
// no less than the points' cost, sweep need not be planned at all.
double sweepFloor(const MotionPlan& points);

}  // namespace clipblur
