#pragma once

#include <glm/glm.hpp>

#include "renderer/propagation/vertex_path.h"

namespace clipblur {

// The paper's equations of motion (eq. 11-12) for a vertex's image-plane coordinates, closed with an
// equation for the camera-space depth z = n.(r - r_c) so the state carries everything the right-hand side
// needs: y = (p1, p2, z). The paper's sqrt(1+|p|^2)/|r - r_c| equals 1/z for a vertex in front of the
// camera (see docs/vertex-dynamics.md); using 1/z keeps the equations right for z < 0 as well.
class VertexOde {
public:
    explicit VertexOde(const VertexPath& path);

    // dy/df at (f, y).
    glm::dvec3 derivative(double f, const glm::dvec3& y) const;
    // The exact state at f, for initial values and for reference.
    glm::dvec3 exactState(double f) const;
    // The paper's omega: e1 . de2/df = -alpha alpha_hat . n, constant over the frame (erratum to eq. 23).
    double omega() const { return -w_.z; }

private:
    VertexPath path_;
    glm::dvec3 w_{0.0};  // angular velocity, components in the moving camera basis (constant)
};

enum class OdeMethod { Euler, Rk4 };

// A fixed-step integrator: the method and how many equal steps.
struct OdeStepping {
    OdeMethod method = OdeMethod::Rk4;
    int steps = 1;
};

// Fixed-step integration from (f0, y0) to f1; f1 < f0 integrates backward, as needed for triangles
// propagated from the end of the frame. Throws a Render error when steps < 1 or the state stops being
// finite (the vertex crossed the camera plane).
glm::dvec3 integrateFixed(const VertexOde& ode, const OdeStepping& stepping, double f0, const glm::dvec3& y0,
                          double f1);

struct AdaptiveResult {
    glm::dvec3 y{0.0};
    int accepted = 0;
    int rejected = 0;
    int evaluations = 0;  // right-hand side evaluations
};

// RK4 with step doubling: each step is compared with two half steps, the local error estimate is
// |y_half - y_full| / 15 in the norm max(|dp1|, |dp2|, |dz| / |z|), and the Richardson-extrapolated
// (fifth-order) value is kept. Tolerance is per step. Throws a Render error when the step size underflows
// or the step budget (kMaxAdaptiveSteps) is exhausted.
inline constexpr int kMaxAdaptiveSteps = 100000;
AdaptiveResult integrateAdaptive(const VertexOde& ode, double f0, const glm::dvec3& y0, double f1, double tolerance);

}  // namespace clipblur
