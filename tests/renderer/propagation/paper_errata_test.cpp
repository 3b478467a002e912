// Each printed equation of section 2-3 evaluated as printed next to the corrected form, both against
// finite differences or independent constructions of the exact path. docs/errata.md cites these tests.
#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "random_motion.h"
#include "renderer/propagation/blur_path_cases.h"
#include "renderer/propagation/vertex_path.h"

namespace clipblur {
namespace {

using testing::randomMotion;
using testing::RandomMotion;

constexpr double kH = 1e-5;
// Central differences of smooth paths with |third derivative| <~ 10: h^2 * 10 / 6 + 1e-16 / h < 1e-8.
constexpr double kFdTol = 1e-7;

int eps(int i, int j, int k) { return (i - j) * (j - k) * (k - i) / 2; }

// World-space quantities of section 2 at f for one relative motion.
struct WorldState {
    glm::dvec3 e1, e2, n, d, d_dot, p;
};

WorldState worldAt(const RandomMotion& m, double f) {
    const CameraFrame c = m.camera.at(f);
    WorldState s;
    s.e1 = c.e1;
    s.e2 = c.e2;
    s.n = c.e3;
    s.d = m.start + f * (m.end - m.start) - c.position;
    s.d_dot = (m.end - m.start) - m.camera.velocity();
    s.p = s.d / glm::dot(s.n, s.d) - s.n;  // eq. 3
    return s;
}

template <class F>
auto centralDiff(F fn, double f) {
    return (fn(f + kH) - fn(f - kH)) / (2.0 * kH);
}

// Eq. 22 as printed (it is right: the derivative of eq. 21).
glm::dvec3 eq22(const CameraMotion& cam, double f) {
    const double a = cam.rotation().angle();
    const glm::dvec3 u = cam.rotation().axis();
    const glm::dvec3 n0 = cam.start().e3;
    return -n0 * a * std::sin(a * f) + u * glm::dot(u, n0) * a * std::sin(a * f) + a * glm::cross(u, n0) * std::cos(a * f);
}

glm::dvec3 eq7Printed(const WorldState& s, const glm::dvec3& n_dot) {
    const glm::dvec3 pn = s.p + s.n;
    const glm::dvec3 first = s.d_dot - pn * glm::dot(s.n, s.d_dot);  // {1 - (p + n) n} . d'
    const glm::dvec3 second = n_dot + pn * glm::dot(s.p, n_dot);    // {1 + (p + n) p} . n'
    return std::sqrt(1.0 + glm::dot(s.p, s.p)) * first / glm::length(s.d) - second;
}

glm::dvec3 eq7Corrected(const WorldState& s, const glm::dvec3& n_dot) {
    const glm::dvec3 pn = s.p + s.n;
    return (s.d_dot - pn * glm::dot(s.n, s.d_dot)) / glm::dot(s.n, s.d) - (n_dot + pn * glm::dot(s.p, n_dot));
}

TEST(PaperErrata, Eq22IsTheDerivativeOfEq21) {
    std::mt19937_64 rng(41);
    for (int i = 0; i < 100; ++i) {
        const RandomMotion m = randomMotion(rng);
        const double f = 0.1 + 0.8 * i / 100.0;
        const glm::dvec3 fd = centralDiff([&](double t) { return m.camera.at(t).e3; }, f);
        EXPECT_LT(glm::length(eq22(m.camera, f) - fd), kFdTol);
    }
}

TEST(PaperErrata, Eq7AsPrintedHoldsInFrontOfTheCamera) {
    std::mt19937_64 rng(42);
    for (int i = 0; i < 200; ++i) {
        const RandomMotion m = randomMotion(rng);
        const double f = 0.1 + 0.8 * i / 200.0;
        const WorldState s = worldAt(m, f);
        if (glm::dot(s.n, s.d) < 1.0) continue;
        const glm::dvec3 fd = centralDiff([&](double t) { return worldAt(m, t).p; }, f);
        const glm::dvec3 n_dot = eq22(m.camera, f);
        EXPECT_LT(glm::length(eq7Printed(s, n_dot) - fd), kFdTol * (1.0 + glm::length(fd)));
        EXPECT_LT(glm::length(eq7Corrected(s, n_dot) - fd), kFdTol * (1.0 + glm::length(fd)));
    }
}

TEST(PaperErrata, Eq7AsPrintedFlipsTheTranslationTermBehindTheCamera) {
    // sqrt(1+|p|^2)/|d| = 1/|n.d|, not 1/(n.d): the printed form is wrong whenever n.d < 0.
    const CameraFrame c0 = makeCameraFrame({0, 0, 0}, {0, 0, 1}, {0, 1, 0});
    const CameraFrame c1 = makeCameraFrame({0, 0, 0}, {0, 0.1, 1}, {0.1, 1, 0});
    const RandomMotion m{CameraMotion(c0, c1), {1, 2, -5}, {3, 1, -8}};
    const double f = 0.5;
    const WorldState s = worldAt(m, f);
    ASSERT_LT(glm::dot(s.n, s.d), 0.0);
    const glm::dvec3 fd = centralDiff([&](double t) { return worldAt(m, t).p; }, f);
    const glm::dvec3 n_dot = eq22(m.camera, f);
    EXPECT_GT(glm::length(eq7Printed(s, n_dot) - fd), 0.1);
    EXPECT_LT(glm::length(eq7Corrected(s, n_dot) - fd), kFdTol);
}

TEST(PaperErrata, Eq8NeedsDerivativesOfTheBasisVectors) {
    std::mt19937_64 rng(43);
    for (int i = 0; i < 100; ++i) {
        const RandomMotion m = randomMotion(rng);
        if (m.camera.rotation().angle() < 0.05) continue;
        const double f = 0.1 + 0.8 * i / 100.0;
        const WorldState s = worldAt(m, f);
        if (glm::dot(s.n, s.d) < 1.0) continue;
        auto comp = [&](double t) {
            const WorldState w = worldAt(m, t);
            return glm::dvec2(glm::dot(w.e1, w.p), glm::dot(w.e2, w.p));
        };
        const glm::dvec2 p = comp(f);
        const glm::dvec2 p_dot = centralDiff(comp, f);
        const glm::dvec3 e1_dot = centralDiff([&](double t) { return m.camera.at(t).e1; }, f);
        const glm::dvec3 e2_dot = centralDiff([&](double t) { return m.camera.at(t).e2; }, f);
        const glm::dvec3 pvec_dot = centralDiff([&](double t) { return worldAt(m, t).p; }, f);
        const glm::dvec3 printed = p_dot.x * s.e1 + p_dot.y * s.e2 + p.x * s.e1 + p.y * s.e2;
        const glm::dvec3 corrected = p_dot.x * s.e1 + p_dot.y * s.e2 + p.x * e1_dot + p.y * e2_dot;
        EXPECT_LT(glm::length(corrected - pvec_dot), kFdTol * (1.0 + glm::length(pvec_dot)));
        EXPECT_GT(glm::length(printed - pvec_dot), 1e-3 * glm::length(p));
    }
}

// Eq. 9 as printed (e_i . e_j = eps_ij omega) has lost a dot. Eq. 10 and eq. 23 both hold only with
// omega = e1 . de2/df (dot on the second factor); the other placement, de1/df . e2, is -omega and
// makes eq. 10 rotate the image the wrong way.
TEST(PaperErrata, Eq9OmegaIsE1DotDerivativeOfE2) {
    const auto c = *findBlurPathCase("spin_pan");
    const CameraMotion cam = c.cameraMotion();
    const RandomMotion m{cam, c.vertexStart(12, -8), c.vertexEnd(12, -8)};
    for (double f : {0.2, 0.5, 0.8}) {
        const WorldState s = worldAt(m, f);
        const glm::dvec3 e1_dot = centralDiff([&](double t) { return cam.at(t).e1; }, f);
        const glm::dvec3 e2_dot = centralDiff([&](double t) { return cam.at(t).e2; }, f);
        const double omega = glm::dot(s.e1, e2_dot);
        const double omega_other = glm::dot(e1_dot, s.e2);
        EXPECT_NEAR(omega_other, -omega, kFdTol);
        ASSERT_GT(std::abs(omega), 0.05);
        auto comp = [&](double t) {
            const WorldState w = worldAt(m, t);
            return glm::dvec2(glm::dot(w.e1, w.p), glm::dot(w.e2, w.p));
        };
        const glm::dvec2 p = comp(f);
        const glm::dvec2 p_dot = centralDiff(comp, f);
        const glm::dvec3 pvec_dot = centralDiff([&](double t) { return worldAt(m, t).p; }, f);
        auto eq10 = [&](double w) {
            return glm::dvec2(-p.y * w + glm::dot(s.e1, pvec_dot), p.x * w + glm::dot(s.e2, pvec_dot));
        };
        EXPECT_LT(glm::length(eq10(omega) - p_dot), kFdTol);
        EXPECT_GT(glm::length(eq10(omega_other) - p_dot), 1e-2);
        // Eq. 11 and 12 as printed, with that omega, match the measured component velocities.
        const glm::dvec3 n_dot = eq22(cam, f);
        const double k = std::sqrt(1.0 + glm::dot(s.p, s.p)) / glm::length(s.d);
        const double eq11 = -p.y * omega + k * glm::dot(s.e1 - p.x * s.n, s.d_dot) - glm::dot(s.e1 + p.x * s.p, n_dot);
        const double eq12 = p.x * omega + k * glm::dot(s.e2 - p.y * s.n, s.d_dot) - glm::dot(s.e2 + p.y * s.p, n_dot);
        EXPECT_NEAR(eq11, p_dot.x, kFdTol);
        EXPECT_NEAR(eq12, p_dot.y, kFdTol);
    }
}

TEST(PaperErrata, Eq23OmegaIsConstantWithoutTheSinCosTerm) {
    std::mt19937_64 rng(44);
    int strong = 0;
    for (int i = 0; i < 200; ++i) {
        const RandomMotion m = randomMotion(rng, 2.5);
        const CameraMotion& cam = m.camera;
        const double a = cam.rotation().angle();
        const glm::dvec3 u = cam.rotation().axis();
        const CameraFrame& c0 = cam.start();
        const double first = a * glm::dot(c0.e1, glm::cross(u, c0.e2));
        const double coupling = a * glm::dot(u, c0.e1) * glm::dot(u, c0.e2);
        for (double f : {0.0, 0.3, 0.7, 1.0}) {
            const double fd_f = std::clamp(f, kH, 1.0 - kH);
            const glm::dvec3 e2_dot = centralDiff([&](double t) { return cam.at(t).e2; }, fd_f);
            const double omega = glm::dot(cam.at(fd_f).e1, e2_dot);
            EXPECT_NEAR(first, omega, 1e-6) << "f " << f;  // rotations up to 2.5 rad: |R'''| h^2 ~ 3e-10
            const double printed = first + coupling * std::sin(a * fd_f) * std::cos(a * fd_f);
            if (std::abs(coupling * std::sin(a * fd_f) * std::cos(a * fd_f)) > 1e-2) {
                EXPECT_GT(std::abs(printed - omega), 1e-3);
                ++strong;
            }
        }
    }
    EXPECT_GT(strong, 50);
}

glm::dmat3 tau(int k, double sign) {
    glm::dmat3 t(0.0);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) t[j][i] = sign * eps(i, j, k);  // glm: t[col][row] = (tau_k)_ij
    return t;
}

glm::dmat3 eq15(const glm::dvec3& axis, double angle, double tau_sign) {
    glm::dmat3 dot_tau(0.0);
    for (int k = 0; k < 3; ++k) dot_tau += axis[k] * tau(k, tau_sign);
    return std::cos(angle) * glm::dmat3(1.0) + glm::outerProduct(axis, axis) * (1.0 - std::cos(angle)) +
           dot_tau * std::sin(angle);
}

double maxAbsDiff(const glm::dmat3& a, const glm::dmat3& b) {
    double m = 0.0;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) m = std::max(m, std::abs(a[c][r] - b[c][r]));
    return m;
}

// The matrix of eq. 14, M_ij = e_i(0).e_j(1).
glm::dmat3 eq14(const CameraMotion& cam) {
    const glm::dmat3 b0 = cam.start().basis(), b1 = cam.end().basis();
    glm::dmat3 m;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) m[j][i] = glm::dot(b0[i], b1[j]);
    return m;
}

TEST(PaperErrata, Eq14IsTheRotationInTheInitialCameraBasis) {
    const CameraMotion cam = findBlurPathCase("spin_pan")->cameraMotion();
    const glm::dmat3 world = cam.rotation().matrix(1.0);
    const glm::dmat3 b0 = cam.start().basis();
    const glm::dmat3 m = eq14(cam);
    EXPECT_LT(maxAbsDiff(m, glm::transpose(b0) * world * b0), 1e-14);
    // It is not the world matrix (B0 is not the identity in Table 1: e2 = -x) nor its transpose.
    EXPECT_GT(maxAbsDiff(m, world), 0.05);
    EXPECT_GT(maxAbsDiff(m, glm::transpose(world)), 0.05);
}

TEST(PaperErrata, Eq16SignMakesEq15TheInverseRotation) {
    std::mt19937_64 rng(45);
    for (int i = 0; i < 50; ++i) {
        const RandomMotion m = randomMotion(rng, 2.0);
        const IntraframeRotation& r = m.camera.rotation();
        if (r.angle() < 0.05) continue;
        const glm::dmat3 world = r.matrix(1.0);
        const glm::dmat3 printed = eq15(r.axis(), r.angle(), +1.0);
        const glm::dmat3 corrected = eq15(r.axis(), r.angle(), -1.0);
        EXPECT_LT(maxAbsDiff(corrected, world), 1e-13);
        EXPECT_LT(maxAbsDiff(printed, glm::transpose(world)), 1e-13);
        EXPECT_GT(maxAbsDiff(printed, world), 0.01);
    }
}

TEST(PaperErrata, Eq18HoldsWithCorrectedTauAndInitialBasisComponents) {
    std::mt19937_64 rng(46);
    for (int i = 0; i < 50; ++i) {
        const RandomMotion m = randomMotion(rng, 2.0);
        const IntraframeRotation& r = m.camera.rotation();
        if (r.angle() < 0.05) continue;
        const glm::dmat3 mat = eq14(m.camera);
        const glm::dmat3 b0 = m.camera.start().basis();
        for (int k = 0; k < 3; ++k) {
            const double axis_k = glm::dot(r.axis(), b0[k]);  // (alpha_hat)_k in the e(0) basis
            const double want = -2.0 * axis_k * std::sin(r.angle());
            double middle = 0.0;
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b) middle += eps(a, b, k) * mat[b][a];
            auto trace = [&](const glm::dmat3& x) { return x[0][0] + x[1][1] + x[2][2]; };
            EXPECT_NEAR(middle, want, 1e-13);
            EXPECT_NEAR(trace(tau(k, -1.0) * mat), want, 1e-13);
            EXPECT_NEAR(trace(tau(k, +1.0) * mat), -want, 1e-13);  // printed tau: opposite sign
        }
    }
}

// Eq. 24 takes the max over vertices of sqrt(a_p)/|p'|, i.e. the spacing of the slowest vertex; the
// fastest then moves several pixels per subframe. The min (over vertices and over the frame) bounds
// every displacement by one pixel, since |p(f+df) - p(f)| <= df max|p'|. Where one vertex is still
// (the image centre under spin or recede), the printed max is infinite.
TEST(PaperErrata, Eq24NeedsMinNotMax) {
    const Projection projection(1920, 1080, 40.0);
    const double pixel = std::sqrt(projection.pixelArea());
    for (const BlurPathCase& c : blurPathCases()) {
        std::vector<VertexPath> paths;
        for (double x : blurPathGrid())
            for (double y : blurPathGrid()) paths.emplace_back(c.cameraMotion(), c.vertexStart(x, y), c.vertexEnd(x, y));
        double df_max = 0.0, df_min = HUGE_VAL;
        for (const VertexPath& path : paths) {
            double slowest_spacing = HUGE_VAL;
            for (int s = 0; s <= 64; ++s) {
                const glm::dvec3 v = path.derivative(s / 64.0);
                slowest_spacing = std::min(slowest_spacing, pixel / std::hypot(v.x, v.y));
            }
            df_max = std::max(df_max, slowest_spacing);
            df_min = std::min(df_min, slowest_spacing);
        }
        auto worstStep = [&](double df) {
            // A still vertex (spin, recede: the centre) makes the printed max infinite: one subframe.
            const int n = std::max(1, static_cast<int>(std::ceil(1.0 / df)));
            double worst = 0.0;
            for (const VertexPath& path : paths)
                for (int k = 0; k < n; ++k)
                    worst = std::max(worst, glm::length(path.at((k + 1.0) / n).p - path.at(static_cast<double>(k) / n).p));
            return worst / pixel;
        };
        // Speeds sampled at 65 times; between samples |p'| changes by < 1 % for these smooth paths.
        EXPECT_LE(worstStep(df_min), 1.01) << c.name;
        EXPECT_GT(worstStep(df_max), 2.0) << c.name;
    }
}

}  // namespace
}  // namespace clipblur
