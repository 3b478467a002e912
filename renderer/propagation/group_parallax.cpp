#include "renderer/propagation/group_parallax.h"

#include <algorithm>
#include <cmath>

#include "scene/object_motion.h"

namespace clipblur {

GroupParallax::GroupParallax(const FrameMotion& motion, const Projection& projection, const MotionWindow& window,
                             const std::vector<std::uint32_t>& groups)
    : projection_(projection), open_(motion.camera(window.t0)), close_(motion.camera(window.t1)) {
    const Scene& scene = motion.scene();
    carry_.assign(groups.size(), glm::dmat4(1.0));
    slides_.assign(groups.size(), 0);
    // Rounding of the eye's place at the scene's scale is not motion.
    const double tolerance = 1e-9 * (1.0 + glm::length(open_.position) + glm::length(close_.position));
    for (std::size_t o = 0; o < groups.size(); ++o) {
        if (groups[o] != o) continue;
        const Object& object = scene.objects[o];
        carry_[o] = worldMatrix(object, window.t1) * glm::inverse(worldMatrix(object, window.t0));
        const glm::dvec3 eye = glm::dvec3(carry_[o] * glm::dvec4(open_.position, 1.0));
        slides_[o] = glm::length(eye - close_.position) > tolerance ? 1 : 0;
    }
}

double GroupParallax::between(std::uint32_t group, const glm::dvec2& raster, double wa, double wb) const {
    if (!(wa > 0.0) || !(wb > 0.0)) return 0.0;
    const glm::dvec2 p = projection_.toImagePlane(raster);
    const glm::dvec3 ray = open_.e3 + p.x * open_.e1 + p.y * open_.e2;  // unit depth along e3
    const glm::dmat4& carry = carry_[group];
    glm::dvec2 image[2];
    const double w[2] = {wa, wb};
    for (int k = 0; k < 2; ++k) {
        const glm::dvec3 world = glm::dvec3(carry * glm::dvec4(open_.position + ray / w[k], 1.0));
        const ImagePoint q = projectToImagePlane(close_, world);
        if (!(q.depth > 0.0)) return 0.0;
        image[k] = projection_.toRaster(q.p);
    }
    return glm::length(image[0] - image[1]);
}

}  // namespace clipblur
