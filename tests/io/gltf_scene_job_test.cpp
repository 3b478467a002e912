#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "io/job_loader.h"
#include "renderer/render.h"
#include "support/cli_harness.h"
#include "support/gltf_writer.h"

namespace clipblur {

namespace {

using nlohmann::json;
using testing::GltfWriter;

// A tetrahedron named "floor" with a blue double-sided material, and a camera at z = 10 looking down -z.
GltfWriter shot(bool with_camera) {
    GltfWriter w;
    const int pos = w.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1}, "VEC3", 34962);
    const int idx = w.addIndices({0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3}, 5123);
    w.doc()["materials"] = json::array(
        {{{"name", "blue"}, {"doubleSided", true}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.25, 0.5, 0.75, 1}}}}}});
    w.doc()["meshes"] = json::array({{{"primitives", json::array({{{"attributes", {{"POSITION", pos}}}, {"indices", idx}, {"material", 0}}})}}});
    w.doc()["nodes"] = json::array({{{"name", "floor"}, {"mesh", 0}}});
    std::vector<int> roots{0};
    if (with_camera) {
        w.doc()["cameras"] = json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.1}}}}});
        w.doc()["nodes"].push_back({{"name", "cam"}, {"camera", 0}, {"translation", {0.2, 0.3, 10}}});
        roots.push_back(1);
    }
    w.doc()["scene"] = 0;
    w.doc()["scenes"] = json::array({{{"nodes", roots}}});
    return w;
}

const char* kJobHead = R"(version: 1
film: {width: 64, height: 36}
scene: shot.glb
materials:
  - {name: red, color: [1, 0, 0]}
objects:
  - {name: floor, material: red, primitive: {type: quad, size: 10}}
)";

const char* kYamlCamera = R"(camera:
  keys: [{position: [0, 0, -5], view: [0, 0, 1]}]
)";

std::filesystem::path writeJob(const std::string& name, const std::string& text, bool with_camera = true) {
    const auto dir = testing::freshTempDir("clipblur_gltf_job_" + name);
    shot(with_camera).writeGlb(dir / "shot.glb");
    shot(with_camera).writeGlb(testing::validatedAssetDir() / (with_camera ? "job_shot.glb" : "job_shot_nocam.glb"));
    std::ofstream(dir / "job.yaml") << text;
    return dir / "job.yaml";
}

Error loadError(const std::filesystem::path& job) {
    try {
        loadJob(job);
    } catch (const Error& e) {
        return e;
    }
    ADD_FAILURE() << job << " loaded";
    return Error(ExitCode::Ok, "");
}

}  // namespace

TEST(GltfJob, SceneAddsObjectsMaterialsAndTheCameraBesideTheJobs) {
    std::vector<std::filesystem::path> read;
    const auto file = writeJob("adds", kJobHead);
    const RenderJob job = loadJob(file, {}, &read);
    ASSERT_EQ(job.scene.objects.size(), 2u);
    EXPECT_EQ(job.scene.objects[0].name, "floor");
    EXPECT_EQ(job.scene.objects[1].name, "floor#2");  // the job's name is taken first
    const Material& m = job.scene.materials.at(static_cast<std::size_t>(job.scene.objects[1].material));
    EXPECT_EQ(m.base_color, glm::dvec3(0.25, 0.5, 0.75));
    EXPECT_TRUE(m.two_sided);
    ASSERT_EQ(job.scene.camera.keys.size(), 1u);
    EXPECT_LT(glm::length(job.scene.camera.keys[0].position - glm::dvec3(0.2, 0.3, 10)), 1e-6);
    EXPECT_LT(glm::length(job.scene.camera.keys[0].view - glm::dvec3(0, 0, -1)), 1e-12);
    EXPECT_NEAR(job.scene.camera.vfov_degrees, 0.7 * 180 / M_PI, 1e-5);
    EXPECT_EQ(read.back(), file.parent_path() / "shot.glb");
    // The glTF camera's default aspect is the film's; no warning then.
    for (const std::string& w : job.warnings) EXPECT_EQ(w.find("aspectRatio"), std::string::npos) << w;
}

TEST(GltfJob, TheJobsCameraWinsAndRenderCameraBesideItIsRefused) {
    const RenderJob job = loadJob(writeJob("yaml_camera", std::string(kJobHead) + kYamlCamera));
    EXPECT_EQ(job.scene.camera.keys.at(0).position, glm::dvec3(0, 0, -5));

    const Error both = loadError(writeJob("both", std::string(kJobHead) + kYamlCamera + "render: {camera: cam}\n"));
    EXPECT_EQ(both.code(), ExitCode::Config);
    EXPECT_EQ(both.loc().line, 10);
    EXPECT_NE(both.message().find("give one of them"), std::string::npos) << both.what();

    const Error unknown = loadError(writeJob("unknown", std::string(kJobHead) + "render: {camera: nosuch}\n"));
    EXPECT_EQ(unknown.code(), ExitCode::Config);
    EXPECT_EQ(unknown.loc().line, 8);
    EXPECT_NE(unknown.message().find("no camera node or camera named 'nosuch'"), std::string::npos) << unknown.what();

    const Error none = loadError(writeJob("nocam", kJobHead, false));
    EXPECT_EQ(none.code(), ExitCode::Config);
    EXPECT_EQ(none.loc().line, 3);

    const RenderJob picked = loadJob(writeJob("picked", std::string(kJobHead) + "render: {camera: cam}\n"));
    EXPECT_LT(glm::length(picked.scene.camera.keys.at(0).position - glm::dvec3(0.2, 0.3, 10)), 1e-6);

    // A square glTF camera on a 16:9 film: the film wins, yfov is kept, and a warning says so.
    const auto square = writeJob("square", kJobHead);
    GltfWriter w = shot(true);
    w.doc()["cameras"][0]["perspective"]["aspectRatio"] = 1.0;
    w.writeGlb(square.parent_path() / "shot.glb");
    const RenderJob sq = loadJob(square);
    EXPECT_NEAR(sq.scene.camera.vfov_degrees, 0.7 * 180 / M_PI, 1e-5);
    EXPECT_TRUE(std::any_of(sq.warnings.begin(), sq.warnings.end(),
                            [](const std::string& m) { return m.find("aspectRatio 1.000000 differs") != std::string::npos; }));
}

TEST(GltfJob, CliExitCodesAndARender) {
    const std::string bin = CLIPBLUR_BINARY;
    const std::string quiet = " > /dev/null 2>&1";
    const auto good = writeJob("cli_good", std::string(kJobHead) + "output: {path: out.exr}\n");
    EXPECT_EQ(testing::runShell(bin + " validate " + good.string() + quiet), 0);
    EXPECT_EQ(testing::runShell("cd " + good.parent_path().string() + " && " + bin + " render job.yaml --progress none" + quiet), 0);
    EXPECT_TRUE(std::filesystem::exists(good.parent_path() / "out.exr"));

    const auto unknown = writeJob("cli_unknown", std::string(kJobHead) + "render: {camera: nosuch}\n");
    EXPECT_EQ(testing::runShell(bin + " validate " + unknown.string() + quiet), 3);

    const auto bad = writeJob("cli_bad", kJobHead);
    std::ofstream(bad.parent_path() / "shot.glb", std::ios::binary | std::ios::trunc) << "glTF\x02";
    EXPECT_EQ(testing::runShell(bin + " validate " + bad.string() + quiet), 4);
    const std::string out = testing::captureShell(bin + " validate " + bad.string() + " 2>&1");
    EXPECT_NE(out.find("shot.glb: not a valid glTF file"), std::string::npos) << out;
    EXPECT_NE(out.find("job.yaml:3:8"), std::string::npos) << out;
}

namespace {

// Two quads in the z = 0 plane facing -z: an unlit one (x in [-2, -0.5]) and an emissive one with
// emissiveStrength 3 (x in [0.5, 2]).
GltfWriter unlitAndEmissivePanels() {
    GltfWriter w;
    const int pos = w.addFloats({-2, -1, 0, -0.5, -1, 0, -0.5, 1, 0, -2, 1, 0, 0.5, -1, 0, 2, -1, 0, 2, 1, 0, 0.5, 1, 0},
                                "VEC3", 34962);
    // (v3 - v0) x (v1 - v0) points to -z: the front faces the camera at z = -5.
    const int left = w.addIndices({0, 3, 1, 1, 3, 2}, 5123);
    const int right = w.addIndices({4, 7, 5, 5, 7, 6}, 5123);
    w.doc()["extensionsUsed"] = {"KHR_materials_unlit", "KHR_materials_emissive_strength"};
    w.doc()["materials"] = json::array(
        {{{"pbrMetallicRoughness", {{"baseColorFactor", {0.2, 0.4, 0.6, 1}}}}, {"extensions", {{"KHR_materials_unlit", json::object()}}}},
         {{"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5, 1}}}},
          {"emissiveFactor", {1, 0.5, 0.25}},
          {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 3}}}}}}});
    w.doc()["meshes"] = json::array({{{"primitives", json::array({{{"attributes", {{"POSITION", pos}}}, {"indices", left}, {"material", 0}},
                                                                  {{"attributes", {{"POSITION", pos}}}, {"indices", right}, {"material", 1}}})}}});
    w.doc()["nodes"] = json::array({{{"name", "panels"}, {"mesh", 0}}});
    w.doc()["scene"] = 0;
    w.doc()["scenes"] = json::array({{{"nodes", {0}}}});
    return w;
}

}  // namespace

// A job over a glTF scene with KHR_materials_unlit and KHR_materials_emissive_strength renders them through
// the job's lights: every fully covered pixel is the unlit panel's base colour or the emissive panel's
// 0.5 x (ambient 0.1 + 1 x cos 0) + 3 x (1, 0.5, 0.25), clipped and stochastic (1e-6: float channels).
TEST(GltfJob, UnlitAndEmissiveMaterialsRenderThroughTheJobsLights) {
    const auto dir = testing::freshTempDir("clipblur_gltf_job_emissive");
    unlitAndEmissivePanels().writeGlb(dir / "panels.glb");
    unlitAndEmissivePanels().writeGlb(testing::validatedAssetDir() / "job_unlit_emissive.glb");
    std::ofstream(dir / "job.yaml") << "version: 1\n"
                                       "film: {width: 64, height: 36}\n"
                                       "scene: panels.glb\n"
                                       "camera: {keys: [{position: [0, 0, -5], view: [0, 0, 1]}]}\n"
                                       "lights: [{type: directional, direction: [0, 0, 1]}]\n"
                                       "ambient: 0.1\n"
                                       "render: {samples: 16}\n";
    const glm::dvec3 unlit(0.2, 0.4, 0.6);
    const glm::dvec3 emissive = 0.5 * (0.1 + 1.0) + 3.0 * glm::dvec3(1, 0.5, 0.25);
    for (const char* method : {"clipped", "stochastic"}) {
        const RenderJob job = loadJob(dir / "job.yaml", {std::string("render.method=") + method});
        EXPECT_TRUE(job.warnings.empty()) << job.warnings.front();
        const RenderResult r = renderFrame(job, 0);
        int unlit_pixels = 0, emissive_pixels = 0;
        const auto& a = r.image.find("A")->values;
        for (std::size_t i = 0; i < a.size(); ++i) {
            if (a[i] < 1.0f) continue;
            const glm::dvec3 c(r.image.find("R")->values[i], r.image.find("G")->values[i], r.image.find("B")->values[i]);
            if (glm::length(c - unlit) < 1e-6) ++unlit_pixels;
            else if (glm::length(c - emissive) < 1e-6) ++emissive_pixels;
            else ADD_FAILURE() << method << ": pixel " << i << " is (" << c.r << ", " << c.g << ", " << c.b << ")";
        }
        EXPECT_GT(unlit_pixels, 50) << method;
        EXPECT_GT(emissive_pixels, 50) << method;
    }
}

}  // namespace clipblur
