#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/frame_motion.h"
#include "scene/camera.h"

namespace clipblur {

// How far two surfaces of one motion group (motionGroups) slide over each other in the image over a
// window. The group's motion carries all of it alike, so only where the eye is relative to the group can
// change what one of its surfaces hides of another: by parallax, none when the eye keeps its place
// relative to the group (a camera that only turns, or one riding along with it). Measured exactly, not
// from the surfaces' affine screen maps, whose perspective error is not motion.
class GroupParallax {
public:
    GroupParallax(const FrameMotion& motion, const Projection& projection, const MotionWindow& window,
                  const std::vector<std::uint32_t>& groups);

    // Whether the eye moves relative to `group` (its first object) over the window.
    bool slides(std::uint32_t group) const { return slides_[group] != 0; }
    // The distance in pixels between the images at the window's end of the two surface points that lie
    // on the ray through `raster` at its start, at inverse depths wa and wb; 0 when either is not in
    // front of the camera at both ends.
    double between(std::uint32_t group, const glm::dvec2& raster, double wa, double wb) const;

private:
    const Projection& projection_;
    CameraFrame open_, close_;
    std::vector<glm::dmat4> carry_;  // per group's first object: world at the start to world at the end
    std::vector<char> slides_;
};

}  // namespace clipblur
