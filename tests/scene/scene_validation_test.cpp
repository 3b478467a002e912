#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "scene/primitives.h"
#include "scene/scene_validation.h"

namespace clipblur {

namespace {

Scene oneBoxScene() {
    Scene s;
    s.materials.push_back(Material{});
    s.camera.keys.push_back(CameraKey{0.0, {0, 0, -5}, {0, 0, 1}, {0, 1, 0}});
    Object o;
    o.name = "box";
    o.mesh = makeBox(glm::dvec3(1.0));
    o.loc = FileLoc{"j.yaml", 9, 5};
    s.objects.push_back(o);
    return s;
}

template <typename F>
Error sceneError(F&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e;
    }
    ADD_FAILURE() << "expected an error";
    return Error(ExitCode::Ok, "");
}

}  // namespace

TEST(SceneValidation, ValidSceneHasNoWarnings) { EXPECT_TRUE(validateScene(oneBoxScene()).empty()); }

TEST(SceneValidation, NonFiniteVertexIsLocatedAtTheObject) {
    for (const double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), -1.5e8}) {
        Scene s = oneBoxScene();
        s.objects[0].mesh.positions[3].y = bad;
        const Error e = sceneError([&] { validateScene(s); });
        EXPECT_EQ(e.code(), ExitCode::Scene);
        EXPECT_EQ(e.loc().toString(), "j.yaml:9:5");
    }
}

TEST(SceneValidation, KeysMustIncrease) {
    Scene s = oneBoxScene();
    s.objects[0].transform = {TransformKey{1.0}, TransformKey{0.0}};
    SceneLocations locs;
    locs.transform_keys = {{FileLoc{"j.yaml", 11, 9}, FileLoc{"j.yaml", 12, 9}}};
    EXPECT_EQ(sceneError([&] { validateScene(s, locs); }).loc().toString(), "j.yaml:12:9");
}

TEST(SceneValidation, EmptySceneAndBadIndices) {
    Scene s = oneBoxScene();
    s.objects.clear();
    EXPECT_EQ(sceneError([&] { validateScene(s); }).code(), ExitCode::Scene);
    s = oneBoxScene();
    s.objects[0].mesh.triangles[0][2] = 8;
    EXPECT_EQ(sceneError([&] { validateScene(s); }).loc().toString(), "j.yaml:9:5");
    s = oneBoxScene();
    s.objects[0].material = 1;
    EXPECT_EQ(sceneError([&] { validateScene(s); }).code(), ExitCode::Scene);
    s = oneBoxScene();
    s.objects[0].deformation.push_back(DeformationKey{0.0, {glm::dvec3(0.0)}});
    EXPECT_EQ(sceneError([&] { validateScene(s); }).code(), ExitCode::Scene);
}

// An image texture on a mesh without UVs would read the texel at (0, 0) everywhere: refused at the object,
// for the base colour and the emission image alike; with UVs it is fine.
TEST(SceneValidation, ImageTextureNeedsUvs) {
    for (const bool emission : {false, true}) {
        Scene s = oneBoxScene();
        (emission ? s.materials[0].emission_image : s.materials[0].image).file = "wood.png";
        const Error e = sceneError([&] { validateScene(s); });
        EXPECT_EQ(e.code(), ExitCode::Scene);
        EXPECT_EQ(e.loc().toString(), "j.yaml:9:5");
        EXPECT_NE(e.message().find("no texture coordinates"), std::string::npos) << e.what();
        s.objects[0].mesh.corner_uvs.assign(3 * s.objects[0].mesh.triangles.size(), glm::dvec2(0.5));
        EXPECT_NO_THROW(validateScene(s));
    }
}

TEST(SceneValidation, DegenerateTrianglesAreCountedNotRemoved) {
    const glm::dvec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
    EXPECT_FALSE(isDegenerate(a, b, c));
    EXPECT_TRUE(isDegenerate(a, b, 2.0 * b));   // collinear
    EXPECT_TRUE(isDegenerate(a, a, a));         // a point
    // A sliver of height 1e-6 on a unit base is thin but real.
    EXPECT_FALSE(isDegenerate(a, b, glm::dvec3(0.5, 1e-6, 0)));
    Scene s = oneBoxScene();
    s.objects[0].mesh.triangles.push_back({0, 0, 1});
    const auto warnings = validateScene(s);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(s.objects[0].mesh.triangles.size(), 13u);
    EXPECT_EQ(summarizeScene(s).degenerate_triangles, 1u);
    EXPECT_EQ(summarizeScene(s).triangles, 13u);
}

TEST(SceneValidation, CameraInsideMovingBoxWarnsOnlyWhenInside) {
    Scene s = oneBoxScene();
    // The box moves onto the camera at time 1.
    s.objects[0].transform = {TransformKey{0.0}, TransformKey{1.0, {0, 0, -5}}};
    s.camera.keys.push_back(CameraKey{1.0, {0, 0, -5}, {0, 0, 1}, {0, 1, 0}});
    const auto warnings = validateScene(s);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("camera key 1"), std::string::npos) << warnings[0];
}

}  // namespace clipblur
