#include "renderer/camera_path.h"

#include <algorithm>

namespace clipblur {

CameraPath::CameraPath(const Camera& camera) : exact_(camera.motion) {
    if (exact_) return;
    for (const CameraKey& k : camera.keys) {
        times_.push_back(k.time);
        frames_.push_back(makeCameraFrame(k.position, k.view, k.up));
    }
    for (std::size_t i = 0; i + 1 < frames_.size(); ++i) segments_.emplace_back(frames_[i], frames_[i + 1]);
}

CameraFrame CameraPath::at(double t) const {
    // Same branches and arithmetic as evalCamera.
    if (exact_) return exact_->at(t);
    if (frames_.empty()) return {};
    if (frames_.size() == 1 || t <= times_.front()) return frames_.front();
    if (t >= times_.back()) return frames_.back();
    const auto next = std::upper_bound(times_.begin(), times_.end(), t);
    const std::size_t i = static_cast<std::size_t>(next - times_.begin()) - 1;
    const double f = (t - times_[i]) / (times_[i + 1] - times_[i]);
    return segments_[i].at(f);
}

CameraTable::CameraTable(const CameraPath& path, double t0, double t1, int steps) : t0_(t0) {
    if (!(t1 > t0) || steps < 1) {
        frames_.push_back(path.at(t0));
        return;
    }
    steps_per_time_ = steps / (t1 - t0);
    frames_.reserve(static_cast<std::size_t>(steps) + 1);
    for (int i = 0; i <= steps; ++i) frames_.push_back(path.at(i == steps ? t1 : t0 + (t1 - t0) * i / steps));
    last_ = static_cast<double>(steps);
}

}  // namespace clipblur
