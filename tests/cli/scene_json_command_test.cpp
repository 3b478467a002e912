#include "cli/scene_json_command.h"

#include <string>

#include <gtest/gtest.h>

#include "io/job_loader.h"

namespace clipblur {

namespace {

std::size_t triangleCount(const Scene& scene) {
    std::size_t n = 0;
    for (const Object& o : scene.objects) n += o.mesh.triangles.size();
    return n;
}

}  // namespace

TEST(SceneJsonCommand, SpinPanCheckerMatchesTheLoadedScene) {
    const RenderJob job = loadJob(std::string(CLIPBLUR_SOURCE_DIR) + "/configs/bench/peers/spin_pan_checker.yaml",
                                  {"film.width=320"});
    const nlohmann::json j = cli::sceneJson(job);

    ASSERT_EQ(j["objects"].size(), 1u);
    ASSERT_EQ(job.scene.objects.size(), 1u);
    std::size_t triangles = 0;
    for (const auto& o : j["objects"]) triangles += o["triangles"].size();
    EXPECT_EQ(triangles, 768u);
    EXPECT_EQ(triangles, triangleCount(job.scene));
    EXPECT_EQ(j["objects"][0]["positions"].size(), job.scene.objects[0].mesh.positions.size());
    EXPECT_EQ(j["camera"]["keys"].size(), 2u);
    EXPECT_EQ(j["camera"]["keys"].size(), job.scene.camera.keys.size());
    EXPECT_EQ(j["film"]["width"], 320);  // --set applied
    EXPECT_EQ(j["lights"].size(), 0u);
    EXPECT_EQ(j["materials"][0]["texture"]["kind"], "checker");

    // Values survive at full precision: the rotation key and the second camera key's up.
    const TransformKey& key = job.scene.objects[0].transform.at(0);
    const auto& rotate = j["objects"][0]["transform"][0]["rotate"];
    EXPECT_EQ(rotate[0].get<double>(), key.rotate.w);
    EXPECT_EQ(rotate[1].get<double>(), key.rotate.x);
    EXPECT_EQ(j["camera"]["keys"][1]["up"][0].get<double>(), job.scene.camera.keys[1].up.x);

    // Round trip through text, as the peer reads it.
    EXPECT_EQ(nlohmann::json::parse(j.dump()), j);
}

// The Cycles peer reads the shutter from here: a curve is exported (so the peer can refuse it), a box
// is not (a box job's export is what it was).
TEST(SceneJsonCommand, ShutterCurveIsExportedOnlyWhenGiven) {
    const std::string path = std::string(CLIPBLUR_SOURCE_DIR) + "/configs/bench/peers/spin_pan_checker.yaml";
    const nlohmann::json box = cli::sceneJson(loadJob(path, {"shutter.open=-0.25", "shutter.close=0.25"}));
    EXPECT_EQ(box["shutter"]["open"], -0.25);
    EXPECT_FALSE(box["shutter"].contains("curve"));
    const nlohmann::json curve =
        cli::sceneJson(loadJob(path, {"shutter.open=0", "shutter.close=0.5", "shutter.curve=[[0, 0], [0.25, 1], [0.5, 0]]"}));
    EXPECT_EQ(curve["shutter"]["curve"], nlohmann::json::parse("[[0, 0], [0.25, 1], [0.5, 0]]"));
}

}  // namespace clipblur
