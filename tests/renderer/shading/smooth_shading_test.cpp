#include <algorithm>
#include <cmath>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "renderer/render.h"
#include "renderer/shading/shading.h"
#include "renderer/test_scenes.h"
#include "scene/primitives.h"

namespace clipblur {

namespace {

constexpr int kFilm = 64;
const glm::dvec3 kCentre(0.0, 0.0, 2.5);
const glm::dvec3 kLightTravel(0.3, -0.4, 1.0);

// The unit sphere about kCentre, 64 segments, lit by one directional light, no ambient; `smooth` gives
// every corner the sphere's exact normal at its vertex. `turn` is the object's rotation about its centre,
// held all shutter: corner normals must turn with it.
RenderJob sphereJob(bool smooth, const glm::dquat& turn) {
    RenderJob job = test::squareFilmJob(kFilm);
    job.render.method = Method::Clipped;
    job.scene.ambient = glm::dvec3(0.0);
    Light light;
    light.direction = kLightTravel;
    job.scene.lights.push_back(light);
    Object sphere;
    sphere.name = "sphere";
    sphere.mesh = makeSphere(1.0, 64);
    if (smooth)
        for (const auto& t : sphere.mesh.triangles)
            for (const std::uint32_t v : t) sphere.mesh.corner_normals.push_back(sphere.mesh.positions[v]);
    sphere.transform.push_back(TransformKey{0.0, kCentre, turn, glm::dvec3(1.0)});
    job.scene.objects.push_back(sphere);
    return job;
}

// Lambert on the true sphere seen through raster point (x, y): the nearer root of |t d - c| = 1.
// Returns -1 where the ray misses.
double analyticLambert(double x, double y) {
    const glm::dvec3 d = test::worldAtRaster(x, y, 1.0, kFilm);
    const double b = glm::dot(d, kCentre), a = glm::dot(d, d);
    const double disc = b * b - a * (glm::dot(kCentre, kCentre) - 1.0);
    if (disc < 0.0) return -1.0;
    const double t = (b - std::sqrt(disc)) / a;
    const glm::dvec3 n = t * d - kCentre;
    return std::max(0.0, glm::dot(n, -glm::normalize(kLightTravel)));
}

struct Errors {
    double worst = 0.0;
    int pixels = 0;
};

// Over pixels whose 5 x 5 sub-pixel points all hit the sphere and are at least 2 px inside the silhouette
// (the test of the centre point and its 2 px neighbours), the pixel's red channel against the mean of
// the analytic value at those points: the box-filtered pixel to within the curvature of n.l over a pixel.
Errors againstAnalytic(const RenderResult& r) {
    const auto& red = r.image.find("R")->values;
    Errors e;
    for (int y = 0; y < kFilm; ++y)
        for (int x = 0; x < kFilm; ++x) {
            bool inside = true;
            for (const glm::dvec2 o : {glm::dvec2(-2, 0), glm::dvec2(2, 0), glm::dvec2(0, -2), glm::dvec2(0, 2)})
                inside = inside && analyticLambert(x + 0.5 + o.x, y + 0.5 + o.y) >= 0.0;
            if (!inside) continue;
            double sum = 0.0;
            for (int j = 0; j < 5; ++j)
                for (int i = 0; i < 5; ++i) sum += analyticLambert(x + (i + 0.5) / 5.0, y + (j + 0.5) / 5.0);
            e.worst = std::max(e.worst, std::abs(red[static_cast<std::size_t>(y * kFilm + x)] - sum / 25.0));
            ++e.pixels;
        }
    return e;
}

}  // namespace

// Interpolated corner normals reproduce the true sphere's Lambert shading away from its silhouette;
// the faceted mesh does not. Tolerance 0.01: 64 segments span 0.098 rad, and a normalised blend of corner
// normals errs from the true normal by about that squared over 8 (0.0012), the mesh's facets lie off
// the sphere by its sagitta (0.0012 of the radius); faceted normals are off by up to half a segment (0.049 rad), so faceted shading errs by several times 0.01.
TEST(SmoothShading, SphereMatchesAnalyticLambertAwayFromEdges) {
    const glm::dquat still(1.0, 0.0, 0.0, 0.0);
    const Errors smooth = againstAnalytic(renderFrame(sphereJob(true, still), 0));
    EXPECT_GT(smooth.pixels, 300);
    EXPECT_LT(smooth.worst, 0.01);
    const Errors faceted = againstAnalytic(renderFrame(sphereJob(false, still), 0));
    EXPECT_GT(faceted.worst, 0.02);
    // Rotated (a sphere looks the same), its corner normals turn with it through the transform's inverse
    // transpose; left unturned, they would light the sphere from the wrong side.
    const glm::dquat turn = glm::angleAxis(1.2, glm::normalize(glm::dvec3(1.0, 1.0, 0.0)));
    EXPECT_LT(againstAnalytic(renderFrame(sphereJob(true, turn), 0)).worst, 0.01);
    RenderJob stochastic = sphereJob(true, turn);
    stochastic.render.method = Method::Stochastic;
    stochastic.render.samples = 64;
    // The stochastic method shades its hits the same way; 64 jittered samples of n.l, which varies by at
    // most 0.05 across a pixel here, leave a standard error under 0.005; 0.03 is 6 of those plus 0.01.
    EXPECT_LT(againstAnalytic(renderFrame(stochastic, 0)).worst, 0.03);
}

// Deformation keys carry no normals: the blended corner normal turns with its triangle. A triangle whose
// key turns it by R about an axis in its own plane has R as the smallest rotation taking its face normal
// to the new one, so the shading normal must be R times the rest blend, to rounding (1e-12).
TEST(SmoothShading, NormalsFollowADeformingTriangle) {
    Scene scene;
    Object tri;
    tri.mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};  // face normal +z
    tri.mesh.triangles = {{0, 1, 2}};
    tri.mesh.corner_normals = {{0.3, 0, 1}, {0, -0.2, 1}, {0.1, 0.1, 1}};
    const glm::dquat r = glm::angleAxis(0.9, glm::normalize(glm::dvec3(1, 1, 0)));
    std::vector<glm::dvec3> turned;
    for (const glm::dvec3& p : tri.mesh.positions) turned.push_back(r * p + glm::dvec3(0.5, -2, 3));
    tri.deformation = {DeformationKey{0.0, tri.mesh.positions}, DeformationKey{1.0, turned}};
    scene.objects.push_back(tri);
    scene.materials.push_back(Material{});
    const FrameMotion motion(scene, 0.0, 1.0);
    const Shader shader(motion);
    const double u = 0.2, v = 0.5;
    const glm::dvec3 blend = (1 - u - v) * tri.mesh.corner_normals[0] + u * tri.mesh.corner_normals[1] +
                             v * tri.mesh.corner_normals[2];
    const SurfaceGeometry rest = shader.geometry(SurfacePoint{0, 0, u, v, 0.0});
    EXPECT_LT(glm::length(rest.shading_normal - glm::normalize(blend)), 1e-12);
    const SurfaceGeometry end = shader.geometry(SurfacePoint{0, 0, u, v, 1.0});
    EXPECT_LT(glm::length(end.shading_normal - glm::normalize(r * blend)), 1e-12);
    EXPECT_LT(glm::length(end.normal - r * glm::dvec3(0, 0, 1)), 1e-12);
}

}  // namespace clipblur
