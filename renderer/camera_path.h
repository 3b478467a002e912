#pragma once

#include <vector>

#include "scene/camera.h"

namespace clipblur {

// evalCamera with the key frames and per-segment rotations built once: at(t) returns exactly (bit for
// bit) what evalCamera(camera, t) returns, without re-orthonormalising keys and re-deriving the segment
// rotation for every ray.
class CameraPath {
public:
    explicit CameraPath(const Camera& camera);
    CameraFrame at(double t) const;

private:
    std::vector<double> times_;
    std::vector<CameraFrame> frames_;     // per key
    std::vector<CameraMotion> segments_;  // between keys i and i+1
};

}  // namespace clipblur
