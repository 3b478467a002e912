#include <cmath>

#include <gtest/gtest.h>

#include "renderer/shading/shading.h"
#include "renderer/visibility/embree_scene.h"
#include "scene/error.h"

namespace clipblur {

namespace {

// A unit right triangle in the z = 0 plane, front face toward -z: (v1-v0) x (v2-v0) = (0,1,0)x(1,0,0) = -z.
Scene triangleScene() {
    Scene scene;
    Object tri;
    tri.name = "tri";
    tri.mesh.positions = {{0, 0, 0}, {0, 1, 0}, {1, 0, 0}};
    tri.mesh.triangles = {{0, 1, 2}};
    scene.objects.push_back(tri);
    Material m;
    m.base_color = {0.5, 0.25, 1.0};
    scene.materials.push_back(m);
    scene.ambient = glm::dvec3(0.1);
    return scene;
}

void expectColour(const glm::dvec3& got, const glm::dvec3& want) {
    // Hand-computed values; 1e-12 allows the rounding of a handful of operations.
    EXPECT_NEAR(got.r, want.r, 1e-12);
    EXPECT_NEAR(got.g, want.g, 1e-12);
    EXPECT_NEAR(got.b, want.b, 1e-12);
}

}  // namespace

TEST(Shading, DirectionalLightAtSixtyDegrees) {
    Scene scene = triangleScene();
    Light light;
    light.kind = Light::Kind::Directional;
    light.intensity = 2.0;
    light.color = {1.0, 0.5, 1.0};
    // Travelling into the surface (+z) tilted 60 degrees from the normal: cos = 0.5.
    light.direction = {std::sin(M_PI / 3), 0.0, std::cos(M_PI / 3)};
    scene.lights.push_back(light);
    const FrameMotion motion(scene, 0.0, 1.0);
    const Shader shader(motion);
    const SurfacePoint p{0, 0, 0.25, 0.25, 0.5};
    const glm::dvec3 eye(0.2, 0.2, -3.0);
    // albedo * (0.1 + 2 * color * 0.5)
    expectColour(shader.shade(p, eye), glm::dvec3(0.5 * 1.1, 0.25 * 0.6, 1.0 * 1.1));
}

TEST(Shading, PointLightFallsOffWithSquaredDistance) {
    Scene scene = triangleScene();
    Light light;
    light.kind = Light::Kind::Point;
    light.intensity = 8.0;
    light.color = glm::dvec3(1.0);
    // Surface point (u,v) = (0.25, 0.5): (1-u-v) v0 + u v1 + v v2 = (0.5, 0.25, 0).
    light.position = {0.5, 0.25, -2.0};  // straight above it at distance 2: 8 * 1 / 4 = 2
    scene.lights.push_back(light);
    const FrameMotion motion(scene, 0.0, 1.0);
    const Shader shader(motion);
    const SurfacePoint p{0, 0, 0.25, 0.5, 0.0};
    const SurfaceGeometry g = shader.geometry(p);
    EXPECT_NEAR(g.position.x, 0.5, 1e-15);
    EXPECT_NEAR(g.position.y, 0.25, 1e-15);
    EXPECT_NEAR(g.normal.z, -1.0, 1e-15);
    expectColour(shader.shade(p, glm::dvec3(0, 0, -1)), glm::dvec3(0.5, 0.25, 1.0) * 2.1);
}

TEST(Shading, BackFacesFlipWhenTwoSidedAndAreBlackWhenOneSided) {
    Scene scene = triangleScene();
    Light light;
    light.direction = {0, 0, -1};  // lights the back (+z) side
    scene.lights.push_back(light);
    const SurfacePoint p{0, 0, 0.2, 0.2, 0.0};
    const glm::dvec3 behind(0.2, 0.2, 4.0);
    expectColour(Shader(FrameMotion(scene, 0, 1)).shade(p, behind), glm::dvec3(0.5, 0.25, 1.0) * 1.1);
    // Seen from the front, the back-side light does not reach the normal toward the eye: ambient only.
    expectColour(Shader(FrameMotion(scene, 0, 1)).shade(p, glm::dvec3(0.2, 0.2, -4.0)), glm::dvec3(0.5, 0.25, 1.0) * 0.1);
    scene.materials[0].two_sided = false;
    expectColour(Shader(FrameMotion(scene, 0, 1)).shade(p, behind), glm::dvec3(0.0));
}

TEST(Shading, CheckerAndStripeFollowFloorParity) {
    Material m;
    m.base_color = glm::dvec3(1.0);
    m.texture.kind = Texture::Kind::Checker;
    m.texture.color2 = glm::dvec3(0.0);
    m.texture.scale = 0.5;
    // floor(x/0.5)+floor(y/0.5)+floor(z/0.5): (0.1,0.1,0.1) -> 0 even; (0.6,0.1,0.1) -> 1 odd;
    // (0.6,0.6,0.1) -> 2 even; (-0.1,0.1,0.1) -> -1 odd; (-0.1,-0.1,-0.1) -> -3 odd.
    EXPECT_EQ(albedo(m, {0.1, 0.1, 0.1}), glm::dvec3(1.0));
    EXPECT_EQ(albedo(m, {0.6, 0.1, 0.1}), glm::dvec3(0.0));
    EXPECT_EQ(albedo(m, {0.6, 0.6, 0.1}), glm::dvec3(1.0));
    EXPECT_EQ(albedo(m, {-0.1, 0.1, 0.1}), glm::dvec3(0.0));
    EXPECT_EQ(albedo(m, {-0.1, -0.1, -0.1}), glm::dvec3(0.0));
    m.texture.kind = Texture::Kind::Stripe;
    EXPECT_EQ(albedo(m, {0.1, 0.6, 0.6}), glm::dvec3(1.0));
    EXPECT_EQ(albedo(m, {0.6, 0.1, 0.1}), glm::dvec3(0.0));
    EXPECT_EQ(albedo(m, {-0.6, 0.1, 0.1}), glm::dvec3(1.0));  // floor(-1.2) = -2
}

TEST(Shading, TextureMovesWithTheObject) {
    Scene scene = triangleScene();
    scene.ambient = glm::dvec3(1.0);
    scene.materials[0].base_color = glm::dvec3(1.0);
    scene.materials[0].texture = {Texture::Kind::Stripe, glm::dvec3(0.0), 0.5};
    // Translated by 0.5 in x over the frame: the world position moves, the rest position does not.
    scene.objects[0].transform = {TransformKey{0.0, glm::dvec3(0.0)}, TransformKey{1.0, glm::dvec3(0.5, 0, 0)}};
    const FrameMotion motion(scene, 0.0, 1.0);
    const Shader shader(motion);
    const SurfacePoint early{0, 0, 0.1, 0.1, 0.0};  // rest x = 0.1 -> stripe 0 -> base colour
    SurfacePoint late = early;
    late.time = 1.0;
    EXPECT_NEAR(shader.geometry(late).position.x - shader.geometry(early).position.x, 0.5, 1e-15);
    EXPECT_EQ(shader.shade(early, glm::dvec3(0, 0, -1)), glm::dvec3(1.0));
    EXPECT_EQ(shader.shade(late, glm::dvec3(0, 0, -1)), glm::dvec3(1.0));
}

TEST(Shading, ShadowRayBlocksAPointLight) {
    Scene scene = triangleScene();
    Light light;
    light.kind = Light::Kind::Point;
    light.intensity = 8.0;
    light.position = {0.25, 0.25, -2.0};
    scene.lights.push_back(light);
    // A blocker halfway between the surface point and the light.
    Object blocker;
    blocker.name = "blocker";
    blocker.mesh.positions = {{-1, -1, -1}, {2, -1, -1}, {-1, 2, -1}};
    blocker.mesh.triangles = {{0, 1, 2}};
    scene.objects.push_back(blocker);
    const EmbreeDevice device;
    const EmbreeScene embree(device, FrameMotion(scene, 0.0, 1.0));
    const FrameMotion with_blocker(scene, 0.0, 1.0);
    const Shader shaded(with_blocker, &embree);
    long long rays = 0;
    const SurfacePoint p{0, 0, 0.25, 0.25, 0.5};
    expectColour(shaded.shade(p, glm::dvec3(0.25, 0.25, -0.5), &rays), glm::dvec3(0.5, 0.25, 1.0) * 0.1);
    EXPECT_EQ(rays, 1);
    scene.objects.pop_back();
    const EmbreeScene open(device, FrameMotion(scene, 0.0, 1.0));
    const FrameMotion without(scene, 0.0, 1.0);
    const Shader lit(without, &open);
    // Unblocked: 8 / 2^2 * cos 0 = 2.
    expectColour(lit.shade(p, glm::dvec3(0.25, 0.25, -0.5), &rays), glm::dvec3(0.5, 0.25, 1.0) * 2.1);
}

// Two eyes see a still triangle's points in the same colour when they are on the same side of its plane;
// one-sided, it is black from behind.
TEST(Shading, SameFromBothEyesOnOneSideOfAStillFace) {
    Scene scene = triangleScene();
    Light light;
    light.direction = {0.3, -0.2, 1.0};
    scene.lights.push_back(light);
    const FrameMotion motion(scene, 0.0, 1.0);
    const Shader shader(motion);
    const glm::dvec3 front_a(0.2, 0.3, -2.0), front_b(-3.0, 4.0, -0.5), back(0.2, 0.3, 1.0);
    const SurfacePoint p0{0, 0, 0.25, 0.25, 0.0}, p1{0, 0, 0.25, 0.25, 1.0};
    EXPECT_EQ(shader.shade(p0, front_a), shader.shade(p1, front_b));
    EXPECT_NE(shader.shade(p0, front_a), shader.shade(p1, back));  // one-sided: black from behind
}

}  // namespace clipblur
