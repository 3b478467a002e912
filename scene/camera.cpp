#include "scene/camera.h"

#include <algorithm>
#include <cmath>

#include "scene/exact_camera.h"

namespace clipblur {

CameraFrame makeCameraFrame(const glm::dvec3& position, const glm::dvec3& view, const glm::dvec3& up,
                            const FileLoc& loc) {
    const double view_len = glm::length(view);
    if (!(view_len > 0.0) || !std::isfinite(view_len)) throwSceneError(loc, "camera view direction is zero or not finite");
    CameraFrame frame;
    frame.position = position;
    frame.e3 = view / view_len;
    // Gram-Schmidt: the part of up orthogonal to the view.
    const glm::dvec3 up_perp = up - frame.e3 * glm::dot(up, frame.e3);
    const double up_len = glm::length(up_perp);
    if (!(up_len > 1e-9 * std::max(1.0, glm::length(up))))
        throwSceneError(loc, "camera up direction is zero or parallel to the view direction");
    frame.e1 = up_perp / up_len;
    frame.e2 = glm::cross(frame.e3, frame.e1);
    return frame;
}

ImagePoint projectToImagePlane(const CameraFrame& camera, const glm::dvec3& world) {
    const glm::dvec3 d = world - camera.position;
    const double depth = glm::dot(camera.e3, d);
    return {glm::dvec2(glm::dot(camera.e1, d), glm::dot(camera.e2, d)) / depth, depth};
}

CameraMotion::CameraMotion(const CameraFrame& start, const CameraFrame& end)
    : start_(start), end_(end), rotation_(IntraframeRotation::betweenBases(start.basis(), end.basis())) {}

CameraFrame CameraMotion::at(double f) const {
    if (f == 0.0) return start_;
    if (f == 1.0) return end_;
    CameraFrame frame;
    frame.position = start_.position + f * (end_.position - start_.position);
    frame.e1 = rotation_.rotate(start_.e1, f);
    frame.e2 = rotation_.rotate(start_.e2, f);
    frame.e3 = rotation_.rotate(start_.e3, f);
    return frame;
}

CameraFrame evalCamera(const Camera& camera, double t) {
    if (camera.motion) return camera.motion->at(t);
    const auto& keys = camera.keys;
    if (keys.empty()) return {};
    auto frameOf = [](const CameraKey& k) { return makeCameraFrame(k.position, k.view, k.up); };
    if (keys.size() == 1 || t <= keys.front().time) return frameOf(keys.front());
    if (t >= keys.back().time) return frameOf(keys.back());
    const auto next = std::upper_bound(keys.begin(), keys.end(), t,
                                       [](double time, const CameraKey& k) { return time < k.time; });
    const CameraKey& k0 = *(next - 1);
    const CameraKey& k1 = *next;
    const double f = (t - k0.time) / (k1.time - k0.time);
    return CameraMotion(frameOf(k0), frameOf(k1)).at(f);
}

Projection::Projection(int w, int h, double vfov_degrees)
    : width(w), height(h), tan_half_vfov(std::tan(0.5 * vfov_degrees * M_PI / 180.0)) {}

glm::dvec2 Projection::toRaster(const glm::dvec2& p) const {
    const double k = pixelsPerUnit();
    return {0.5 * width + p.y * k, 0.5 * height - p.x * k};
}

glm::dvec2 Projection::toImagePlane(const glm::dvec2& raster) const {
    const double k = pixelsPerUnit();
    return {(0.5 * height - raster.y) / k, (raster.x - 0.5 * width) / k};
}

}  // namespace clipblur
