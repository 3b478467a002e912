#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "tests/cli/cli_test_util.h"
#include "tests/support/gltf_writer.h"

namespace clipblur {

namespace {

using nlohmann::json;

// configs/table1/spin_pan.yaml's camera keys (times 0 and 1) as a glTF camera node: it looks down -Z
// with +Y up, so its rotation takes (X, Y, Z) to (up x back, up, back) with back = -view.
testing::GltfWriter spinPanCamera() {
    const glm::dvec3 views[2] = {{0, 0, 1}, {0, 0.1, 1}};
    const glm::dvec3 ups[2] = {{0, 1, 0}, {0.1, 1, 0}};
    std::vector<float> rot;
    for (int k = 0; k < 2; ++k) {
        const glm::dvec3 z = -glm::normalize(views[k]);
        const glm::dvec3 y = glm::normalize(ups[k] - glm::dot(ups[k], z) * z);
        const glm::dquat q = glm::quat_cast(glm::dmat3(glm::cross(y, z), y, z));
        rot.insert(rot.end(), {float(q.x), float(q.y), float(q.z), float(q.w)});
    }
    testing::GltfWriter w;
    w.doc()["cameras"] = json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 40 * M_PI / 180}, {"znear", 0.1}}}}});
    w.doc()["nodes"] = json::array({{{"name", "spin_pan"}, {"camera", 0}}});
    w.doc()["scene"] = 0;
    w.doc()["scenes"] = json::array({{{"nodes", {0}}}});
    const int in = w.addFloats({0, 1}, "SCALAR");
    const int out = w.addFloats(rot, "VEC4");
    w.doc()["animations"] = json::array(
        {{{"samplers", json::array({{{"input", in}, {"output", out}, {"interpolation", "LINEAR"}}})},
          {"channels", json::array({{{"sampler", 0}, {"target", {{"node", 0}, {"path", "rotation"}}}}})}}});
    return w;
}

}  // namespace

// The same shot twice: Table 1's spin_pan with its YAML camera keys, and with the camera from a glTF
// file (fps 1, so glTF seconds are the YAML's frames). The glTF stores the rotations as float.
TEST(GltfRender, SpinPanCameraFromGltfRendersLikeTheYamlKeys) {
    const auto dir = testing::freshTempDir("clipblur_gltf_spin_pan");
    spinPanCamera().writeGltf(dir / "cam.gltf");
    spinPanCamera().writeGltf(testing::validatedAssetDir() / "spin_pan_render_camera.gltf");
    const std::string yaml = testing::readText(std::string(CLIPBLUR_SOURCE_DIR) + "/configs/table1/spin_pan.yaml");
    const std::size_t cam_begin = yaml.find("camera:");
    const std::size_t cam_end = yaml.find("shutter:");
    ASSERT_NE(cam_begin, std::string::npos);
    ASSERT_NE(cam_end, std::string::npos);
    std::string gltf_job = yaml;
    gltf_job.replace(cam_begin, cam_end - cam_begin, "scene: cam.gltf\n\n");
    std::ofstream(dir / "yaml.yaml") << yaml;
    std::ofstream(dir / "gltf.yaml") << gltf_job;
    const std::string common = " --set frames.fps=1 --set film.width=160 --set film.height=90 --set output.half=false"
                               " --set render.time_integration=subframes"
                               " --set output.png_preview=false --progress none > /dev/null 2>&1";
    const std::string bin = CLIPBLUR_BINARY;
    ASSERT_EQ(testing::runShell(bin + " render " + (dir / "yaml.yaml").string() + " --out " + (dir / "yaml.exr").string() + common), 0);
    ASSERT_EQ(testing::runShell(bin + " render " + (dir / "gltf.yaml").string() + " --out " + (dir / "gltf.exr").string() + common), 0);
    const testing::ExrPixels a = testing::readExrPixels(dir / "yaml.exr");
    const testing::ExrPixels b = testing::readExrPixels(dir / "gltf.exr");
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) worst = std::max(worst, double(std::abs(a.pixels[i] - b.pixels[i])));
    std::cout << "spin_pan, glTF camera against YAML keys: max |difference| " << worst << "\n";
    // The comparison can fail: without the second key (a still camera) the image differs by far more.
    std::string still = yaml;
    const std::size_t second = still.find("    - {time: 1");
    ASSERT_NE(second, std::string::npos);
    still.erase(second, still.find('\n', second) + 1 - second);
    std::ofstream(dir / "still.yaml") << still;
    ASSERT_EQ(testing::runShell(bin + " render " + (dir / "still.yaml").string() + " --out " + (dir / "still.exr").string() + common), 0);
    const testing::ExrPixels c = testing::readExrPixels(dir / "still.exr");
    double still_worst = 0.0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) still_worst = std::max(still_worst, double(std::abs(a.pixels[i] - c.pixels[i])));
    EXPECT_GT(still_worst, 0.1);
    // 1e-5: the float-stored glTF rotations move the image by about 1e-4 pixel at most.
    EXPECT_LT(worst, 1e-5);
}

}  // namespace clipblur
