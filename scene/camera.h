#pragma once

#include <glm/glm.hpp>

#include "scene/rotation.h"
#include "scene/scene.h"

namespace clipblur {

// Orthonormal right-handed camera basis of the paper: e1 = up (made orthogonal to the view),
// e2 = e3 x e1 (image right), e3 = n = view.
struct CameraFrame {
    glm::dvec3 position{0.0};
    glm::dvec3 e1{0.0, 1.0, 0.0};
    glm::dvec3 e2{-1.0, 0.0, 0.0};
    glm::dvec3 e3{0.0, 0.0, 1.0};

    glm::dmat3 basis() const { return glm::dmat3(e1, e2, e3); }
};

// Throws a scene error when view is zero or parallel to up.
CameraFrame makeCameraFrame(const glm::dvec3& position, const glm::dvec3& view, const glm::dvec3& up,
                            const FileLoc& loc = {});

// Paper eq. 3 and 6: image-plane coordinates (p1 along up, p2 along right) of a point at unit focal
// distance, and the camera-space depth n.(r - rc). Valid for depth > 0.
struct ImagePoint {
    glm::dvec2 p{0.0};  // (p1, p2)
    double depth = 0.0;
};
ImagePoint projectToImagePlane(const CameraFrame& camera, const glm::dvec3& world);

// One segment between two camera keys: position linear in f, basis rotated by R(f) (section 2.3).
class CameraMotion {
public:
    CameraMotion() = default;
    CameraMotion(const CameraFrame& start, const CameraFrame& end);

    CameraFrame at(double f) const;
    glm::dvec3 velocity() const { return end_.position - start_.position; }  // d rc / df
    const IntraframeRotation& rotation() const { return rotation_; }
    const CameraFrame& start() const { return start_; }
    const CameraFrame& end() const { return end_; }

private:
    CameraFrame start_;
    CameraFrame end_;
    IntraframeRotation rotation_;
};

// The camera at absolute time t (frames): its exact motion when it has one, else the key segment
// containing t, held constant outside the keys.
CameraFrame evalCamera(const Camera& camera, double t);

// Image plane (p1, p2) to raster coordinates (x right, y down, pixel centres at +0.5) and back.
struct Projection {
    int width = 0;
    int height = 0;
    double tan_half_vfov = 0.0;

    Projection(int width, int height, double vfov_degrees);
    double pixelsPerUnit() const { return 0.5 * height / tan_half_vfov; }
    glm::dvec2 toRaster(const glm::dvec2& p) const;
    glm::dvec2 toImagePlane(const glm::dvec2& raster) const;
    double pixelArea() const { return 1.0 / (pixelsPerUnit() * pixelsPerUnit()); }  // a_p of eq. 24
};

}  // namespace clipblur
