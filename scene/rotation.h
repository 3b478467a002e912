#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace clipblur {

// The intraframe rotation R(f) = exp(f alpha . tau) of the paper (eq. 15, 19) held as a unit quaternion.
// exp(f alpha . tau) and slerp(identity, q, f) are the same curve; the quaternion form stays well
// conditioned as alpha -> 0 and alpha -> pi, where the axis of eq. 18 is not.
class IntraframeRotation {
public:
    IntraframeRotation() = default;
    // The rotation taking the orthonormal basis b0 (columns) to b1 (columns): R b0 = b1.
    static IntraframeRotation betweenBases(const glm::dmat3& b0, const glm::dmat3& b1);
    explicit IntraframeRotation(const glm::dquat& q);

    double angle() const { return angle_; }       // alpha in [0, pi]
    glm::dvec3 axis() const { return axis_; }     // unit; (0,0,1) when alpha == 0
    glm::dquat quaternion() const { return q_; }
    glm::dmat3 matrix(double f) const;            // R(f)
    glm::dvec3 rotate(const glm::dvec3& v, double f) const;  // R(f) v, Rodrigues form of eq. 20
    glm::dvec3 angularVelocity() const { return angle_ * axis_; }  // constant: d/df R(f) = [alpha x] R(f)

private:
    glm::dquat q_{1.0, 0.0, 0.0, 0.0};
    double angle_ = 0.0;
    glm::dvec3 axis_{0.0, 0.0, 1.0};
};

}  // namespace clipblur
