#include "renderer/propagation/blur_path_cases.h"

namespace clipblur {

CameraMotion BlurPathCase::cameraMotion() const {
    const glm::dvec3 origin(0.0);
    return CameraMotion(makeCameraFrame(origin, start_view, start_up), makeCameraFrame(origin, end_view, end_up));
}

const std::vector<BlurPathCase>& blurPathCases() {
    static const std::vector<BlurPathCase> cases = {
        {"spin", {0, 0, 1}, {0, 1, 0}, {0, 0, 1}, {0.1, 1, 0}, 10.0, 10.0},
        {"pan", {0, 0, 1}, {0, 1, 0}, {0, 0.1, 1}, {0, 1, 0}, 10.0, 10.0},
        {"spin_pan", {0, 0, 1}, {0, 1, 0}, {0, 0.1, 1}, {0.1, 1, 0}, 10.0, 10.0},
        {"recede", {0, 0, 1}, {0, 1, 0}, {0, 0, 1}, {0, 1, 0}, 10.0, 20.0},
        {"recede_spin_pan", {0, 0, 1}, {0, 1, 0}, {0, 0.1, 1}, {0.1, 1, 0}, 10.0, 20.0},
    };
    return cases;
}

std::optional<BlurPathCase> findBlurPathCase(std::string_view name) {
    for (const BlurPathCase& c : blurPathCases())
        if (c.name == name) return c;
    return std::nullopt;
}

std::vector<double> blurPathGrid() {
    std::vector<double> grid;
    for (int i = -20; i <= 20; i += 4) grid.push_back(i);
    return grid;
}

}  // namespace clipblur
