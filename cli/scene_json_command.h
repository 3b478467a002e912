#pragma once

#include <optional>

#include <nlohmann/json.hpp>

#include "scene/job.h"

namespace clipblur::cli {

// The loaded, expanded scene of a job as JSON (primitives as meshes, keys as the renderer sees them), for
// external peers such as scripts/bench/cycles_peer.py that must rebuild the exact geometry:
//   film {width, height, background}, camera {vfov, keys [{time, position, view, up}]},
//   shutter {open, close}, frames {first, last, fps}, frame (the first), ambient, render {method,
//   samples, seed, shadows}, lights [{type, color, intensity, direction, position}], materials
//   [{base_color, texture {kind none|checker|stripe, color2, scale}, two_sided, unlit, emission, image,
//   emission_image (image files, "" for none)}], objects [{name, material, positions, triangles, transform
//   [{time, translate, rotate [w, x, y, z], scale}], deformation [{time, positions}], exact_motion, smooth
//   (has shading normals), uvs, posed {time, positions} (with `at` only)}].
// exact_motion: the object moves by glTF tracks evaluated exactly (docs/config.md, "glTF scenes"), which
// neither transform nor deformation keys show; `posed` holds every object's world-space vertices at time
// `at` however it moves (what a peer or a check compares against the source's own pose).
// Times are absolute, in frames; vectors are [x, y, z]; doubles keep full precision.
nlohmann::json sceneJson(const RenderJob& job, const std::optional<double>& at = std::nullopt);

}  // namespace clipblur::cli
