#include "renderer/propagation/vertex_path.h"

#include <cmath>

namespace clipblur {

CameraRotationPath::CameraRotationPath(const CameraMotion& motion) {
    const IntraframeRotation& r = motion.rotation();
    angle_ = r.angle();
    axis_ = glm::transpose(motion.start().basis()) * r.axis();
}

glm::dmat3 CameraRotationPath::at(double f) const {
    // Rodrigues matrix for a rotation by -alpha f about u: cI + (1-c) u u^T - s [u x].
    const double a = angle_ * f;
    const double c = std::cos(a);
    const double s = std::sin(a);
    const double k = 1.0 - c;
    const glm::dvec3& u = axis_;
    // glm is column-major: m[col][row].
    glm::dmat3 m;
    m[0][0] = c + k * u.x * u.x;
    m[1][1] = c + k * u.y * u.y;
    m[2][2] = c + k * u.z * u.z;
    m[1][0] = k * u.x * u.y + s * u.z;
    m[0][1] = k * u.x * u.y - s * u.z;
    m[2][0] = k * u.x * u.z - s * u.y;
    m[0][2] = k * u.x * u.z + s * u.y;
    m[2][1] = k * u.y * u.z + s * u.x;
    m[1][2] = k * u.y * u.z - s * u.x;
    return m;
}

VertexPath::VertexPath(const CameraMotion& camera, const glm::dvec3& start, const glm::dvec3& end)
    : rotation_(camera) {
    const glm::dmat3 to_camera0 = glm::transpose(camera.start().basis());
    start_ = to_camera0 * (start - camera.start().position);
    velocity_ = to_camera0 * ((end - start) - camera.velocity());
}

glm::dvec3 VertexPath::derivative(double f) const {
    const glm::dmat3 q = rotation_.at(f);
    const glm::dvec3 c = cameraCoordinates(q, f);
    const glm::dvec3 dc = -glm::cross(rotation_.angularVelocity(), c) + q * velocity_;
    const double inv = 1.0 / c.z;
    return {(dc.x - c.x * inv * dc.z) * inv, (dc.y - c.y * inv * dc.z) * inv, dc.z};
}

}  // namespace clipblur
