#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/quaternion.hpp>

#include "renderer/clipped/shutter_segments.h"
#include "renderer/render.h"
#include "renderer/test_scenes.h"

namespace clipblur {

namespace {

glm::dquat aboutY(double degrees) {
    return glm::angleAxis(degrees * std::numbers::pi / 180.0, glm::dvec3(0, 1, 0));
}

}  // namespace

TEST(ShutterSegments, StillSceneIsOneSegment) {
    RenderJob job = test::squareFilmJob();
    job.scene.objects.push_back(test::rasterQuad(2, 2, 20, 20, 5.0));
    EXPECT_NEAR(FrameMotion(job.scene, 0.0, 1.0).turns(0.0, 1.0).camera, 0.0, 1e-12);
    EXPECT_NEAR(FrameMotion(job.scene, 0.0, 1.0).turns(0.0, 1.0).objects, 0.0, 1e-12);
    EXPECT_EQ(shutterSegments(FrameMotion(job.scene, 0.0, 1.0), 0, 16), 1);
    EXPECT_EQ(shutterSegments(FrameMotion(job.scene, 0.0, 1.0), 4, 16), 4);   // requested counts are kept
    EXPECT_EQ(shutterSegments(FrameMotion(job.scene, 0.0, 1.0), 40, 16), 16);  // up to the cap
}

// An object turning 90 degrees in two keys of 45 (slerp is a constant-rate turn): the summed angle is
// 90 degrees whatever the sampling, so auto gives ceil(90 / 60) = 2 segments; half the shutter 1, and
// a third key turning it on to 150 degrees ceil(150 / 60) = 3.
TEST(ShutterSegments, ObjectTurnSetsTheCount) {
    RenderJob job = test::squareFilmJob();
    Object quad = test::rasterQuad(2, 2, 20, 20, 5.0);
    quad.transform = {TransformKey{0.0, glm::dvec3(0.0), aboutY(0), glm::dvec3(1.0)},
                      TransformKey{0.5, glm::dvec3(0.0), aboutY(45), glm::dvec3(1.0)},
                      TransformKey{1.0, glm::dvec3(0.0), aboutY(90), glm::dvec3(1.0)}};
    job.scene.objects.push_back(quad);
    const FrameMotion motion(job.scene, 0.0, 1.0);
    EXPECT_NEAR(motion.turns(0.0, 1.0).objects, std::numbers::pi / 2, 1e-9);
    EXPECT_NEAR(motion.objectTurn(0, 0.25, 0.5), std::numbers::pi / 8, 1e-9);
    EXPECT_EQ(motion.turns(0.0, 1.0).camera, 0.0);
    EXPECT_EQ(shutterSegments(motion, 0, 16), 2);
    EXPECT_EQ(shutterSegments(FrameMotion(job.scene, 0.0, 0.5), 0, 16), 1);
    job.scene.objects[0].transform.push_back(TransformKey{2.0, glm::dvec3(0.0), aboutY(150), glm::dvec3(1.0)});
    EXPECT_EQ(shutterSegments(FrameMotion(job.scene, 0.0, 2.0), 0, 16), 3);
}

// A camera yawing 100 degrees: the basis turns by the angle between the view directions, and what it
// turns to see lies outside both end frames, so the camera keeps a segment per 15 degrees: 7.
TEST(ShutterSegments, CameraTurnSetsTheCount) {
    RenderJob job = test::squareFilmJob();
    job.scene.objects.push_back(test::rasterQuad(2, 2, 20, 20, 5.0));
    const double a = 100.0 * std::numbers::pi / 180.0;
    job.scene.camera.keys.push_back(
        CameraKey{1.0, glm::dvec3(0.0), glm::dvec3(std::sin(a), 0, std::cos(a)), glm::dvec3(0, 1, 0)});
    EXPECT_NEAR(FrameMotion(job.scene, 0.0, 1.0).turns(0.0, 1.0).camera, a, 1e-9);
    EXPECT_EQ(FrameMotion(job.scene, 0.0, 1.0).turns(0.0, 1.0).objects, 0.0);
    EXPECT_EQ(shutterSegments(FrameMotion(job.scene, 0.0, 1.0), 0, 16), 7);
}

// Both turning: the count is the larger of the two rules', not their sum. The camera yaws 40 degrees
// (ceil(40 / 15) = 3) while the quad turns 90 (2): 3; with the quad at 200 degrees (4): 4.
TEST(ShutterSegments, CameraAndObjectTurnsTakeTheLargerCount) {
    RenderJob job = test::squareFilmJob();
    Object quad = test::rasterQuad(2, 2, 20, 20, 5.0);
    quad.transform = {TransformKey{0.0, glm::dvec3(0.0), aboutY(0), glm::dvec3(1.0)},
                      TransformKey{1.0, glm::dvec3(0.0), aboutY(90), glm::dvec3(1.0)}};
    job.scene.objects.push_back(quad);
    const double a = 40.0 * std::numbers::pi / 180.0;
    job.scene.camera.keys.push_back(
        CameraKey{1.0, glm::dvec3(0.0), glm::dvec3(std::sin(a), 0, std::cos(a)), glm::dvec3(0, 1, 0)});
    EXPECT_EQ(shutterSegments(FrameMotion(job.scene, 0.0, 1.0), 0, 16), 3);
    job.scene.objects[0].transform = {TransformKey{0.0, glm::dvec3(0.0), aboutY(0), glm::dvec3(1.0)},
                                      TransformKey{0.5, glm::dvec3(0.0), aboutY(100), glm::dvec3(1.0)},
                                      TransformKey{1.0, glm::dvec3(0.0), aboutY(200), glm::dvec3(1.0)}};
    EXPECT_EQ(shutterSegments(FrameMotion(job.scene, 0.0, 1.0), 0, 16), 4);
}

// Neighbouring segments meet at one time, so the set closing one opens the next: S segments build S + 1
// fragment sets, and a still last segment builds none of its own.
TEST(ShutterSegments, NeighboursShareTheirEndSet) {
    RenderJob job = test::squareFilmJob();
    job.render.method = Method::Clipped;
    Object quad = test::rasterQuad(2, 2, 20, 20, 5.0);
    quad.transform = {TransformKey{0.0, glm::dvec3(0.0), aboutY(0), glm::dvec3(1.0)},
                      TransformKey{0.5, glm::dvec3(0.0), aboutY(20), glm::dvec3(1.0)}};
    job.scene.objects.push_back(quad);
    job.render.segments = 2;  // the second half of the shutter is still
    EXPECT_EQ(renderFrame(job, 0).stats.clipped().frame_sets, 2);
    job.scene.objects[0].transform.push_back(TransformKey{1.0, glm::dvec3(0.0), aboutY(40), glm::dvec3(1.0)});
    job.render.segments = 3;
    EXPECT_EQ(renderFrame(job, 0).stats.clipped().frame_sets, 4);
}

// Equal segments meet at one double and share the shutter equally.
TEST(ShutterSegments, EqualSegmentsTileTheShutter) {
    const std::vector<ShutterSegment> s = equalSegments(2.25, 3.0, 3);
    ASSERT_EQ(s.size(), 3u);
    EXPECT_EQ(s.front().begin, 2.25);
    EXPECT_EQ(s.back().end, 3.0);
    for (std::size_t i = 0; i < s.size(); ++i) {
        EXPECT_EQ(s[i].weight, 1.0 / 3.0);
        if (i > 0) {
            EXPECT_EQ(s[i].begin, s[i - 1].end);
        }
    }
}

}  // namespace clipblur
