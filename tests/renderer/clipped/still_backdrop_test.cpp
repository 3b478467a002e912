#include "renderer/clipped/still_backdrop.h"

#include <gtest/gtest.h>

#include "renderer/test_scenes.h"

namespace clipblur {

namespace {

using test::rasterQuad;
using test::squareFilmJob;

// A wall at depth `wall` and a quad over raster [8, 24)^2 at depth 6 sliding by `shift` (world units).
RenderJob wallAndQuad(double wall, glm::dvec3 shift) {
    RenderJob job = squareFilmJob();
    job.render.method = Method::Clipped;
    job.render.time_integration = TimeIntegration::Sweep;
    job.scene.objects.push_back(rasterQuad(0.0, 0.0, 32.0, 32.0, wall));
    Object quad = rasterQuad(8.0, 8.0, 24.0, 24.0, 6.0);
    quad.transform.push_back(TransformKey{0.0, glm::dvec3(0.0), {1, 0, 0, 0}, glm::dvec3(1.0)});
    quad.transform.push_back(TransformKey{1.0, shift, {1, 0, 0, 0}, glm::dvec3(1.0)});
    job.scene.objects.push_back(quad);
    return job;
}

Backdrop backdropOf(const RenderJob& job) { return findBackdrop(job, FrameMotion(job.scene, 0.0, 1.0)); }

}  // namespace

// The quad's vertices are 6 / cos of their angle off axis from the origin, its transform's pivot:
// |(3, 3, 6)| = 7.35, so its bounding sphere reaches depth 7.35 plus how far it moves toward the wall.
TEST(StillBackdrop, BehindEverythingByBoundingSpheres) {
    const Backdrop far = backdropOf(wallAndQuad(10.0, {1, 0, 0}));
    ASSERT_EQ(far.objects.size(), 2u);
    EXPECT_TRUE(far.objects[0]);
    EXPECT_FALSE(far.objects[1]);
    EXPECT_TRUE(far.behind_everything);
    // Moving 2.5 toward the wall: 7.35 + 2.5 = 9.85 < 10, still behind; 3 more: 10.35, not.
    EXPECT_TRUE(backdropOf(wallAndQuad(10.0, {0, 0, 2.5})).behind_everything);
    const Backdrop near = backdropOf(wallAndQuad(10.0, {0, 0, 3.0}));
    EXPECT_FALSE(near.empty());
    EXPECT_FALSE(near.behind_everything);
}

// A backdrop needs a still camera, no shadows (moving objects would cast them on it), sweep integration,
// and something still and something moving.
TEST(StillBackdrop, OnlyWhereItHolds) {
    RenderJob job = wallAndQuad(10.0, {1, 0, 0});
    EXPECT_FALSE(backdropOf(job).empty());
    RenderJob panning = job;
    panning.scene.camera.keys.push_back(CameraKey{1.0, glm::dvec3(0.1, 0, 0), glm::dvec3(0, 0, 1), glm::dvec3(0, 1, 0)});
    EXPECT_TRUE(backdropOf(panning).empty());
    RenderJob shadows = job;
    shadows.render.shadows = true;
    EXPECT_TRUE(backdropOf(shadows).empty());
    RenderJob point = job;
    point.render.time_integration = TimeIntegration::Subframes;
    EXPECT_TRUE(backdropOf(point).empty());
    RenderJob still = wallAndQuad(10.0, {0, 0, 0});
    still.scene.objects[1].transform.clear();
    EXPECT_TRUE(backdropOf(still).empty());
}

}  // namespace clipblur
