#pragma once

#include <vector>

#include "renderer/clipped/frame_fragments.h"
#include "renderer/render.h"
#include "renderer/tiles.h"

namespace clipblur {

// Sweep integration under a camera that stays still all shutter, without shadows: per object, whether it
// is still and so can be part of a backdrop (planMotion splits it off behind what moves near a tile).
// Empty when no backdrop can exist (a moving camera, shadows that moving objects would cast on it, point
// subframes, or nothing still).
std::vector<char> backdropObjects(const RenderJob& job, double t0, double t1);

// The backdrop's image: the still objects alone, resolved and shaded as a still frame. With no light
// moving and no shadows it looks the same at every time, and since nothing else is in it, the parts that
// moving objects hide at both ends of a segment are there too (the frame-0 / frame-1 union misses them).
PixelSums renderBackdrop(const RenderJob& job, const std::vector<char>& backdrop_objects, double time,
                         const Projection& projection, const TileGrid& grid, const RenderCallbacks& callbacks,
                         FrameFragmentStats& stats);

}  // namespace clipblur
