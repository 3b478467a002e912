#include "renderer/propagation/vertex_ode.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "scene/error.h"

namespace clipblur {

VertexOde::VertexOde(const VertexPath& path) : path_(path), w_(path.rotation().angularVelocity()) {}

glm::dvec3 VertexOde::exactState(double f) const {
    const ImagePoint ip = path_.at(f);
    return {ip.p.x, ip.p.y, ip.depth};
}

glm::dvec3 VertexOde::derivative(double f, const glm::dvec3& y) const {
    const double p1 = y.x;
    const double p2 = y.y;
    const double inv_z = 1.0 / y.z;
    // (r' - r_c') in the camera basis at f: e_i(f).d' = e_i(0).R(f)^T d'.
    const glm::dvec3 v = path_.rotation().at(f) * path_.velocityCamera0();
    // n' = w x n, so e1.n' = w2 and e2.n' = -w1 (components in the moving basis are constant).
    const double e1_dn = w_.y;
    const double e2_dn = -w_.x;
    const double p_dn = p1 * e1_dn + p2 * e2_dn;
    const double omega = -w_.z;
    // Eq. 11 and 12 with sqrt(1+|p|^2)/|r - r_c| written as 1/z.
    const double dp1 = -p2 * omega + (v.x - p1 * v.z) * inv_z - (e1_dn + p1 * p_dn);
    const double dp2 = p1 * omega + (v.y - p2 * v.z) * inv_z - (e2_dn + p2 * p_dn);
    // z = n.d: z' = n'.d + n.d' = z (n'.p) + n.d', using d = z (p + n) and n'.n = 0.
    const double dz = y.z * p_dn + v.z;
    return {dp1, dp2, dz};
}

namespace {

bool isFinite(const glm::dvec3& y) { return std::isfinite(y.x) && std::isfinite(y.y) && std::isfinite(y.z); }

// A step that lands on or across the camera plane (depth changes sign) has stepped over the pole of
// p = c / z; its end value may look finite but the path in between is not.
void checkSameSide(const glm::dvec3& before, const glm::dvec3& after, double f) {
    if (!isFinite(after) || !(before.z * after.z > 0.0))
        throw Error(ExitCode::Render,
                    "vertex path crosses the camera plane (depth 0) near f = " + std::to_string(f));
}

[[noreturn]] void throwRenderError(const std::string& message) { throw Error(ExitCode::Render, message); }

glm::dvec3 rk4Step(const VertexOde& ode, double f, const glm::dvec3& y, double h) {
    const glm::dvec3 k1 = ode.derivative(f, y);
    const glm::dvec3 k2 = ode.derivative(f + 0.5 * h, y + 0.5 * h * k1);
    const glm::dvec3 k3 = ode.derivative(f + 0.5 * h, y + 0.5 * h * k2);
    const glm::dvec3 k4 = ode.derivative(f + h, y + h * k3);
    return y + (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
}

double errorNorm(const glm::dvec3& diff, const glm::dvec3& y) {
    return std::max({std::abs(diff.x), std::abs(diff.y), std::abs(diff.z) / std::max(std::abs(y.z), 1e-300)});
}

}  // namespace

glm::dvec3 integrateFixed(const VertexOde& ode, const OdeStepping& stepping, double f0, const glm::dvec3& y0,
                          double f1) {
    const OdeMethod method = stepping.method;
    const int steps = stepping.steps;
    if (steps < 1) throwRenderError("ODE step count must be at least 1, got " + std::to_string(steps));
    const double h = (f1 - f0) / steps;
    glm::dvec3 y = y0;
    for (int i = 0; i < steps; ++i) {
        // Times from the index, not by accumulation, so the last step lands on f1 exactly.
        const double f = f0 + i * h;
        const glm::dvec3 next = method == OdeMethod::Euler ? y + h * ode.derivative(f, y) : rk4Step(ode, f, y, h);
        checkSameSide(y, next, f);
        y = next;
    }
    return y;
}

AdaptiveResult integrateAdaptive(const VertexOde& ode, double f0, const glm::dvec3& y0, double f1,
                                 double tolerance) {
    constexpr int max_steps = kMaxAdaptiveSteps;
    if (!(tolerance > 0.0)) throwRenderError("ODE tolerance must be positive");
    AdaptiveResult result;
    result.y = y0;
    const double span = f1 - f0;
    if (span == 0.0) return result;
    const double direction = span > 0.0 ? 1.0 : -1.0;
    const double min_step = 1e-12 * std::abs(span);
    double f = f0;
    double h = span;
    while (direction * (f1 - f) > 0.0) {
        if (result.accepted + result.rejected >= max_steps)
            throwRenderError("adaptive ODE exceeded " + std::to_string(max_steps) + " steps");
        if (direction * (f + h - f1) > 0.0) h = f1 - f;
        const glm::dvec3 full = rk4Step(ode, f, result.y, h);
        const glm::dvec3 half = rk4Step(ode, f, result.y, 0.5 * h);
        const glm::dvec3 both = rk4Step(ode, f + 0.5 * h, half, 0.5 * h);
        result.evaluations += 12;
        const glm::dvec3 diff = (both - full) / 15.0;
        const double err = isFinite(full) && isFinite(both) ? errorNorm(diff, both) : HUGE_VAL;
        // Fifth-order step-size law with the usual safety factor, growth and shrink capped.
        const double scale =
            err == 0.0 ? 5.0 : std::clamp(0.9 * std::pow(tolerance / err, 0.2), 0.2, 5.0);
        if (err <= tolerance) {
            const bool last = f + h == f1 || direction * (f + h - f1) >= 0.0;
            checkSameSide(result.y, both + diff, f);
            f = last ? f1 : f + h;
            result.y = both + diff;
            ++result.accepted;
        } else {
            ++result.rejected;
        }
        h *= scale;
        if (std::abs(h) < min_step && direction * (f1 - f) > 0.0)
            throwRenderError("adaptive ODE step size underflow near f = " + std::to_string(f) +
                             " (vertex crossing the camera plane?)");
    }
    return result;
}

}  // namespace clipblur
