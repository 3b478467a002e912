#pragma once

#include <glm/glm.hpp>

#include "scene/camera.h"

namespace clipblur {

// The camera rotation of one frame interval seen from the camera itself. Components are taken in the
// camera basis at f = 0 (B0), the basis in which eq. 14's R_ij = e_i(0).e_j(1) is written. The vertex's
// camera coordinates at f are c(f) = B(f)^T d(f) = Q(f) B0^T d(f) with Q(f) = B0^T R(f)^T B0: a rotation by
// -alpha f about the axis u = B0^T alpha_hat. Because R(f) leaves alpha_hat fixed, u (and the angular
// velocity w = alpha u) also has constant components in the moving basis B(f).
class CameraRotationPath {
public:
    CameraRotationPath() = default;
    explicit CameraRotationPath(const CameraMotion& motion);

    // Q(f). One sincos; share the result between all vertices propagated to the same f.
    glm::dmat3 at(double f) const;
    double angle() const { return angle_; }
    glm::dvec3 axis() const { return axis_; }                       // u, unit, camera-0 components
    glm::dvec3 angularVelocity() const { return angle_ * axis_; }   // w, constant in the moving basis

private:
    glm::dvec3 axis_{0.0, 0.0, 1.0};
    double angle_ = 0.0;
};

// Exact image-plane path of one vertex over a frame interval (section 2.3): camera position and vertex
// position linear in f, camera basis rotated by R(f). p_i(f) = e_i(f).d(f) / (n(f).d(f)) with d = r - r_c,
// evaluated by rotating d once into the camera frame rather than projecting on three rotated axes.
class VertexPath {
public:
    VertexPath() = default;
    // start/end: world positions of the vertex at f = 0 and f = 1.
    VertexPath(const CameraMotion& camera, const glm::dvec3& start, const glm::dvec3& end);

    // Camera coordinates (e1.d, e2.d, n.d) at f, given q = rotation().at(f).
    glm::dvec3 cameraCoordinates(const glm::dmat3& q, double f) const { return q * (start_ + f * velocity_); }
    // Projection at f given q = rotation().at(f); depth <= 0 means the vertex is not in front of the camera
    // and p is then meaningless (infinite or mirrored).
    ImagePoint at(const glm::dmat3& q, double f) const {
        const glm::dvec3 c = cameraCoordinates(q, f);
        const double inv = 1.0 / c.z;
        return {glm::dvec2(c.x * inv, c.y * inv), c.z};
    }
    ImagePoint at(double f) const { return at(rotation_.at(f), f); }
    // d/df of (p1, p2, depth) along the exact path, from c' = -w x c + Q(f) B0^T d'.
    glm::dvec3 derivative(double f) const;

    const CameraRotationPath& rotation() const { return rotation_; }
    glm::dvec3 startCamera() const { return start_; }        // B0^T d(0)
    glm::dvec3 velocityCamera0() const { return velocity_; } // B0^T d', constant

private:
    CameraRotationPath rotation_;
    glm::dvec3 start_{0.0};
    glm::dvec3 velocity_{0.0};
};

}  // namespace clipblur
