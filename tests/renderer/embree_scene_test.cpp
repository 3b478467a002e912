#include <cmath>

#include <gtest/gtest.h>

#include "renderer/visibility/embree_scene.h"
#include "scene/camera.h"
#include "scene/error.h"
#include "scene/object_motion.h"
#include "tests/renderer/test_scenes.h"

namespace clipblur {

TEST(EmbreeDevice, ErrorCallbackBecomesAClipblurError) {
    const EmbreeDevice device;
    RTCGeometry geometry = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryTimeStepCount(geometry, 1000);  // above RTC_MAX_TIME_STEP_COUNT: invalid argument
    rtcReleaseGeometry(geometry);
    try {
        device.check("testing");
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::Render);
        EXPECT_NE(e.message().find("invalid argument"), std::string::npos) << e.message();
    }
    EXPECT_NO_THROW(device.check("after the error was reported"));
}

TEST(EmbreeScene, StillSceneHitsTheQuadAtItsDepth) {
    RenderJob job = test::squareFilmJob();
    job.scene.objects.push_back(test::rasterQuad(10, 10, 20, 20, 5.0));
    const EmbreeDevice device;
    const EmbreeScene scene(device, FrameMotion(job.scene, 0.0, 0.0));
    EXPECT_EQ(scene.timeSteps(0), 1);
    const EmbreeHit hit = scene.intersect(glm::dvec3(0.0), test::worldAtRaster(15, 15, 1.0), 0.0);
    ASSERT_TRUE(hit.hit);
    EXPECT_EQ(hit.object, 0);
    EXPECT_NEAR(hit.distance, 5.0, 5.0 * 1e-6);  // float ray parameter
    EXPECT_FALSE(scene.intersect(glm::dvec3(0.0), test::worldAtRaster(25, 15, 1.0), 0.0).hit);
}

// The stochastic renderer shades with the hit's normal instead of re-evaluating the triangle, so its
// sign must be the shader's front side, (v1-v0) x (v2-v0), for both windings and while turning.
TEST(EmbreeScene, HitNormalPointsAlongTheTrianglesOwnCrossProduct) {
    RenderJob job = test::squareFilmJob(512);
    Object tri;
    tri.name = "tri";
    tri.mesh.positions = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
    tri.mesh.triangles = {{0, 1, 2}, {0, 2, 1}};  // both windings, one behind the other
    tri.transform = {TransformKey{0.0, glm::dvec3(0, 0, 5)},
                     TransformKey{1.0, glm::dvec3(0, 0, 6), glm::angleAxis(0.6, glm::dvec3(0.3, 1, 0.2))}};
    job.scene.objects.push_back(tri);
    const EmbreeDevice device;
    const EmbreeScene scene(device, FrameMotion(job.scene, 0.0, 1.0));
    for (double t : {0.0, 0.37, 1.0}) {
        const EmbreeHit hit = scene.intersect(glm::dvec3(0.0), glm::dvec3(0.01, -0.02, 1.0), t);
        ASSERT_TRUE(hit.hit) << "t = " << t;
        const auto& ids = job.scene.objects[0].mesh.triangles[hit.triangle];
        glm::dvec3 v[3];
        for (int k = 0; k < 3; ++k) v[k] = evalVertex(job.scene.objects[0], ids[static_cast<std::size_t>(k)], t);
        const glm::dvec3 n = glm::normalize(glm::cross(v[1] - v[0], v[2] - v[0]));
        // Embree's vertices are linear between its time steps, off their arcs by up to 0.1 px: at 256 px
        // per unit and depth <= 7, 0.0027 units, which tilts a triangle of smallest altitude 1.79 by at
        // most 2 x 0.0027 / 1.79 = 0.003 rad. A wrong sign would give -1.
        EXPECT_GT(glm::dot(glm::normalize(hit.normal), n), std::cos(0.003)) << "t = " << t << " triangle " << hit.triangle;
    }
}

TEST(EmbreeScene, TranslationNeedsTwoStepsAndRotationMore) {
    RenderJob job = test::squareFilmJob(256);
    Object slide = test::rasterQuad(100, 100, 150, 150, 5.0, 256);
    slide.transform = {TransformKey{0.0, glm::dvec3(0.0)}, TransformKey{1.0, glm::dvec3(0.3, 0.0, 0.0)}};
    job.scene.objects.push_back(slide);
    // A quad of half-size 1 centred on the view axis at depth 5, spun 90 degrees about the view axis.
    Object spin;
    spin.name = "spin";
    spin.mesh.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    spin.mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
    spin.transform = {TransformKey{0.0, glm::dvec3(0, 0, 5)},
                      TransformKey{1.0, glm::dvec3(0, 0, 5), glm::angleAxis(M_PI / 2, glm::dvec3(0, 0, 1))}};
    job.scene.objects.push_back(spin);
    const EmbreeDevice device;
    const EmbreeScene scene(device, FrameMotion(job.scene, 0.0, 1.0));
    EXPECT_EQ(scene.timeSteps(0), 2);
    // Corner radius r = sqrt 2 at depth 5 with 128 px per unit; the sagitta of a 90/(n-1) degree chord is
    // r (1 - cos(theta/2)), times (1 + r/5) / 5 * 128 in pixels: 13.6 px (n = 2), 3.5 (3), 0.89 (5),
    // 0.22 (9), 0.056 (17). The first count below 0.1 px in the 2, 3, 5, 9, 17 sequence is 17.
    EXPECT_EQ(scene.timeSteps(1), 17);
    EXPECT_EQ(scene.stats().moving_objects, 2);
    EXPECT_EQ(scene.stats().dropped_triangles, 0);
}

TEST(EmbreeScene, RotatingQuadIsHitWhereTheExactMotionPutsIt) {
    RenderJob job = test::squareFilmJob(256);
    Object spin;
    spin.name = "spin";
    spin.mesh.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    spin.mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
    spin.transform = {TransformKey{0.0, glm::dvec3(0, 0, 5)},
                      TransformKey{1.0, glm::dvec3(0, 0, 5), glm::angleAxis(M_PI / 2, glm::dvec3(0, 0, 1))}};
    job.scene.objects.push_back(spin);
    const EmbreeDevice device;
    const EmbreeScene scene(device, FrameMotion(job.scene, 0.0, 1.0));
    // Aim at a point just inside corner 2 of the exactly rotated quad: 0.98 of the way from the centre
    // is 0.028 world units (0.7 px) inside, more than the 0.1 px chord bound, so it must be hit.
    for (int i = 0; i <= 20; ++i) {
        const double t = i / 20.0;
        const glm::dvec3 corner = evalVertex(spin, 2, t);
        const glm::dvec3 target = glm::dvec3(0, 0, 5) + 0.98 * (corner - glm::dvec3(0, 0, 5));
        const EmbreeHit hit = scene.intersect(glm::dvec3(0.0), target, t);
        EXPECT_TRUE(hit.hit) << "t = " << t;
        // And just outside the corner (1.02) there is nothing.
        const glm::dvec3 outside = glm::dvec3(0, 0, 5) + 1.02 * (corner - glm::dvec3(0, 0, 5));
        EXPECT_FALSE(scene.intersect(glm::dvec3(0.0), outside, t).hit) << "t = " << t;
    }
}

TEST(EmbreeScene, CountsTrianglesEmbreeWouldDrop) {
    RenderJob job = test::squareFilmJob();
    Object quad = test::rasterQuad(10, 10, 20, 20, 5.0);
    quad.mesh.positions.push_back({1e30, 0, 5});  // beyond Embree's coordinate range
    quad.mesh.positions.push_back({0, NAN, 5});
    quad.mesh.triangles.push_back({0, 1, 4});
    quad.mesh.triangles.push_back({0, 5, 1});
    job.scene.objects.push_back(quad);
    const EmbreeDevice device;
    const EmbreeScene scene(device, FrameMotion(job.scene, 0.0, 1.0));
    EXPECT_EQ(scene.stats().triangles, 4);
    EXPECT_EQ(scene.stats().dropped_triangles, 2);
}

TEST(EmbreeScene, BadIndexIsASceneError) {
    RenderJob job = test::squareFilmJob();
    Object quad = test::rasterQuad(10, 10, 20, 20, 5.0);
    quad.mesh.triangles.push_back({0, 1, 9});
    job.scene.objects.push_back(quad);
    const EmbreeDevice device;
    try {
        EmbreeScene scene(device, FrameMotion(job.scene, 0.0, 1.0));
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::Scene);
    }
}

namespace {

// A quad spun 90 degrees about the view axis (17 time steps, 16 segments at 256 px, as above) beside a
// sliding one, meshed finely so rays meet shared edges and vertices.
RenderJob spinningGridJob() {
    RenderJob job = test::squareFilmJob(256);
    Object spin;
    spin.name = "spin";
    constexpr std::uint32_t n = 8;
    for (std::uint32_t j = 0; j <= n; ++j)
        for (std::uint32_t i = 0; i <= n; ++i) spin.mesh.positions.push_back({-1.0 + 2.0 * i / n, -1.0 + 2.0 * j / n, 0.0});
    for (std::uint32_t j = 0; j < n; ++j)
        for (std::uint32_t i = 0; i < n; ++i) {
            const std::uint32_t a = j * (n + 1) + i;
            spin.mesh.triangles.push_back({a, a + 1, a + n + 2});
            spin.mesh.triangles.push_back({a, a + n + 2, a + n + 1});
        }
    spin.transform = {TransformKey{0.0, glm::dvec3(0, 0, 5)},
                      TransformKey{1.0, glm::dvec3(0, 0, 5), glm::angleAxis(M_PI / 2, glm::dvec3(0, 0, 1))}};
    job.scene.objects.push_back(spin);
    return job;
}

}  // namespace

// Per-segment scenes must answer every ray as the scene of all steps does: same hit or miss, same float
// distance, and the same triangle with the same barycentrics and normal, except in an exact tie, a ray
// through an edge two triangles share, where the BVHs' visiting orders may pick either triangle.
TEST(EmbreeScene, SegmentScenesAnswerAsTheWholeScene) {
    const RenderJob job = spinningGridJob();
    const EmbreeDevice device;
    const FrameMotion motion(job.scene, 0.0, 1.0);
    const EmbreeScene whole(device, motion);
    const EmbreeScene segmented(device, motion, nullptr, EmbreeScene::Layout::PerSegment);
    ASSERT_EQ(segmented.timeSteps(0), 17);
    // Within 1e-6 of an edge in barycentrics: float hits on an edge land within a few ulps of it.
    const auto onEdge = [](const EmbreeHit& h) { return h.u < 1e-6 || h.v < 1e-6 || h.u + h.v > 1.0 - 1e-6; };
    long long hits = 0, ties = 0;
    for (int k = 0; k <= 64; ++k) {
        const double t = k / 64.0 + (k % 3 == 1 ? 1e-7 : 0.0);  // segment ends (k % 4 == 0) and between
        for (int y = 0; y < 256; y += 5) {
            for (int x = 0; x < 256; x += 5) {
                const glm::dvec3 dir = test::worldAtRaster(x + 0.5, y + 0.5, 1.0, 256);
                const EmbreeHit a = whole.intersect(glm::dvec3(0.0), dir, t), b = segmented.intersect(glm::dvec3(0.0), dir, t);
                ASSERT_EQ(a.hit, b.hit) << "t " << t << " at " << x << "," << y;
                EXPECT_EQ(whole.occluded(glm::dvec3(0.0), dir, 100.0, t), segmented.occluded(glm::dvec3(0.0), dir, 100.0, t));
                if (!a.hit) continue;
                ++hits;
                EXPECT_EQ(a.distance, b.distance);
                if (a.triangle != b.triangle) {
                    ++ties;
                    EXPECT_TRUE(onEdge(a) && onEdge(b)) << "t " << t << " at " << x << "," << y;
                    continue;
                }
                EXPECT_EQ(a.u, b.u);
                EXPECT_EQ(a.v, b.v);
                EXPECT_EQ(a.normal, b.normal);
            }
        }
    }
    EXPECT_GT(hits, 1000);  // the quad covers a few percent of the rays at every time
    EXPECT_LT(ties, hits / 100);
    EXPECT_EQ(segmented.segmentScenesBuilt(), 16);
}

// A frame's fragment sets ask at the shutter's ends: only those two segments are built.
TEST(EmbreeScene, SegmentScenesAreBuiltWhenFirstAsked) {
    const RenderJob job = spinningGridJob();
    const EmbreeDevice device;
    const EmbreeScene scene(device, FrameMotion(job.scene, 0.0, 1.0), nullptr, EmbreeScene::Layout::PerSegment);
    EXPECT_EQ(scene.segmentScenesBuilt(), 0);
    EXPECT_EQ(scene.get(), nullptr);
    EXPECT_TRUE(scene.intersect(glm::dvec3(0.0), glm::dvec3(0.0, 0.0, 1.0), 0.0).hit);
    EXPECT_TRUE(scene.intersect(glm::dvec3(0.0), glm::dvec3(0.0, 0.0, 1.0), 1.0).hit);
    EXPECT_TRUE(scene.intersect(glm::dvec3(0.0), glm::dvec3(0.0, 0.0, 1.0), 0.99).hit);  // the last segment again
    EXPECT_EQ(scene.segmentScenesBuilt(), 2);
}

// Freed segment scenes are rebuilt when a ray asks again, and answer as before: same hit, distance and
// barycentrics, bit for bit (the same steps, built the same way).
TEST(EmbreeScene, ReleasedSegmentScenesAreRebuiltAndAnswerAlike) {
    const RenderJob job = spinningGridJob();
    const EmbreeDevice device;
    const EmbreeScene scene(device, FrameMotion(job.scene, 0.0, 1.0), nullptr, EmbreeScene::Layout::PerSegment);
    const glm::dvec3 dir = test::worldAtRaster(131.5, 126.5, 1.0, 256);  // near the middle: on the grid at every time
    const double times[] = {0.0, 0.3, 0.55, 1.0};  // segments 0, 4, 8 and 15 of 16
    std::vector<EmbreeHit> before;
    for (const double t : times) before.push_back(scene.intersect(glm::dvec3(0.0), dir, t));
    ASSERT_EQ(scene.segmentScenesBuilt(), 4);
    const double keep[] = {0.31, 0.999};  // in the segments of 0.3 and 1.0
    scene.releaseSegmentScenes(keep);
    EXPECT_EQ(scene.segmentScenesBuilt(), 2);
    for (std::size_t i = 0; i < std::size(times); ++i) {
        const EmbreeHit hit = scene.intersect(glm::dvec3(0.0), dir, times[i]);
        ASSERT_TRUE(before[i].hit);
        EXPECT_EQ(hit.triangle, before[i].triangle) << "t " << times[i];
        EXPECT_EQ(hit.u, before[i].u);
        EXPECT_EQ(hit.v, before[i].v);
        EXPECT_EQ(hit.distance, before[i].distance);
    }
    EXPECT_EQ(scene.segmentScenesBuilt(), 4);
    scene.releaseSegmentScenes({});
    EXPECT_EQ(scene.segmentScenesBuilt(), 0);
}

// Moving objects with different step counts cut the shutter differently: one scene holds every step.
TEST(EmbreeScene, UnequalStepCountsKeepOneScene) {
    RenderJob job = spinningGridJob();
    Object slide = test::rasterQuad(10, 10, 30, 30, 5.0, 256);
    slide.transform = {TransformKey{0.0, glm::dvec3(0.0)}, TransformKey{1.0, glm::dvec3(0.1, 0.0, 0.0)}};
    job.scene.objects.push_back(slide);
    const EmbreeDevice device;
    const EmbreeScene scene(device, FrameMotion(job.scene, 0.0, 1.0), nullptr, EmbreeScene::Layout::PerSegment);
    ASSERT_EQ(scene.timeSteps(1), 2);
    EXPECT_NE(scene.get(), nullptr);
    EXPECT_TRUE(scene.intersect(glm::dvec3(0.0), glm::dvec3(0.0, 0.0, 1.0), 0.5).hit);
    EXPECT_EQ(scene.segmentScenesBuilt(), 0);
}

}  // namespace clipblur
