#include "renderer/propagation/surface_path.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "support/motion_scenes.h"

namespace clipblur {
namespace {

using testing::referenceProjection;

glm::dvec3 randomBarycentric(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    glm::dvec3 b(u(rng), u(rng), u(rng));
    return b / (b.x + b.y + b.z);
}

Projection projectionOf(const Scene& scene) {
    return Projection(scene.film.width, scene.film.height, scene.camera.vfov_degrees);
}

TEST(SurfacePath, MatchesReferenceProjectionOfPropagatedPoint) {
    // The snapshot path and the slow path (evalVertex per corner, evalCamera, projectToImagePlane) differ
    // only in the order of floating point operations: raster positions of a few hundred pixels agree to
    // far better than 1e-8 px.
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> time(-0.3, 1.3);
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
        const Scene scene = testing::randomMovingScene(seed);
        const Projection proj = projectionOf(scene);
        for (int i = 0; i < 20; ++i) {
            const double t = time(rng);
            const MotionSnapshot snapshot(scene, proj, t);
            const MeshPoint sp{static_cast<std::uint32_t>(i % 3), static_cast<std::uint32_t>(i % 3),
                                  randomBarycentric(rng)};
            const ProjectedPoint got = project(snapshot, scene, sp);
            const auto want = referenceProjection(scene, proj, sp.object, sp.triangle, sp.b, t);
            ASSERT_FALSE(got.behind);
            EXPECT_NEAR(got.raster.x, want.raster.x, 1e-8) << "seed " << seed << " t " << t;
            EXPECT_NEAR(got.raster.y, want.raster.y, 1e-8) << "seed " << seed << " t " << t;
            EXPECT_NEAR(got.depth, want.depth, 1e-11);
            EXPECT_NEAR(got.inv_depth, 1.0 / want.depth, 1e-12);
            // projectMotion must report the same position.
            const ProjectedMotion motion = projectMotion(snapshot, scene, sp);
            EXPECT_EQ(motion.point.raster, got.raster);
        }
    }
}

// A point's camera-relative position d and rate g are its barycentric combination of its triangle's
// corners' (the world position and rate are, and the camera's terms are affine in them), so the path
// sampler projects fragment vertices from cached corners. Property over seeded scenes whose objects turn,
// scale and deform and whose camera moves and turns: the combination projects where projectMotion does,
// to 1e-8 px and 1e-8 px per frame of velocity (rasters and speeds of a few hundred: rounding).
TEST(SurfacePath, CameraRelativeMotionIsLinearInBarycentrics) {
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> time(0.0, 1.0);
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
        const Scene scene = testing::randomMovingScene(seed);
        const Projection proj = projectionOf(scene);
        for (int i = 0; i < 20; ++i) {
            const MotionSnapshot snapshot(scene, proj, time(rng));
            const MeshPoint p{static_cast<std::uint32_t>(i % 3), static_cast<std::uint32_t>(i % 3), randomBarycentric(rng)};
            CameraRelative combined;
            for (int j = 0; j < 3; ++j) {
                MeshPoint corner{p.object, p.triangle, glm::dvec3(0.0)};
                corner.b[j] = 1.0;
                const CameraRelative c = cameraRelative(snapshot, scene, corner);
                combined.d += p.b[j] * c.d;
                combined.g += p.b[j] * c.g;
            }
            const ProjectedMotion want = projectMotion(snapshot, scene, p), got = projectMotion(snapshot, combined);
            ASSERT_FALSE(want.point.behind);
            ASSERT_FALSE(got.point.behind);
            EXPECT_LT(glm::length(got.point.raster - want.point.raster), 1e-8) << "seed " << seed;
            EXPECT_LT(glm::length(got.raster_velocity - want.raster_velocity), 1e-8) << "seed " << seed;
            EXPECT_NEAR(got.point.depth, want.point.depth, 1e-11);
            EXPECT_NEAR(got.depth_rate, want.depth_rate, 1e-10);
            EXPECT_GT(glm::length(want.raster_velocity), 1.0);  // the scene moves: velocity is tested
        }
    }
}

// cameraTurn: a point at offset d from the camera centre, seen at A as (raster x depth, depth), is seen at
// B (same offset from B's centre) at cameraTurn(B, A) times that, with B's depth as the third component.
// Projected here by hand from the two camera frames (p = (e1 . d, e2 . d) / (e3 . d), Projection's raster
// map). Seeded random scenes whose camera both moves and turns; rasters of a few hundred pixels.
TEST(SurfacePath, CameraTurnMapsWhatOneOrientationSeesToAnother) {
    std::mt19937_64 rng(23);
    std::uniform_real_distribution<double> u(-1.0, 1.0), time(0.0, 1.0);
    int checked = 0;
    for (std::uint64_t seed = 1; seed <= 10; ++seed) {
        const Scene scene = testing::randomMovingScene(seed);
        const Projection proj = projectionOf(scene);
        for (int i = 0; i < 20; ++i) {
            const MotionSnapshot a(scene, proj, time(rng)), b(scene, proj, time(rng));
            const glm::dmat3 turn = cameraTurn(b, a);
            const glm::dvec3 d = 10.0 * a.camera.e3 + 3.0 * glm::dvec3(u(rng), u(rng), u(rng));
            const auto seen = [&](const CameraFrame& c) {
                const double z = glm::dot(c.e3, d);
                return glm::dvec3(proj.toRaster(glm::dvec2(glm::dot(c.e1, d), glm::dot(c.e2, d)) / z), z);
            };
            const glm::dvec3 at_a = seen(a.camera), at_b = seen(b.camera);
            if (at_b.z < 1.0) continue;  // behind B: no raster position to compare
            ++checked;
            const glm::dvec3 h = turn * glm::dvec3(glm::dvec2(at_a) * at_a.z, at_a.z);
            EXPECT_NEAR(h.z, at_b.z, 1e-10);
            EXPECT_NEAR(glm::length(glm::dvec2(h) / h.z - glm::dvec2(at_b)), 0.0, 1e-8) << seed << " " << i;
        }
    }
    EXPECT_GT(checked, 150);
}

TEST(SurfacePath, VelocityMatchesCentralDifferences) {
    // Central differences of the reference path with h = 1e-5 frames: truncation h^2/6 |x'''| stays below
    // 1e-7 px/frame for these scenes (|x'''| < 1e4), rounding eps |x| / h about 1e-8 with |x| < 1e3 px.
    // Tolerance 1e-5 (1 + |v|) px/frame leaves margin (observed agreement is better than 1e-8 relative);
    // a wrong term (missing angular velocity, wrong sign, a dropped scale or deformation rate) is off by
    // whole pixels per frame.
    const double h = 1e-5;
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> time(0.0, 1.0);
    int checked = 0;
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
        const Scene scene = testing::randomMovingScene(seed);
        const Projection proj = projectionOf(scene);
        auto nearKey = [&](double t) {
            auto close = [&](double k) { return std::abs(t - k) < 4.0 * h; };
            for (const auto& k : scene.camera.keys) if (close(k.time)) return true;
            for (const auto& o : scene.objects) {
                for (const auto& k : o.transform) if (close(k.time)) return true;
                for (const auto& k : o.deformation) if (close(k.time)) return true;
            }
            return false;
        };
        for (int i = 0; i < 30; ++i) {
            const double t = time(rng);
            if (nearKey(t)) continue;  // velocity jumps at keys; differences straddling one are meaningless
            const MeshPoint sp{static_cast<std::uint32_t>(i % 3), static_cast<std::uint32_t>((i / 3) % 3),
                                  randomBarycentric(rng)};
            const ProjectedMotion got = projectMotion(MotionSnapshot(scene, proj, t), scene, sp);
            const auto plus = referenceProjection(scene, proj, sp.object, sp.triangle, sp.b, t + h);
            const auto minus = referenceProjection(scene, proj, sp.object, sp.triangle, sp.b, t - h);
            const glm::dvec2 fd = (plus.raster - minus.raster) / (2.0 * h);
            const double fd_depth = (plus.depth - minus.depth) / (2.0 * h);
            const double tol = 1e-5 * (1.0 + glm::length(fd));
            EXPECT_NEAR(got.raster_velocity.x, fd.x, tol) << "seed " << seed << " t " << t;
            EXPECT_NEAR(got.raster_velocity.y, fd.y, tol) << "seed " << seed << " t " << t;
            EXPECT_NEAR(got.depth_rate, fd_depth, 1e-5 * (1.0 + std::abs(fd_depth)));
            ++checked;
        }
    }
    EXPECT_GT(checked, 500);
}

TEST(SurfacePath, TranslationAtConstantDepthHasAnalyticVelocity) {
    // Camera at the origin looking down +z with +y up: image right is e2 = e3 x e1 = -x. A point at depth
    // z moving by dx along world x moves k dx / z pixels to the left, k = (H/2) / tan(vfov/2).
    Scene scene = testing::stillCameraScene(640, 360, 40.0);
    Object tri = testing::triangleObject({-1, -1, 10}, {1, -1, 10}, {0, 1, 10});
    testing::addTransformKey(tri, 0.0, {0, 0, 0});
    testing::addTransformKey(tri, 1.0, {2.0, 0, 0});
    scene.objects.push_back(tri);
    const Projection proj = projectionOf(scene);
    const double k = 180.0 / std::tan(20.0 * M_PI / 180.0);
    const ProjectedMotion m = projectMotion(MotionSnapshot(scene, proj, 0.3), scene, {0, 0, {1, 0, 0}});
    EXPECT_NEAR(m.raster_velocity.x, -k * 2.0 / 10.0, 1e-10);
    EXPECT_NEAR(m.raster_velocity.y, 0.0, 1e-12);
    EXPECT_NEAR(m.depth_rate, 0.0, 1e-12);
    // Vertex 0 at t = 0.3 is at world (-1 + 0.6, -1, 10): raster (320 + k 0.4/10, 180 + k/10).
    EXPECT_NEAR(m.point.raster.x, 320.0 + k * 0.04, 1e-10);
    EXPECT_NEAR(m.point.raster.y, 180.0 + k * 0.1, 1e-10);
}

TEST(SurfacePath, CameraRollMovesPointsOnCircles) {
    // A pure roll by theta over the shutter turns the image about its centre: a point r pixels from the
    // centre moves at theta r pixels per frame, perpendicular to its offset.
    Scene scene = testing::stillCameraScene(640, 360, 40.0);
    const double theta = 0.3;
    scene.camera.keys.push_back({1.0, {0, 0, 0}, {0, 0, 1}, {std::sin(theta), std::cos(theta), 0}});
    scene.objects.push_back(testing::triangleObject({1, 0.5, 10}, {2, 0.5, 10}, {1, 1.5, 10}));
    const Projection proj = projectionOf(scene);
    for (double t : {0.0, 0.25, 0.8}) {
        const ProjectedMotion m = projectMotion(MotionSnapshot(scene, proj, t), scene, {0, 0, {0, 1, 0}});
        const glm::dvec2 offset = m.point.raster - glm::dvec2(320, 180);
        EXPECT_NEAR(glm::length(m.raster_velocity), theta * glm::length(offset), 1e-9);
        EXPECT_NEAR(glm::dot(m.raster_velocity, offset), 0.0, 1e-8);
        EXPECT_NEAR(glm::length(offset), proj.pixelsPerUnit() * std::hypot(0.05, 0.2), 1e-9);  // p = (0.05, -0.2)
    }
}

TEST(SurfacePath, RecedingPointHasDepthRateAndShrinksTowardCentre) {
    // Camera recedes from z = 0 to z = -10 (Table 1 case 5 seen from the camera): depth grows by 10 per
    // frame, a point at image-plane p moves at p' = -p z'/z.
    Scene scene = testing::stillCameraScene(640, 360, 40.0);
    scene.camera.keys.push_back({1.0, {0, 0, -10}, {0, 0, 1}, {0, 1, 0}});
    scene.objects.push_back(testing::triangleObject({1, 2, 10}, {2, 2, 10}, {1, 3, 10}));
    const Projection proj = projectionOf(scene);
    const double k = proj.pixelsPerUnit();
    const double t = 0.5;  // depth 15
    const ProjectedMotion m = projectMotion(MotionSnapshot(scene, proj, t), scene, {0, 0, {1, 0, 0}});
    EXPECT_NEAR(m.point.depth, 15.0, 1e-12);
    EXPECT_NEAR(m.depth_rate, 10.0, 1e-12);
    // p1 = 2/15 (up), p2 = -1/15 (right is -x); p' = -p 10/15.
    EXPECT_NEAR(m.raster_velocity.x, k * (1.0 / 15.0) * (10.0 / 15.0), 1e-10);
    EXPECT_NEAR(m.raster_velocity.y, k * (2.0 / 15.0) * (10.0 / 15.0), 1e-10);
}

TEST(SurfacePath, PointsBehindTheCameraAreFlagged) {
    Scene scene = testing::stillCameraScene();
    scene.objects.push_back(testing::triangleObject({0, 0, -1}, {1, 0, 1}, {0, 1, 1}));
    const Projection proj = projectionOf(scene);
    const MotionSnapshot snapshot(scene, proj, 0.0);
    const ProjectedPoint behind = project(snapshot, scene, {0, 0, {1, 0, 0}});
    EXPECT_TRUE(behind.behind);
    EXPECT_EQ(behind.inv_depth, 0.0);
    EXPECT_NEAR(behind.depth, -1.0, 1e-15);
    // On the camera plane exactly: also behind (depth 0 <= near).
    EXPECT_TRUE(project(snapshot, scene, {0, 0, {0.5, 0.5, 0}}).behind);
    EXPECT_FALSE(project(snapshot, scene, {0, 0, {0, 0.5, 0.5}}).behind);
    const ProjectedMotion m = projectMotion(snapshot, scene, {0, 0, {1, 0, 0}});
    EXPECT_TRUE(m.point.behind);
    EXPECT_EQ(m.raster_velocity, glm::dvec2(0.0));
}

TEST(SurfacePath, HeldOutsideKeysHasZeroVelocity) {
    Scene scene = testing::stillCameraScene();
    Object tri = testing::triangleObject({-1, -1, 10}, {1, -1, 10}, {0, 1, 10});
    testing::addTransformKey(tri, 0.2, {0, 0, 0});
    testing::addTransformKey(tri, 0.6, {1, 0, 0}, {0, 0, 1}, 0.5);
    scene.objects.push_back(tri);
    const Projection proj = projectionOf(scene);
    for (double t : {0.0, 0.1, 0.6, 0.9}) {
        const ProjectedMotion m = projectMotion(MotionSnapshot(scene, proj, t), scene, {0, 0, {0.2, 0.3, 0.5}});
        EXPECT_EQ(m.raster_velocity, glm::dvec2(0.0)) << t;
    }
    // At the first key the right derivative applies: the object starts moving.
    const ProjectedMotion start = projectMotion(MotionSnapshot(scene, proj, 0.2), scene, {0, 0, {0.2, 0.3, 0.5}});
    EXPECT_GT(glm::length(start.raster_velocity), 1.0);
}

}  // namespace
}  // namespace clipblur
