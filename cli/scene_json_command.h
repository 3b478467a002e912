#pragma once

#include <nlohmann/json.hpp>

#include "scene/job.h"

namespace clipblur::cli {

// The loaded, expanded scene of a job as JSON (primitives as meshes, keys as the renderer sees them), for
// external peers such as scripts/bench/cycles_peer.py that must rebuild the exact geometry:
//   film {width, height, background}, camera {vfov, keys [{time, position, view, up}]},
//   shutter {open, close}, frames {first, last, fps}, frame (the first), ambient, render {method,
//   samples, seed, shadows}, lights [{type, color, intensity, direction, position}], materials
//   [{base_color, texture {kind none|checker|stripe, color2, scale}, two_sided, unlit, emission}], objects [{name,
//   material, positions, triangles, transform [{time, translate, rotate [w, x, y, z], scale}],
//   deformation [{time, positions}]}].
// Times are absolute, in frames; vectors are [x, y, z]; doubles keep full precision.
nlohmann::json sceneJson(const RenderJob& job);

}  // namespace clipblur::cli
