#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "renderer/render.h"
#include "renderer/test_scenes.h"
#include "support/render_compare.h"
#include "support/texture_files.h"

namespace clipblur {

namespace {

// Every method and every fragment_shading rule of both clipped time integrations: each must shade
// emission and unlit materials the same way.
struct MethodCase {
    const char* name;
    Method method;
    TimeIntegration integration;
    FragmentShading shading;
};

const MethodCase kMethods[] = {
    {"clipped subframes centroid", Method::Clipped, TimeIntegration::Subframes, FragmentShading::Centroid},
    {"clipped subframes fan", Method::Clipped, TimeIntegration::Subframes, FragmentShading::Fan},
    {"clipped sweep centroid", Method::Clipped, TimeIntegration::Sweep, FragmentShading::Centroid},
    {"clipped sweep fan", Method::Clipped, TimeIntegration::Sweep, FragmentShading::Fan},
    {"clipped subframes integral", Method::Clipped, TimeIntegration::Subframes, FragmentShading::Integral},
    {"clipped sweep integral", Method::Clipped, TimeIntegration::Sweep, FragmentShading::Integral},
    {"accumulation", Method::Accumulation, TimeIntegration::Subframes, FragmentShading::Centroid},
    {"frame0_only", Method::Frame0Only, TimeIntegration::Subframes, FragmentShading::Centroid},
    {"stochastic", Method::Stochastic, TimeIntegration::Subframes, FragmentShading::Centroid},
};

RenderResult renderWith(RenderJob job, const MethodCase& m) {
    job.render.method = m.method;
    job.render.time_integration = m.integration;
    job.render.fragment_shading = m.shading;
    job.render.samples = m.method == Method::Accumulation ? 8 : 16;
    return renderFrame(job, 0);
}

// Smooth normals (all the face's own, toward the camera) make the fan rule shade several points per piece
// instead of leaving faceted pieces at their centroid, so both rules are exercised.
Object smoothQuad(Object quad) {
    quad.mesh.corner_normals.assign(3 * quad.mesh.triangles.size(), glm::dvec3(0, 0, -1));
    return quad;
}

float value(const RenderResult& r, const char* channel, int x, int y, int film = 32) {
    return r.image.find(channel)->values[static_cast<std::size_t>(y * film + x)];
}

// Largest |C - A c(x, y)| over every pixel and colour channel: premultiplied colour is coverage times the
// surface's colour wherever one surface of colour c is all a pixel shows.
double worstPremultiplied(const RenderResult& r, const std::function<glm::dvec3(int, int)>& colour, int film = 32) {
    double worst = 0.0;
    for (int y = 0; y < film; ++y)
        for (int x = 0; x < film; ++x) {
            const glm::dvec3 c = colour(x, y);
            const double a = value(r, "A", x, y, film);
            const char* names[3] = {"R", "G", "B"};
            for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(value(r, names[k], x, y, film) - a * c[k]));
        }
    return worst;
}

// A blocker behind the camera (never drawn: it is behind the near plane) that hides a point light at
// (0, 0, -4) from every quad point at depth 2 with world x > 0, which squareFilmJob shows at raster x < 16.
Object blockerBehindTheCamera() {
    Object blocker;
    blocker.name = "blocker";
    blocker.mesh.positions = {{0, -10, -1}, {10, -10, -1}, {10, 10, -1}, {0, 10, -1}};
    blocker.mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
    return blocker;
}

Light pointLight() {
    Light l;
    l.kind = Light::Kind::Point;
    l.intensity = 20.0;
    l.position = {0, 0, -4};
    return l;
}

// Travelling into the quad (+z) tilted 60 degrees from its normal, so it reaches no shadow behind the
// camera's blocker (it leaves the quad toward -x).
Light directionalLight() {
    Light l;
    l.kind = Light::Kind::Directional;
    l.intensity = 2.0;
    l.color = {1.0, 0.5, 1.0};
    l.direction = {std::sin(M_PI / 3), 0.0, std::cos(M_PI / 3)};
    return l;
}

// Lambert for one directional light on the quad's normal (0, 0, -1), computed here from the definition.
glm::dvec3 directionalIrradiance(const Light& l) {
    const glm::dvec3 to_light = -glm::normalize(l.direction);
    return l.intensity * l.color * std::max(0.0, glm::dot(glm::dvec3(0, 0, -1), to_light));
}

// A still quad over raster [4.5, 28) x [4, 28) at depth 2: column 4 is half covered.
RenderJob stillQuadJob(const Material& material) {
    RenderJob job = test::squareFilmJob(32);
    job.scene.materials = {material};
    job.scene.objects = {smoothQuad(test::rasterQuad(4.5, 4, 28, 28, 2.0))};
    return job;
}

// The same quad under ambient light, a directional and a point light, with shadow rays and a blocker
// shadowing the point light on its left half.
RenderJob litVariant(RenderJob job) {
    job.scene.ambient = glm::dvec3(0.4);
    job.scene.lights = {directionalLight(), pointLight()};
    job.scene.objects.push_back(blockerBehindTheCamera());
    job.render.shadows = true;
    return job;
}

}  // namespace

// An unlit quad is its base colour in every pixel it covers, under no light at all or under ambient,
// a directional and a point light with a shadow, in every method. The lit material under the same lights
// differs from its base colour by more than 0.05 and varies across the quad (shadowed on its left): the
// lights and the shadow do reach the quad, and unlit ignores them. 1e-6: channels are float (6e-8
// relative) and a pixel's fragment areas sum to its coverage to ~1e-15.
TEST(Unlit, QuadIsItsBaseColourWhateverTheLightsInEveryMethod) {
    Material unlit;
    unlit.base_color = {0.7, 0.2, 0.05};
    unlit.model = ShadingModel::Unlit;
    const RenderJob dark = [&] {
        RenderJob j = stillQuadJob(unlit);
        j.scene.ambient = glm::dvec3(0.0);
        return j;
    }();
    const RenderJob lit = litVariant(stillQuadJob(unlit));
    const auto base = [&](int, int) { return unlit.base_color; };
    for (const MethodCase& m : kMethods) {
        for (const RenderJob* job : {&dark, &lit}) {
            const RenderResult r = renderWith(*job, m);
            EXPECT_LT(worstPremultiplied(r, base), 1e-6) << m.name << (job == &lit ? " lit" : " dark");
            EXPECT_NEAR(value(r, "A", 16, 16), 1.0, 1e-6) << m.name;
            EXPECT_NEAR(value(r, "R", 16, 16), unlit.base_color.r, 1e-7) << m.name;
            if (m.method != Method::Stochastic) {
                EXPECT_NEAR(value(r, "A", 4, 16), 0.5, 1e-6) << m.name;
            }
        }
        RenderJob shaded = lit;
        shaded.scene.materials[0].model = ShadingModel::Lit;
        const RenderResult r = renderWith(shaded, m);
        EXPECT_GT(worstPremultiplied(r, base), 0.05) << m.name;
        EXPECT_GT(std::abs(value(r, "R", 24, 16) - value(r, "R", 8, 16)), 0.05) << m.name << ": no shadow";
    }
}

// With no light at all (ambient 0, no lights) an emissive quad is its emission, above 1 and whatever its
// base colour: radiance, linear, premultiplied by coverage. Tolerance as above.
TEST(Emission, QuadWithoutLightsIsItsEmissionInEveryMethod) {
    Material glow;
    glow.base_color = glm::dvec3(0.8);
    glow.emission = {2.5, 0.5, 0.0};
    RenderJob job = stillQuadJob(glow);
    job.scene.ambient = glm::dvec3(0.0);
    for (const MethodCase& m : kMethods) {
        const RenderResult r = renderWith(job, m);
        EXPECT_LT(worstPremultiplied(r, [&](int, int) { return glow.emission; }), 1e-6) << m.name;
        EXPECT_NEAR(value(r, "R", 16, 16), 2.5, 1e-6) << m.name;
    }
}

// Emission adds to Lambert shading: base x (ambient + directional irradiance) + emission, the irradiance
// computed here from the light's direction. Under the point light's shadow (raster x 5..14, every shading
// point at world x > 0.25) that is all there is: emission is not shadowed. Where the point light reaches,
// the pixel is brighter than that by its Lambert term. Tolerance as above, and the point light's fall-off
// over a pixel is not in the shadowed pixels checked.
TEST(Emission, AddsToLambertShadingInEveryMethod) {
    Material glow;
    glow.base_color = {0.5, 0.25, 1.0};
    glow.emission = {0.3, 1.7, 0.05};
    const RenderJob job = litVariant(stillQuadJob(glow));
    const glm::dvec3 expected =
        glow.base_color * (job.scene.ambient + directionalIrradiance(job.scene.lights[0])) + glow.emission;
    for (const MethodCase& m : kMethods) {
        const RenderResult r = renderWith(job, m);
        double worst = 0.0;
        for (int y = 4; y < 28; ++y)
            for (int x = 5; x < 15; ++x)
                for (int k = 0; k < 3; ++k)
                    worst = std::max(worst, std::abs(value(r, k == 0 ? "R" : k == 1 ? "G" : "B", x, y) - expected[k]));
        EXPECT_LT(worst, 1e-6) << m.name;
        EXPECT_GT(value(r, "B", 24, 16), expected.b + 0.05) << m.name << ": the point light is missing";
    }
}

namespace {

using testing::averaged;
using testing::meanSquaredDifference;

// Three surfaces for the comparisons with the stochastic method: a lit wall filling the film (depth 6), an
// emissive quad (depth 3) moving 10 px right and 4 down, and an unlit quad (depth 2) in front of it
// moving 8 px left and 2 down, under ambient and a directional light (constant on translating flat faces,
// so per-frame shading and per-sample shading agree: AgainstStochastic explains why that matters).
RenderJob movingEmissiveJob() {
    RenderJob job = test::squareFilmJob(32);
    job.scene.ambient = glm::dvec3(0.2);
    job.scene.lights = {directionalLight()};
    Material wall, glow, flat;
    wall.base_color = glm::dvec3(0.5);
    glow.base_color = glm::dvec3(0.3);
    glow.emission = {1.5, 0.6, 0.1};
    flat.base_color = {0.1, 0.9, 0.4};
    flat.model = ShadingModel::Unlit;
    job.scene.materials = {wall, glow, flat};
    Object back = test::rasterQuad(-4, -4, 36, 36, 6.0);
    back.name = "wall";
    Object front = test::movingQuad(6, 6, 18, 18, 3.0, {10, 4});
    front.name = "glow";
    front.material = 1;
    Object nearest = test::movingQuad(14, 12, 26, 24, 2.0, {-8, 2});
    nearest.name = "flat";
    nearest.material = 2;
    job.scene.objects = {back, front, nearest};
    return job;
}

}  // namespace

// Moving emissive and unlit objects, clipped (point subframes and sweep, both at 64 re-clips per segment so
// the time quadrature is far below the noise) and accumulated (128 stills) against two 400-sample
// stochastic renders: the variance-ratio test of AgainstStochastic.DifferenceIsExplainedBySamplingNoise
// (R = mean (c - s)^2 / V is 1 plus noise for an exact method; 1.5 allows the noise of a few hundred edge
// pixels and a bias of at most sqrt(0.5 V), while an emission that were dropped, shadowed or mixed wrongly
// between the frames shows over whole streaks). Sweep and accumulation pass it (measured 0.93 and 0.93).
// Point subframes do not, on this scene with plain lit materials as well (ratio 21.6 there, 4.1 here, the
// same at 16, 64 or 65 subframes and any tile size: a bias of ~0.03 along the unlit quad's edges where it
// passes in front of the emissive one, not from shading), so they are held to AgainstStochastic's RMSE
// bound for clipped renders instead (measured 0.0056; a missing emission of 1.5 over the streaks
// exceeds it tenfold).
TEST(Emission, MovingEmissiveAndUnlitObjectsMatchTheStochasticReference) {
    const RenderJob job = movingEmissiveJob();
    const auto render = [&](Method method, TimeIntegration integration, int samples, std::uint64_t seed) {
        RenderJob j = job;
        j.render.method = method;
        j.render.time_integration = integration;
        j.render.samples = samples;
        j.render.subframes = method == Method::Clipped ? 64 : 0;
        j.render.seed = seed;
        return renderFrame(j, 0);
    };
    const RenderResult s1 = render(Method::Stochastic, TimeIntegration::Subframes, 400, 1);
    const RenderResult s2 = render(Method::Stochastic, TimeIntegration::Subframes, 400, 2);
    const RenderResult reference = averaged(s1, s2);
    const double variance = meanSquaredDifference(s1, s2) / 4.0;
    const struct {
        const char* name;
        RenderResult result;
    } cases[] = {{"clipped subframes", render(Method::Clipped, TimeIntegration::Subframes, 16, 0)},
                 {"clipped sweep", render(Method::Clipped, TimeIntegration::Sweep, 16, 0)},
                 {"accumulation", render(Method::Accumulation, TimeIntegration::Subframes, 128, 0)}};
    for (const auto& c : cases) {
        const double ratio = meanSquaredDifference(c.result, reference) / variance;
        RecordProperty(std::string("ratio ") + c.name, std::to_string(ratio));
        if (&c == &cases[0]) {
            EXPECT_LT(std::sqrt(meanSquaredDifference(c.result, reference)), 0.01) << c.name;
            continue;
        }
        EXPECT_LT(ratio, 1.5) << c.name << ", variance " << variance;
    }
    // Not vacuous: there is sampling noise (motion), and pixel (16, 10), under the emissive quad all
    // shutter, shows 0.3 x (0.2 + 2 x 0.5) + 1.5 in red.
    EXPECT_GT(variance, 1e-6);
    EXPECT_NEAR(value(cases[1].result, "R", 16, 10), 0.3 * 1.2 + 1.5, 1e-5);
}

// Cryptomatte coverage and the depth, motion and coverage AOVs do not depend on how surfaces are shaded:
// the moving scene with its emissive and unlit materials gives them bit for bit as with plain lit ones,
// clipped and stochastic, while its colour differs.
TEST(Emission, CryptomatteAndAovsDoNotDependOnTheShadingModel) {
    RenderJob job = movingEmissiveJob();
    job.output.aov_depth = true;
    job.output.aov_motion = true;
    job.output.aov_coverage = true;
    job.output.cryptomatte.enabled = true;
    RenderJob plain = job;
    for (Material& m : plain.scene.materials) {
        m.model = ShadingModel::Lit;
        m.emission = glm::dvec3(0.0);
    }
    for (const Method method : {Method::Clipped, Method::Stochastic}) {
        job.render.method = plain.render.method = method;
        const RenderResult a = renderFrame(job, 0), b = renderFrame(plain, 0);
        ASSERT_EQ(a.image.channels.size(), b.image.channels.size());
        std::size_t compared = 0;
        for (std::size_t c = 0; c < a.image.channels.size(); ++c) {
            const std::string& name = a.image.channels[c].name;
            if (name == "R" || name == "G" || name == "B") {
                EXPECT_NE(a.image.channels[c].values, b.image.channels[c].values) << name;
                continue;
            }
            EXPECT_EQ(a.image.channels[c].values, b.image.channels[c].values) << methodName(method) << " " << name;
            ++compared;
        }
        EXPECT_GE(compared, 5u) << "A, Z, two motion channels and coverage";
        ASSERT_EQ(a.objects.pixels.size(), b.objects.pixels.size());
        ASSERT_FALSE(a.objects.pixels.empty());
        for (std::size_t i = 0; i < a.objects.pixels.size(); ++i) {
            ASSERT_EQ(a.objects.pixels[i].size(), b.objects.pixels[i].size()) << i;
            for (std::size_t k = 0; k < a.objects.pixels[i].size(); ++k) {
                EXPECT_EQ(a.objects.pixels[i][k].object, b.objects.pixels[i][k].object);
                EXPECT_EQ(a.objects.pixels[i][k].coverage, b.objects.pixels[i][k].coverage);
            }
        }
    }
}

// An emission image multiplies the emission, and an unlit material's image its base colour, through the
// same path as a lit base colour image (filtered lookups under centroid, exact means under integral): the
// textured quad of
// ImageTextures.TexturedQuadClippedMatchesStochastic (an affine 8 x 8 float ramp filling the film), emissive
// with no light or unlit under a light, gives the ramp at a pixel's centre, and clipped matches stochastic
// within 1e-4 over pixels 10..21 (that test's argument: float texels, an affine image, symmetric filters).
TEST(Emission, EmissionAndUnlitImagesAreFilteredLikeBaseColourImages) {
    const int film = 32, texels = 8;
    const auto file = std::filesystem::path(::testing::TempDir()) / "clipblur_emission_ramp.exr";
    std::vector<float> ramp;
    for (int j = 0; j < texels; ++j)
        for (int i = 0; i < texels; ++i)
            for (int k = 0; k < 3; ++k) ramp.push_back(0.1f + 0.03f * static_cast<float>(i * (k + 1)) + 0.06f * static_cast<float>(j));
    testing::writeRgbFloatExr(file, texels, texels, ramp);
    Object quad = test::rasterQuad(0, 0, film, film, 2.0, film);
    const glm::dvec2 st[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (const auto& t : quad.mesh.triangles)
        for (const std::uint32_t v : t) quad.mesh.corner_uvs.push_back(st[v]);
    Material glow;
    glow.base_color = glm::dvec3(0.0);
    glow.emission = glm::dvec3(2.0);
    glow.emission_image.file = file.string();
    Material unlit;
    unlit.base_color = glm::dvec3(2.0);
    unlit.image.file = file.string();
    unlit.model = ShadingModel::Unlit;
    for (const Material& material : {glow, unlit}) {
        for (const FragmentShading rule : {FragmentShading::Centroid, FragmentShading::Integral}) {
            RenderJob job = test::squareFilmJob(film);
            job.render.fragment_shading = rule;
            job.scene.ambient = glm::dvec3(material.model == ShadingModel::Unlit ? 0.7 : 0.0);
            job.scene.lights = {directionalLight()};
            job.scene.materials = {material};
            job.scene.objects = {quad};
            job.render.samples = 256;
            RenderJob stochastic_job = job;
            job.render.method = Method::Clipped;
            const RenderResult clipped = renderFrame(job, 0);
            const RenderResult stochastic = renderFrame(stochastic_job, 0);
            double worst = 0.0;
            for (const char* c : {"R", "G", "B"})
                for (int py = 10; py < 22; ++py)
                    for (int px = 10; px < 22; ++px) worst = std::max(worst, double(std::abs(value(clipped, c, px, py) - value(stochastic, c, px, py))));
            EXPECT_LT(worst, 1e-4);
            // Pixel (10, 10)'s centre: s = t = 10.5 / 32, texel coordinate 2.125; red is 0.1 + 0.03 i + 0.06 j.
            const double texel = 10.5 / film * texels - 0.5;
            EXPECT_NEAR(value(clipped, "R", 10, 10), 2.0 * (0.1 + 0.03 * texel + 0.06 * texel), 2e-5);
        }
    }
}

}  // namespace clipblur
