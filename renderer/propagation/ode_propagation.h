#pragma once

#include <optional>

#include <glm/glm.hpp>

#include "renderer/propagation/surface_path.h"
#include "renderer/propagation/vertex_ode.h"

namespace clipblur {

// The paper's propagation (sections 2.3 and 3.2, eq. 11-12) as a render option beside the exact path.
// Over one shutter segment [ts, te] the camera moves as one CameraMotion (position linear, basis turned
// by R(f) on SO(3)) and a surface point moves on the straight line between its positions at ts and te:
// the paper's model, exact for a still or translating surface seen by a camera without keys inside the
// segment, a chord for rotating objects. The point's image-plane state (p1, p2, z) is integrated with
// Euler or RK4 from the segment end its fragment was clipped at to the subframe time.
class OdePropagator {
public:
    // `steps` are ODE steps over the whole segment; a subframe at distance |df| from the start end
    // integrates ceil(steps |df|) of them (at least one).
    OdePropagator(const Scene& scene, const Projection& projection, double ts, double te, const OdeStepping& stepping);

    // World position at time t of the point integrated from segment end `from` (0: ts, 1: te); empty
    // when the point is not in front of the camera at that end or the integration crosses the camera
    // plane (the caller then uses the exact path).
    std::optional<glm::dvec3> propagate(const MeshPoint& point, int from, double t) const;

private:
    const Scene& scene_;
    MotionSnapshot start_;
    MotionSnapshot end_;
    CameraMotion camera_;
    double ts_;
    double te_;
    OdeStepping stepping_;
};

}  // namespace clipblur
