#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "io/job_loader.h"
#include "renderer/render.h"
#include "support/cli_harness.h"
#include "support/gltf_writer.h"
#include "support/render_compare.h"

namespace clipblur {

namespace {

using nlohmann::json;
using testing::meanSquaredDifference;

std::vector<float> zQuat(double degrees) {
    const glm::dquat q = glm::angleAxis(glm::radians(degrees), glm::dvec3(0, 0, 1));
    return {float(q.x), float(q.y), float(q.z), float(q.w)};
}

void animate(testing::GltfWriter& w, int node, const std::string& path, const std::vector<float>& values) {
    const int in = w.addFloats({0, 1}, "SCALAR");
    const int out = w.addFloats(values, path == "rotation" ? "VEC4" : path == "weights" ? "SCALAR" : "VEC3");
    w.doc()["animations"].push_back(
        {{"samplers", json::array({{{"input", in}, {"output", out}, {"interpolation", "LINEAR"}}})},
         {"channels", json::array({{{"sampler", 0}, {"target", {{"node", node}, {"path", path}}}}})}});
}

// A flag whose corner a morph target pulls out during the shutter (exact deformation keys), a wheel
// spinning on a car that drives and turns, a skinned leg bending at the knee and a crate turning under a
// parent stretched along y, so that its world matrix shears (all three exact motions), over 1 s = 1
// frame at fps 1.
testing::GltfWriter movingScene() {
    testing::GltfWriter w;
    w.doc()["materials"] = json::array(
        {{{"doubleSided", true}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.9, 0.2, 0.2, 1}}}}},
         {{"doubleSided", true}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.2, 0.9, 0.2, 1}}}}},
         {{"doubleSided", true}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.2, 0.3, 0.9, 1}}}}}});
    const int quad = w.addFloats({-1.5, -1, 0, -0.5, -1, 0, -0.5, 0.5, 0, -1.5, 0.5, 0}, "VEC3", 34962);
    const int pull = w.addFloats({0, 0, 0, 0, 0, 0, 0.8f, 0.3f, 0, 0, 0, 0}, "VEC3", 34962);
    const int quad_idx = w.addIndices({0, 1, 2, 0, 2, 3}, 5123);
    const int tetra = w.addFloats({0, 0, 0, 0.6f, 0, 0, 0, 0.6f, 0, 0, 0, 0.6f}, "VEC3", 34962);
    const int tetra_idx = w.addIndices({0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3}, 5123);
    // A leg from (2.5, -1.5) up to (2.5, 0.5), clear of the car's path, hip at its foot, knee halfway;
    // components of zero weight name joint 0.
    const int leg = w.addFloats({2.35f, -1.5f, 0, 2.65f, -1.5f, 0, 2.35f, -0.5f, 0, 2.65f, -0.5f, 0, 2.35f, 0.5f, 0, 2.65f, 0.5f, 0},
                                "VEC3", 34962);
    const int leg_idx = w.addIndices({0, 1, 3, 0, 3, 2, 2, 3, 5, 2, 5, 4}, 5123);
    const int joints = w.addUnsigned({0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, 5121, "VEC4");
    const int weights = w.addFloats({1, 0, 0, 0, 1, 0, 0, 0, 0.5f, 0.5f, 0, 0, 0.5f, 0.5f, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4", 34962);
    const int ibm = w.addFloats({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -2.5f, 1.5f, 0, 1, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -2.5f, 0.5f, 0, 1}, "MAT4");
    w.doc()["meshes"] = json::array(
        {{{"primitives", json::array({{{"attributes", {{"POSITION", quad}}}, {"indices", quad_idx}, {"material", 0},
                                       {"targets", json::array({{{"POSITION", pull}}})}}})},
          {"weights", {0}}},
         {{"primitives", json::array({{{"attributes", {{"POSITION", tetra}}}, {"indices", tetra_idx}, {"material", 1}}})}},
         {{"primitives", json::array({{{"attributes", {{"POSITION", leg}, {"JOINTS_0", joints}, {"WEIGHTS_0", weights}}},
                                       {"indices", leg_idx}, {"material", 2}}})}}});
    w.doc()["nodes"] = json::array({{{"name", "flag"}, {"mesh", 0}},
                                    {{"name", "car"}, {"children", {2}}},
                                    {{"name", "wheel"}, {"mesh", 1}, {"translation", {0.3, 0.2, 0}}},
                                    {{"name", "leg"}, {"mesh", 2}, {"skin", 0}},
                                    {{"name", "hip"}, {"translation", {2.5, -1.5, 0}}, {"children", {5}}},
                                    {{"name", "knee"}, {"translation", {0, 1, 0}}},
                                    {{"name", "stretch"}, {"translation", {-3, 0.8, 0}}, {"scale", {1, 1.6, 1}}, {"children", {7}}},
                                    {{"name", "crate"}, {"mesh", 1}}});
    w.doc()["skins"] = json::array({{{"joints", {4, 5}}, {"inverseBindMatrices", ibm}}});
    w.doc()["scene"] = 0;
    w.doc()["scenes"] = json::array({{{"nodes", {0, 1, 3, 4, 6}}}});
    animate(w, 0, "weights", {0, 1});
    animate(w, 1, "translation", {0.3f, -0.5f, 0, 1.3f, -0.2f, 0});
    std::vector<float> turn = zQuat(0);
    for (const float v : zQuat(60)) turn.push_back(v);
    animate(w, 1, "rotation", turn);
    std::vector<float> spin = zQuat(0);
    for (const float v : zQuat(-120)) spin.push_back(v);
    animate(w, 2, "rotation", spin);
    std::vector<float> bend = zQuat(0);
    for (const float v : zQuat(-70)) bend.push_back(v);
    animate(w, 5, "rotation", bend);
    std::vector<float> tumble = zQuat(0);
    for (const float v : zQuat(90)) tumble.push_back(v);
    animate(w, 7, "rotation", tumble);
    return w;
}

const char* kJob = R"(version: 1
film: {width: 64, height: 36}
scene: moving.gltf
camera:
  vfov: 40
  keys: [{position: [0, 0, -6], view: [0, 0, 1]}]
frames: {first: 0, last: 0, fps: 1}
ambient: 1
materials:
  - {name: back, color: 0.3}
objects:
  - name: backdrop
    material: back
    primitive: {type: quad, size: 12}
    transform: [{translate: [0, 0, 3], rotate: {axis: [1, 0, 0], angle_deg: -90}}]
render: {tile_size: 16, audit: true}
)";

// movingScene filmed from a boom: the camera 6 units out, facing the scene, on a node swinging 15
// degrees about +Y during the shutter (an exact camera: its motion is not linear).
testing::GltfWriter boomScene() {
    testing::GltfWriter w = movingScene();
    w.doc()["cameras"] = json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 40 * M_PI / 180}, {"znear", 0.1}}}}});
    const std::size_t boom = w.doc()["nodes"].size();
    w.doc()["nodes"].push_back({{"name", "boom"}, {"children", {boom + 1}}});
    w.doc()["nodes"].push_back({{"name", "cam"}, {"camera", 0}, {"translation", {0, 0, -6}}, {"rotation", {0, 1, 0, 0}}});
    w.doc()["scenes"][0]["nodes"].push_back(boom);
    std::vector<float> swing = {0, 0, 0, 1};
    const glm::dquat q = glm::angleAxis(glm::radians(15.0), glm::dvec3(0, 1, 0));
    swing.insert(swing.end(), {float(q.x), float(q.y), float(q.z), float(q.w)});
    animate(w, static_cast<int>(boom), "rotation", swing);
    return w;
}

const char* kBoomJob = R"(version: 1
film: {width: 64, height: 36}
scene: boom.gltf
frames: {first: 0, last: 0, fps: 1}
ambient: 1
materials:
  - {name: back, color: 0.3}
objects:
  - name: backdrop
    material: back
    primitive: {type: quad, size: 12}
    transform: [{translate: [0, 0, 3], rotate: {axis: [1, 0, 0], angle_deg: -90}}]
render: {tile_size: 16, audit: true}
)";

}  // namespace

// The statistic of tests/renderer/clipped/clipped_vs_stochastic_test.cpp: two stochastic renders with
// independent seeds estimate the variance V of their average; an exact clipped render differs from
// that average by V in the mean, so the ratio stays near 1 (< 1.5 allows ~5 standard errors), while a
// wrong morph or a wheel off its path is a bias over whole edges that the ratio does not survive.
TEST(GltfRender, MorphSkinShearAndExactMotionAgreeWithTheStochasticReference) {
    const auto dir = testing::freshTempDir("clipblur_gltf_vs_stochastic");
    movingScene().writeGltf(dir / "moving.gltf");
    movingScene().writeGltf(testing::validatedAssetDir() / "moving_vs_stochastic.gltf");
    std::ofstream(dir / "job.yaml") << kJob;
    const auto load = [&](const std::vector<std::string>& overrides) { return loadJob(dir / "job.yaml", overrides); };
    const RenderJob job = load({});
    ASSERT_EQ(job.scene.objects.size(), 5u);
    EXPECT_EQ(job.scene.objects[1].deformation.size(), 2u);
    for (const std::size_t o : {2u, 3u, 4u}) {  // wheel, leg, crate: followed exactly, no keys
        EXPECT_TRUE(job.scene.objects[o].motion) << o;
        EXPECT_TRUE(job.scene.objects[o].transform.empty() && job.scene.objects[o].deformation.empty()) << o;
    }
    const RenderResult clipped = renderFrame(load({"render.subframes=64"}), 0);
    const RenderResult s1 = renderFrame(load({"render.method=stochastic", "render.samples=400", "render.seed=1"}), 0);
    const RenderResult s2 = renderFrame(load({"render.method=stochastic", "render.samples=400", "render.seed=2"}), 0);
    const double variance = meanSquaredDifference(s1, s2) / 4.0;
    const double ratio = meanSquaredDifference(clipped, s1, &s2) / variance;
    RecordProperty("ratio", std::to_string(ratio));
    EXPECT_LT(ratio, 1.5) << "variance " << variance;
    // The motion is visible: a still render differs from the moving one far beyond the noise.
    const RenderResult still = renderFrame(load({"shutter.close=0"}), 0);
    EXPECT_GT(meanSquaredDifference(still, s1, &s2) / variance, 10.0);
}

// The same statistic with the camera on a swinging boom: a camera off its exact path shifts every edge
// of the image, which the ratio does not survive.
TEST(GltfRender, BoomCameraAgreesWithTheStochasticReference) {
    const auto dir = testing::freshTempDir("clipblur_gltf_boom_vs_stochastic");
    boomScene().writeGltf(dir / "boom.gltf");
    boomScene().writeGltf(testing::validatedAssetDir() / "boom_vs_stochastic.gltf");
    std::ofstream(dir / "job.yaml") << kBoomJob;
    const auto load = [&](const std::vector<std::string>& overrides) { return loadJob(dir / "job.yaml", overrides); };
    ASSERT_TRUE(load({}).scene.camera.motion);
    const RenderResult clipped = renderFrame(load({"render.subframes=64"}), 0);
    const RenderResult s1 = renderFrame(load({"render.method=stochastic", "render.samples=400", "render.seed=1"}), 0);
    const RenderResult s2 = renderFrame(load({"render.method=stochastic", "render.samples=400", "render.seed=2"}), 0);
    const double variance = meanSquaredDifference(s1, s2) / 4.0;
    const double ratio = meanSquaredDifference(clipped, s1, &s2) / variance;
    RecordProperty("ratio", std::to_string(ratio));
    EXPECT_LT(ratio, 1.5) << "variance " << variance;
    const RenderResult still = renderFrame(load({"shutter.close=0"}), 0);
    EXPECT_GT(meanSquaredDifference(still, s1, &s2) / variance, 10.0);
}

}  // namespace clipblur
