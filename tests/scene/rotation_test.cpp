#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "scene/camera.h"
#include "scene/rotation.h"

namespace clipblur {
namespace {

glm::dvec3 randomUnit(std::mt19937_64& rng) {
    std::normal_distribution<double> n(0.0, 1.0);
    const glm::dvec3 v(n(rng), n(rng), n(rng));
    return glm::normalize(v);
}

// Right-handed rotation by `angle` about unit `axis`, written out independently of the class under test.
glm::dmat3 axisAngle(const glm::dvec3& axis, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    const glm::dmat3 cross(glm::dvec3(0, axis.z, -axis.y), glm::dvec3(-axis.z, 0, axis.x),
                           glm::dvec3(axis.y, -axis.x, 0));
    return c * glm::dmat3(1.0) + (1.0 - c) * glm::outerProduct(axis, axis) + s * cross;
}

glm::dmat3 randomBasis(std::mt19937_64& rng) {
    const CameraFrame f = makeCameraFrame({0, 0, 0}, randomUnit(rng), randomUnit(rng));
    return f.basis();
}

double maxAbsDiff(const glm::dmat3& a, const glm::dmat3& b) {
    double m = 0.0;
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) m = std::max(m, std::abs(a[c][r] - b[c][r]));
    return m;
}

// The generators of eq. 15 with the sign that makes eq. 15 a right-handed rotation: (tau_k)_ij = -eps_ijk,
// i.e. tau_k v = e_k x v. The printed eq. 16 has the opposite sign (see errata_test.cpp).
glm::dmat3 alphaDotTau(const glm::dvec3& a) {
    return glm::dmat3(glm::dvec3(0, a.z, -a.y), glm::dvec3(-a.z, 0, a.x), glm::dvec3(a.y, -a.x, 0));
}

TEST(IntraframeRotation, EndpointsForRandomBases) {
    std::mt19937_64 rng(11);
    for (int i = 0; i < 200; ++i) {
        const glm::dmat3 b0 = randomBasis(rng);
        const glm::dmat3 b1 = randomBasis(rng);
        const IntraframeRotation r = IntraframeRotation::betweenBases(b0, b1);
        EXPECT_LT(maxAbsDiff(r.matrix(0.0), glm::dmat3(1.0)), 1e-15);
        // Orthonormal input to ~1e-16 per entry; a handful of roundings in quat_cast and Rodrigues.
        EXPECT_LT(maxAbsDiff(r.matrix(1.0) * b0, b1), 1e-13) << "case " << i;
        EXPECT_GE(r.angle(), 0.0);
        EXPECT_LE(r.angle(), M_PI);
    }
}

TEST(IntraframeRotation, Eq15MatrixFormEqualsMatrix) {
    std::mt19937_64 rng(12);
    std::uniform_real_distribution<double> uf(0.0, 1.0);
    for (int i = 0; i < 100; ++i) {
        const IntraframeRotation r = IntraframeRotation::betweenBases(randomBasis(rng), randomBasis(rng));
        const double f = uf(rng);
        const double a = r.angle() * f;
        const glm::dvec3 n = r.axis();
        const glm::dmat3 eq15 = std::cos(a) * glm::dmat3(1.0) + glm::outerProduct(n, n) * (1.0 - std::cos(a)) +
                                alphaDotTau(n) * std::sin(a);
        EXPECT_LT(maxAbsDiff(eq15, r.matrix(f)), 1e-14);
        EXPECT_LT(maxAbsDiff(eq15, axisAngle(n, a)), 1e-14);
    }
}

TEST(IntraframeRotation, TinyAngleStaysFinite) {
    std::mt19937_64 rng(13);
    for (int i = 0; i < 50; ++i) {
        const glm::dmat3 b0 = randomBasis(rng);
        const glm::dvec3 axis = randomUnit(rng);
        const double alpha = 1e-12;
        const IntraframeRotation r = IntraframeRotation::betweenBases(b0, axisAngle(axis, alpha) * b0);
        // The angle is resolved to absolute precision ~1e-16 (atan2 of quaternion parts), the axis is not
        // meaningful at this size and only has to be a finite unit vector.
        EXPECT_NEAR(r.angle(), alpha, 1e-15);
        EXPECT_NEAR(glm::length(r.axis()), 1.0, 1e-12);
        // R(1/2) is a 5e-13 rad turn; only the product angle * axis matters and that is accurate to ~1e-4
        // relative, i.e. ~1e-16 absolute in the matrix.
        EXPECT_LT(maxAbsDiff(r.matrix(0.5), axisAngle(axis, 0.5 * alpha)), 1e-15);
    }
    const IntraframeRotation still = IntraframeRotation::betweenBases(glm::dmat3(1.0), glm::dmat3(1.0));
    EXPECT_EQ(still.angle(), 0.0);
    EXPECT_LT(maxAbsDiff(still.matrix(0.7), glm::dmat3(1.0)), 1e-16);
}

TEST(IntraframeRotation, NearHalfTurnKeepsAxisAndAngle) {
    std::mt19937_64 rng(14);
    for (int i = 0; i < 50; ++i) {
        const glm::dmat3 b0 = randomBasis(rng);
        const glm::dvec3 axis = randomUnit(rng);
        const double alpha = M_PI - 1e-9;
        const IntraframeRotation r = IntraframeRotation::betweenBases(b0, axisAngle(axis, alpha) * b0);
        // Off-diagonal differences of size 2 sin(alpha) ~ 2e-9 carry the angle's distance from pi; their
        // rounding (~1e-16) shows up as ~1e-13 in the angle at worst.
        EXPECT_NEAR(r.angle(), alpha, 1e-12);
        EXPECT_NEAR(glm::dot(r.axis(), axis), 1.0, 1e-12);
        EXPECT_LT(maxAbsDiff(r.matrix(0.5), axisAngle(axis, 0.5 * alpha)), 1e-12);
        EXPECT_LT(maxAbsDiff(r.matrix(1.0) * b0, axisAngle(axis, alpha) * b0), 1e-12);
    }
}

TEST(IntraframeRotation, ExactHalfTurnCameraTurnsAround) {
    // A 180 degree turn about up: both senses of turning are valid; either must end at the final basis
    // and pass through a quarter turn about +-up at f = 1/2.
    const CameraFrame c0 = makeCameraFrame({0, 0, 0}, {0, 0, 1}, {0, 1, 0});
    const CameraFrame c1 = makeCameraFrame({0, 0, 0}, {0, 0, -1}, {0, 1, 0});
    const IntraframeRotation r = IntraframeRotation::betweenBases(c0.basis(), c1.basis());
    EXPECT_DOUBLE_EQ(r.angle(), M_PI);
    EXPECT_NEAR(std::abs(r.axis().y), 1.0, 1e-15);
    EXPECT_LT(maxAbsDiff(r.matrix(1.0) * c0.basis(), c1.basis()), 1e-15);
    const glm::dvec3 mid_view = r.rotate(c0.e3, 0.5);
    EXPECT_NEAR(std::abs(mid_view.x), 1.0, 1e-15);
    EXPECT_NEAR(mid_view.z, 0.0, 1e-15);
    EXPECT_LT(glm::length(r.rotate(c0.e1, 0.5) - c0.e1), 1e-15);
}

TEST(IntraframeRotation, Eq17TraceRelation) {
    std::mt19937_64 rng(15);
    for (int i = 0; i < 200; ++i) {
        const glm::dmat3 b0 = randomBasis(rng);
        const glm::dmat3 b1 = randomBasis(rng);
        double trace = 0.0;  // sum_i e_i(0).e_i(1)
        for (int k = 0; k < 3; ++k) trace += glm::dot(b0[k], b1[k]);
        const IntraframeRotation r = IntraframeRotation::betweenBases(b0, b1);
        EXPECT_NEAR(trace, 1.0 + 2.0 * std::cos(r.angle()), 1e-14);
    }
}

TEST(IntraframeRotation, DerivativeIsAlphaCrossR) {
    std::mt19937_64 rng(16);
    std::uniform_real_distribution<double> uf(0.05, 0.95);
    for (int i = 0; i < 100; ++i) {
        const IntraframeRotation r = IntraframeRotation::betweenBases(randomBasis(rng), randomBasis(rng));
        const double f = uf(rng);
        const double h = 1e-5;
        const glm::dmat3 fd = (r.matrix(f + h) - r.matrix(f - h)) / (2.0 * h);
        const glm::dmat3 analytic = alphaDotTau(r.angularVelocity()) * r.matrix(f);
        // Central difference truncation alpha^3 h^2 / 6 < 6e-10 plus rounding 1e-16 / h = 1e-11.
        EXPECT_LT(maxAbsDiff(fd, analytic), 1e-9);
    }
}

}  // namespace
}  // namespace clipblur
