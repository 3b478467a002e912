#pragma once

#include <glm/vec3.hpp>

#include "renderer/image.h"

namespace clipblur {

// What a compositor expects of a rendered image, applied just before it is written.

// Composites `background` under the premultiplied colour ("over": RGB += (1 - A) background) and makes
// the image opaque (A = 1), so a later "over" cannot add the background a second time. The coverage
// AOV, when present, keeps the surfaces' covered fraction.
void bakeBackground(Image& image, const glm::dvec3& background);

// Replaces the renderers' motion.x / motion.y (raster displacement from shutter open to close, y down)
// by forward.u / forward.v: the mean image velocity over the shutter in pixels per frame with y up, the
// convention of Nuke's VectorBlur. `shutter_frames` is close - open; a zero-length shutter has no
// measurable motion and gives zero vectors. No-op when the image has no motion channels.
void toForwardVectors(Image& image, double shutter_frames);

}  // namespace clipblur
