#include "renderer/frame_motion.h"

#include <cstring>
#include <numbers>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "renderer/sampling/hash_rng.h"
#include "renderer/test_scenes.h"

namespace clipblur {

namespace {

// A still wall, a quad that slides during the first half of the shutter only (held after its last key),
// and a quad that deforms over the whole shutter.
Scene threeObjects() {
    RenderJob job = test::squareFilmJob();
    job.scene.objects.push_back(test::rasterQuad(0, 0, 32, 32, 10.0));
    Object slide = test::rasterQuad(4, 4, 12, 12, 5.0);
    slide.transform = {TransformKey{0.0, glm::dvec3(0.0)}, TransformKey{0.5, glm::dvec3(0.5, 0, 0)}};
    job.scene.objects.push_back(slide);
    Object bend = test::rasterQuad(20, 20, 28, 28, 6.0);
    std::vector<glm::dvec3> bent = bend.mesh.positions;
    bent[0].z += 0.5;
    bend.deformation = {DeformationKey{0.0, bend.mesh.positions}, DeformationKey{1.0, bent}};
    job.scene.objects.push_back(bend);
    return job.scene;
}

}  // namespace

// Which objects move is read off the keys: held values outside the keys are still, deformation moves.
TEST(FrameMotion, StillnessOverTheShutterAndItsWindows) {
    const Scene scene = threeObjects();
    const FrameMotion motion(scene, 0.0, 1.0);
    const MotionWindow& shutter = motion.shutter();
    EXPECT_TRUE(shutter.camera_still);
    EXPECT_TRUE(shutter.objectStill(0));
    EXPECT_FALSE(shutter.objectStill(1));
    EXPECT_FALSE(shutter.objectStill(2));
    EXPECT_FALSE(shutter.still());

    const MotionWindow late = motion.window(0.5, 1.0);  // the slide has stopped, the bend goes on
    EXPECT_TRUE(late.objectStill(0));
    EXPECT_TRUE(late.objectStill(1));
    EXPECT_FALSE(late.objectStill(2));
    EXPECT_TRUE(late.stillInImage(1));

    Scene frozen = scene;
    frozen.objects[2].deformation.clear();
    EXPECT_TRUE(FrameMotion(frozen, 0.0, 1.0).window(0.5, 1.0).still());
    EXPECT_TRUE(FrameMotion(frozen, 0.6, 0.9).shutter().still());  // a window past every key
}

// A camera that turns on the spot keeps its eye still: the same surfaces are seen from the same point.
TEST(FrameMotion, TurningCameraKeepsItsEyeStill) {
    Scene scene = threeObjects();
    scene.objects.resize(1);
    scene.camera.keys.push_back(CameraKey{1.0, glm::dvec3(0.0), glm::dvec3(0.2, 0, 1), glm::dvec3(0, 1, 0)});
    const FrameMotion turning(scene, 0.0, 1.0);
    EXPECT_FALSE(turning.shutter().camera_still);
    EXPECT_TRUE(turning.shutter().eye_still);
    EXPECT_FALSE(turning.shutter().stillInImage(0));
    EXPECT_GT(turning.turns(0.0, 1.0).camera, 0.0);
    EXPECT_EQ(turning.turns(0.0, 1.0).objects, 0.0);
    scene.camera.keys.back().position = glm::dvec3(0.0, 0.0, 0.1);
    EXPECT_FALSE(FrameMotion(scene, 0.0, 1.0).shutter().eye_still);
    EXPECT_TRUE(FrameMotion(scene, 1.0, 2.0).shutter().camera_still);  // held after its last key
}

// The frame's camera is evalCamera bit for bit (it is read instead of the keys everywhere), and its
// groups and poses are those of the scene's own functions.
TEST(FrameMotion, CameraPosesAndGroupsAreTheScenesOwn) {
    Scene scene = threeObjects();
    scene.camera.keys = {CameraKey{0.0, {0, 0.5, -1}, {0, -0.1, 1}, {0, 1, 0}},
                         CameraKey{0.7, {0.3, 0.5, -1}, {0.2, -0.1, 1}, {0.1, 1, 0}},
                         CameraKey{1.0, {0.4, 0.6, -0.8}, {0.1, 0, 1}, {0, 1, 0.1}}};
    const FrameMotion motion(scene, 0.0, 1.0);
    const HashRng rng = HashRng::forKey(25, 4);
    for (int i = 0; i < 200; ++i) {
        const double t = -0.25 + 1.5 * rng.uniform(static_cast<std::uint64_t>(i));
        const CameraFrame a = motion.camera(t), b = evalCamera(scene.camera, t);
        EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0) << "t = " << t;
        const RigidTransform x = motion.transform(1, t), y = evalTransform(scene.objects[1].transform, t);
        EXPECT_EQ(x.translate, y.translate) << "t = " << t;
    }
    EXPECT_EQ(motion.groups(motion.shutter()), motionGroups(scene, 0.0, 1.0));
    EXPECT_EQ(motion.groups(motion.window(0.5, 1.0)), motionGroups(scene, 0.5, 1.0));
}

}  // namespace clipblur
