#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/camera.h"
#include "scene/scene.h"

namespace clipblur::testing {

// Scene builders and an independent reference projection for propagation tests.

// A still camera at the origin looking along +z with +y up; film and field of view as given.
Scene stillCameraScene(int width = 640, int height = 360, double vfov_degrees = 40.0);

// One triangle, no motion.
Object triangleObject(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

// Appends a transform key (rotation given as axis and angle in radians).
void addTransformKey(Object& object, double time, const glm::dvec3& translate,
                     const glm::dvec3& axis = {0, 0, 1}, double angle = 0.0, const glm::dvec3& scale = glm::dvec3(1.0));

// A randomly moving scene: a camera with three keys (one inside [0, 1]) that translates, pans and
// spins, and objects some ten units in front of it with random rigid motion, scale and deformation keys.
Scene randomMovingScene(std::uint64_t seed, int objects = 3);

// The surface point's raster position and camera depth at time t, computed the slow obvious way:
// sum_i b_i evalVertex(...) projected with evalCamera(t).
struct ReferencePoint {
    glm::dvec2 raster;
    double depth;
};
ReferencePoint referenceProjection(const Scene& scene, const Projection& projection, std::uint32_t object,
                                   std::uint32_t triangle, const glm::dvec3& b, double t);

}  // namespace clipblur::testing
