#include <cmath>
#include <map>
#include <utility>

#include <gtest/gtest.h>

#include "scene/primitives.h"
#include "scene/scene_validation.h"

namespace clipblur {

namespace {

glm::dvec3 areaVector(const Mesh& m, const std::array<std::uint32_t, 3>& t) {
    const glm::dvec3 a = m.positions[t[0]], b = m.positions[t[1]], c = m.positions[t[2]];
    return 0.5 * glm::cross(b - a, c - a);
}

double totalArea(const Mesh& m) {
    double area = 0.0;
    for (const auto& t : m.triangles) area += glm::length(areaVector(m, t));
    return area;
}

// Divergence theorem: sum of a . (b x c) / 6 is the enclosed volume, positive for outward winding.
double signedVolume(const Mesh& m) {
    double v = 0.0;
    for (const auto& t : m.triangles)
        v += glm::dot(m.positions[t[0]], glm::cross(m.positions[t[1]], m.positions[t[2]])) / 6.0;
    return v;
}

// Undirected edge -> number of triangles using it; counted here without the library's helper.
std::map<std::pair<std::uint32_t, std::uint32_t>, int> edgeUse(const Mesh& m) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> use;
    for (const auto& t : m.triangles)
        for (int k = 0; k < 3; ++k) ++use[std::minmax(t[k], t[(k + 1) % 3])];
    return use;
}

}  // namespace

TEST(Primitives, QuadFacesUpWithRequestedArea) {
    const Mesh q = makeQuad({3.0, 2.0});
    ASSERT_EQ(q.triangles.size(), 2u);
    EXPECT_NEAR(totalArea(q), 6.0, 1e-14);
    for (const auto& t : q.triangles) {
        const glm::dvec3 n = glm::normalize(areaVector(q, t));
        EXPECT_NEAR(n.y, 1.0, 1e-15);
    }
}

TEST(Primitives, GridCountsAreaAndWinding) {
    const Mesh g = makeGrid({4.0, 6.0}, 5, 3);
    EXPECT_EQ(g.triangles.size(), gridTriangleCount(5, 3));
    EXPECT_EQ(g.triangles.size(), 30u);
    EXPECT_EQ(g.positions.size(), 6u * 4u);
    EXPECT_NEAR(totalArea(g), 24.0, 1e-12);
    for (const auto& t : g.triangles) {
        const glm::dvec3 av = areaVector(g, t);
        // Every cell is 0.8 x 2, each triangle half of it, all facing +y.
        EXPECT_NEAR(av.y, 0.8, 1e-12);
        EXPECT_NEAR(av.x, 0.0, 1e-15);
        EXPECT_NEAR(av.z, 0.0, 1e-15);
    }
    // Interior edges are shared by two triangles, the boundary edges by one: 2*(5+3) boundary edges.
    int boundary = 0;
    for (const auto& [edge, n] : edgeUse(g)) {
        EXPECT_LE(n, 2);
        boundary += n == 1;
    }
    EXPECT_EQ(boundary, 16);
    EXPECT_FALSE(isClosedManifold(g));
}

TEST(Primitives, BoxIsClosedAndWoundOutward) {
    const glm::dvec3 size(1.0, 2.0, 3.0);
    const Mesh b = makeBox(size);
    EXPECT_EQ(b.positions.size(), 8u);
    ASSERT_EQ(b.triangles.size(), 12u);
    const auto use = edgeUse(b);
    EXPECT_EQ(use.size(), 18u);  // 12 cube edges + 6 face diagonals
    for (const auto& [edge, n] : use) EXPECT_EQ(n, 2);
    for (const auto& t : b.triangles) {
        const glm::dvec3 centroid = (b.positions[t[0]] + b.positions[t[1]] + b.positions[t[2]]) / 3.0;
        EXPECT_GT(glm::dot(areaVector(b, t), centroid), 0.0);  // the box is centred on the origin
    }
    EXPECT_NEAR(signedVolume(b), 6.0, 1e-12);
    EXPECT_NEAR(totalArea(b), 2.0 * (2.0 + 3.0 + 6.0), 1e-12);
    EXPECT_TRUE(isClosedManifold(b));
}

TEST(Primitives, SphereIsClosedOutwardAndConvergesToTheSphere) {
    const double r = 1.5;
    double previous_error = 1.0;
    for (const int n : {8, 16, 32, 64, 128, 256}) {
        const Mesh s = makeSphere(r, n);
        EXPECT_EQ(s.triangles.size(), sphereTriangleCount(n));
        for (const auto& [edge, uses] : edgeUse(s)) EXPECT_EQ(uses, 2);
        EXPECT_TRUE(isClosedManifold(s));
        EXPECT_EQ(countDegenerateTriangles(s), 0u);
        for (const glm::dvec3& p : s.positions) EXPECT_NEAR(glm::length(p), r, 1e-12);
        for (const auto& t : s.triangles) {
            const glm::dvec3 centroid = (s.positions[t[0]] + s.positions[t[1]] + s.positions[t[2]]) / 3.0;
            EXPECT_GT(glm::dot(areaVector(s, t), centroid), 0.0);
        }
        const double exact = 4.0 * M_PI * r * r;
        const double error = (exact - totalArea(s)) / exact;
        // A convex polyhedron inscribed in the sphere has less surface area than the sphere, and flat
        // facets of angular size h = 2 pi / n miss it by O(h^2): halving the step quarters the error.
        // The ratio tolerance of 0.1 covers the O(h^4) remainder, which is below 2% of h^2 from n = 32.
        EXPECT_GT(error, 0.0);
        if (n >= 32) {
            EXPECT_NEAR(previous_error / error, 4.0, 0.1) << "segments " << n;
        }
        EXPECT_LT(error, previous_error);
        previous_error = error;
        // Each facet is the base of a pyramid with apex at the centre and height r cos(rho) ~
        // r (1 - rho^2 / 2), rho the facet's angular radius, while its area falls short by ~ rho^2 / 3:
        // the volume deficit is ~ (1/3 + 1/2) / (1/3) = 2.5 times the area deficit. [1, 3] allows for
        // the spread of facet shapes between equator and poles.
        const double exact_volume = 4.0 / 3.0 * M_PI * r * r * r;
        const double volume_error = (exact_volume - signedVolume(s)) / exact_volume;
        EXPECT_GT(volume_error, 1.0 * error) << "segments " << n;
        EXPECT_LT(volume_error, 3.0 * error) << "segments " << n;
    }
}

TEST(Primitives, OddAndTinySegmentCounts) {
    for (const int n : {3, 4, 5, 7}) {
        const Mesh s = makeSphere(1.0, n);
        EXPECT_EQ(s.triangles.size(), sphereTriangleCount(n));
        EXPECT_TRUE(isClosedManifold(s)) << n;
        EXPECT_GT(signedVolume(s), 0.0);
    }
}

}  // namespace clipblur
