#pragma once

#include <algorithm>
#include <memory>
#include <vector>

#include "scene/camera.h"
#include "scene/exact_camera.h"

namespace clipblur {

// evalCamera with the key frames and per-segment rotations built once: at(t) returns exactly (bit for
// bit) what evalCamera(camera, t) returns, without re-orthonormalising keys and re-deriving the segment
// rotation for every ray. An exact glTF camera is evaluated from its chain, as evalCamera does.
class CameraPath {
public:
    explicit CameraPath(const Camera& camera);
    CameraFrame at(double t) const;

    // The camera's exact motion, or null for a keyed camera.
    const ExactCamera* exact() const { return exact_.get(); }

private:
    std::shared_ptr<const ExactCamera> exact_;
    std::vector<double> times_;
    std::vector<CameraFrame> frames_;     // per key
    std::vector<CameraMotion> segments_;  // between keys i and i+1
};

// The camera at `steps` + 1 evenly spaced times over [t0, t1], read back by linear interpolation
// between neighbours, so a renderer that asks for the camera once per ray does no trigonometry.
// Between two entries a basis turning at a constant rate leaves its arc by at most (angle step)^2 / 8
// radians (1.5e-10 for the paper's 0.14 rad spin/pan in 4096 steps); across a key inside the window,
// where the turn changes, by at most half the angle step.
class CameraTable {
public:
    CameraTable(const CameraPath& path, double t0, double t1, int steps);
    // Inline: called once per ray.
    CameraFrame at(double t) const {
        const double u = std::clamp((t - t0_) * steps_per_time_, 0.0, last_);
        const std::size_t i = static_cast<std::size_t>(u);
        if (i + 1 >= frames_.size()) return frames_.back();
        const double f = u - static_cast<double>(i);
        const CameraFrame& a = frames_[i];
        const CameraFrame& b = frames_[i + 1];
        return {a.position + f * (b.position - a.position), a.e1 + f * (b.e1 - a.e1), a.e2 + f * (b.e2 - a.e2),
                a.e3 + f * (b.e3 - a.e3)};
    }

private:
    double t0_ = 0.0;
    double steps_per_time_ = 0.0;  // 0 for a window of no length: entry 0 always
    double last_ = 0.0;            // the last entry's index
    std::vector<CameraFrame> frames_;
};

}  // namespace clipblur
