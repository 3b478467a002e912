#pragma once

#include <vector>

#include <tbb/enumerable_thread_specific.h>

#include "renderer/clipped/frame_fragments.h"
#include "renderer/clipped/motion_plan.h"
#include "renderer/clipped/subframe_reclip.h"
#include "renderer/frame_setup.h"
#include "renderer/integrate/interval_layout.h"
#include "renderer/integrate/window_sums.h"
#include "renderer/propagation/snapshot_cache.h"

namespace clipblur {

// One shutter segment as its tiles integrate it: the frame and the window written, the segment's span,
// weight and fixed re-clip count, its opening still image, and its plan (the fragment layers, each
// tile's re-clips and, with sweep integration, the intervals the moving tiles share).
struct SegmentIntegration {
    const FrameSetup& frame;
    PixelBounds window;
    SegmentSpan span;
    double weight = 1.0;
    int subframes = 0;           // > 0: the segment's fixed re-clip count (no tile is then taken as still)
    bool shadows = false;        // a moving shadow can change a still tile's lighting
    bool audit = false;          // check every resolved pixel (ReclipStats::audit)
    bool track_objects = false;  // ID mattes
    const PixelSums& still;      // the segment-start image
    bool still_scene = false;    // nothing moves: `still` is every tile's answer
    const FragmentLayers& layers;
    const MotionPlan& motion;
    const SweepSchedule* sweep = nullptr;  // null: point subframes
    const SnapshotCache& snapshots;        // at the re-clip times and sweep intervals' ends
};

// What the tiles of one segment write: their own pixels of the window directly (each tile owns them)
// and, with sweep integration, what they spill into other tiles' pixels, kept per tile in row-major
// order (addSpills). Scratch buffers are per thread, not per task (allocating them is page faults):
// every use clears what it reads, and reclipSubframe starts no TBB work, so a thread never holds its
// scratch across a steal.
struct TileOutputs {
    WindowSums& sums;
    std::vector<std::vector<Spill>>& spills;
    tbb::enumerable_thread_specific<ReclipScratch>& scratches;
};

// Steps 3-5 for tile `index`: per subframe propagate, re-clip and reduce; the tile adds weight x the
// average of its subframes to its pixels, in subframe order (bit-identical for any thread count). Where
// nothing moves (and no moving shadow can change the lighting between the frames) the segment-start
// image is the answer. Writes only the pixels of the window. Returns the tile's re-clip count, or -1
// when nothing it reaches is in the window.
int integrateTile(const SegmentIntegration& segment, int index, TileOutputs& out, ReclipStats& stats);

}  // namespace clipblur
