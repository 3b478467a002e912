#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/job_loader.h"
#include "renderer/propagation/ode_propagation.h"
#include "renderer/render.h"

namespace clipblur {

namespace {

RenderJob table1(const std::string& name, std::vector<std::string> overrides = {}) {
    overrides.insert(overrides.end(), {"film.width=48", "film.height=27", "render.tile_size=16"});
    return loadJob(std::string(CLIPBLUR_SOURCE_DIR) + "/configs/table1/" + name + ".yaml", overrides);
}

// Largest distance from the exact surface point at t over a few points of the wall and times, for
// points integrated from shutter open (forward) and from shutter close (backward).
double worstError(const RenderJob& job, OdeMethod method, int steps) {
    const Scene& scene = job.scene;
    const Projection projection(scene.film.width, scene.film.height, scene.camera.vfov_degrees);
    const OdePropagator ode(scene, projection, 0.0, 1.0, {method, steps});
    double worst = 0.0;
    for (std::uint32_t tri : {0u, 7u, 31u}) {
        const MeshPoint point{0, tri, glm::dvec3(0.2, 0.5, 0.3)};
        for (double t : {0.125, 0.5, 0.875}) {
            const glm::dvec3 exact = project(MotionSnapshot(scene, projection, t), scene, point).world;
            for (int from : {0, 1}) {
                const auto moved = ode.propagate(point, from, t);
                EXPECT_TRUE(moved.has_value());
                if (moved) worst = std::max(worst, glm::length(*moved - exact));
            }
        }
    }
    return worst;
}

}  // namespace

// The wall of the Table 1 jobs is still and the camera has keys at 0 and 1 only: the paper's model is
// exact there, so RK4 must converge to the exact path at fourth order and Euler at first order.
TEST(OdePropagation, ConvergesToTheExactPathOnTable1Moves) {
    for (const char* name : {"recede_spin_pan", "spin_pan"}) {
        const RenderJob job = table1(name);
        const double euler8 = worstError(job, OdeMethod::Euler, 8);
        const double euler64 = worstError(job, OdeMethod::Euler, 64);
        const double rk4_8 = worstError(job, OdeMethod::Rk4, 8);
        const double rk4_64 = worstError(job, OdeMethod::Rk4, 64);
        // First order: 8x the steps divides the error by ~8 (accept 5-11); fourth order by ~4096
        // (accept > 1000 unless both are at rounding, ~1e-12 world units at range 10).
        EXPECT_GT(euler8 / euler64, 5.0) << name;
        EXPECT_LT(euler8 / euler64, 11.0) << name;
        EXPECT_GT(euler8, 1e-3) << name;  // the Euler error is real, not rounding
        EXPECT_TRUE(rk4_64 < 1e-10 || rk4_8 / rk4_64 > 1000.0) << name << " " << rk4_8 << " " << rk4_64;
        EXPECT_LT(rk4_64, 1e-8) << name;
    }
}

// Rendered with path_method rk4 the image equals the exact-path render to float rounding; with one
// Euler step per segment it visibly does not (edges land in the wrong place).
TEST(OdePropagation, RenderWithRk4MatchesExactPaths) {
    const RenderResult exact = renderFrame(table1("spin_pan", {"render.subframes=8", "render.audit=true"}), 0);
    const RenderResult rk4 = renderFrame(
        table1("spin_pan", {"render.subframes=8", "render.path_method=rk4", "render.ode_steps=64", "render.audit=true"}), 0);
    const RenderResult euler = renderFrame(
        table1("spin_pan", {"render.subframes=8", "render.path_method=euler", "render.ode_steps=1"}), 0);
    double rk4_diff = 0.0, euler_diff = 0.0;
    for (std::size_t c = 0; c < 3; ++c) {
        for (std::size_t i = 0; i < exact.image.channels[c].values.size(); ++i) {
            const double e = exact.image.channels[c].values[i];
            rk4_diff = std::max(rk4_diff, std::abs(rk4.image.channels[c].values[i] - e));
            euler_diff = std::max(euler_diff, std::abs(euler.image.channels[c].values[i] - e));
        }
    }
    EXPECT_EQ(rk4.stats.clipped().reclip.ode_fallbacks, 0);
    EXPECT_LT(rk4_diff, 1e-5);
    EXPECT_GT(euler_diff, 1e-3);
}

}  // namespace clipblur
