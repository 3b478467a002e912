#include "renderer/propagation/subframes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "renderer/visibility/frame_geometry.h"
#include "support/motion_scenes.h"

namespace clipblur {
namespace {

Projection projectionOf(const Scene& scene) {
    return Projection(scene.film.width, scene.film.height, scene.camera.vfov_degrees);
}

const RasterBounds kWholeFilm{{0, 0}, {640, 360}};

// A triangle at depth `depth` whose points all move `pixels` raster pixels along x over [0, 1].
Object slidingTriangle(const Projection& proj, double depth, double pixels) {
    Object tri = testing::triangleObject({-1, -1, depth}, {1, -1, depth}, {0, 1, depth});
    testing::addTransformKey(tri, 0.0, {0, 0, 0});
    // Image right is -x (e2 = e3 x e1); a world shift dx at depth z moves k dx / z pixels.
    testing::addTransformKey(tri, 1.0, {-pixels * depth / proj.pixelsPerUnit(), 0, 0});
    return tri;
}

TEST(Subframes, StaticSceneNeedsOneSubframe) {
    Scene scene = testing::stillCameraScene();
    scene.objects.push_back(testing::triangleObject({-1, -1, 10}, {1, -1, 10}, {0, 1, 10}));
    const ShutterPathSampler sampler(scene, projectionOf(scene), 0.0, 1.0);
    const MeshPoint verts[3] = {{0, 0, {1, 0, 0}}, {0, 0, {0, 1, 0}}, {0, 0, {0, 0, 1}}};
    const FragmentMotion fm = sampler.measure(verts);
    EXPECT_EQ(fm.max_path_pixels, 0.0);
    EXPECT_FALSE(fm.crosses_near);
    const SubframePlan plan = planSubframes(std::span(&fm, 1), kWholeFilm, 256);
    EXPECT_EQ(plan.count, 1);
    EXPECT_FALSE(plan.capped);
    EXPECT_EQ(plan.fragments, 1);
    // Nothing at all in the tile: also one subframe.
    EXPECT_EQ(planSubframes({}, kWholeFilm, 256).count, 1);
}

TEST(Subframes, VertexMoving10Point3PixelsNeeds11) {
    Scene scene = testing::stillCameraScene();
    const Projection proj = projectionOf(scene);
    scene.objects.push_back(slidingTriangle(proj, 10.0, 10.3));
    const ShutterPathSampler sampler(scene, proj, 0.0, 1.0);
    const MeshPoint verts[3] = {{0, 0, {1, 0, 0}}, {0, 0, {0, 1, 0}}, {0, 0, {0, 0, 1}}};
    const FragmentMotion fm = sampler.measure(verts);
    // Constant velocity: Gauss-Legendre integrates it exactly, up to rounding.
    EXPECT_NEAR(fm.max_path_pixels, 10.3, 1e-10);
    const SubframePlan plan = planSubframes(std::span(&fm, 1), kWholeFilm, 256);
    EXPECT_EQ(plan.count, 11);
    EXPECT_FALSE(plan.capped);
}

TEST(Subframes, CurvedPathGetsMoreSubframesThanItsChord) {
    // A quarter-turn roll of the camera: a point 100 px from the image centre travels an arc of
    // 50 pi = 157.08 px, its chord is 100 sqrt(2) = 141.42 px and its endpoint speeds are equal.
    Scene scene = testing::stillCameraScene();
    scene.camera.keys.push_back({1.0, {0, 0, 0}, {0, 0, 1}, {1, 0, 0}});
    const Projection proj = projectionOf(scene);
    // 100 px from the centre, diagonally (right and down) at depth 10, so the quarter arc passes an
    // axis and bulges past the box of its end points.
    const double c = -100.0 / std::sqrt(2.0) / proj.pixelsPerUnit() * 10.0;
    scene.objects.push_back(testing::triangleObject({c, c, 10}, {c + 1, c, 10}, {c, c + 1, 10}));
    const ShutterPathSampler sampler(scene, proj, 0.0, 1.0);
    const MeshPoint corner{0, 0, {1, 0, 0}};
    // Constant speed along the arc, so the quadrature is exact up to rounding.
    EXPECT_NEAR(sampler.pathLength(corner), 50.0 * M_PI, 1e-9);
    const FragmentMotion fm = sampler.measure(std::span(&corner, 1));
    const SubframePlan plan = planSubframes(std::span(&fm, 1), kWholeFilm, 1024);
    EXPECT_EQ(plan.count, 158);
    const glm::dvec2 a = project(MotionSnapshot(scene, proj, 0.0), scene, corner).raster;
    const glm::dvec2 b = project(MotionSnapshot(scene, proj, 1.0), scene, corner).raster;
    const int chord_count = subframeCount(glm::length(b - a), 1024);
    EXPECT_EQ(chord_count, 142);
    EXPECT_GT(plan.count, chord_count);
    // The swept box holds the whole arc, which bulges beyond the end points' box.
    RasterBounds ends;
    ends.expand(a);
    ends.expand(b);
    int outside_ends = 0;
    for (int i = 0; i <= 1000; ++i) {
        const glm::dvec2 p = project(MotionSnapshot(scene, proj, i / 1000.0), scene, corner).raster;
        EXPECT_TRUE(fm.swept.overlaps(RasterBounds{p, p})) << i;
        if (!ends.overlaps(RasterBounds{p, p})) ++outside_ends;
    }
    EXPECT_GT(outside_ends, 100);
}

TEST(Subframes, PathThereAndBackCountsBothWays) {
    // Keys at 0, 0.5, 1: out 8 px and back. The chord is zero; the path is 16 px.
    Scene scene = testing::stillCameraScene();
    const Projection proj = projectionOf(scene);
    Object tri = testing::triangleObject({-1, -1, 10}, {1, -1, 10}, {0, 1, 10});
    testing::addTransformKey(tri, 0.0, {0, 0, 0});
    testing::addTransformKey(tri, 0.5, {8.0 * 10.0 / proj.pixelsPerUnit(), 0, 0});
    testing::addTransformKey(tri, 1.0, {0, 0, 0});
    scene.objects.push_back(tri);
    const ShutterPathSampler sampler(scene, proj, 0.0, 1.0);
    EXPECT_EQ(sampler.breakpoints(), (std::vector<double>{0.0, 0.5, 1.0}));
    EXPECT_NEAR(sampler.pathLength({0, 0, {0.3, 0.3, 0.4}}), 16.0, 1e-10);
}

// Largest raster distance a vertex covers between consecutive subframes (and from the shutter ends
// to the first and last subframe, which the midpoint rule leaves at half a step).
double maxSubframeStep(const Scene& scene, const Projection& proj, std::span<const MeshPoint> verts,
                       double t0, double t1, int count) {
    std::vector<double> times = subframeTimes(t0, t1, count);
    double step = 0.0;
    for (const MeshPoint& v : verts) {
        glm::dvec2 prev = project(MotionSnapshot(scene, proj, times[0]), scene, v).raster;
        const glm::dvec2 open = project(MotionSnapshot(scene, proj, t0), scene, v).raster;
        step = std::max(step, 2.0 * glm::length(prev - open));
        for (std::size_t k = 1; k < times.size(); ++k) {
            const glm::dvec2 p = project(MotionSnapshot(scene, proj, times[k]), scene, v).raster;
            step = std::max(step, glm::length(p - prev));
            prev = p;
        }
        const glm::dvec2 close = project(MotionSnapshot(scene, proj, t1), scene, v).raster;
        step = std::max(step, 2.0 * glm::length(close - prev));
    }
    return step;
}

TEST(Subframes, NonUniformSpeedIsPlannedFromPeakSpeed) {
    // Still for the first half of the shutter, then 10 px in the second half. The path is 10 px, but ten
    // equal subframes would put two pixels between the moving ones; the count follows the peak speed
    // (20 px/frame x 1 frame) so every step stays within a pixel.
    Scene scene = testing::stillCameraScene();
    const Projection proj = projectionOf(scene);
    Object tri = testing::triangleObject({-1, -1, 10}, {1, -1, 10}, {0, 1, 10});
    testing::addTransformKey(tri, 0.0, {0, 0, 0});
    testing::addTransformKey(tri, 0.5, {0, 0, 0});
    testing::addTransformKey(tri, 1.0, {-10.0 * 10.0 / proj.pixelsPerUnit(), 0, 0});
    scene.objects.push_back(tri);
    const ShutterPathSampler sampler(scene, proj, 0.0, 1.0);
    const MeshPoint v{0, 0, {0.2, 0.5, 0.3}};
    const FragmentMotion fm = sampler.measure(std::span(&v, 1));
    EXPECT_NEAR(fm.max_path_pixels, 10.0, 1e-10);
    EXPECT_NEAR(fm.max_sweep_pixels, 20.0, 1e-10);
    const SubframePlan plan = planSubframes(std::span(&fm, 1), kWholeFilm, 256);
    EXPECT_EQ(plan.count, 20);
    EXPECT_LE(maxSubframeStep(scene, proj, std::span(&v, 1), 0.0, 1.0, plan.count), 1.0 + 1e-9);
    EXPECT_NEAR(maxSubframeStep(scene, proj, std::span(&v, 1), 0.0, 1.0, 10), 2.0, 1e-9);
}

// A sweep interval follows the parabola through a point's homogeneous raster coordinates (raster x depth,
// depth) at t = 0, 1/2 and 1, and divides (SweepPath::through). Under translation those coordinates are
// linear in time, so a receding point, whose raster path bends as 1 / depth and leaves the raster parabola
// through the same three positions by pixels, is followed exactly. A turning point is not: its distance
// from that path is computed here by hand (raster x = W/2 - k X / z, y = H/2 - k Y / z for this camera,
// the point turned about y by the angle t) over 2001 times. The sampler sees only its nodes (33 with 8
// intervals), so it may fall a little short of the dense maximum but never above it; 2% covers the
// nodes' spacing near the maxima.
TEST(Subframes, SweepPathDeviationOfRecedingAndTurningPoints) {
    const glm::dvec3 a(-3.0, 1.0, 5.0);
    const MeshPoint v{0, 0, {1, 0, 0}};
    const auto lagrange = [](double u, const auto& p0, const auto& pm, const auto& p1) {
        return p0 * (2.0 * (u - 0.5) * (u - 1.0)) - pm * (4.0 * u * (u - 1.0)) + p1 * (2.0 * u * (u - 0.5));
    };
    {
        Scene scene = testing::stillCameraScene();
        const Projection proj = projectionOf(scene);
        Object tri = testing::triangleObject(a, {1, -1, 5}, {0, 1, 5});
        testing::addTransformKey(tri, 0.0, {0, 0, 0});
        testing::addTransformKey(tri, 1.0, {0, 0, 5});
        scene.objects.push_back(tri);
        const double k = proj.pixelsPerUnit();
        const auto raster = [&](double t) {
            const double z = a.z + 5.0 * t;
            return glm::dvec2(0.5 * scene.film.width - k * a.x / z, 0.5 * scene.film.height - k * a.y / z);
        };
        double raster_parabola = 0.0;
        for (int i = 0; i <= 2000; ++i) {
            const double u = i / 2000.0;
            raster_parabola =
                std::max(raster_parabola, glm::length(raster(u) - lagrange(u, raster(0.0), raster(0.5), raster(1.0))));
        }
        EXPECT_GT(raster_parabola, 1.0);  // what the raster parabola would miss: a few pixels
        const FragmentMotion fm = ShutterPathSampler(scene, proj, 0.0, 1.0, 8).measure(std::span(&v, 1));
        EXPECT_LT(fm.parabola_deviation, 1e-9);
    }
    {
        Scene scene = testing::stillCameraScene();
        const Projection proj = projectionOf(scene);
        Object tri = testing::triangleObject(a, {1, -1, 5}, {0, 1, 5});
        testing::addTransformKey(tri, 0.0, {0, 0, 0});
        testing::addTransformKey(tri, 1.0, {0, 0, 0}, {0, 1, 0}, 1.0);
        scene.objects.push_back(tri);
        const double k = proj.pixelsPerUnit();
        const auto homogeneous = [&](double t) {  // (raster x z, raster y z, z)
            const double x = a.x * std::cos(t) + a.z * std::sin(t), z = -a.x * std::sin(t) + a.z * std::cos(t);
            return glm::dvec3(0.5 * scene.film.width * z - k * x, 0.5 * scene.film.height * z - k * a.y, z);
        };
        double dense = 0.0;
        for (int i = 0; i <= 2000; ++i) {
            const double u = i / 2000.0;
            const glm::dvec3 h = homogeneous(u), q = lagrange(u, homogeneous(0.0), homogeneous(0.5), homogeneous(1.0));
            dense = std::max(dense, glm::length(glm::dvec2(h) / h.z - glm::dvec2(q) / q.z));
        }
        const FragmentMotion fm = ShutterPathSampler(scene, proj, 0.0, 1.0, 8).measure(std::span(&v, 1));
        EXPECT_GT(dense, 0.1);  // the test means something
        EXPECT_LE(fm.parabola_deviation, dense + 1e-9);
        EXPECT_GE(fm.parabola_deviation, 0.98 * dense);
    }
    {
        // A camera backing away while it pans by 0.3 rad: the homogeneous parabola through the point's
        // positions misses its path (by hand: raster x = W/2 + k (e2 . d) / z with the camera turned by
        // 0.3 t about y, e2 = -(cos, 0, -sin)), but with the camera's turn taken out and put back the
        // sweep's path is exact.
        Scene scene = testing::stillCameraScene();
        const Projection proj = projectionOf(scene);
        scene.objects.push_back(testing::triangleObject(a, {1, -1, 5}, {0, 1, 5}));
        scene.camera.keys.push_back(
            CameraKey{1.0, glm::dvec3(0, 0, -5), glm::dvec3(std::sin(0.3), 0, std::cos(0.3)), glm::dvec3(0, 1, 0)});
        const double k = proj.pixelsPerUnit();
        const auto homogeneous = [&](double t) {
            const glm::dvec3 d = a - glm::dvec3(0, 0, -5.0 * t);
            const glm::dvec3 e1(0, 1, 0), e3(std::sin(0.3 * t), 0, std::cos(0.3 * t)), e2 = glm::cross(e3, e1);
            const double z = glm::dot(e3, d);
            return glm::dvec3(0.5 * scene.film.width * z + k * glm::dot(e2, d), 0.5 * scene.film.height * z - k * glm::dot(e1, d), z);
        };
        double unturned = 0.0;
        for (int i = 0; i <= 2000; ++i) {
            const double u = i / 2000.0;
            const glm::dvec3 h = homogeneous(u), q = lagrange(u, homogeneous(0.0), homogeneous(0.5), homogeneous(1.0));
            unturned = std::max(unturned, glm::length(glm::dvec2(h) / h.z - glm::dvec2(q) / q.z));
        }
        EXPECT_GT(unturned, 0.1);
        const FragmentMotion fm = ShutterPathSampler(scene, proj, 0.0, 1.0, 8).measure(std::span(&v, 1));
        EXPECT_LT(fm.parabola_deviation, 1e-9);
    }
    Scene slide = testing::stillCameraScene();
    const Projection proj = projectionOf(slide);
    slide.objects.push_back(slidingTriangle(proj, 10.0, 37.0));
    EXPECT_LT(ShutterPathSampler(slide, proj, 0.0, 1.0).measure(std::span(&v, 1)).parabola_deviation, 1e-9);
}

// A turn about the view axis turns the image about its centre, an affine map: a fragment's displacement
// (FragmentMotion::displacement, the map of its whole source triangle) then gives every surface point's
// open-to-close move exactly, also for a sliver piece whose own three vertices pin no map across it.
// Expected positions by hand: the point turned by 0.5 rad about z, projected as raster = (W/2 - k x / z,
// H/2 - k y / z). Seeded points of the triangle; 1e-9 px is rounding.
TEST(Subframes, DisplacementOfASliverFollowsItsTurningTriangle) {
    Scene scene = testing::stillCameraScene();
    const Projection proj = projectionOf(scene);
    const glm::dvec3 a(-3.0, 1.0, 5.0), b(1.0, -1.0, 5.0), c(0.0, 2.0, 5.0);
    Object tri = testing::triangleObject(a, b, c);
    testing::addTransformKey(tri, 0.0, {0, 0, 0});
    testing::addTransformKey(tri, 1.0, {0, 0, 0}, {0, 0, 1}, 0.5);
    scene.objects.push_back(tri);
    const double k = proj.pixelsPerUnit();
    const auto raster = [&](const glm::dvec3& p, double angle) {
        const glm::dvec3 q(p.x * std::cos(angle) - p.y * std::sin(angle), p.x * std::sin(angle) + p.y * std::cos(angle), p.z);
        return glm::dvec2(0.5 * scene.film.width - k * q.x / q.z, 0.5 * scene.film.height - k * q.y / q.z);
    };
    const std::array<MeshPoint, 3> sliver{MeshPoint{0, 0, {0.6, 0.2, 0.2}}, MeshPoint{0, 0, {0.2, 0.6, 0.2}},
                                          MeshPoint{0, 0, {0.4 + 1e-4, 0.4, 0.2 - 1e-4}}};
    const FragmentMotion fm = ShutterPathSampler(scene, proj, 0.0, 1.0, 8).measure(sliver);
    EXPECT_EQ(fm.unstretched_error, 0.0) << "the piece's own map is ill-posed";
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int i = 0; i < 50; ++i) {
        double s = u(rng), t = u(rng);
        if (s + t > 1.0) s = 1.0 - s, t = 1.0 - t;
        const glm::dvec3 p = a + s * (b - a) + t * (c - a);
        const glm::dvec2 open = raster(p, 0.0);
        EXPECT_LT(glm::length(fm.displacement(open) - (raster(p, 0.5) - open)), 1e-9) << i;
    }
}

// A face nearly edge-on (a sphere's silhouette) turning to face the camera: its source map is fitted to a
// sliver, so beyond the triangle it extrapolates to hundreds of pixels. displacementNear takes the
// triangle's nearest point, where the map interpolates the corners' moves: never more than the largest of
// them, wherever in the swept box it is asked. By hand: the object turns about its x axis and sits 10
// units ahead, raster = (W/2 - k x / z, H/2 - k y / z). The map is anchored at the piece's own mean
// vertex (FragmentMotion::start, end), which a projective motion moves off the corners' affine fit by
// `anchor`, computed here from the same hand projection; 1e-9 px is rounding.
TEST(Subframes, DisplacementNearAnEdgeOnFaceStaysWithinItsCornersMoves) {
    Scene scene = testing::stillCameraScene();
    const Projection proj = projectionOf(scene);
    const std::array<glm::dvec3, 3> corners{glm::dvec3(-1.0, 0.0, 0.0), glm::dvec3(1.0, 0.0, 0.0),
                                            glm::dvec3(0.0, 0.02, 2.0)};
    constexpr double kTurn = 0.2;  // rad
    Object tri = testing::triangleObject(corners[0], corners[1], corners[2]);
    testing::addTransformKey(tri, 0.0, {0, 0, 10});
    testing::addTransformKey(tri, 1.0, {0, 0, 10}, {1, 0, 0}, kTurn);
    scene.objects.push_back(tri);
    const double k = proj.pixelsPerUnit();
    const auto raster = [&](const glm::dvec3& p, double angle) {
        const glm::dvec3 q(p.x, p.y * std::cos(angle) - p.z * std::sin(angle), p.y * std::sin(angle) + p.z * std::cos(angle) + 10.0);
        return glm::dvec2(0.5 * scene.film.width - k * q.x / q.z, 0.5 * scene.film.height - k * q.y / q.z);
    };
    std::array<glm::dvec2, 3> open{}, close{};
    double largest = 0.0;
    for (std::size_t i = 0; i < 3; ++i) {
        open[i] = raster(corners[i], 0.0);
        close[i] = raster(corners[i], kTurn);
        largest = std::max(largest, glm::length(close[i] - open[i]));
    }
    const glm::dmat2 fit = glm::dmat2(close[1] - close[0], close[2] - close[0]) *
                           glm::inverse(glm::dmat2(open[1] - open[0], open[2] - open[0]));
    const std::array<glm::dvec3, 3> bary{glm::dvec3(0.5, 0.3, 0.2), glm::dvec3(0.3, 0.5, 0.2), glm::dvec3(0.4, 0.3, 0.3)};
    std::array<MeshPoint, 3> piece{};
    glm::dvec2 start(0.0), end(0.0);
    for (std::size_t i = 0; i < 3; ++i) {
        piece[i] = MeshPoint{0, 0, bary[i]};
        const glm::dvec3 p = bary[i].x * corners[0] + bary[i].y * corners[1] + bary[i].z * corners[2];
        start += raster(p, 0.0) / 3.0;
        end += raster(p, kTurn) / 3.0;
    }
    const double anchor = glm::length(end - (close[0] + fit * (start - open[0])));
    const FragmentMotion fm = ShutterPathSampler(scene, proj, 0.0, 1.0, 8).measure(piece);
    ASSERT_TRUE(fm.has_source);
    for (std::size_t i = 0; i < 3; ++i)
        EXPECT_LT(glm::length(fm.displacementNear(open[i]) - (close[i] - open[i])), anchor + 1e-9) << i;
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> ux(fm.swept.lo.x - 4.0, fm.swept.hi.x + 4.0), uy(fm.swept.lo.y - 4.0, fm.swept.hi.y + 4.0);
    double extrapolated = 0.0;
    for (int i = 0; i < 200; ++i) {
        const glm::dvec2 x(ux(rng), uy(rng));
        EXPECT_LE(glm::length(fm.displacementNear(x)), largest + anchor + 1e-9) << i;
        extrapolated = std::max(extrapolated, glm::length(fm.displacement(x)));
    }
    EXPECT_GT(extrapolated, 10.0 * largest) << "the map beyond the triangle is what the test guards against";
}

TEST(Subframes, MotionAfterTheShutterDoesNotCount) {
    // Keys at the shutter close and later: still during [0, 1], fast afterwards.
    Scene scene = testing::stillCameraScene();
    const Projection proj = projectionOf(scene);
    Object tri = testing::triangleObject({-1, -1, 10}, {1, -1, 10}, {0, 1, 10});
    testing::addTransformKey(tri, 1.0, {0, 0, 0});
    testing::addTransformKey(tri, 2.0, {5, 0, 0});
    scene.objects.push_back(tri);
    const MeshPoint v{0, 0, {1, 0, 0}};
    const FragmentMotion fm = ShutterPathSampler(scene, proj, 0.0, 1.0).measure(std::span(&v, 1));
    EXPECT_EQ(fm.max_sweep_pixels, 0.0);
    EXPECT_EQ(planSubframes(std::span(&fm, 1), kWholeFilm, 256).count, 1);
}

TEST(Subframes, PlannedCountKeepsRandomMotionWithinAPixelPerStep) {
    // Property over random camera and object motion (curved paths, keys inside the shutter, deformation):
    // with the planned count, no vertex moves more than a pixel between subframes. The peak speed is
    // sampled at Gauss nodes, not maximised exactly, so allow 2% over a pixel.
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (std::uint64_t seed = 1; seed <= 8; ++seed) {
        const Scene scene = testing::randomMovingScene(seed);
        const Projection proj = projectionOf(scene);
        const ShutterPathSampler sampler(scene, proj, 0.0, 1.0);
        for (std::uint32_t obj = 0; obj < 3; ++obj) {
            std::vector<MeshPoint> verts;
            for (int j = 0; j < 3; ++j) {
                glm::dvec3 b(u(rng), u(rng), u(rng));
                verts.push_back({obj, obj, b / (b.x + b.y + b.z)});
            }
            const FragmentMotion fm = sampler.measure(verts);
            const SubframePlan plan = planSubframes(std::span(&fm, 1), RasterBounds::everything(), 1 << 20);
            ASSERT_FALSE(plan.capped);
            EXPECT_GT(plan.count, 1);
            EXPECT_LE(maxSubframeStep(scene, proj, verts, 0.0, 1.0, plan.count), 1.02) << "seed " << seed;
        }
    }
}

// A pixel [0, 1] that an edge crosses at L px per shutter, starting at x0: its covered share at time t is
// clamp(x0 + L t, 0, 1), whose integral over [0, 1] has the closed form (G(x0 + L) - G(x0)) / L with G
// the antiderivative of the clamp. The largest error of n midpoint samples over where the edge starts.
double kinkError(double pixels, int n) {
    const auto clamp01 = [](double u) { return std::clamp(u, 0.0, 1.0); };
    const auto antiderivative = [](double u) { return u < 0.0 ? 0.0 : u < 1.0 ? 0.5 * u * u : u - 0.5; };
    double worst = 0.0;
    constexpr int kStarts = 2000;
    for (int i = 0; i <= kStarts; ++i) {
        const double x0 = -pixels - 0.5 + (pixels + 2.0) * i / kStarts;
        const double exact = (antiderivative(x0 + pixels) - antiderivative(x0)) / pixels;
        double sampled = 0.0;
        for (int k = 0; k < n; ++k) sampled += clamp01(x0 + pixels * (k + 0.5) / n);
        worst = std::max(worst, std::abs(sampled / n - exact));
    }
    return worst;
}

// Eq. 24's count leaves short motions a visible step at the edges; kinkSamples holds every motion to
// what eq. 24 leaves at kKinkMotion px, spacing^2 / 512 of the contrast over the whole shutter.
TEST(Subframes, KinkSamplesHoldAnEdgeCrossingAPixelToA512thOfItsContrast) {
    for (const double spacing : {0.5, 1.0, 2.0}) {
        const double bound = spacing * spacing / 512.0;
        for (const double pixels : {0.3, 1.0, 2.0, 3.0, 5.5, 9.0, 17.0, 31.0, 48.0, 100.0}) {
            for (const double share : {1.0, 0.25}) {
                const int n = subframeCount(kinkSamples(pixels, share, spacing), 1 << 20);
                // The error in the frame is the interval's share of it; 1e-9 is rounding in the sum.
                EXPECT_LE(share * kinkError(pixels, n), bound * (1.0 + 1e-9))
                    << pixels << " px, share " << share << ", spacing " << spacing << ", " << n << " samples";
                if (pixels >= kKinkMotion * share) {
                    EXPECT_EQ(n, subframeCount(pixels / spacing, 1 << 20)) << "eq. 24";
                }
            }
        }
    }
    // What the floor is for: eq. 24 at a pixel's spacing leaves a 3 px motion 1/24 of the contrast.
    EXPECT_NEAR(kinkError(3.0, subframeCount(3.0, 256)), 1.0 / 24.0, 1e-3);
    EXPECT_EQ(subframeCount(kinkSamples(0.0, 1.0, 1.0), 256), 1) << "no motion, one sample";
    bool capped = false;
    subframeCount(kinkSamples(std::numeric_limits<double>::quiet_NaN(), 1.0, 1.0), 256, &capped);
    EXPECT_TRUE(capped) << "a NaN path is capped, not a count";
}

TEST(Subframes, CapIsHonouredAndFlagged) {
    bool capped = false;
    EXPECT_EQ(subframeCount(1000.2, 64, &capped), 64);
    EXPECT_TRUE(capped);
    EXPECT_EQ(subframeCount(64.0, 64, &capped), 64);
    EXPECT_FALSE(capped);
    EXPECT_EQ(subframeCount(std::numeric_limits<double>::infinity(), 64, &capped), 64);
    EXPECT_TRUE(capped);

    Scene scene = testing::stillCameraScene();
    const Projection proj = projectionOf(scene);
    // The corner starts 49 px right of the centre and stays on the 640 px image (what is off it does not count).
    scene.objects.push_back(slidingTriangle(proj, 10.0, 250.0));
    const ShutterPathSampler sampler(scene, proj, 0.0, 1.0);
    const MeshPoint v{0, 0, {1, 0, 0}};
    const FragmentMotion fm = sampler.measure(std::span(&v, 1));
    const SubframePlan plan = planSubframes(std::span(&fm, 1), kWholeFilm, 128);
    EXPECT_EQ(plan.count, 128);
    EXPECT_TRUE(plan.capped);
    EXPECT_NEAR(plan.max_path_pixels, 250.0, 1e-9);
}

TEST(Subframes, SpeedOffTheImageDoesNotCount) {
    // A corner one unit off the axis in x and y comes from depth 10 to 0.5: its offset from the image
    // centre is k (1, 1) / z and its speed k sqrt(2) |z'| / z^2, 16x faster at close (18,800 px per
    // shutter) than where it leaves the 640 x 360 image, at z = k / 180 (the vertical half-height).
    // Off the image no pixel sees it: the count follows the speed where it leaves.
    Scene scene = testing::stillCameraScene();
    const Projection proj = projectionOf(scene);
    Object tri = testing::triangleObject({-1, -1, 10}, {1, -1, 10}, {0, 1, 10});
    testing::addTransformKey(tri, 0.0, {0, 0, 0});
    testing::addTransformKey(tri, 1.0, {0, 0, -9.5});
    scene.objects.push_back(tri);
    const ShutterPathSampler sampler(scene, proj, 0.0, 1.0);
    const MeshPoint v{0, 0, {1, 0, 0}};
    const FragmentMotion fm = sampler.measure(std::span(&v, 1));
    const double k = proj.pixelsPerUnit(), leaves = k / 180.0;
    const double at_edge = k * std::sqrt(2.0) * 9.5 / (leaves * leaves);
    // Exact: on a line, the square root of the speed is affine in the distance along it (1/z is).
    EXPECT_NEAR(fm.max_sweep_pixels, at_edge, 1e-9 * at_edge);
    EXPECT_FALSE(fm.crosses_near);
    // The path on the image: from 49 px off the centre in y to the edge, 180 px, times sqrt 2.
    EXPECT_NEAR(fm.max_path_pixels, std::sqrt(2.0) * (180.0 - k / 10.0), 1e-9);
}

TEST(Subframes, PrintedEquation24LetsTheFastestVertexStrobe) {
    // Two vertices: one at depth 100 moving 1 px per frame, one at depth 10 moving 10 px per frame. The
    // printed eq. 24, df = max_v sqrt(a_p) / |p'_v|, takes the slow vertex: df = 1 frame, one subframe,
    // and the fast vertex jumps 10 px between subframes. The minimum (our count) keeps every vertex
    // within a pixel per subframe.
    Scene scene = testing::stillCameraScene();
    const Projection proj = projectionOf(scene);
    scene.objects.push_back(slidingTriangle(proj, 100.0, 1.0));
    scene.objects.push_back(slidingTriangle(proj, 10.0, 10.0));
    // Image-plane speeds by construction: pixels per frame / pixels per unit.
    const double speeds[2] = {1.0 / proj.pixelsPerUnit(), 10.0 / proj.pixelsPerUnit()};
    const double sqrt_ap = std::sqrt(proj.pixelArea());
    const double df_printed = std::max(sqrt_ap / speeds[0], sqrt_ap / speeds[1]);
    const double df_corrected = std::min(sqrt_ap / speeds[0], sqrt_ap / speeds[1]);
    EXPECT_NEAR(df_printed, 1.0, 1e-12);
    EXPECT_NEAR(df_corrected, 0.1, 1e-12);

    const ShutterPathSampler sampler(scene, proj, 0.0, 1.0);
    const MeshPoint verts[2] = {{0, 0, {1, 0, 0}}, {1, 0, {1, 0, 0}}};
    const FragmentMotion fm = sampler.measure(verts);
    const SubframePlan plan = planSubframes(std::span(&fm, 1), kWholeFilm, 256);
    EXPECT_EQ(plan.count, 10);

    EXPECT_GT(maxSubframeStep(scene, proj, verts, 0.0, 1.0, static_cast<int>(std::ceil(1.0 / df_printed))), 9.0);
    EXPECT_LE(maxSubframeStep(scene, proj, verts, 0.0, 1.0, plan.count), 1.0 + 1e-9);
}

TEST(Subframes, TimesAreShutterMidpointsWithEqualWeights) {
    const std::vector<double> t = subframeTimes(2.25, 2.75, 4);
    ASSERT_EQ(t.size(), 4u);
    EXPECT_DOUBLE_EQ(t[0], 2.25 + 0.0625);
    EXPECT_DOUBLE_EQ(t[1], 2.25 + 0.1875);
    EXPECT_DOUBLE_EQ(t[3], 2.75 - 0.0625);
    EXPECT_DOUBLE_EQ(subframeWeight(4), 0.25);
    EXPECT_EQ(subframeTimes(0.0, 1.0, 1), std::vector<double>{0.5});
    // The midpoint rule integrates any linear function of time exactly: the mean of the times is the
    // shutter centre.
    double mean = 0.0;
    for (double x : subframeTimes(0.0, 1.0, 7)) mean += x * subframeWeight(7);
    EXPECT_NEAR(mean, 0.5, 1e-15);
}

TEST(Subframes, SweptBoxHoldsDenselySampledPaths) {
    // Property: every position on the image of every vertex and of points inside the fragment (its
    // centroid, its edges' midpoints), sampled at 2001 times across the shutter, lies in the fragment's
    // swept box. Fragments are random sub-triangles of random moving scenes.
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (std::uint64_t seed = 1; seed <= 10; ++seed) {
        const Scene scene = testing::randomMovingScene(seed);
        const Projection proj = projectionOf(scene);
        const ShutterPathSampler sampler(scene, proj, 0.0, 1.0, 4);
        std::vector<MotionSnapshot> dense;
        for (int i = 0; i <= 2000; ++i) dense.emplace_back(scene, proj, i / 2000.0);
        for (std::uint32_t obj = 0; obj < 3; ++obj) {
            std::vector<MeshPoint> verts;
            for (int j = 0; j < 3; ++j) {
                glm::dvec3 b(u(rng), u(rng), u(rng));
                verts.push_back({obj, obj, b / (b.x + b.y + b.z)});
            }
            const FragmentMotion fm = sampler.measure(verts);
            ASSERT_FALSE(fm.crosses_near);
            std::vector<MeshPoint> points = verts;
            points.push_back({obj, obj, (verts[0].b + verts[1].b + verts[2].b) / 3.0});
            for (int j = 0; j < 3; ++j) points.push_back({obj, obj, 0.5 * (verts[j].b + verts[(j + 1) % 3].b)});
            const RasterBounds film{{0.0, 0.0}, {double(proj.width), double(proj.height)}};
            for (const MotionSnapshot& s : dense) {
                for (const MeshPoint& v : points) {
                    const glm::dvec2 p = project(s, scene, v).raster;
                    if (film.contains(p)) {
                        ASSERT_TRUE(fm.swept.contains(p)) << "seed " << seed << " t " << s.time;
                    }
                }
            }
        }
    }
}

// Under a camera moving on a line without turning, a translating object's points move on straight image
// lines, and measure takes each path from its ends (ShutterPathSampler::straight). Property, over seeded
// scenes with the camera dollying and panning sideways and triangles translating (some receding to
// twice their depth, so speed varies 4x along the path), against 4001 positions projected at even times:
// the box is the dense positions' box (1e-9 px: rounding), the path length their polyline (a line's
// polyline is its chord; 1e-9 relative), the peak speed at least the largest step's and within 0.2 %
// of it (a step's mean speed trails the peak by under a step's change of 1 / z^2), and the homogeneous
// parabola through open, middle and close (the sweep's path) holds every dense position (1e-9 px).
TEST(Subframes, StraightPathsAreMeasuredFromTheirEnds) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int seed = 0; seed < 8; ++seed) {
        Scene scene = testing::stillCameraScene();
        scene.camera.keys.push_back({1.0, {u(rng) - 0.5, 0.3 * u(rng), 2.0 * u(rng)}, {0, 0, 1}, {0, 1, 0}});
        for (int o = 0; o < 3; ++o) {
            const glm::dvec3 c(4.0 * u(rng) - 2.0, 2.0 * u(rng) - 1.0, 8.0 + 4.0 * u(rng));
            Object tri = testing::triangleObject(c, c + glm::dvec3(1, 0, 0.5), c + glm::dvec3(0, 1, -0.5));
            testing::addTransformKey(tri, 0.0, {0, 0, 0});
            testing::addTransformKey(tri, 1.0, {2.0 * u(rng) - 1.0, u(rng) - 0.5, o == 0 ? c.z : 3.0 * u(rng) - 1.5});
            scene.objects.push_back(tri);
        }
        Object turning = testing::triangleObject({-1, -1, 10}, {1, -1, 10}, {0, 1, 10});
        testing::addTransformKey(turning, 0.0, {0, 0, 0});
        testing::addTransformKey(turning, 1.0, {0, 0, 0}, {0, 0, 1}, 0.2);
        scene.objects.push_back(turning);
        const Projection proj = projectionOf(scene);
        const ShutterPathSampler sampler(scene, proj, 0.0, 1.0, 2);
        ASSERT_FALSE(sampler.straight(3)) << "a turning object";
        std::vector<MotionSnapshot> dense;
        for (int i = 0; i <= 4000; ++i) dense.emplace_back(scene, proj, i / 4000.0);
        const MotionSnapshot middle(scene, proj, 0.5);
        for (std::uint32_t o = 0; o < 3; ++o) {
            ASSERT_TRUE(sampler.straight(o));
            std::vector<MeshPoint> verts;
            for (int j = 0; j < 3; ++j) {
                const glm::dvec3 b(u(rng), u(rng), u(rng));
                verts.push_back({o, 0, b / (b.x + b.y + b.z)});
            }
            const FragmentMotion fm = sampler.measure(verts);
            ASSERT_FALSE(fm.crosses_near);
            RasterBounds box;
            double longest = 0.0, fastest = 0.0, off_parabola = 0.0;
            for (const MeshPoint& v : verts) {
                const auto homogeneous = [&](const MotionSnapshot& s) {
                    const ProjectedPoint p = project(s, scene, v);
                    return glm::dvec3(p.raster * p.depth, p.depth);
                };
                const glm::dvec3 h0 = homogeneous(dense.front()), hm = homogeneous(middle), h1 = homogeneous(dense.back());
                double length = 0.0;
                for (std::size_t i = 0; i < dense.size(); ++i) {
                    const glm::dvec2 p = project(dense[i], scene, v).raster;
                    box.expand(p);
                    const double w = dense[i].time;
                    const glm::dvec3 q = h0 * (2.0 * (w - 0.5) * (w - 1.0)) - hm * (4.0 * w * (w - 1.0)) + h1 * (2.0 * w * (w - 0.5));
                    off_parabola = std::max(off_parabola, glm::length(p - glm::dvec2(q) / q.z));
                    if (i == 0) continue;
                    const double step = glm::length(p - project(dense[i - 1], scene, v).raster);
                    length += step;
                    fastest = std::max(fastest, step * 4000.0);
                }
                longest = std::max(longest, length);
            }
            EXPECT_LT(glm::length(fm.swept.lo - box.lo) + glm::length(fm.swept.hi - box.hi), 1e-9) << seed;
            EXPECT_NEAR(fm.max_path_pixels, longest, 1e-9 * longest) << seed;
            EXPECT_GE(fm.max_sweep_pixels, fastest) << seed;
            EXPECT_LE(fm.max_sweep_pixels, 1.002 * fastest) << seed;
            EXPECT_EQ(fm.parabola_deviation, 0.0);
            EXPECT_LT(off_parabola, 1e-9) << seed;
        }
    }
}

TEST(Subframes, TilesIgnoreFragmentsThatNeverReachThem) {
    Scene scene = testing::stillCameraScene();
    const Projection proj = projectionOf(scene);
    scene.objects.push_back(slidingTriangle(proj, 10.0, 40.0));
    const ShutterPathSampler sampler(scene, proj, 0.0, 1.0);
    const MeshPoint verts[3] = {{0, 0, {1, 0, 0}}, {0, 0, {0, 1, 0}}, {0, 0, {0, 0, 1}}};
    const FragmentMotion fm = sampler.measure(verts);
    const RasterBounds far_tile{{0, 0}, {32, 32}};
    const SubframePlan far_plan = planSubframes(std::span(&fm, 1), far_tile, 256);
    EXPECT_EQ(far_plan.fragments, 0);
    EXPECT_EQ(far_plan.count, 1);
    const RasterBounds centre_tile{{320, 160}, {352, 192}};
    EXPECT_EQ(planSubframes(std::span(&fm, 1), centre_tile, 256).count, 40);
}

TEST(Subframes, CrossingTheCameraPlaneIsFlagged) {
    // The triangle flies from 5 units in front of the camera to 5 behind it.
    Scene scene = testing::stillCameraScene();
    Object tri = testing::triangleObject({-1, -1, 5}, {1, -1, 5}, {0, 1, 5});
    testing::addTransformKey(tri, 0.0, {0, 0, 0});
    testing::addTransformKey(tri, 1.0, {0, 0, -10});
    scene.objects.push_back(tri);
    const ShutterPathSampler sampler(scene, projectionOf(scene), 0.0, 1.0);
    const MeshPoint verts[3] = {{0, 0, {1, 0, 0}}, {0, 0, {0, 1, 0}}, {0, 0, {0, 0, 1}}};
    const FragmentMotion fm = sampler.measure(verts);
    EXPECT_TRUE(fm.crosses_near);
    // It passes through the eye: where it crosses the near depth (1e-6) its corners project some
    // k / 1e-6 = 4.9e8 px from the centre on every side.
    EXPECT_TRUE(fm.swept.contains({-1e8, -1e8}) && fm.swept.contains({1e8, 1e8}));
    const SubframePlan plan = planSubframes(std::span(&fm, 1), RasterBounds{{0, 0}, {32, 32}}, 256);
    EXPECT_EQ(plan.near_crossings, 1);
}

// A face of a post beside the camera's path (configs/bench/near_plane.yaml): the camera dollies 5 units
// past it, so the face goes from 1.8-2.2 units in front to behind the camera. Every point of it it could
// draw (cut at the re-clip's near depth, at 2001 times) lies in its swept box, and the box stays on the
// right of the image: its inner edge is the nearest corner's image at open (|x| / z is least there over
// the swept hull: 1.0 / 1.8), so the tiles left of it never re-clip the face.
TEST(Subframes, CrossingOnAStraightPathIsBoundedByWhatIsInFront) {
    Scene scene = testing::stillCameraScene();
    scene.camera.keys.push_back({1.0, {0, 0, 5}, {0, 0, 1}, {0, 1, 0}});
    scene.objects.push_back(testing::triangleObject({-1.0, -1.5, 1.8}, {-1.4, -1.5, 2.2}, {-1.2, 1.5, 2.0}));
    const Projection proj = projectionOf(scene);
    const ShutterPathSampler sampler(scene, proj, 0.0, 1.0);
    const MeshPoint verts[3] = {{0, 0, {1, 0, 0}}, {0, 0, {0, 1, 0}}, {0, 0, {0, 0, 1}}};
    const FragmentMotion fm = sampler.measure(verts);
    ASSERT_TRUE(fm.crosses_near);
    EXPECT_NEAR(fm.swept.lo.x, project(MotionSnapshot(scene, proj, 0.0), scene, verts[0]).raster.x, 1e-9);
    for (int i = 0; i <= 2000; ++i) {
        const MotionSnapshot at(scene, proj, i / 2000.0);
        std::vector<glm::dvec3> polygon, cut;
        for (const MeshPoint& v : verts) polygon.push_back(project(at, scene, v).world - at.camera.position);
        const auto depth = [&](const glm::dvec3& d) { return glm::dot(at.camera.e3, d); };
        for (std::size_t k = 0; k < polygon.size(); ++k) {  // Sutherland-Hodgman against depth >= kNearDepth
            const glm::dvec3 &p = polygon[k], &q = polygon[(k + 1) % polygon.size()];
            if (depth(p) >= kNearDepth) cut.push_back(p);
            if ((depth(p) < kNearDepth) != (depth(q) < kNearDepth))
                cut.push_back(p + (kNearDepth - depth(p)) / (depth(q) - depth(p)) * (q - p));
        }
        for (const glm::dvec3& d : cut) {
            const glm::dvec2 r = proj.toRaster(glm::dvec2(glm::dot(at.camera.e1, d), glm::dot(at.camera.e2, d)) / depth(d));
            RasterBounds box = fm.swept;
            box.pad(1e-9 * (1.0 + glm::length(r)));  // rounding of coordinates up to 1e7 px
            EXPECT_TRUE(box.contains(r)) << "t " << at.time << " at " << r.x << ", " << r.y;
        }
    }
    const SubframePlan left = planSubframes(std::span(&fm, 1), RasterBounds{{0, 0}, {320, 360}}, 256);
    EXPECT_EQ(left.fragments, 0);
    const SubframePlan right = planSubframes(std::span(&fm, 1), RasterBounds{{608, 160}, {640, 192}}, 256);
    EXPECT_EQ(right.near_crossings, 1);
}

}  // namespace
}  // namespace clipblur
