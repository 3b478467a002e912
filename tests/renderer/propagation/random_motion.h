#pragma once

#include <random>

#include <glm/glm.hpp>

#include "scene/camera.h"

namespace clipblur::testing {

// Seeded random camera keys and vertex motions for property tests. Rotations up to `max_turn` radians
// between the keys; vertices placed 3..20 units in front of both camera keys.
struct RandomMotion {
    CameraMotion camera;
    glm::dvec3 start{0.0};
    glm::dvec3 end{0.0};
};

inline glm::dvec3 randomUnit(std::mt19937_64& rng) {
    std::normal_distribution<double> n(0.0, 1.0);
    for (;;) {
        const glm::dvec3 v(n(rng), n(rng), n(rng));
        const double len = glm::length(v);
        if (len > 1e-6) return v / len;
    }
}

inline glm::dmat3 rodrigues(const glm::dvec3& axis, double angle) {
    // Columns are the images of the world axes under a right-handed rotation.
    auto rot = [&](const glm::dvec3& v) {
        return v * std::cos(angle) + axis * glm::dot(axis, v) * (1.0 - std::cos(angle)) +
               glm::cross(axis, v) * std::sin(angle);
    };
    return glm::dmat3(rot({1, 0, 0}), rot({0, 1, 0}), rot({0, 0, 1}));
}

inline RandomMotion randomMotion(std::mt19937_64& rng, double max_turn = 0.6) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::uniform_real_distribution<double> depth(3.0, 20.0);
    const glm::dvec3 pos0(5 * u(rng), 5 * u(rng), 5 * u(rng));
    const glm::dvec3 pos1 = pos0 + glm::dvec3(2 * u(rng), 2 * u(rng), 2 * u(rng));
    const glm::dvec3 view0 = randomUnit(rng);
    const glm::dvec3 up0 = randomUnit(rng);
    const glm::dmat3 turn = rodrigues(randomUnit(rng), max_turn * std::abs(u(rng)));
    const CameraFrame c0 = makeCameraFrame(pos0, view0, up0);
    const CameraFrame c1 = makeCameraFrame(pos1, turn * view0, turn * up0);
    auto inFront = [&](const CameraFrame& c) {
        return c.position + depth(rng) * c.e3 + 0.4 * depth(rng) * (u(rng) * c.e1 + u(rng) * c.e2);
    };
    return {CameraMotion(c0, c1), inFront(c0), inFront(c1)};
}

}  // namespace clipblur::testing
