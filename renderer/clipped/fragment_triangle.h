#pragma once

#include <array>
#include <cstdint>

#include <glm/glm.hpp>

namespace clipblur {

// One clipped triangle of the paper's eq. 2, kept as three points on its mesh triangle (barycentrics)
// rather than as image-plane positions: wherever the mesh triangle goes, the same three surface points
// give the triangle's exact image at that time, with its range. Colour is the shaded value at the frame
// the triangle was made in.
struct FragmentTriangle {
    std::uint32_t object = 0;
    std::uint32_t triangle = 0;
    std::array<glm::dvec3, 3> bary{};
    glm::vec3 colour{0.0f};
};

}  // namespace clipblur
