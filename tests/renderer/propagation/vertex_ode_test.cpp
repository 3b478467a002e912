#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "random_motion.h"
#include "renderer/propagation/blur_path_cases.h"
#include "renderer/propagation/vertex_ode.h"
#include "scene/error.h"

namespace clipblur {
namespace {

using testing::randomMotion;

TEST(VertexOde, RightHandSideMatchesFiniteDifferencesOfExactPath) {
    std::mt19937_64 rng(31);
    std::uniform_real_distribution<double> uf(0.05, 0.95);
    int checked = 0;
    for (int i = 0; i < 500; ++i) {
        const auto m = randomMotion(rng);
        const VertexOde ode(VertexPath(m.camera, m.start, m.end));
        const double f = uf(rng);
        const glm::dvec3 y = ode.exactState(f);
        if (y.z < 1.0) continue;
        const double h = 1e-5;
        const glm::dvec3 fd = (ode.exactState(f + h) - ode.exactState(f - h)) / (2.0 * h);
        const glm::dvec3 rhs = ode.derivative(f, y);
        // Central differences: truncation h^2 |y'''| / 6 ~ 1e-9, rounding ~1e-16 * 20 / h ~ 1e-10.
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(rhs[k], fd[k], 1e-7 * (1.0 + std::abs(fd[k]))) << i << " " << k;
        ++checked;
    }
    EXPECT_GT(checked, 400);
}

// Least-squares slope of log(error) against log(steps); -slope is the observed order.
double observedOrder(OdeMethod method, const std::vector<int>& ladder) {
    const auto c = *findBlurPathCase("recede_spin_pan");
    const VertexOde ode(VertexPath(c.cameraMotion(), c.vertexStart(20, 20), c.vertexEnd(20, 20)));
    const glm::dvec3 exact = ode.exactState(1.0);
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int n : ladder) {
        const glm::dvec3 y = integrateFixed(ode, {method, n}, 0.0, ode.exactState(0.0), 1.0);
        const double err = glm::length(glm::dvec2(y.x - exact.x, y.y - exact.y));
        // Stay well above round-off so the slope measures truncation only.
        EXPECT_GT(err, 1e-12) << "ladder reaches round-off at " << n << " steps";
        const double lx = std::log(static_cast<double>(n)), ly = std::log(err);
        sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
    }
    const double k = static_cast<double>(ladder.size());
    return -(k * sxy - sx * sy) / (k * sxx - sx * sx);
}

TEST(VertexOde, EulerConvergesAtFirstOrder) {
    // Asymptotic order 1; the ladder starts at 16 steps where higher-order terms are below ~10 %.
    const double order = observedOrder(OdeMethod::Euler, {16, 32, 64, 128, 256, 512});
    EXPECT_GT(order, 0.8);
    EXPECT_LT(order, 1.2);
}

TEST(VertexOde, Rk4ConvergesAtFourthOrder) {
    // Asymptotic order 4; 4..128 steps keeps errors between ~1e-4 and ~1e-11, above round-off.
    const double order = observedOrder(OdeMethod::Rk4, {4, 8, 16, 32, 64, 128});
    EXPECT_GT(order, 3.5);
    EXPECT_LT(order, 4.5);
}

TEST(VertexOde, Rk4TracksExactPathOnAllTable1Cases) {
    for (const BlurPathCase& c : blurPathCases())
        for (double x : blurPathGrid())
            for (double y : blurPathGrid()) {
                const VertexOde ode(VertexPath(c.cameraMotion(), c.vertexStart(x, y), c.vertexEnd(x, y)));
                glm::dvec3 state = ode.exactState(0.0);
                for (int k = 1; k <= 20; ++k) {
                    state = integrateFixed(ode, {OdeMethod::Rk4, 2}, (k - 1) / 20.0, state, k / 20.0);
                    const glm::dvec3 exact = ode.exactState(k / 20.0);
                    // 40 RK4 steps over the frame: error ~1e-9 at the grid corners (see convergence chart).
                    EXPECT_NEAR(state.x, exact.x, 1e-8) << c.name << " " << x << "," << y;
                    EXPECT_NEAR(state.y, exact.y, 1e-8) << c.name << " " << x << "," << y;
                }
            }
}

TEST(VertexOde, BackwardFromEndOfFrame) {
    std::mt19937_64 rng(32);
    for (int i = 0; i < 50; ++i) {
        const auto m = randomMotion(rng);
        const VertexOde ode(VertexPath(m.camera, m.start, m.end));
        const glm::dvec3 y = integrateFixed(ode, {OdeMethod::Rk4, 200}, 1.0, ode.exactState(1.0), 0.3);
        const glm::dvec3 exact = ode.exactState(0.3);
        // 200 RK4 steps of 0.0035: truncation far below 1e-9 for these motions.
        EXPECT_NEAR(y.x, exact.x, 1e-9);
        EXPECT_NEAR(y.y, exact.y, 1e-9);
        EXPECT_NEAR(y.z, exact.z, 1e-9 * exact.z);
    }
}

TEST(VertexOde, AdaptiveMeetsToleranceWithFewerStepsWhenLoose) {
    std::mt19937_64 rng(33);
    for (int i = 0; i < 50; ++i) {
        const auto m = randomMotion(rng);
        const VertexOde ode(VertexPath(m.camera, m.start, m.end));
        const glm::dvec3 exact = ode.exactState(1.0);
        const AdaptiveResult tight = integrateAdaptive(ode, 0.0, ode.exactState(0.0), 1.0, 1e-11);
        const AdaptiveResult loose = integrateAdaptive(ode, 0.0, ode.exactState(0.0), 1.0, 1e-6);
        // A per-step tolerance accumulates over at most `accepted` steps; the extrapolated value is
        // usually much better than that bound.
        EXPECT_LT(std::abs(tight.y.x - exact.x), 1e-11 * tight.accepted);
        EXPECT_LT(std::abs(tight.y.y - exact.y), 1e-11 * tight.accepted);
        EXPECT_LT(std::abs(loose.y.x - exact.x), 1e-6 * loose.accepted);
        EXPECT_LE(loose.evaluations, tight.evaluations);
    }
}

TEST(VertexOde, CrossingTheCameraPlaneIsARenderError) {
    // The vertex passes through the camera's centre plane at f = 1/2.
    const CameraFrame c = makeCameraFrame({0, 0, 0}, {0, 0, 1}, {0, 1, 0});
    const VertexOde ode(VertexPath(CameraMotion(c, c), {1, 1, 1}, {1, 1, -1}));
    try {
        integrateFixed(ode, {OdeMethod::Rk4, 64}, 0.0, ode.exactState(0.0), 1.0);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::Render);
    }
    EXPECT_THROW(integrateAdaptive(ode, 0.0, ode.exactState(0.0), 1.0, 1e-9), Error);
    EXPECT_THROW(integrateFixed(ode, {OdeMethod::Euler, 0}, 0.0, ode.exactState(0.0), 0.25), Error);
    EXPECT_THROW(integrateAdaptive(ode, 0.0, ode.exactState(0.0), 0.25, 0.0), Error);
}

TEST(VertexOde, OmegaIsConstantProjectionOfAngularVelocity) {
    // Pure spin by beta about the view axis: omega = e1 . de2/df = -beta.
    const auto c = *findBlurPathCase("spin");
    const VertexOde ode(VertexPath(c.cameraMotion(), c.vertexStart(4, 8), c.vertexEnd(4, 8)));
    EXPECT_NEAR(ode.omega(), std::atan(0.1), 1e-15);
}

}  // namespace
}  // namespace clipblur
