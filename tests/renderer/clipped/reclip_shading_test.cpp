#include <cmath>
#include <string>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "renderer/render.h"
#include "renderer/test_scenes.h"
#include "scene/primitives.h"
#include "support/render_compare.h"

namespace clipblur {

namespace {

using testing::averaged;
using testing::meanSquaredDifference;

// A square facing the camera turns 50 degrees about the vertical during the shutter under a directional
// light 26.6 degrees off the view axis, in one shutter segment (so the fragment sets are at its ends
// only). n.l runs from cos(51.6) = 0.62 through cos(26.6) = 0.89 at mid-shutter to cos(1.6) = 1.0: the
// frames' colours mixed along the chord would be 0.81 at mid-shutter, 0.08 too dark over the whole
// face, where shading each re-clip at its own time follows the cosine.
RenderJob turningFaceUnderALight() {
    RenderJob job = test::squareFilmJob(32);
    job.scene.ambient = glm::dvec3(0.2);
    Light light;
    light.direction = glm::normalize(glm::dvec3(-0.5, 0.0, 1.0));
    light.intensity = 0.7;
    job.scene.lights.push_back(light);
    Object face;
    face.name = "face";
    face.mesh = makeQuad(glm::dvec2(10.0));  // in the xz plane; turned to face the camera below
    const glm::dquat upright = glm::angleAxis(glm::radians(-90.0), glm::dvec3(1, 0, 0));
    for (const auto& [time, degrees] : {std::pair{0.0, -25.0}, {1.0, 25.0}}) {
        const glm::dquat turn = glm::angleAxis(glm::radians(degrees), glm::dvec3(0, 1, 0));
        face.transform.push_back(TransformKey{time, glm::dvec3(0.0, 0.0, 10.0), turn * upright, glm::dvec3(1.0)});
    }
    job.scene.objects.push_back(face);
    job.render.segments = 1;
    return job;
}

}  // namespace

// The statistical test of AgainstStochastic (clipped_vs_stochastic_test.cpp): two stochastic renders
// with independent seeds estimate the reference's variance V; an exact clipped render gives
// mean (c - s)^2 / V = 1 plus noise, and R < 1.5 leaves room for about 5 standard errors. A bias of 0.08
// over the face's ~150 pixels is R in the hundreds.
TEST(ReclipShading, FaceTurningUnderALightMatchesTheStochasticReference) {
    RenderJob job = turningFaceUnderALight();
    job.render.samples = 400;
    job.render.seed = 1;
    const RenderResult s1 = renderFrame(job, 0);
    job.render.seed = 2;
    const RenderResult s2 = renderFrame(job, 0);
    const double variance = meanSquaredDifference(s1, s2) / 4.0;
    const RenderResult reference = averaged(s1, s2);

    job.render.method = Method::Clipped;
    job.render.subframes = 32;
    const RenderResult point = renderFrame(job, 0);
    EXPECT_EQ(point.stats.clipped().segments, 1);
    const double point_ratio = meanSquaredDifference(point, reference) / variance;
    RecordProperty("point_ratio", std::to_string(point_ratio));
    EXPECT_LT(point_ratio, 1.5) << "variance " << variance;

    // Sweep: one colour per re-clip interval (its middle's), so 8 re-clips leave the cosine's change
    // within an interval, 6 degrees, about 0.01 at most; auto asks for fewer than that here.
    job.render.time_integration = TimeIntegration::Sweep;
    job.render.subframes = 8;
    const RenderResult sweep = renderFrame(job, 0);
    const double sweep_ratio = meanSquaredDifference(sweep, reference) / variance;
    RecordProperty("sweep_ratio", std::to_string(sweep_ratio));
    EXPECT_LT(sweep_ratio, 1.5) << "variance " << variance;
}

}  // namespace clipblur
