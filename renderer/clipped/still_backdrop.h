#pragma once

#include <vector>

#include "renderer/clipped/frame_fragments.h"
#include "renderer/frame_setup.h"
#include "scene/job.h"

namespace clipblur {

// Sweep integration under a camera that stays still all shutter, without shadows: the still objects can
// form a backdrop, split off behind what moves near a tile (planMotion), resolved once as a still frame of
// their own and composited under the moving surfaces' swept coverage.
struct Backdrop {
    std::vector<char> objects;  // per object: still all shutter; empty when no backdrop can exist
    // Every still object stays behind every moving one all shutter (the moving ones' bounding spheres
    // against the still ones' vertices): the fragment sets can leave the backdrop out and every tile
    // composites over it.
    bool behind_everything = false;

    bool empty() const { return objects.empty(); }
};

// Empty for a moving camera, shadows (moving objects would cast them on the backdrop), point subframes
// (time_integration subframes, or auto with a fixed subframe count), or when nothing or everything is
// still. Under auto a backdrop behind everything makes every segment sweep (the fragment sets leave it out).
Backdrop findBackdrop(const RenderJob& job, const FrameMotion& motion);

// The backdrop's image: the still objects alone, resolved and shaded as a still frame. With no light
// moving and no shadows it looks the same at every time, and since nothing else is in it, the parts that
// moving objects hide at both ends of a segment are there too (the frame-0 / frame-1 union misses them).
// At `time`, with the frame's projection, tiles and callbacks.
PixelSums renderBackdrop(const RenderJob& job, const FrameSetup& frame, const Backdrop& backdrop, double time,
                         FrameFragmentStats& stats);

}  // namespace clipblur
