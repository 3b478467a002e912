#include "cli/scene_json_command.h"

#include <string>

#include <glm/gtc/quaternion.hpp>
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

// The shipped shot's wheels turn under moving cars: an exact motion, which no key shows, so the export
// flags it and `at` poses it. Checked against what the keys and rest positions say independently: a
// static object's pose is its rest mesh, a keyed car's is translate + rotate (scale p) at a key time.
TEST(SceneJsonCommand, ExactMotionIsFlaggedAndEveryObjectIsPosedAt) {
    const RenderJob job = loadJob(std::string(CLIPBLUR_SOURCE_DIR) + "/configs/shot.yaml", {});
    const nlohmann::json plain = cli::sceneJson(job);
    const nlohmann::json j = cli::sceneJson(job, 24.0);
    const auto object = [&](const nlohmann::json& doc, const std::string& name) {
        for (const auto& o : doc["objects"])
            if (o["name"] == name) return o;
        ADD_FAILURE() << name << " missing";
        return nlohmann::json();
    };
    EXPECT_FALSE(plain["objects"][0].contains("posed"));
    EXPECT_TRUE(object(j, "car_red_wheel_fl")["exact_motion"].get<bool>());
    EXPECT_TRUE(object(j, "car_red_wheel_fl")["transform"].empty());
    EXPECT_FALSE(object(j, "car_red")["exact_motion"].get<bool>());
    EXPECT_FALSE(object(j, "road")["exact_motion"].get<bool>());

    const nlohmann::json road = object(j, "road");
    EXPECT_EQ(road["posed"]["time"], 24.0);
    EXPECT_EQ(road["posed"]["positions"], road["positions"]);

    const nlohmann::json car = object(j, "car_red");
    const nlohmann::json* key = nullptr;
    for (const auto& k : car["transform"])
        if (k["time"] == 24.0) key = &k;
    ASSERT_NE(key, nullptr) << "no car key at frame 24";
    const auto v3 = [](const nlohmann::json& a) { return glm::dvec3(a[0].get<double>(), a[1].get<double>(), a[2].get<double>()); };
    const auto& r = (*key)["rotate"];
    const glm::dquat q(r[0].get<double>(), r[1].get<double>(), r[2].get<double>(), r[3].get<double>());
    ASSERT_EQ(car["posed"]["positions"].size(), car["positions"].size());
    for (std::size_t i = 0; i < car["positions"].size(); ++i) {
        const glm::dvec3 expected = v3((*key)["translate"]) + q * (v3((*key)["scale"]) * v3(car["positions"][i]));
        EXPECT_LT(glm::length(v3(car["posed"]["positions"][i]) - expected), 1e-12) << i;
    }

    // The wheel's pose moves with the car: its centre at frame 24 differs from its rest mesh's.
    const nlohmann::json wheel = object(j, "car_red_wheel_fl");
    glm::dvec3 rest(0.0), posed(0.0);
    for (std::size_t i = 0; i < wheel["positions"].size(); ++i) {
        rest += v3(wheel["positions"][i]);
        posed += v3(wheel["posed"]["positions"][i]);
    }
    EXPECT_GT(glm::length(posed - rest) / static_cast<double>(wheel["positions"].size()), 0.1);
}

}  // namespace clipblur
