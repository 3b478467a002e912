#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "scene/camera.h"

namespace clipblur {

// One demonstration case of the paper's Table 1. The table's "position" columns are the vertex position
// relative to the camera (Figure 1's start_p/end_p), so the camera stays at the origin and the vertex
// moves from (x, y, start_range) to (x, y, end_range).
struct BlurPathCase {
    std::string_view name;
    glm::dvec3 start_view;
    glm::dvec3 start_up;
    glm::dvec3 end_view;
    glm::dvec3 end_up;
    double start_range;
    double end_range;

    CameraMotion cameraMotion() const;
    glm::dvec3 vertexStart(double x, double y) const { return {x, y, start_range}; }
    glm::dvec3 vertexEnd(double x, double y) const { return {x, y, end_range}; }
};

// spin, pan, spin_pan, recede, recede_spin_pan in Table 1 order.
const std::vector<BlurPathCase>& blurPathCases();
std::optional<BlurPathCase> findBlurPathCase(std::string_view name);

// The grid of Figure 1: x, y in {-20, -16, ..., 20}.
std::vector<double> blurPathGrid();

}  // namespace clipblur
