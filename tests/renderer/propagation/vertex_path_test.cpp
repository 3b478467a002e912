#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "renderer/propagation/blur_path_cases.h"
#include "random_motion.h"
#include "renderer/propagation/vertex_path.h"

namespace clipblur {
namespace {

using testing::randomMotion;

TEST(VertexPath, MatchesProjectionOfInterpolatedCamera) {
    std::mt19937_64 rng(21);
    std::uniform_real_distribution<double> uf(0.0, 1.0);
    int checked = 0;
    for (int i = 0; i < 300; ++i) {
        const auto m = randomMotion(rng);
        const VertexPath path(m.camera, m.start, m.end);
        for (int s = 0; s < 5; ++s) {
            const double f = uf(rng);
            // Independent route: the world-space camera of CameraMotion::at and eq. 3's projection.
            const ImagePoint ref = projectToImagePlane(m.camera.at(f), m.start + f * (m.end - m.start));
            if (ref.depth < 0.5) continue;
            const ImagePoint got = path.at(f);
            // |p| up to ~10 and depth >= 0.5: a few ulps of 20-unit coordinates over the depth.
            const double tol = 1e-13 * (1.0 + glm::length(ref.p)) * std::max(1.0, 20.0 / ref.depth);
            EXPECT_NEAR(got.p.x, ref.p.x, tol);
            EXPECT_NEAR(got.p.y, ref.p.y, tol);
            EXPECT_NEAR(got.depth, ref.depth, 1e-12 * std::max(1.0, ref.depth));
            ++checked;
        }
    }
    EXPECT_GT(checked, 1000);
}

TEST(VertexPath, EndpointsAreTheKeyProjections) {
    std::mt19937_64 rng(22);
    for (int i = 0; i < 100; ++i) {
        const auto m = randomMotion(rng);
        const VertexPath path(m.camera, m.start, m.end);
        const ImagePoint p0 = projectToImagePlane(m.camera.start(), m.start);
        const ImagePoint p1 = projectToImagePlane(m.camera.end(), m.end);
        EXPECT_NEAR(glm::length(path.at(0.0).p - p0.p), 0.0, 1e-13);
        // f = 1 goes through R(1) rather than the stored end frame: quaternion round trip, ~1e-14.
        EXPECT_NEAR(glm::length(path.at(1.0).p - p1.p), 0.0, 1e-12 * (1.0 + glm::length(p1.p)));
        EXPECT_NEAR(path.at(1.0).depth, p1.depth, 1e-12 * p1.depth);
    }
}

TEST(VertexPath, DerivativeMatchesFiniteDifferences) {
    std::mt19937_64 rng(23);
    std::uniform_real_distribution<double> uf(0.05, 0.95);
    for (int i = 0; i < 300; ++i) {
        const auto m = randomMotion(rng);
        const VertexPath path(m.camera, m.start, m.end);
        const double f = uf(rng);
        if (path.at(f).depth < 1.0) continue;
        const double h = 1e-5;
        const ImagePoint a = path.at(f + h);
        const ImagePoint b = path.at(f - h);
        const glm::dvec3 fd((a.p.x - b.p.x) / (2 * h), (a.p.y - b.p.y) / (2 * h), (a.depth - b.depth) / (2 * h));
        const glm::dvec3 d = path.derivative(f);
        // Central differences: h^2 |p'''| / 6 ~ 1e-9 for these motions, rounding ~1e-16 / h ~ 1e-11.
        EXPECT_NEAR(d.x, fd.x, 1e-7 * (1.0 + std::abs(fd.x)));
        EXPECT_NEAR(d.y, fd.y, 1e-7 * (1.0 + std::abs(fd.y)));
        EXPECT_NEAR(d.z, fd.z, 1e-7 * (1.0 + std::abs(fd.z)));
    }
}

TEST(VertexPath, DependsOnlyOnRelativeMotion) {
    // Moving the camera by t with a still vertex is the same path as a still camera and a vertex moving by -t.
    const CameraFrame a0 = makeCameraFrame({0, 0, 0}, {0, 0, 1}, {0, 1, 0});
    const CameraFrame a1 = makeCameraFrame({0, 0, 0}, {0, 0.1, 1}, {0.1, 1, 0});
    const CameraFrame b1 = makeCameraFrame({-1, 2, -10}, {0, 0.1, 1}, {0.1, 1, 0});
    const VertexPath moving_vertex(CameraMotion(a0, a1), {3, 4, 10}, {4, 2, 20});
    const VertexPath moving_camera(CameraMotion(a0, b1), {3, 4, 10}, {3, 4, 10});
    for (double f = 0.0; f <= 1.0; f += 0.125) {
        EXPECT_NEAR(glm::length(moving_vertex.at(f).p - moving_camera.at(f).p), 0.0, 1e-14);
    }
}

TEST(BlurPathCases, MatchTable1) {
    const auto& cases = blurPathCases();
    ASSERT_EQ(cases.size(), 5u);
    EXPECT_EQ(cases[0].name, "spin");
    EXPECT_EQ(cases[0].end_up, glm::dvec3(0.1, 1, 0));
    EXPECT_EQ(cases[1].end_view, glm::dvec3(0, 0.1, 1));
    EXPECT_EQ(cases[3].end_range, 20.0);
    EXPECT_EQ(cases[4].end_view, glm::dvec3(0, 0.1, 1));
    EXPECT_EQ(cases[4].end_up, glm::dvec3(0.1, 1, 0));
    for (const auto& c : cases) EXPECT_EQ(c.start_range, 10.0);
    EXPECT_EQ(blurPathGrid().size(), 11u);
    EXPECT_FALSE(findBlurPathCase("tumble").has_value());
}

// Figure 2: a spin about the view axis by beta = -atan(0.1) (up turns towards +x = -e2) moves every
// image point on a circle about the centre by -beta f.
TEST(BlurPathCases, SpinIsARotationAboutTheCentre) {
    const auto c = *findBlurPathCase("spin");
    const double beta = -std::atan(0.1);
    for (double x : blurPathGrid())
        for (double y : blurPathGrid()) {
            const VertexPath path(c.cameraMotion(), c.vertexStart(x, y), c.vertexEnd(x, y));
            const glm::dvec2 p0 = path.at(0.0).p;
            EXPECT_NEAR(p0.x, y / 10.0, 1e-15);   // e1 = up = +y
            EXPECT_NEAR(p0.y, -x / 10.0, 1e-15);  // e2 = view x up = -x
            for (double f = 0.0; f <= 1.0; f += 0.25) {
                const double a = beta * f;
                const glm::dvec2 want(p0.x * std::cos(a) + p0.y * std::sin(a), -p0.x * std::sin(a) + p0.y * std::cos(a));
                EXPECT_NEAR(glm::length(path.at(f).p - want), 0.0, 1e-14);
            }
        }
}

// Figure 3: the view tilts up by gamma = atan(0.1) about e2; in camera coordinates the vertex turns by
// -gamma f about e2: p1 = (p1 - t) / (1 + p1 t), p2 = p2 / (cos + p1 sin) with t = tan(gamma f).
TEST(BlurPathCases, PanFollowsTheTangentLaw) {
    const auto c = *findBlurPathCase("pan");
    const double gamma = std::atan(0.1);
    for (double x : blurPathGrid())
        for (double y : blurPathGrid()) {
            const VertexPath path(c.cameraMotion(), c.vertexStart(x, y), c.vertexEnd(x, y));
            const glm::dvec2 p0 = path.at(0.0).p;
            for (double f = 0.0; f <= 1.0; f += 0.25) {
                const double g = gamma * f;
                const double p1 = (p0.x - std::tan(g)) / (1.0 + p0.x * std::tan(g));
                const double p2 = p0.y / (std::cos(g) + p0.x * std::sin(g));
                EXPECT_NEAR(path.at(f).p.x, p1, 1e-14);
                EXPECT_NEAR(path.at(f).p.y, p2, 1e-14);
            }
        }
    const VertexPath centre(c.cameraMotion(), c.vertexStart(0, 0), c.vertexEnd(0, 0));
    EXPECT_NEAR(centre.at(1.0).p.x, -0.1, 1e-15);
}

// Figure 5: receding from range 10 to 20 shrinks every point towards the centre, p(f) = p(0) / (1 + f).
TEST(BlurPathCases, RecedeIsRadialShrink) {
    const auto c = *findBlurPathCase("recede");
    for (double x : blurPathGrid())
        for (double y : blurPathGrid()) {
            const VertexPath path(c.cameraMotion(), c.vertexStart(x, y), c.vertexEnd(x, y));
            for (double f = 0.0; f <= 1.0; f += 0.125) {
                EXPECT_NEAR(glm::length(path.at(f).p - path.at(0.0).p / (1.0 + f)), 0.0, 1e-15);
                EXPECT_NEAR(path.at(f).depth, 10.0 * (1.0 + f), 1e-13);
            }
        }
}

// Figures 4 and 6: the end of each path is the vertex seen by the final camera of Table 1.
TEST(BlurPathCases, CombinedCasesEndAtFinalCameraProjection) {
    for (const char* name : {"spin_pan", "recede_spin_pan"}) {
        const auto c = *findBlurPathCase(name);
        const CameraFrame end = makeCameraFrame({0, 0, 0}, c.end_view, c.end_up);
        for (double x : blurPathGrid())
            for (double y : blurPathGrid()) {
                const VertexPath path(c.cameraMotion(), c.vertexStart(x, y), c.vertexEnd(x, y));
                const ImagePoint want = projectToImagePlane(end, c.vertexEnd(x, y));
                EXPECT_NEAR(glm::length(path.at(1.0).p - want.p), 0.0, 1e-14) << name << " " << x << "," << y;
            }
    }
}

}  // namespace
}  // namespace clipblur
