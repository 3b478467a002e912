#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace clipblur {

// One clipped triangle of the paper's eq. 2, kept as three points on its mesh triangle (barycentrics)
// rather than as image-plane positions: wherever the mesh triangle goes, the same three surface points
// give the triangle's exact image at that time, with its range. Its colour is the surface's shading at
// the frame the triangle was made in; that is a property of the surface points, so it is evaluated on the
// re-clipped pieces (renderer/clipped/subframe_reclip.h) rather than stored: one value per stored
// triangle would blur textures and lighting over triangles larger than a pixel.
struct FragmentTriangle {
    std::uint32_t object = 0;
    std::uint32_t triangle = 0;
    std::array<glm::dvec3, 3> bary{};
};

class OdePropagator;
struct MotionSnapshot;

// A fragment triangle of frame 0 (layer 0) or frame 1 (layer 1), in 4 bytes: a segment's tiles hold
// about ten per fragment triangle. index < 2^31.
class FragmentRef {
public:
    FragmentRef() = default;
    FragmentRef(std::uint32_t index, std::uint32_t layer) : bits_(index << 1 | (layer & 1u)) {}
    std::uint32_t index() const { return bits_ >> 1; }
    std::uint32_t layer() const { return bits_ & 1u; }

private:
    std::uint32_t bits_ = 0;
};

// The fragment triangles of both frames.
struct FragmentLayers {
    std::array<const std::vector<FragmentTriangle>*, 2> triangles{};
    // With the motion AOV, the shutter's open and close (the frame's, not a segment's): a re-clipped piece
    // moves as the surface point at its centroid does between them. Null without the AOV.
    std::array<const MotionSnapshot*, 2> shutter{};
    const OdePropagator* ode = nullptr;  // render.path_method euler/rk4: the paper's ODE, else exact paths
};

}  // namespace clipblur
