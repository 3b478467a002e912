#include "scene/rotation.h"

#include <cmath>

namespace clipblur {

IntraframeRotation IntraframeRotation::betweenBases(const glm::dmat3& b0, const glm::dmat3& b1) {
    // Both bases are orthonormal, so b0^-1 = b0^T.
    return IntraframeRotation(glm::quat_cast(b1 * glm::transpose(b0)));
}

IntraframeRotation::IntraframeRotation(const glm::dquat& q) {
    q_ = glm::normalize(q);
    if (q_.w < 0.0) q_ = -q_;  // the shorter of the two arcs, so alpha <= pi
    const glm::dvec3 v(q_.x, q_.y, q_.z);
    const double s = glm::length(v);
    // atan2 keeps full precision for small and for near-pi angles, unlike acos(trace) of eq. 17.
    angle_ = 2.0 * std::atan2(s, q_.w);
    axis_ = s > 0.0 ? v / s : glm::dvec3(0.0, 0.0, 1.0);
}

glm::dvec3 IntraframeRotation::rotate(const glm::dvec3& v, double f) const {
    const double a = angle_ * f;
    const double c = std::cos(a);
    const double s = std::sin(a);
    return v * c + axis_ * glm::dot(axis_, v) * (1.0 - c) + glm::cross(axis_, v) * s;
}

glm::dmat3 IntraframeRotation::matrix(double f) const {
    return glm::dmat3(rotate({1.0, 0.0, 0.0}, f), rotate({0.0, 1.0, 0.0}, f), rotate({0.0, 0.0, 1.0}, f));
}

}  // namespace clipblur
