#include <cstdint>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "scene/object_motion.h"
#include "support/motion_scenes.h"

namespace clipblur {

namespace {

using testing::addTransformKey;
using testing::triangleObject;

Scene sceneOf(std::vector<Object> objects) {
    Scene scene = testing::stillCameraScene();
    scene.objects = std::move(objects);
    return scene;
}

Object at(const glm::dvec3& origin) { return triangleObject(origin, origin + glm::dvec3(1, 0, 0), origin + glm::dvec3(0, 1, 0)); }

}  // namespace

// Objects without keys do not move: one group whatever their number and place.
TEST(MotionGroups, StillObjectsShareOneGroup) {
    const Scene scene = sceneOf({at({0, 0, 5}), at({3, 1, 9}), at({-4, 2, 20})});
    EXPECT_EQ(motionGroups(scene, 0.0, 1.0), (std::vector<std::uint32_t>{0, 0, 0}));
}

// The same translation keys move objects at different places together; a translation 1e-6 longer over a
// scene a few units across is a different motion.
TEST(MotionGroups, SameTranslationSharesAGroupWhereverTheObjectIs) {
    std::vector<Object> objects{at({0, 0, 5}), at({3, 1, 9}), at({-2, 0, 7})};
    for (Object& o : objects) {
        addTransformKey(o, 0.0, {0, 0, 0});
        addTransformKey(o, 1.0, {0.5, 0.2, 0});
    }
    objects[2].transform[1].translate.x += 1e-6;
    EXPECT_EQ(motionGroups(sceneOf(objects), 0.0, 1.0), (std::vector<std::uint32_t>{0, 0, 2}));
}

// Two blades turning about the same axis through the same point move together, even when each has its
// own rest rotation; the same turn about a different point (another translation key) moves differently.
TEST(MotionGroups, TurnsAboutTheSamePointShareAGroup) {
    Object a = at({1, 0, 6}), b = at({-1, 0.5, 6}), c = at({0, 1, 6});
    const glm::dvec3 z(0, 0, 1);
    addTransformKey(a, 0.0, {0, 0, 0}, z, 0.0);
    addTransformKey(a, 1.0, {0, 0, 0}, z, 0.4);
    addTransformKey(b, 0.0, {0, 0, 0}, z, 1.0);  // a quarter of a turn ahead of a all the time
    addTransformKey(b, 1.0, {0, 0, 0}, z, 1.4);
    addTransformKey(c, 0.0, {2, 0, 0}, z, 0.0);
    addTransformKey(c, 1.0, {2, 0, 0}, z, 0.4);
    EXPECT_EQ(motionGroups(sceneOf({a, b, c}), 0.0, 1.0), (std::vector<std::uint32_t>{0, 0, 2}));
}

// Keys at other times that describe the same motion (a middle key exactly on the line) are the same
// motion; a middle key off the line is not, though both agree at the shutter's ends.
TEST(MotionGroups, ComparesTheMotionInsideTheShutterNotOnlyItsEnds) {
    Object a = at({0, 0, 5}), b = at({2, 0, 5}), c = at({4, 0, 5});
    addTransformKey(a, 0.0, {0, 0, 0});
    addTransformKey(a, 1.0, {1, 0, 0});
    addTransformKey(b, 0.0, {0, 0, 0});
    addTransformKey(b, 0.25, {0.25, 0, 0});
    addTransformKey(b, 1.0, {1, 0, 0});
    addTransformKey(c, 0.0, {0, 0, 0});
    addTransformKey(c, 0.5, {0.5, 0.3, 0});
    addTransformKey(c, 1.0, {1, 0, 0});
    EXPECT_EQ(motionGroups(sceneOf({a, b, c}), 0.0, 1.0), (std::vector<std::uint32_t>{0, 0, 2}));
    // Over [0.6, 1] only c's last gap counts, where it also drifts down (0.3 in y over 0.5 of time).
    EXPECT_EQ(motionGroups(sceneOf({a, b, c}), 0.6, 1.0), (std::vector<std::uint32_t>{0, 0, 2}));
}

// A deforming object moves relative to itself: it keeps a group of its own, even beside a twin.
TEST(MotionGroups, DeformingObjectsKeepTheirOwnGroup) {
    Object a = at({0, 0, 5}), b = at({0, 0, 5}), c = at({3, 0, 5});
    for (double t : {0.0, 1.0}) {
        DeformationKey key{t, b.mesh.positions};
        key.positions[0].z += t;
        b.deformation.push_back(key);
    }
    EXPECT_EQ(motionGroups(sceneOf({a, b, c}), 0.0, 1.0), (std::vector<std::uint32_t>{0, 1, 0}));
    // Outside the deformation keys' span nothing deforms: b is as still as the rest there.
    EXPECT_EQ(motionGroups(sceneOf({a, b, c}), 1.0, 2.0), (std::vector<std::uint32_t>{0, 0, 0}));
}

}  // namespace clipblur
