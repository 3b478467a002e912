#include "renderer/propagation/ode_propagation.h"

#include <algorithm>
#include <cmath>

#include "scene/error.h"

namespace clipblur {

OdePropagator::OdePropagator(const Scene& scene, const Projection& projection, double ts, double te,
                             const OdeStepping& stepping)
    : scene_(scene), start_(scene, projection, ts), end_(scene, projection, te),
      camera_(start_.camera, end_.camera), ts_(ts), te_(te), stepping_{stepping.method, std::max(1, stepping.steps)} {}

std::optional<glm::dvec3> OdePropagator::propagate(const MeshPoint& point, int from, double t) const {
    const ProjectedPoint a = project(start_, scene_, point);
    const ProjectedPoint b = project(end_, scene_, point);
    if ((from == 0 ? a : b).behind) return std::nullopt;
    const VertexOde ode(VertexPath(camera_, a.world, b.world));
    const double f0 = from;
    const double f = (t - ts_) / (te_ - ts_);
    const int steps = std::max(1, static_cast<int>(std::ceil(stepping_.steps * std::abs(f - f0) - 1e-9)));
    glm::dvec3 y;
    try {
        y = f == f0 ? ode.exactState(f0) : integrateFixed(ode, {stepping_.method, steps}, f0, ode.exactState(f0), f);
    } catch (const Error&) {
        return std::nullopt;  // the state crossed the camera plane
    }
    if (!(y.z > 0.0) || !std::isfinite(y.x) || !std::isfinite(y.y)) return std::nullopt;
    const CameraFrame c = camera_.at(f);
    return c.position + y.z * (c.e3 + y.x * c.e1 + y.y * c.e2);
}

}  // namespace clipblur
