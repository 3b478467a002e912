#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <OpenImageIO/imageio.h>

#include "support/cli_harness.h"

namespace clipblur {

namespace fs = std::filesystem;

namespace {

// Three objects, each with its own untextured material, one moving and turning across the other two:
// blurred edges where several objects share a pixel. Stochastic, so each pixel's coverage is counted
// per sample.
const char* kScene = R"(version: 1
film: {width: 40, height: 24, background: 0.3}
camera:
  vfov: 40
  keys: [{time: 0, position: [0, 1, -8], view: [0, -0.1, 1], up: [0, 1, 0]}]
materials:
  - {name: m_ball, color: [0.9, 0.3, 0.2]}
  - {name: m_box, color: [0.2, 0.7, 0.3]}
  - {name: m_floor, color: 0.5}
lights: [{type: directional, direction: [0.3, -1, 0.5]}]
objects:
  - name: ball
    material: m_ball
    primitive: {type: sphere, size: 1.5, segments: 24}
    transform: [{time: 0, translate: [-2.5, 0.8, 0]}, {time: 1, translate: [2.5, 0.8, 0.5]}]
  - name: box
    material: m_box
    primitive: {type: box, size: 1.2}
    transform:
      - {time: 0, translate: [0.5, 0.6, 1.5], rotate: {axis: [0, 1, 0], angle_deg: 0}}
      - {time: 1, translate: [0.5, 0.6, 1.5], rotate: {axis: [0, 1, 0], angle_deg: 60}}
  - name: floor
    material: m_floor
    primitive: {type: quad, size: 12}
render: {method: stochastic, samples: 16, seed: 5}
output: {half: false, cryptomatte: {name: CryptoObject}}
)";

using testing::ExrPixels;

// A decoder written from the Cryptomatte specification alone: find the type whose
// cryptomatte/<key>/name is `type`, read the object's ID from the manifest (hex of the float's bits),
// and sum, over the layers <type>00, <type>01, ..., the coverage (G, A) of every rank whose ID (R, B)
// has exactly those bits.
std::vector<float> decodeMatte(const ExrPixels& e, const std::string& type, const std::string& object) {
    std::string manifest;
    for (const OIIO::ParamValue& p : e.spec.extra_attribs) {
        const std::string name = p.name().string();
        if (name.rfind("cryptomatte/", 0) == 0 && name.size() > 5 && name.substr(name.size() - 5) == "/name" &&
            e.spec.get_string_attribute(name) == type)
            manifest = e.spec.get_string_attribute(name.substr(0, name.size() - 5) + "/manifest");
    }
    EXPECT_FALSE(manifest.empty()) << "no manifest for " << type;
    const std::uint32_t bits = static_cast<std::uint32_t>(std::stoul(nlohmann::json::parse(manifest).at(object).get<std::string>(), nullptr, 16));
    std::vector<float> matte(static_cast<std::size_t>(e.spec.width) * e.spec.height, 0.0f);
    for (int layer = 0;; ++layer) {
        const std::string prefix = type + (layer < 10 ? "0" : "") + std::to_string(layer) + ".";
        const int r = e.spec.channelindex(prefix + "R");
        if (r < 0) break;
        const int pairs[2][2] = {{r, e.spec.channelindex(prefix + "G")},
                                 {e.spec.channelindex(prefix + "B"), e.spec.channelindex(prefix + "A")}};
        for (std::size_t i = 0; i < matte.size(); ++i)
            for (const auto& pair : pairs) {
                const float id = e.at(pair[0], i);
                std::uint32_t id_bits;
                std::memcpy(&id_bits, &id, 4);
                if (id_bits == bits) matte[i] += e.at(pair[1], i);
            }
    }
    return matte;
}

}  // namespace

TEST(CryptomatteRender, DecodedMatteEqualsAWhiteOnBlackRender) {
    const fs::path dir = testing::freshTempDir("clipblur_cryptomatte_render");
    std::ofstream(dir / "scene.yaml") << kScene;
    const std::string render = std::string(CLIPBLUR_BINARY) + " render " + (dir / "scene.yaml").string() + " --progress none";
    const std::string quiet = " > " + (dir / "log.txt").string() + " 2>&1";
    ASSERT_EQ(testing::runShell(render + " --threads 1 --out " + (dir / "crypto.exr").string() + quiet), 0);
    ASSERT_EQ(testing::runShell(render + " --threads 2 --out " + (dir / "crypto2.exr").string() + quiet), 0);
    // The box white, everything else black, unlit (ambient 1, no lights), in float: the same seed gives
    // the same samples, so each pixel's R is the fraction of its samples that hit the box.
    ASSERT_EQ(testing::runShell(render + " --set materials.1.color=1 --set materials.0.color=0 --set materials.2.color=0" +
                  " --set ambient=1 --set 'lights=[]' --out " + (dir / "white.exr").string() + quiet),
              0);
    const ExrPixels crypto = testing::readExrPixels(dir / "crypto.exr");
    const ExrPixels crypto2 = testing::readExrPixels(dir / "crypto2.exr");
    const ExrPixels white = testing::readExrPixels(dir / "white.exr");
    ASSERT_EQ(crypto.pixels, crypto2.pixels);  // bit for bit on 1 and 2 threads

    const std::vector<float> box = decodeMatte(crypto, "CryptoObject", "box");
    const int r = white.spec.channelindex("R");
    int partial = 0;
    for (std::size_t i = 0; i < box.size(); ++i) {
        // Both are (samples on the box) / 16 rounded to float once; 1e-6 allows the sums' rounding.
        EXPECT_NEAR(box[i], white.at(r, i), 1e-6f) << i;
        if (box[i] > 0.0f && box[i] < 1.0f) ++partial;
    }
    EXPECT_GT(partial, 10);  // the turning box's blurred edges are in the test

    // Every pixel's coverages sum to its alpha: three objects fit in depth 6.
    const int alpha = crypto.spec.channelindex("A");
    std::vector<float> sum(box.size(), 0.0f);
    for (const char* object : {"ball", "box", "floor"}) {
        const std::vector<float> m = decodeMatte(crypto, "CryptoObject", object);
        for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += m[i];
    }
    for (std::size_t i = 0; i < sum.size(); ++i) EXPECT_NEAR(sum[i], crypto.at(alpha, i), 1e-6f) << i;
}

}  // namespace clipblur
